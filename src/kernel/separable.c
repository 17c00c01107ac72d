/* kernel/separable.c — the separable 1D kernels of Jimenez et al. 2019: the pre-integrated kernel a_p (Eq. 4-5)
 * and the artist-friendly two-Gaussian a_m (Eq. 6), each discretised into importance-sampled taps
 * (section 7, "Importance sampling").
 *
 * Discretisation (both kernels): the taps sit at the quantiles (k + 1/2) / N of the dominant channel's
 * kernel (the widest one: Jimenez et al. 2019 sample every channel at the positions of the dominant one)
 * restricted to [-range, range]; each tap's weight is the integral of each channel's kernel over the
 * tap's interval, bounded by the midpoints to its neighbours and by -inf / +inf at the ends (the tails
 * beyond the outer taps land on them, so no energy is lost), divided by the kernel's integral. Both
 * need the kernel's cumulative integral F(X) = int_-inf^X a(x) dx. For a_p that is the integral of R_d
 * over the half-plane x < X (Eq. 4), which we write as a 1D ring integral:
 *   H(X) = int_X^inf a_p = int_X^inf 2 pi rho R_d(rho) acos(X / rho) / pi d rho   (X >= 0),
 * the fraction acos(X / rho) / pi of each ring lying beyond the line x = X. */
#include "sss/kernel.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "kernel/kernel_internal.h"

#define DEFAULT_TAPS 7
#define MAX_TAPS 1025
#define RANGE_FRACTION 0.999 /* default range: the central 99.9% of the dominant kernel */

void sss_separable_kernel_free(sss_separable_kernel *k)
{
    if (!k) return;
    free(k->offsets);
    free(k->weights);
    memset(k, 0, sizeof *k);
}

/* ---- The pre-integrated kernel a_p (Jimenez et al. 2019, Eq. 4) ---------------------------------------- */

typedef struct ap_ctx {
    const sss_profile *p;
    double x;       /* |x| of a_p(x), or X of H(X) */
    double r_end;   /* R_d is negligible beyond */
    double s_feat;  /* kq_profile_length_scale */
    double abs_tol; /* absolute tolerance of a_p (1/length units) */
    double abs_tol_h; /* absolute tolerance of H and the total (dimensionless) */
} ap_ctx;

static double ap_r_end(const sss_profile *p)
{
    double r = sss_profile_reach(p, 1.0 - 1e-12);
    return r > 0.0 ? r : 1.0;
}

static void ap_init(ap_ctx *a, const sss_profile *p)
{
    a->p = p;
    a->x = 0.0;
    a->r_end = ap_r_end(p);
    a->s_feat = kq_profile_length_scale(p);
    double tot = 0.0;
    for (int c = 0; c < 3; c++) tot = fmax(tot, sss_profile_total(p, c));
    /* Absolute tolerances 1e-11 of the total (of a_p(0) ~ total / length scale for a_p): the PBD
     * profile is a C^1 spline whose far tail wiggles around 0, where relative tolerances never end. */
    if (!(tot > 0.0)) tot = 1.0;
    a->abs_tol_h = 1e-11 * tot;
    a->abs_tol = a->abs_tol_h / a->s_feat;
}

/* y = x sinh t: R_d(x cosh t) x cosh t, the integrand of a_p / 2 in t. */
static void ap_sinh(double t, void *ctx, double out[3])
{
    const ap_ctx *a = ctx;
    double rho = a->x * cosh(t);
    sss_profile_eval_rgb(a->p, rho, out);
    for (int c = 0; c < 3; c++) out[c] *= rho;
}

static void ap_line(double y, void *ctx, double out[3])
{
    sss_profile_eval_rgb(((const ap_ctx *)ctx)->p, y, out);
}

/* a_p(x) = 2 int_0^inf R_d(sqrt(x^2 + y^2)) dy for all channels. */
static void ap_eval3(ap_ctx *a, double x, double out[3])
{
    x = fabs(x);
    out[0] = out[1] = out[2] = 0.0;
    if (!(x < a->r_end)) return;
    if (x < 1e-6 * a->s_feat) {
        /* On the line through the origin: graded from the peak at y = 0. */
        kq_integrate3_graded(ap_line, a, 0.0, a->r_end, 1e-3 * a->s_feat, 1e-6, a->abs_tol, out);
    } else {
        /* y = x sinh t removes the kink of sqrt(x^2 + y^2) at y = 0 and makes the tail a log scale. */
        a->x = x;
        kq_integrate3(ap_sinh, a, 0.0, acosh(a->r_end / x), 1e-6, a->abs_tol, out);
    }
    for (int c = 0; c < 3; c++) out[c] *= 2.0;
}

