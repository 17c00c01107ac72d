/* Separable kernels of Jimenez et al. 2019 against properties the paper fixes and independent quadratures:
 * the pre-integrated a_p integrates to ||R_d||_1 and, convolved with a straight shadow edge, gives
 * the full 2D convolution (Eq. 4 says exactly); discretised taps are symmetric, ascending, sit at the
 * quantiles of the dominant channel and weigh each channel's kernel over their intervals; the artist
 * model's a_m integrates to 1; the SVD obeys Eckart-Young. */
#include <math.h>
#include <string.h>

#include "check.h"
#include "kernel/kernel_internal.h"
#include "kernel/kernel_test.h"
#include "kernel_test_util.h"
#include "sss/kernel.h"

static sss_pbd_table table;

/* ---- Integrals of the library's continuous a_p (graded panels from 0) ------------------------ */

typedef struct ap_q {
    const sss_profile *p;
} ap_q;

static void ap_fn(double x, void *ctx, double out[3])
{
    sss_kernel_preintegrated_eval_rgb(((ap_q *)ctx)->p, x, out);
}

/* int_a^b a_p for 0 <= a <= b (a_p has its peak, log-sharp for PBD, at 0). */
static void ap_integral(const sss_profile *p, double a, double b, double out[3])
{
    ap_q q = {p};
    out[0] = out[1] = out[2] = 0.0;
    if (b > a) tu_graded(ap_fn, &q, a, b, a, a == 0.0 ? 20 : 6, out);
}

/* int_-inf^x a_p by symmetry, with the total T = int_-inf^inf a_p. */
static void ap_cdf(const sss_profile *p, double x, const double total[3], double out[3])
{
    double part[3];
    ap_integral(p, 0.0, fabs(x), part);
    for (int c = 0; c < 3; c++) out[c] = 0.5 * total[c] + (x >= 0.0 ? part[c] : -part[c]);
}

/* ---- The 2D convolution of a shadow edge (E = 1 for x > 0) with R_d, in polar coordinates around
 * the receiving point x: of the circle of radius rho > |x| around it, a fraction acos(|x| / rho) / pi
 * lies beyond the edge (on the far side of the line x' = 0); circles with rho <= |x| lie wholly on
 * x's side. So the lit fraction is 1 - that for x > 0 and that for x < 0. */
typedef struct edge {
    const sss_profile *p;
    double x;
} edge;

static void edge_fn(double rho, void *ctx, double out[3])
{
    const edge *e = ctx;
    double ax = fabs(e->x), lit;
    if (rho <= ax)
        lit = e->x > 0.0 ? 1.0 : 0.0;
    else {
        double beyond = acos(ax / rho) / TU_PI; /* fraction of the circle beyond the line, away from x */
        lit = e->x > 0.0 ? 1.0 - beyond : beyond;
    }
    sss_profile_eval_rgb(e->p, rho, out);
    for (int c = 0; c < 3; c++) out[c] *= 2.0 * TU_PI * rho * lit;
}

static void edge_2d(const sss_profile *p, double x, double r_end, double out[3])
{
    edge e = {p, x};
    out[0] = out[1] = out[2] = 0.0;
    tu_graded(edge_fn, &e, 0.0, fabs(x), 0.0, 30, out);
    tu_graded(edge_fn, &e, fabs(x), r_end, fabs(x), 30, out);
}

