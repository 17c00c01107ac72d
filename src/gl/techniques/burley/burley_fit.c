/* gl/techniques/burley/burley_fit.c — the CPU side of `burley`: Burley's normalized diffusion profile
 * (Christensen & Burley 2015), its radial CDF and closed-form inverse, the transmittance integral, the
 * fits of A and d to a material, their distance to the material's own profile, and the per-material
 * block the passes read (tech_burley.h). No GL. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl/techniques/burley/tech_burley.h"

/* Radii of the distance integral (squares of even steps: dense where both profiles peak). */
#define TV_STEPS 2048
/* Golden-section iterations of BURLEY_FIT_PROFILE over log d (a factor 64 shrinks below 1e-6). */
#define FIT_ITERATIONS 48

double burley_profile(double A, double d, double r)
{
    if (!(d > 0.0) || !(r > 0.0)) return r == 0.0 && d > 0.0 ? INFINITY : 0.0;
    return A * (exp(-r / d) + exp(-r / (3.0 * d))) / (8.0 * M_PI * d * r);
}

double burley_cdf(double x)
{
    if (!(x > 0.0)) return 0.0;
    return 1.0 - 0.25 * exp(-x) - 0.75 * exp(-x / 3.0);
}

/* 1 - F(x) = q reads y^3 + 3 y - 4 q = 0 for y = e^(-x/3), a depressed cubic with one real root
 * (Cardano): y = G^(1/3) - G^(-1/3), G = 2q + sqrt(4q^2 + 1). Written as y = 4q / (1 + g^(1/3) + g^(-1/3)),
 * g = G^2 (G - 1/G = 4q), it has no cancellation near q = 0 (the form of Golubev 2018 and HDRP). */
double burley_inverse_cdf(double u)
{
    if (!(u > 0.0)) return 0.0;
    double q = 1.0 - u;
    if (!(q > 0.0)) return INFINITY;
    double g = 1.0 + 4.0 * q * (2.0 * q + sqrt(1.0 + 4.0 * q * q));
    double c = 1.0 + cbrt(g) + 1.0 / cbrt(g);
    return 3.0 * log(c / (4.0 * q));
}

double burley_transmittance(double A, double d, double t)
{
    if (!(d > 0.0)) return 0.0;
    return A * (1.0 - burley_cdf(t / d));
}

double burley_scale_factor(burley_fit_kind fit, double A)
{
    switch (fit) {
    case BURLEY_FIT_DIFFUSE: return 1.9 - A + 3.5 * (A - 0.8) * (A - 0.8);
    case BURLEY_FIT_DMFP: return 3.5 + 100.0 * pow(A - 0.33, 4.0);
    default: return 1.85 - A + 7.0 * pow(fabs(A - 0.8), 3.0);
    }
}

/* ---- Distance to a profile ------------------------------------------------------------------- */

/* The normalised radial density 2 pi r R(r) / A of channel c of p at the TV_STEPS + 1 radii
 * r_i = r_end (i / TV_STEPS)^2, into dens; 0 when the channel has no energy. */
static double profile_density(const sss_profile *p, int c, double r_end, double *dens)
{
    double total = sss_profile_total(p, c);
    for (int i = 0; i <= TV_STEPS; i++) {
        double t = (double)i / TV_STEPS, r = r_end * t * t;
        dens[i] = total > 0.0 ? 2.0 * M_PI * r * sss_profile_eval(p, c, r) / total : 0.0;
    }
    return total;
}

/* 1/2 int |p_B - p| dr by trapezoids on the radii of profile_density; p_B(r) = (e^(-r/d) + e^(-r/3d)) / (4d). */
static double tv_from_density(const double *dens, double r_end, double d)
{
    double sum = 0.0, prev = 0.0, r_prev = 0.0;
    for (int i = 0; i <= TV_STEPS; i++) {
        double t = (double)i / TV_STEPS, r = r_end * t * t;
        double pb = (exp(-r / d) + exp(-r / (3.0 * d))) / (4.0 * d);
        double v = fabs(pb - dens[i]);
        if (i > 0) sum += 0.5 * (v + prev) * (r - r_prev);
        prev = v;
        r_prev = r;
    }
    return fmin(0.5 * sum, 1.0);
}

/* The radius both densities have (practically) ended by: the profile's 1 - 1e-6 radius and Burley's
 * with the largest d tried. */
static double tv_range(const sss_profile *p, int c, double d_max)
{
    double r_p = sss_profile_radius_for_fraction(p, c, 1.0 - 1e-6);
    double r_b = burley_inverse_cdf(1.0 - 1e-6) * d_max;
    return fmax(isfinite(r_p) ? r_p : 0.0, r_b);
}

double burley_tv_distance(const sss_profile *p, int c, double d)
{
    double r_end = tv_range(p, c, d);
    double *dens = malloc(sizeof(double) * (TV_STEPS + 1));
    if (!dens || !(r_end > 0.0) || !(d > 0.0)) {
        free(dens);
        return 1.0;
    }
    profile_density(p, c, r_end, dens);
    double tv = tv_from_density(dens, r_end, d);
    free(dens);
    return tv;
}