void sss_kernel_preintegrated_eval_rgb(const sss_profile *profile, double x, double out[3])
{
    out[0] = out[1] = out[2] = 0.0;
    if (!profile || !isfinite(x)) return;
    ap_ctx a;
    ap_init(&a, profile);
    ap_eval3(&a, x, out);
    for (int c = 0; c < 3; c++)
        if (!(out[c] > 0.0) || !isfinite(out[c])) out[c] = 0.0;
}

double sss_kernel_preintegrated_eval(const sss_profile *profile, int channel, double x)
{
    if (channel < 0 || channel > 2) return 0.0;
    double v[3];
    sss_kernel_preintegrated_eval_rgb(profile, x, v);
    return v[channel];
}

/* rho = X cosh t: P(rho) gd(t) / pi X sinh t, the integrand of H(X) in t (gd = acos(1 / cosh t)). */
static void h_sinh(double t, void *ctx, double out[3])
{
    const ap_ctx *a = ctx;
    double ch = cosh(t), rho = a->x * ch, frac = acos(1.0 / ch) / KQ_PI;
    sss_profile_eval_rgb(a->p, rho, out);
    for (int c = 0; c < 3; c++) out[c] *= 2.0 * KQ_PI * rho * frac * a->x * sinh(t);
}

static void ring(double x, void *ctx, double out[3])
{
    sss_profile_eval_rgb(((const ap_ctx *)ctx)->p, x, out);
    for (int c = 0; c < 3; c++) out[c] *= 2.0 * KQ_PI * x;
}

/* The plane integral of R_d, numerically (so that F runs exactly from 0 to it). */
static void plane_total(ap_ctx *a, double out[3])
{
    kq_integrate3_graded(ring, a, 0.0, a->r_end, 1e-3 * a->s_feat, 1e-9, a->abs_tol_h, out);
}

/* H(X) = int_X^inf a_p for X >= 0 (half the total at X = 0). */
static void h_tail(ap_ctx *a, double X, const double total[3], double out[3])
{
    out[0] = out[1] = out[2] = 0.0;
    if (!(X > 0.0)) {
        for (int c = 0; c < 3; c++) out[c] = 0.5 * total[c];
        return;
    }
    if (!(X < a->r_end)) return;
    a->x = X;
    kq_integrate3(h_sinh, a, 0.0, acosh(a->r_end / X), 1e-7, a->abs_tol_h, out);
}

/* F(X) = int_-inf^X a_p. */
static void f_cdf(ap_ctx *a, double X, const double total[3], double out[3])
{
    double h[3];
    h_tail(a, fabs(X), total, h);
    for (int c = 0; c < 3; c++) out[c] = X >= 0.0 ? total[c] - h[c] : h[c];
}

/* The X >= 0 with H_c(X) = target (H decreases from total/2 to 0 with H' = -a_p): Newton steps
 * (H is convex for X > 0), kept inside a shrinking bracket [lo, hi] by bisection when they leave it. */
static double h_invert(ap_ctx *a, int c, double target, const double total[3], double hi)
{
    double lo = 0.0, x = 0.5 * hi, h[3], ap[3];
    for (int it = 0; it < 100 && hi - lo > 1e-10 * hi; it++) {
        h_tail(a, x, total, h);
        double f = h[c] - target;
        if (f > 0.0)
            lo = x;
        else
            hi = x;
        if (fabs(f) <= 1e-10 * total[c]) break;
        ap_eval3(a, x, ap);
        double nx = ap[c] > 0.0 ? x + f / ap[c] : -1.0;
        x = nx > lo && nx < hi ? nx : 0.5 * (lo + hi);
    }
    return x;
}

/* ---- Tap placement and weights, shared by both kernels --------------------------------------- */

/* One kernel's cumulative integral for all channels (normalised: F(-inf) = 0, F(inf) = 1). */
typedef void (*cdf_fn)(void *ctx, double x, double out[3]);