static void check_preintegrated(const sss_profile *p, const char *what, double r_end, const double total[3])
{
    /* Symmetric, the channels as in the RGB call, and int a_p = ||R_d||_1 (Eq. 4). */
    double rgb[3];
    sss_kernel_preintegrated_eval_rgb(p, 0.37, rgb);
    for (int c = 0; c < 3; c++) {
        CHECK(sss_kernel_preintegrated_eval(p, c, -0.37) == rgb[c]);
        CHECK(rgb[c] > 0.0);
    }
    double half[3];
    ap_integral(p, 0.0, r_end, half);
    for (int c = 0; c < 3; c++) CHECK_MSG(fabs(2.0 * half[c] - total[c]) <= 1e-4 * total[c], "%s: int a_p %g vs ||R_d|| %g", what, 2.0 * half[c], total[c]);

    /* Shadow edge: 1D convolution with a_p / ||R_d|| equals the 2D convolution / ||R_d||. */
    double xs[] = {-2.0, -0.6, -0.1, 0.0, 0.05, 0.3, 1.5};
    for (size_t k = 0; k < sizeof xs / sizeof xs[0]; k++) {
        double one[3], two[3];
        ap_cdf(p, xs[k], total, one);
        edge_2d(p, xs[k], r_end, two);
        for (int c = 0; c < 3; c++)
            CHECK_MSG(fabs(one[c] - two[c]) <= 5e-3 * two[c] + 1e-9 * total[c],
                      "%s: edge at x = %g, channel %d: 1D %g vs 2D %g", what, xs[k], c, one[c] / total[c],
                      two[c] / total[c]);
    }

    /* The discretised kernel. */
    sss_separable_kernel k;
    sss_error err = {0};
    CHECK_MSG(sss_kernel_preintegrated(p, 7, 0.0, &k, &err) == SSS_OK, "%s", err.message);
    CHECK(k.taps == 7 && k.offsets[3] == 0.0f);
    for (int c = 0; c < 3; c++) CHECK(k.total[c] == sss_profile_total(p, c));
    for (int i = 0; i + 1 < 7; i++) CHECK(k.offsets[i] < k.offsets[i + 1]);
    double sum[3] = {0, 0, 0};
    for (int i = 0; i < 7; i++)
        for (int c = 0; c < 3; c++) {
            CHECK(k.offsets[i] == -k.offsets[6 - i]);
            CHECK(k.weights[3 * i + c] == k.weights[3 * (6 - i) + c]);
            CHECK(k.weights[3 * i + c] > 0.0f);
            sum[c] += k.weights[3 * i + c];
        }
    for (int c = 0; c < 3; c++) CHECK_NEAR(sum[c], 1.0, 1e-5);
    /* The range holds 99.9% of the dominant (red: least absorbing) channel's a_p, and the taps right of
     * 0 sit at its quantiles (i + 1/2) / 7 within [-range, range]. */
    double in[3];
    ap_integral(p, 0.0, k.range, in);
    CHECK_MSG(fabs(2.0 * in[0] / total[0] - 0.999) < 2e-5, "%s: range %g holds %g", what, k.range, 2.0 * in[0] / total[0]);
    for (int i = 4; i < 7; i++) {
        double part[3];
        ap_integral(p, 0.0, k.offsets[i], part);
        double q = (in[0] + part[0]) / (2.0 * in[0]);
        CHECK_MSG(fabs(q - (i + 0.5) / 7.0) < 1e-4, "%s: tap %d at quantile %g", what, i, q);
    }
    /* Each tap's weight is the channel's a_p over [midpoint left, midpoint right] / ||R_d||. */
    for (int i = 4; i < 7; i++) {
        double lo = 0.5 * (k.offsets[i - 1] + k.offsets[i]), hi = i == 6 ? r_end : 0.5 * (k.offsets[i] + k.offsets[i + 1]);
        double w[3];
        ap_integral(p, lo, hi, w);
        for (int c = 0; c < 3; c++) CHECK_MSG(fabs(k.weights[3 * i + c] - w[c] / total[c]) < 1e-4, "%s: tap %d channel %d weight %g vs %g", what, i, c, k.weights[3 * i + c], w[c] / total[c]);
    }
    sss_separable_kernel_free(&k);

    /* One tap takes everything; default tap count 7; even counts and NULLs are errors. */
    CHECK(sss_kernel_preintegrated(p, 1, 0.0, &k, &err) == SSS_OK && k.taps == 1);
    if (k.taps == 1)
        for (int c = 0; c < 3; c++) CHECK_NEAR(k.weights[c], 1.0, 1e-6);
    sss_separable_kernel_free(&k);
    CHECK(sss_kernel_preintegrated(p, 0, 2.0, &k, &err) == SSS_OK && k.taps == 7 && k.range == 2.0);
    CHECK(k.offsets[6] < 2.0f);
    sss_separable_kernel_free(&k);
    CHECK(sss_kernel_preintegrated(p, 6, 0.0, &k, &err) == SSS_ERROR_INVALID_ARGUMENT && strstr(err.message, "6 taps"));
    CHECK(k.offsets == NULL && k.weights == NULL);
    CHECK(sss_kernel_preintegrated(NULL, 7, 0.0, &k, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(sss_kernel_preintegrated(p, 7, NAN, &k, &err) == SSS_ERROR_INVALID_ARGUMENT);
    sss_separable_kernel_free(&k);
}

/* ---- Artist model ----------------------------------------------------------------------------- */

typedef struct am_q {
    const sss_artist_params *a;
} am_q;

static void am_fn(double x, void *ctx, double out[3])
{
    for (int c = 0; c < 3; c++) out[c] = sss_artist_eval_1d(((am_q *)ctx)->a, c, x);
}

static void check_artist(const char *preset)
{
    sss_artist_params a;
    CHECK(sss_artist_preset(preset, &a, NULL) == SSS_OK);
    am_q q = {&a};
    /* The continuous a_m integrates to 1 (a normalised mixture, Jimenez et al. 2019, Eq. 6). */
    double tot[3] = {0, 0, 0};
    tu_graded(am_fn, &q, -20.0 * a.s, 20.0 * a.s, 0.0, 24, tot);
    for (int c = 0; c < 3; c++) CHECK_NEAR(tot[c], 1.0, 1e-9);

    sss_separable_kernel k;
    sss_error err = {0};
    CHECK_MSG(sss_kernel_artist(&a, 9, &k, &err) == SSS_OK, "%s", err.message);
    CHECK(k.taps == 9 && k.offsets[4] == 0.0f && k.total[0] == 1.0);
    double sum[3] = {0, 0, 0};
    for (int i = 0; i < 9; i++) {
        if (i + 1 < 9) CHECK(k.offsets[i] < k.offsets[i + 1]);
        CHECK(k.offsets[i] == -k.offsets[8 - i]);
        for (int c = 0; c < 3; c++) {
            CHECK(k.weights[3 * i + c] == k.weights[3 * (8 - i) + c]);
            sum[c] += k.weights[3 * i + c];
        }
    }
    for (int c = 0; c < 3; c++) CHECK_NEAR(sum[c], 1.0, 1e-6);
    /* Weights are a_m over the midpoint intervals (outer ones to infinity). */
    for (int i = 4; i < 9; i++) {
        double lo = i == 4 ? 0.0 : 0.5 * (k.offsets[i - 1] + k.offsets[i]);
        double hi = i == 8 ? 20.0 * a.s : 0.5 * (k.offsets[i] + k.offsets[i + 1]), w[3] = {0, 0, 0};
        tu_graded(am_fn, &q, lo, hi, lo, 16, w);
        for (int c = 0; c < 3; c++) CHECK_NEAR(k.weights[3 * i + c], i == 4 ? 2.0 * w[c] : w[c], 2e-6);
    }
    /* The range holds 99.9% of the red (widest, far = 1) channel. */
    double in[3] = {0, 0, 0};
    tu_graded(am_fn, &q, -k.range, k.range, 0.0, 20, in);
    CHECK_NEAR(in[0], 0.999, 1e-6);
    sss_separable_kernel_free(&k);

    sss_artist_params bad = a;
    bad.w = 1.5;
    CHECK(sss_kernel_artist(&bad, 7, &k, &err) == SSS_ERROR_INVALID_ARGUMENT && strstr(err.message, "w = 1.5"));
    bad = a;
    bad.s = 0.0;
    CHECK(sss_kernel_artist(&bad, 7, &k, &err) == SSS_ERROR_INVALID_ARGUMENT);
    bad = a;
    bad.far[1] = -1.0;
    CHECK(sss_kernel_artist(&bad, 7, &k, &err) == SSS_ERROR_INVALID_ARGUMENT);
    memset(&bad, 0, sizeof bad);
    bad.s = 1.0;
    CHECK(sss_kernel_artist(&bad, 7, &k, &err) == SSS_ERROR_INVALID_ARGUMENT && strstr(err.message, "zero width"));
    CHECK(sss_kernel_artist(&a, 4, &k, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(sss_kernel_artist(NULL, 7, &k, &err) == SSS_ERROR_INVALID_ARGUMENT);
    sss_separable_kernel_free(&k);
}

/* ---- SVD --------------------------------------------------------------------------------------- */

static void check_svd(const sss_profile *p, const char *what)
{
    const int n = 48;
    const double extent = 3.0;
    sss_svd_kernel k;
    sss_error err = {0};
    CHECK_MSG(sss_kernel_svd(p, n, extent, 6, &k, &err) == SSS_OK, "%s", err.message);
    /* The discretised profile: R_d's cell integrals (kernel_internal.h; checked against brute-force
     * quadrature in test_kernel_cells.c). Here: the SVD's identities for that matrix. */
    static double m[3][48 * 48];
    kq_cell_integrals(p, n, extent, &m[0][0]);
    for (int c = 0; c < 3; c++) {
        const double *s = k.singular_values + c * n;
        double fro2 = 0.0, sum2 = 0.0;
        for (int i = 0; i < n * n; i++) fro2 += m[c][i] * m[c][i];
        for (int i = 0; i < n; i++) {
            CHECK(s[i] >= 0.0);
            if (i + 1 < n) CHECK(s[i] >= s[i + 1]);
            sum2 += s[i] * s[i];
        }
        CHECK_REL(sum2, fro2, 1e-10); /* ||M||_F^2 = sum of squared singular values */
        /* Eckart-Young: || M - M_N ||_F = sqrt(sum_{k >= N} s_k^2), decreasing in N. */
        double last = INFINITY;
        for (int rank = 1; rank <= 6; rank++) {
            double e2 = 0.0, dropped = 0.0;
            for (int i = 0; i < n; i++)
                for (int j = 0; j < n; j++) {
                    double a = 0.0;
                    for (int r = 0; r < rank; r++) {
                        const float *v = k.vectors + ((size_t)r * 3 + c) * n;
                        a += k.signs[r * 3 + c] * (double)v[i] * v[j];
                    }
                    e2 += (m[c][i * n + j] - a) * (m[c][i * n + j] - a);
                }
            for (int i = rank; i < n; i++) dropped += s[i] * s[i];
            double e = sqrt(e2), expect = sqrt(dropped);
            /* float vectors: allow 1e-6 of ||M|| on top of the identity */
            CHECK_MSG(fabs(e - expect) <= 1e-3 * expect + 1e-6 * sqrt(fro2), "%s ch %d rank %d: error %g vs %g", what, c, rank, e, expect);
            CHECK(e < last);
            last = e;
        }
        if (c == 0) printf("%s: leading singular values %.4g %.4g %.4g %.4g (red)\n", what, s[0], s[1], s[2], s[3]);
    }
    sss_svd_kernel_free(&k);
    CHECK(sss_kernel_svd(p, 0, extent, 1, &k, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(sss_kernel_svd(p, 16, -1.0, 1, &k, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(sss_kernel_svd(p, 16, 1.0, 17, &k, &err) == SSS_ERROR_INVALID_ARGUMENT && strstr(err.message, "rank 17"));
    CHECK(sss_kernel_svd(NULL, 16, 1.0, 1, &k, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(k.vectors == NULL);
    sss_svd_kernel_free(&k);
}

/* ---- Guided rank-1 (Jimenez et al. 2019, Appendix A): a constrained minimum ------------------------------- */

static void check_guided(const sss_profile *p, double k, const char *what)
{
    const int n = 40;
    const double extent = 4.0, b = 4.0, h = 2.0 * extent / n;
    double a[3 * 40];
    sss_error err = {0};
    CHECK_MSG(sss_kernel_guided(p, n, extent, k, b, a, &err) == SSS_OK, "%s", err.message);
    for (int c = 0; c < 3; c++) {
        const double *ac = a + c * n;
        /* The energy constraint (h sum a)^2 = ||R_d||_1, and symmetry a(-x) = a(x). */
        double s = 0.0;
        for (int i = 0; i < n; i++) s += ac[i] * h;
        CHECK_REL(s * s, sss_profile_total(p, c), 1e-9);
        for (int i = 0; i < n / 2; i++) CHECK_NEAR(ac[i], ac[n - 1 - i], 1e-9 * fabs(ac[n / 2]));
        /* No worse than the pre-integrated start a_p / sqrt(||R_d||), which meets the constraint too. */
        double start[40], ap[3];
        double t = 0.0;
        for (int i = 0; i < n; i++) {
            sss_kernel_preintegrated_eval_rgb(p, -extent + (i + 0.5) * h, ap);
            start[i] = ap[c];
            t += ap[c] * h;
        }
        for (int i = 0; i < n; i++) start[i] *= sqrt(sss_profile_total(p, c)) / t;
        double f = kernel_guided_objective(p, n, extent, k, b, c, ac);
        double f0 = kernel_guided_objective(p, n, extent, k, b, c, start);
        CHECK_MSG(f <= f0, "%s ch %d: objective %g above the start's %g", what, c, f, f0);
        /* Stationary along the constraint: moving mass between two cells (sum kept) does not lower
         * the objective to first order (central differences), unlike at the start. */
        double worst = 0.0, worst0 = 0.0;
        for (int i = 0; i < n / 2; i += 3) {
            int j = n / 2 + 2;
            double e = 1e-4 * ac[n / 2], d[40], d0[40];
            for (int q = 0; q < n; q++) d[q] = ac[q], d0[q] = start[q];
            d[i] += e, d[n - 1 - i] += e, d[j] -= e, d[n - 1 - j] -= e;
            d0[i] += e, d0[n - 1 - i] += e, d0[j] -= e, d0[n - 1 - j] -= e;
            double fp = kernel_guided_objective(p, n, extent, k, b, c, d);
            double fp0 = kernel_guided_objective(p, n, extent, k, b, c, d0);
            for (int q = 0; q < n; q++) d[q] = 2.0 * ac[q] - d[q], d0[q] = 2.0 * start[q] - d0[q];
            double fm = kernel_guided_objective(p, n, extent, k, b, c, d);
            double fm0 = kernel_guided_objective(p, n, extent, k, b, c, d0);
            worst = fmax(worst, fabs(fp - fm) / (2.0 * e));
            worst0 = fmax(worst0, fabs(fp0 - fm0) / (2.0 * e));
        }
        CHECK_MSG(worst < 1e-3 * worst0, "%s ch %d: directional derivative %g (start %g)", what, c, worst, worst0);
    }
    CHECK(sss_kernel_guided(p, 1, extent, k, b, a, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(sss_kernel_guided(p, n, extent, -1.0, b, a, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(sss_kernel_guided(p, n, extent, k, 0.0, a, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(isnan(kernel_guided_objective(p, n, extent, k, b, 3, a)));
}

int main(void)
{
    sss_error err = {0};
    if (sss_pbd_table_build(1.33, 0.0, &table, &err) != SSS_OK) {
        fprintf(stderr, "PBD table: %s\n", err.message);
        return 1;
    }
    sss_profile dip = tu_profile("Skin1", SSS_PROFILE_DIPOLE, NULL);
    sss_profile pbd = tu_profile("Skin1", SSS_PROFILE_PBD, &table);
    /* Totals: the dipole's closed form; for PBD an independent radial quadrature over the table's
     * support (its last radius is 203 mean free paths). */
    double tdip[3], tpbd[3];
    for (int c = 0; c < 3; c++) tdip[c] = sss_dipole_total_reflectance(&dip.dipole[c]);
    double r_end_pbd = 0.0;
    for (int c = 0; c < 3; c++)
        r_end_pbd = fmax(r_end_pbd, table.radius[SSS_PBD_RADII - 1] / (pbd.material.sigma_a[c] + pbd.material.sigma_s[c]));
    tu_disc_at_origin(&pbd, r_end_pbd, tpbd);
    double r_end_dip = 0.0;
    for (int c = 0; c < 3; c++) r_end_dip = fmax(r_end_dip, 40.0 / dip.dipole[c].sigma_tr);

    check_preintegrated(&dip, "Skin1 dipole", r_end_dip, tdip);
    check_preintegrated(&pbd, "Skin1 PBD", r_end_pbd, tpbd);
    check_artist("single-layer");
    check_artist("multi-layer");
    check_artist("production");
    check_svd(&dip, "Skin1 dipole");
    check_svd(&pbd, "Skin1 PBD");
    check_guided(&dip, 2.0, "Skin1 dipole k 2");
    check_guided(&pbd, 0.0, "Skin1 PBD k 0");
    return CHECK_DONE();
}