/* The d of least TV distance to channel c of p within [d0 / 8, 8 d0]: golden-section search over log d. */
static double fit_profile_channel(const sss_profile *p, int c, double d0, double *dens)
{
    double lo = log(d0 / 8.0), hi = log(d0 * 8.0);
    double r_end = tv_range(p, c, d0 * 8.0);
    profile_density(p, c, r_end, dens);
    const double k = 0.5 * (sqrt(5.0) - 1.0);
    double a = hi - k * (hi - lo), b = lo + k * (hi - lo);
    double fa = tv_from_density(dens, r_end, exp(a)), fb = tv_from_density(dens, r_end, exp(b));
    for (int it = 0; it < FIT_ITERATIONS; it++) {
        if (fa < fb) {
            hi = b, b = a, fb = fa;
            a = hi - k * (hi - lo);
            fa = tv_from_density(dens, r_end, exp(a));
        } else {
            lo = a, a = b, fa = fb;
            b = lo + k * (hi - lo);
            fb = tv_from_density(dens, r_end, exp(b));
        }
    }
    return exp(0.5 * (lo + hi));
}

/* ---- Fits ------------------------------------------------------------------------------------ */

sss_result burley_fit_material(const sss_scene_material *m, burley_fit_kind fit, double A[3], double d[3],
                               sss_error *err)
{
    const sss_material *o = &m->optical;
    double *dens = fit == BURLEY_FIT_PROFILE ? malloc(sizeof(double) * (TV_STEPS + 1)) : NULL;
    if (fit == BURLEY_FIT_PROFILE && !dens) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "burley: out of memory");
    for (int c = 0; c < 3; c++) {
        A[c] = sss_profile_total(&m->rd, c);
        double sigma_t = o->sigma_a[c] + o->sigma_s[c];
        double sigma_tr = sqrt(3.0 * o->sigma_a[c] * (o->sigma_a[c] + o->sigma_s[c] * (1.0 - o->g)));
        /* the mean free path (Christensen & Burley 2015: "l") or the diffuse mean free path ("l_d") */
        double l = fit == BURLEY_FIT_DMFP ? 1.0 / sigma_tr : 1.0 / sigma_t;
        d[c] = l / burley_scale_factor(fit == BURLEY_FIT_PROFILE ? BURLEY_FIT_SEARCHLIGHT : fit, A[c]);
        if (fit == BURLEY_FIT_PROFILE && A[c] > 0.0 && isfinite(d[c])) d[c] = fit_profile_channel(&m->rd, c, d[c], dens);
        if (!(A[c] > 0.0) || !isfinite(A[c]) || !(d[c] > 0.0) || !isfinite(d[c])) {
            free(dens);
            return sss_error_set(err, SSS_ERROR_NUMERIC,
                                 "burley: channel %d has no finite profile (total reflectance %g, length d %g%s)", c,
                                 A[c], d[c], fit == BURLEY_FIT_DMFP ? ": the diffuse mean free path needs absorption" : "");
        }
    }
    free(dens);
    return SSS_OK;
}

/* ---- The material block ------------------------------------------------------------------------ */

static void pack_material(const double A[3], const double d[3], double filter_cdf, float *v)
{
    double d_max = fmax(d[0], fmax(d[1], d[2]));
    for (int c = 0; c < 3; c++) {
        v[c] = (float)A[c];
        v[4 + c] = (float)(1.0 / d[c]);
    }
    v[3] = 1.0f;
    v[7] = (float)d_max;
    v[8] = (float)(burley_inverse_cdf(filter_cdf) * d_max);
}

sss_result burley_block_build(const gl_tech_ctx *c, float **out, int *n_vec4, sss_error *err)
{
    const burley_params *p = c->params;
    const gl_scene *gs = c->gs;
    int nm = gs->mat.count;
    *n_vec4 = BURLEY_MAT_VEC4 * (nm ? nm : 1);
    *out = calloc((size_t)*n_vec4 * 4, sizeof(float));
    if (!*out) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "burley: out of memory");
    sss_result res = SSS_OK;
    for (int mi = 0; mi < nm && res == SSS_OK; mi++) {
        if (!gs->mat.items[mi].subsurface) continue;
        for (size_t i = 0; i < c->scene->object_count && i < (size_t)gs->object_count; i++) {
            if (gs->objects[i].material != mi) continue;
            double A[3], d[3];
            res = burley_fit_material(&c->scene->objects[i].material, (burley_fit_kind)(int)p->fit, A, d, err);
            if (res == SSS_OK) {
                pack_material(A, d, p->filter_cdf, *out + 4 * BURLEY_MAT_VEC4 * mi);
            } else {
                char what[64];
                snprintf(what, sizeof what, "objects[%zu].material", i);
                sss_error_prefix(err, what);
            }
            break;
        }
    }
    for (int i = 0; res == SSS_OK && i < *n_vec4 * 4; i++)
        if (!isfinite((*out)[i])) res = sss_error_set(err, SSS_ERROR_NUMERIC, "burley: non-finite material block");
    if (res != SSS_OK) {
        free(*out);
        *out = NULL;
    }
    return res;
}