/* Fills out (already allocated) with taps at the given ascending, symmetric offsets. */
static void fill_weights(cdf_fn cdf, void *ctx, int taps, const float *offsets, float *weights)
{
    double prev[3] = {0.0, 0.0, 0.0};
    for (int k = 0; k < taps; k++) {
        double next[3] = {1.0, 1.0, 1.0};
        if (k + 1 < taps) cdf(ctx, 0.5 * ((double)offsets[k] + offsets[k + 1]), next);
        for (int c = 0; c < 3; c++) {
            double w = next[c] - prev[c];
            weights[3 * k + c] = (float)(w > 0.0 ? w : 0.0);
        }
        memcpy(prev, next, sizeof prev);
    }
    /* Mirror: the weights of a symmetric kernel at symmetric taps are symmetric; average the two
     * halves so rounding cannot break it. */
    for (int k = 0; k < taps / 2; k++)
        for (int c = 0; c < 3; c++) {
            float m = 0.5f * (weights[3 * k + c] + weights[3 * (taps - 1 - k) + c]);
            weights[3 * k + c] = weights[3 * (taps - 1 - k) + c] = m;
        }
}

static sss_result alloc_kernel(sss_separable_kernel *out, int taps, sss_error *err)
{
    memset(out, 0, sizeof *out);
    out->offsets = malloc(sizeof(float) * (size_t)taps);
    out->weights = malloc(sizeof(float) * 3 * (size_t)taps);
    if (!out->offsets || !out->weights) {
        sss_separable_kernel_free(out);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "separable kernel: no memory for %d taps", taps);
    }
    out->taps = taps;
    return SSS_OK;
}

static sss_result check_taps(const char *what, int *taps, sss_error *err)
{
    if (*taps == 0) *taps = DEFAULT_TAPS;
    if (*taps < 1 || *taps > MAX_TAPS || *taps % 2 == 0)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                             "%s kernel: %d taps (an odd number in [1, %d] is needed: one tap at 0, the "
                             "rest in symmetric pairs)",
                             what, *taps, MAX_TAPS);
    return SSS_OK;
}

/* ---- Pre-integrated kernel: discretised a_p / ||R_d||_1 (Jimenez et al. 2019, Eq. 5) -------------------- */

typedef struct ap_cdf_ctx {
    ap_ctx a;
    double total[3];
} ap_cdf_ctx;

static void ap_cdf(void *ctx, double x, double out[3])
{
    ap_cdf_ctx *q = ctx;
    f_cdf(&q->a, x, q->total, out);
    for (int c = 0; c < 3; c++) out[c] = q->total[c] > 0.0 ? out[c] / q->total[c] : (x >= 0.0 ? 1.0 : 0.0);
}

sss_result sss_kernel_preintegrated(const sss_profile *profile, int taps, double range,
                                    sss_separable_kernel *out, sss_error *err)
{
    if (!out) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "pre-integrated kernel: output is NULL");
    memset(out, 0, sizeof *out);
    if (!profile) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "pre-integrated kernel: profile is NULL");
    sss_result res = check_taps("pre-integrated", &taps, err);
    if (res != SSS_OK) return res;
    if (!isfinite(range))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "pre-integrated kernel: range %g is not finite", range);
    ap_cdf_ctx q;
    ap_init(&q.a, profile);
    plane_total(&q.a, q.total);
    /* The dominant channel: the widest a_p, by the radius holding 99.9% of it. */
    int dom = -1;
    double width = 0.0;
    for (int c = 0; c < 3; c++) {
        if (!(q.total[c] > 0.0)) continue;
        double w = h_invert(&q.a, c, 0.5 * (1.0 - RANGE_FRACTION) * q.total[c], q.total, q.a.r_end);
        if (w > width) {
            width = w;
            dom = c;
        }
    }
    if (dom < 0 || !(width > 0.0))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                             "pre-integrated kernel: the profile is zero in every channel");
    if (!(range > 0.0)) range = width;
    res = alloc_kernel(out, taps, err);
    if (res != SSS_OK) return res;
    /* Quantiles of the dominant a_p restricted to [-range, range]: F(x) = F(-R) + q (F(R) - F(-R)),
     * i.e. H(x) = H(R) + (1 - q) (T - 2 H(R)) for the taps right of 0. */
    double hr[3], T = q.total[dom];
    h_tail(&q.a, range, q.total, hr);
    int mid = taps / 2;
    out->offsets[mid] = 0.0f;
    for (int k = mid + 1; k < taps; k++) {
        double qk = (k + 0.5) / taps, target = hr[dom] + (1.0 - qk) * (T - 2.0 * hr[dom]);
        double x = h_invert(&q.a, dom, target, q.total, range);
        out->offsets[k] = (float)x;
        out->offsets[taps - 1 - k] = (float)-x;
    }
    fill_weights(ap_cdf, &q, taps, out->offsets, out->weights);
    for (int c = 0; c < 3; c++) out->total[c] = sss_profile_total(profile, c);
    out->range = range;
    for (int k = 0; k < 3 * taps; k++)
        if (!isfinite(out->weights[k])) {
            sss_separable_kernel_free(out);
            return sss_error_set(err, SSS_ERROR_NUMERIC, "pre-integrated kernel: non-finite weight");
        }
    return SSS_OK;
}

