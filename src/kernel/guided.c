/* kernel/guided.c — the guided rank-1 approximation of Jimenez et al. 2019, Appendix A (Eq. 8-9):
 *   a_s = argmin_a  int Gamma(x, y) (R_d(x, y) - a(x) a(y))^2 dx dy   subject to  ||a||_1^2 = ||R_d||_1,
 *   Gamma(x, y; k) = (x^2 + y^2)^(k/2) (1 - e^(-b x^2)) (1 - e^(-b y^2)),
 * discretised on grid cells of width h: R_d by its cell averages (the cell integrals of kernel/cells.c
 * over h^2, finite also for the cell holding r = 0), Gamma (a smooth weight) at cell centres, a
 * constant on each cell. With the Lagrange multiplier m of
 * the linear constraint h sum_i a_i = sqrt(||R_d||_1), stationarity reads
 *   a_i d_i = b_i + m,  d_i = sum_j G_ij a_j^2,  b_i = sum_j G_ij R_ij a_j,
 * which we iterate as a fixed point (d, b from the last iterate, m from the constraint, damped),
 * starting from the pre-integrated kernel's a_p / sqrt(||R_d||_1), which already meets the constraint.
 * Gamma vanishes on the axes, where a would be undetermined: we add 1e-3 of its largest value (the
 * guide only selects length scales; the paper leaves b open). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "kernel/kernel_internal.h"
#include "kernel/kernel_test.h"
#include "sss/kernel.h"

#define GUIDED_MAX_GRID 512
#define GUIDED_FLOOR 1e-3
#define GUIDED_ITERATIONS 2000

double kernel_guided_objective(const sss_profile *profile, int grid, double extent, double k, double b, int channel,
                               const double *a)
{
    if (!profile || !a || grid < 1 || grid > GUIDED_MAX_GRID || channel < 0 || channel > 2 || !(extent > 0.0) ||
        !isfinite(extent))
        return NAN;
    size_t n = (size_t)grid;
    double *cells = malloc(sizeof(double) * 3 * n * n);
    if (!cells) return NAN;
    kq_cell_integrals(profile, grid, extent, cells);
    const double *avg = cells + (size_t)channel * n * n;
    double h = 2.0 * extent / grid, gmax = 0.0, sum = 0.0;
    /* Two passes: the floor needs the largest Gamma. */
    for (int pass = 0; pass < 2; pass++)
        for (int i = 0; i < grid; i++)
            for (int j = 0; j < grid; j++) {
                double x = -extent + (i + 0.5) * h, y = -extent + (j + 0.5) * h;
                double g = pow(x * x + y * y, 0.5 * k) * -expm1(-b * x * x) * -expm1(-b * y * y);
                if (pass == 0) {
                    gmax = fmax(gmax, g);
                    continue;
                }
                double r = avg[(size_t)i * n + (size_t)j] / h / h - a[i] * a[j];
                sum += (g + GUIDED_FLOOR * gmax) * r * r * h * h;
            }
    free(cells);
    return sum;
}

sss_result sss_kernel_guided(const sss_profile *profile, int grid, double extent, double k, double b,
                             double *out, sss_error *err)
{
    if (!profile || !out) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "guided kernel: NULL argument");
    if (grid < 2 || grid > GUIDED_MAX_GRID)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "guided kernel: grid %d is outside [2, %d]", grid,
                             GUIDED_MAX_GRID);
    if (!(extent > 0.0) || !isfinite(extent) || !(k >= 0.0) || !(k <= 16.0) || !(b > 0.0) || !isfinite(b))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                             "guided kernel: needs extent > 0, k in [0, 16], b > 0 (got %g, %g, %g)", extent, k, b);
    double h2 = 4.0 * extent * extent / ((double)grid * grid);
    if (!(h2 > 0.0) || !isfinite(h2))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                             "guided kernel: extent %g gives cells whose area is not a finite positive number", extent);
    size_t n = (size_t)grid;
    double *g = malloc(sizeof(double) * n * n), *rd = malloc(sizeof(double) * 3 * n * n);
    double *a = malloc(sizeof(double) * n), *an = malloc(sizeof(double) * n), *bb = malloc(sizeof(double) * n);
    double *dd = malloc(sizeof(double) * n);
    if (!g || !rd || !a || !an || !bb || !dd) {
        free(g), free(rd), free(a), free(an), free(bb), free(dd);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "guided kernel: no memory for a %d-cell grid", grid);
    }
    double h = 2.0 * extent / grid, gmax = 0.0;
    kq_cell_integrals(profile, grid, extent, rd);
    for (size_t i = 0; i < 3 * n * n; i++) rd[i] /= h2; /* cell averages */
    for (size_t i = 0; i < n; i++)
        for (size_t j = 0; j < n; j++) {
            double x = -extent + (i + 0.5) * h, y = -extent + (j + 0.5) * h;
            /* Jimenez et al. 2019, Eq. 9. */
            g[i * n + j] = pow(x * x + y * y, 0.5 * k) * -expm1(-b * x * x) * -expm1(-b * y * y);
            gmax = fmax(gmax, g[i * n + j]);
        }
    for (size_t i = 0; i < n * n; i++) g[i] += GUIDED_FLOOR * gmax;
    sss_result res = SSS_OK;
    for (int c = 0; c < 3 && res == SSS_OK; c++) {
        double total = sss_profile_total(profile, c), target = sqrt(total) / h; /* sum_i a_i */
        const double *r = rd + c * n * n;
        double ap[3];
        for (size_t i = 0; i < n; i++) {
            sss_kernel_preintegrated_eval_rgb(profile, -extent + (i + 0.5) * h, ap);
            a[i] = ap[c];
        }
        double s = 0.0;
        for (size_t i = 0; i < n; i++) s += a[i];
        for (size_t i = 0; i < n; i++) a[i] = s > 0.0 ? a[i] * target / s : target / n;
        for (int it = 0; it < GUIDED_ITERATIONS; it++) {
            double inv_sum = 0.0, ratio_sum = 0.0;
            for (size_t i = 0; i < n; i++) {
                double bi = 0.0, di = 0.0;
                for (size_t j = 0; j < n; j++) {
                    bi += g[i * n + j] * r[i * n + j] * a[j];
                    di += g[i * n + j] * a[j] * a[j];
                }
                bb[i] = bi;
                dd[i] = di > 1e-300 ? di : 1e-300;
                inv_sum += 1.0 / dd[i];
                ratio_sum += bb[i] / dd[i];
            }
            double m = (target - ratio_sum) / inv_sum, change = 0.0, norm = 0.0;
            for (size_t i = 0; i < n; i++) {
                an[i] = 0.5 * a[i] + 0.5 * (bb[i] + m) / dd[i]; /* damped: both keep sum = target */
                change += fabs(an[i] - a[i]);
                norm += fabs(an[i]);
            }
            memcpy(a, an, sizeof(double) * n);
            if (change <= 1e-12 * norm) break;
        }
        for (size_t i = 0; i < n; i++) {
            if (!isfinite(a[i])) {
                res = sss_error_set(err, SSS_ERROR_NUMERIC, "guided kernel: the iteration diverged (channel %d)", c);
                break;
            }
            out[c * n + i] = a[i];
        }
    }
    free(g), free(rd), free(a), free(an), free(bb), free(dd);
    return res;
}
