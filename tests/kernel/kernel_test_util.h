/* tests/kernel/kernel_test_util.h — independent numerical tools for the kernel tests: fixed 8-point
 * Gauss-Legendre panels graded towards a point, a brute-force disc integral in polar coordinates
 * around the disc's centre (not the rings around the origin the library uses), adaptive 1D
 * quadrature, and the materials/profiles the tests share. Nothing here calls the kernel module. */
#ifndef SSS_KERNEL_TEST_UTIL_H
#define SSS_KERNEL_TEST_UTIL_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "sss/profile.h"

#define TU_PI 3.14159265358979323846

/* 8-point Gauss-Legendre on [-1, 1] (standard table). */
static const double tu_gl_x[4] = {0.183434642495649804939476142360184, 0.525532409916328985817739049189254,
                                  0.796666477413626739591553936475830, 0.960289856497536231683560868569473};
static const double tu_gl_w[4] = {0.362683783378361982965150449277196, 0.313706645877887287337962201986601,
                                  0.222381034453374470544355994426241, 0.101228536290376259152531354309963};

typedef void (*tu_fn3)(double x, void *ctx, double out[3]);

/* out += integral of f over [a, b], one 8-point panel. */
static inline void tu_panel(tu_fn3 f, void *ctx, double a, double b, double out[3])
{
    double c = 0.5 * (a + b), h = 0.5 * (b - a);
    for (int i = 0; i < 8; i++) {
        double v[3], x = c + (i < 4 ? -1.0 : 1.0) * h * tu_gl_x[i % 4];
        f(x, ctx, v);
        for (int ch = 0; ch < 3; ch++) out[ch] += h * tu_gl_w[i % 4] * v[ch];
    }
}

/* out += integral over [a, b] with panels halving in width towards t (a <= t <= b), `levels` of
 * them on each side: resolves a peak or kink at t down to (b - a) 2^-levels. */
static inline void tu_graded(tu_fn3 f, void *ctx, double a, double b, double t, int levels, double out[3])
{
    if (t > b) t = b;
    if (t < a) t = a;
    double hi = b, w = 0.5 * (b - t);
    for (int k = 0; k < levels && b > t; k++) {
        double lo = k == levels - 1 ? t : hi - w;
        tu_panel(f, ctx, lo, hi, out);
        hi = lo;
        w *= 0.5;
    }
    double lo = a;
    w = 0.5 * (t - a);
    for (int k = 0; k < levels && t > a; k++) {
        double up = k == levels - 1 ? t : lo + w;
        tu_panel(f, ctx, lo, up, out);
        lo = up;
        w *= 0.5;
    }
}

/* ---- Brute-force disc average: polar coordinates (rho, phi) around the disc's centre ---------- */

typedef struct tu_disc {
    const sss_profile *p;
    double r, rho;
} tu_disc;

static void tu_disc_phi(double phi, void *ctx, double out[3])
{
    tu_disc *d = ctx;
    /* Distance from the origin of the point at (rho, phi) around a centre at distance r. */
    double x2 = d->r * d->r + d->rho * d->rho + 2.0 * d->r * d->rho * cos(phi);
    sss_profile_eval_rgb(d->p, sqrt(x2 > 0.0 ? x2 : 0.0), out);
}

static void tu_disc_rho(double rho, void *ctx, double out[3])
{
    tu_disc *d = ctx;
    d->rho = rho;
    out[0] = out[1] = out[2] = 0.0;
    /* phi in [0, pi] (mirror symmetry), graded towards pi where the circle passes the origin. */
    tu_graded(tu_disc_phi, d, 0.0, TU_PI, TU_PI, 22, out);
    for (int c = 0; c < 3; c++) out[c] *= 2.0 * rho;
}

/* (1/A) * integral of R_d over the disc of area A centred at distance r from the origin. */
static inline void tu_disc_average(const sss_profile *p, double r, double area, double out[3])
{
    tu_disc d = {p, r, 0.0};
    double ra = sqrt(area / TU_PI);
    out[0] = out[1] = out[2] = 0.0;
    /* rho graded towards r, where the circles pass through the profile's peak at the origin. */
    tu_graded(tu_disc_rho, &d, 0.0, ra, r < ra ? r : ra, 22, out);
    for (int c = 0; c < 3; c++) out[c] /= area;
}

/* ---- 1D: integral of R_d(x) 2 pi x over [0, b], graded towards 0 ------------------------------ */

typedef struct tu_radial {
    const sss_profile *p;
} tu_radial;

static void tu_ring(double x, void *ctx, double out[3])
{
    sss_profile_eval_rgb(((tu_radial *)ctx)->p, x, out);
    for (int c = 0; c < 3; c++) out[c] *= 2.0 * TU_PI * x;
}

static inline void tu_disc_at_origin(const sss_profile *p, double ra, double out[3])
{
    tu_radial c = {p};
    out[0] = out[1] = out[2] = 0.0;
    tu_graded(tu_ring, &c, 0.0, ra, 0.0, 40, out);
}

/* ---- Shared set-up -------------------------------------------------------------------------- */

/* A medium's profile at scale 1 (mm), eta 1.33; table is required for PBD. Exits on failure. */
static inline sss_profile tu_profile(const char *medium, sss_profile_model model, const sss_pbd_table *table)
{
    sss_material m;
    sss_profile p;
    sss_error err;
    if (sss_material_from_medium(medium, 1.0, 1.33, &m, &err) != SSS_OK ||
        sss_profile_init(&p, model, &m, table, &err) != SSS_OK) {
        fprintf(stderr, "set-up failed: %s\n", err.message);
        exit(2);
    }
    return p;
}

/* Deterministic uniform numbers in [0, 1). */
static inline double tu_rand(unsigned long long *s)
{
    *s ^= *s >> 12;
    *s ^= *s << 25;
    *s ^= *s >> 27;
    return (double)((*s * 2685821657736338717ULL) >> 11) * (1.0 / 9007199254740992.0);
}

#endif
