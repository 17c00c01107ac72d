/* kernel/quad.c — quadrature helpers of the kernel module: Gauss-Legendre rules, adaptive
 * Gauss-Kronrod for three channels at once, a fast arccos, and the profile's shortest length scale. */
#include "kernel/kernel_internal.h"

#include <math.h>

void kq_gauss_legendre(int n, double *x, double *w)
{
    /* Newton iteration on P_n from the Chebyshev-like initial guess; the three-term recurrence
     * gives P_n and P_{n-1}, P_n' = n (x P_n - P_{n-1}) / (x^2 - 1). */
    for (int i = 0; i < (n + 1) / 2; i++) {
        double z = cos(KQ_PI * (i + 0.75) / (n + 0.5)), dp = 1.0;
        for (int it = 0; it < 100; it++) {
            double p0 = 1.0, p1 = 0.0;
            for (int k = 1; k <= n; k++) {
                double p2 = p1;
                p1 = p0;
                p0 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p2) / k;
            }
            dp = n * (z * p0 - p1) / (z * z - 1.0);
            double dz = p0 / dp;
            z -= dz;
            if (fabs(dz) < 1e-16) break;
        }
        x[i] = -z;
        x[n - 1 - i] = z;
        w[i] = w[n - 1 - i] = 2.0 / ((1.0 - z * z) * dp * dp);
    }
}

/* Gauss-Kronrod 7/15 nodes on [0, 1] (positive half; the rule is symmetric) and weights. */
static const double gk_x[8] = {0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
                               0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
                               0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
                               0.207784955007898467600689403773245, 0.0};
static const double gk_wk[8] = {0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
                                0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
                                0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
                                0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
static const double gk_wg[4] = {0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
                                0.381830050505118944950369775488975, 0.417959183673469387755102040816327};

static void gk15(kq_fn3 f, void *ctx, double a, double b, double res[3], double errv[3])
{
    double c = 0.5 * (a + b), h = 0.5 * (b - a), fc[3];
    f(c, ctx, fc);
    double k[3], g[3];
    for (int ch = 0; ch < 3; ch++) {
        k[ch] = gk_wk[7] * fc[ch];
        g[ch] = gk_wg[3] * fc[ch];
    }
    for (int i = 0; i < 7; i++) {
        double f1[3], f2[3];
        f(c - h * gk_x[i], ctx, f1);
        f(c + h * gk_x[i], ctx, f2);
        for (int ch = 0; ch < 3; ch++) {
            k[ch] += gk_wk[i] * (f1[ch] + f2[ch]);
            if (i % 2 == 1) g[ch] += gk_wg[i / 2] * (f1[ch] + f2[ch]);
        }
    }
    for (int ch = 0; ch < 3; ch++) {
        res[ch] = k[ch] * h;
        errv[ch] = fabs((k[ch] - g[ch]) * h);
    }
}

static void gk_adapt(kq_fn3 f, void *ctx, double a, double b, double rel, double abs_tol, int depth,
                     const double whole[3], const double werr[3], double out[3])
{
    int ok = 1;
    for (int ch = 0; ch < 3; ch++)
        if (werr[ch] > fmax(rel * fabs(whole[ch]), abs_tol)) ok = 0;
    if (ok || depth >= 40) {
        for (int ch = 0; ch < 3; ch++) out[ch] += whole[ch];
        return;
    }
    double m = 0.5 * (a + b), r1[3], e1[3], r2[3], e2[3];
    gk15(f, ctx, a, m, r1, e1);
    gk15(f, ctx, m, b, r2, e2);
    /* Halves get half the absolute budget so the total stays bounded. */
    gk_adapt(f, ctx, a, m, rel, 0.5 * abs_tol, depth + 1, r1, e1, out);
    gk_adapt(f, ctx, m, b, rel, 0.5 * abs_tol, depth + 1, r2, e2, out);
}

void kq_integrate3(kq_fn3 f, void *ctx, double a, double b, double rel_tol, double abs_tol,
                   double out[3])
{
    out[0] = out[1] = out[2] = 0.0;
    if (!(a != b)) return;
    double r[3], e[3];
    gk15(f, ctx, a, b, r, e);
    gk_adapt(f, ctx, a, b, rel_tol, abs_tol, 0, r, e, out);
}

void kq_integrate3_graded(kq_fn3 f, void *ctx, double a, double b, double s, double rel_tol,
                          double abs_tol, double out[3])
{
    out[0] = out[1] = out[2] = 0.0;
    if (!(b > a)) return;
    if (!(s > 0.0) || s > b - a) s = b - a;
    double lo = a, len = s;
    while (lo < b) {
        double hi = fmin(lo + len, b), part[3];
        kq_integrate3(f, ctx, lo, hi, rel_tol, abs_tol, part);
        for (int ch = 0; ch < 3; ch++) out[ch] += part[ch];
        lo = hi;
        len *= 2.0;
    }
}

double kq_profile_length_scale(const sss_profile *p)
{
    double s = INFINITY;
    if (p->model == SSS_PROFILE_GAUSS6) {
        double mm = p->gauss6_mm_per_unit > 0.0 ? p->gauss6_mm_per_unit : 1.0;
        return sqrt(sss_gauss6_variance_mm2[0]) / mm;
    }
    for (int c = 0; c < 3; c++) {
        /* PBD: its single scattering varies on 1/sigma_t; the dipole's sources sit at z_r = 1/sigma_t'. */
        double st = p->model == SSS_PROFILE_DIPOLE
                        ? p->dipole[c].sigma_t_prime
                        : p->material.sigma_a[c] + p->material.sigma_s[c];
        if (st > 0.0 && 1.0 / st < s) s = 1.0 / st;
    }
    return isfinite(s) ? s : 1.0;
}

double kq_profile_decay_length(const sss_profile *p)
{
    if (p->model == SSS_PROFILE_GAUSS6) return kq_profile_length_scale(p);
    double len = INFINITY;
    for (int c = 0; c < 3; c++) {
        double sa = p->material.sigma_a[c], stp = sa + p->material.sigma_s[c] * (1.0 - p->material.g);
        double str = sqrt(3.0 * sa * stp);
        if (str > 0.0 && 1.0 / str < len) len = 1.0 / str;
    }
    return len;
}
