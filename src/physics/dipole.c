/* physics/dipole.c — the classical dipole of Jensen et al. 2001 (Mertens et al. 2003, Table 1; docs/physics.md §2.1),
 * its closed-form plane integral and the exact importance sampling of Mertens et al. 2003, section 4. */
#include "sss/profile.h"

#include <float.h>
#include <math.h>

#define PI 3.14159265358979323846

void sss_dipole_init(sss_dipole *d, double sigma_a, double sigma_s_prime, double eta)
{
    double st = sigma_a + sigma_s_prime; /* sigma_t' */
    if (!(st > 0.0) || !isfinite(st) || sigma_a < 0.0 || sigma_s_prime < 0.0) {
        /* A medium that does not interact (or nonsense input): a zero profile, never NaN. */
        d->sigma_t_prime = 0.0;
        d->alpha_prime = 0.0;
        d->sigma_tr = 0.0;
        d->z_r = 1.0;
        d->z_v = 1.0;
        return;
    }
    /* Mertens et al. 2003, Table 1. */
    double fdr = sss_fresnel_diffuse_reflectance(eta);
    double A = (1.0 + fdr) / (1.0 - fdr);
    double D = 1.0 / (3.0 * st);
    d->sigma_t_prime = st;
    d->alpha_prime = sigma_s_prime / st;
    d->sigma_tr = sqrt(3.0 * sigma_a * st);
    d->z_r = 1.0 / st;
    d->z_v = d->z_r + 4.0 * A * D;
}

/* One source's term z (1 + sigma_tr s) e^(-sigma_tr s) / s^3, s = sqrt(r^2 + z^2). */
static double source_term(double sigma_tr, double z, double r)
{
    double s = sqrt(r * r + z * z);
    return z * (1.0 + sigma_tr * s) * exp(-sigma_tr * s) / (s * s * s);
}

double sss_dipole_rd(const sss_dipole *d, double r)
{
    if (!(d->alpha_prime > 0.0) || !isfinite(r)) return 0.0;
    r = fabs(r);
    /* Mertens et al. 2003, Table 1: R_d = alpha'/(4 pi) [R_d^r + R_d^v]. */
    return d->alpha_prime / (4.0 * PI) *
           (source_term(d->sigma_tr, d->z_r, r) + source_term(d->sigma_tr, d->z_v, r));
}

double sss_dipole_total_reflectance(const sss_dipole *d)
{
    /* Mertens et al. 2003, Eq. 7 summed over both sources: rho = alpha'/2 (e^(-sigma_tr z_r) + e^(-sigma_tr z_v)). */
    return 0.5 * d->alpha_prime * (exp(-d->sigma_tr * d->z_r) + exp(-d->sigma_tr * d->z_v));
}

/* Solves sigma_tr z (u - 1) + ln u + ln(1 - xi) = 0 for u >= 1 (Mertens et al. 2003, section 4) and returns
 * r = z sqrt(u^2 - 1). We iterate on v = ln u: g(v) = a (e^v - 1) + v + L is increasing and convex, so
 * Newton started at an upper bound of the root decreases monotonically onto it (no overshoot). Both
 * -L and log1p(-L/a) bound the root from above, since each of the two terms alone is >= 0. */
static double invert_source(double a, double z, double xi)
{
    double L = log1p(-xi); /* ln(1 - xi) <= 0 */
    if (!(L < 0.0)) return 0.0;
    double v = -L;
    if (a > 0.0) v = fmin(v, log1p(-L / a));
    for (int it = 0; it < 100; it++) {
        double ev = exp(v);
        double g = a * (ev - 1.0) + v + L;
        double step = g / (a * ev + 1.0);
        v -= step;
        if (v < 0.0) v = 0.0;
        if (fabs(step) <= 1e-15 * (1.0 + v)) break;
    }
    /* u^2 - 1 = (u - 1)(u + 1) with u - 1 = expm1(v): accurate for small radii. */
    double um1 = expm1(v);
    return z * sqrt(um1 * (um1 + 2.0));
}

double sss_dipole_sample_radius(const sss_dipole *d, double u_source, double u_radius)
{
    if (!(d->alpha_prime > 0.0)) return 0.0;
    double er = exp(-d->sigma_tr * d->z_r), ev = exp(-d->sigma_tr * d->z_v);
    /* Pick the source by its share of the plane integral (Mertens et al. 2003, Eq. 7). */
    int real = u_source < er / (er + ev);
    double z = real ? d->z_r : d->z_v;
    if (!(u_radius >= 0.0)) u_radius = 0.0;
    if (u_radius > 1.0 - DBL_EPSILON) u_radius = 1.0 - DBL_EPSILON;
    return invert_source(d->sigma_tr * z, z, u_radius);
}

double sss_dipole_pdf_radius(const sss_dipole *d, double r)
{
    double rho = sss_dipole_total_reflectance(d);
    if (!(rho > 0.0) || !(r >= 0.0) || !isfinite(r)) return 0.0;
    /* p(r) = 2 pi r R_d(r) / rho (Mertens et al. 2003, section 4). */
    return 2.0 * PI * r * sss_dipole_rd(d, r) / rho;
}
