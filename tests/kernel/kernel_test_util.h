/* tests/kernel/kernel_test_util.h — independent numerical tools for the kernel tests: fixed 8-point
 * Gauss-Legendre panels graded towards a point, a brute-force disc integral in polar coordinates
 * around the disc's centre (not the rings around the origin the library uses), a brute-force integral
 * over a rectangle along rays from the origin (not the library's rings or tensor rules), adaptive 1D
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

/* ---- Brute-force cell integral: polar coordinates around the origin -------------------------- */

typedef struct tu_cell {
    const sss_profile *p;
    double x0, x1, y0, y1;
    int pieces; /* equal radial panels per chord */
} tu_cell;

static void tu_ring_r(double r, void *ctx, double out[3])
{
    sss_profile_eval_rgb(((tu_cell *)ctx)->p, r, out);
    for (int c = 0; c < 3; c++) out[c] *= r;
}

/* The ray from the origin at angle phi: integral of R_d(r) r dr over its chord through the cell (slab
 * intersection) in `pieces` equal 8-point panels, the first graded towards the chord's near end (40
 * times from r = 0 when the cell holds the origin, where R_d ~ 1/r). */
static void tu_cell_phi(double phi, void *ctx, double out[3])
{
    tu_cell *c = ctx;
    double d[2] = {cos(phi), sin(phi)}, lo[2] = {c->x0, c->y0}, hi[2] = {c->x1, c->y1};
    double t_in = 0.0, t_out = INFINITY;
    out[0] = out[1] = out[2] = 0.0;
    for (int k = 0; k < 2; k++) {
        if (fabs(d[k]) < 1e-300) {
            if (lo[k] > 0.0 || hi[k] < 0.0) return;
            continue;
        }
        double a = lo[k] / d[k], b = hi[k] / d[k];
        if (a > b) {
            double t = a;
            a = b;
            b = t;
        }
        if (a > t_in) t_in = a;
        if (b < t_out) t_out = b;
    }
    if (!(t_out > t_in)) return;
    double len = (t_out - t_in) / c->pieces;
    tu_graded(tu_ring_r, c, t_in, t_in + len, t_in, t_in > 0.0 ? 6 : 40, out);
    for (int i = 1; i < c->pieces; i++) tu_panel(tu_ring_r, c, t_in + i * len, t_in + (i + 1) * len, out);
}

/* Integral of R_d(sqrt(x^2 + y^2)) over [x0, x1] x [y0, y1]: phi over [-pi, pi] split at the corners'
 * angles (the chord is smooth in phi between them), `pieces` equal 8-point panels per angular piece
 * and per chord (32: ~1e-9 relative for the PBD profile, whose C^1 knots no panel follows). */
static inline void tu_cell_integral(const sss_profile *p, double x0, double x1, double y0, double y1,
                                    int pieces, double out[3])
{
    tu_cell c = {p, x0, x1, y0, y1, pieces};
    double cut[6] = {-TU_PI, TU_PI, atan2(y0, x0), atan2(y0, x1), atan2(y1, x0), atan2(y1, x1)};
    for (int i = 1; i < 6; i++) /* insertion sort */
        for (int j = i; j > 0 && cut[j] < cut[j - 1]; j--) {
            double t = cut[j];
            cut[j] = cut[j - 1];
            cut[j - 1] = t;
        }
    out[0] = out[1] = out[2] = 0.0;
    for (int i = 0; i + 1 < 6; i++) {
        double w = (cut[i + 1] - cut[i]) / pieces;
        for (int k = 0; k < pieces && w > 0.0; k++) tu_panel(tu_cell_phi, &c, cut[i] + k * w, cut[i] + (k + 1) * w, out);
    }
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