/* ---- Artist-friendly kernel (Jimenez et al. 2019, Eq. 6) ------------------------------------------------ */

/* Normalised 1D Gaussian's CDF; a zero width is a step at 0. */
static double gauss_cdf(double sigma, double x)
{
    if (!(sigma > 0.0)) return x > 0.0 ? 1.0 : x < 0.0 ? 0.0 : 0.5;
    return 0.5 * erfc(-x / (sigma * sqrt(2.0)));
}

static void artist_cdf(void *ctx, double x, double out[3])
{
    const sss_artist_params *p = ctx;
    for (int c = 0; c < 3; c++)
        out[c] = p->w * gauss_cdf(p->near[c] * p->s, x) + (1.0 - p->w) * gauss_cdf(p->far[c] * p->s, x);
}

/* x >= 0 with artist_cdf_c(x) = u (u >= 1/2), by bisection; 0 for a channel of zero width. */
static double artist_invert(const sss_artist_params *p, int c, double u)
{
    double lo = 0.0, hi = p->s, v[3];
    for (int i = 0; i < 100; i++) { /* the widths are at most 1e6 s */
        artist_cdf((void *)p, hi, v);
        if (v[c] >= u) break;
        hi *= 2.0;
    }
    for (int it = 0; it < 200 && hi - lo > 1e-14 * p->s; it++) {
        double m = 0.5 * (lo + hi);
        artist_cdf((void *)p, m, v);
        if (v[c] < u)
            lo = m;
        else
            hi = m;
    }
    return 0.5 * (lo + hi);
}

sss_result sss_kernel_artist(const sss_artist_params *params, int taps, sss_separable_kernel *out,
                             sss_error *err)
{
    if (!out) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "artist kernel: output is NULL");
    memset(out, 0, sizeof *out);
    if (!params) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "artist kernel: parameters are NULL");
    sss_result res = check_taps("artist", &taps, err);
    if (res != SSS_OK) return res;
    const sss_artist_params *p = params;
    if (!(p->s > 0.0) || !isfinite(p->s))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "artist kernel: scale s = %g is not positive", p->s);
    if (!(p->w >= 0.0 && p->w <= 1.0))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "artist kernel: weight w = %g is outside [0, 1]", p->w);
    for (int c = 0; c < 3; c++)
        if (!(p->near[c] >= 0.0 && p->near[c] <= 1e6) || !(p->far[c] >= 0.0 && p->far[c] <= 1e6))
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                                 "artist kernel: channel %d: near %g / far %g must be non-negative", c,
                                 p->near[c], p->far[c]);
    /* The dominant channel: the widest (the largest 99.9% radius). */
    int dom = 0;
    double width = 0.0, u = 0.5 * (1.0 + RANGE_FRACTION);
    for (int c = 0; c < 3; c++) {
        double w = artist_invert(p, c, u);
        if (w > width) {
            width = w;
            dom = c;
        }
    }
    if (!(width > 1e-12 * p->s))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "artist kernel: every Gaussian has zero width");
    res = alloc_kernel(out, taps, err);
    if (res != SSS_OK) return res;
    double v[3];
    artist_cdf((void *)p, width, v);
    double fr = v[dom], fl = 1.0 - fr; /* F(R), F(-R) */
    int mid = taps / 2;
    out->offsets[mid] = 0.0f;
    for (int k = mid + 1; k < taps; k++) {
        double x = artist_invert(p, dom, fl + (k + 0.5) / taps * (fr - fl));
        out->offsets[k] = (float)x;
        out->offsets[taps - 1 - k] = (float)-x;
    }
    fill_weights(artist_cdf, (void *)p, taps, out->offsets, out->weights);
    out->total[0] = out->total[1] = out->total[2] = 1.0;
    out->range = width;
    return SSS_OK;
}
