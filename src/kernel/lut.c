/* kernel/lut.c — the disc-integrated kernel LUT R'_d(r, A) of Maisch & Ropinski 2020 (Eq. 5, sections 7.1-7.2).
 *
 * R'_d(r, A) A = integral of R_d over a disc of radius r_A = sqrt(A / pi) whose centre lies at distance
 * r from the origin. Like the paper we integrate over rings centred at the origin: the ring of radius
 * x contributes R_d(x) b(x) dx, b(x) the length of its arc inside the disc (Maisch & Ropinski 2020, Eq. 11):
 *   b(x) = 2 pi x                                     for x <= r_A - r   (ring wholly inside),
 *   b(x) = 2 x acos((x^2 - r_A^2 + r^2) / (2 r x))    for |r - r_A| < x < r + r_A,
 *   b(x) = 0                                          otherwise.
 * Maisch & Ropinski 2020's Eq. 10 sums (b_i R_d(x_i) + b_(i+1) R_d(x_(i+1))) (x_(i+1) - x_i) over the rings: that is
 * the trapezoid rule without its factor 1/2 (the area of a trapezoid of heights u, v and width h is
 * (u + v) h / 2), so taken literally it doubles R'_d. It is also only O(h^1.5) accurate here because
 * b(x) has square-root endpoints (b ~ sqrt(x - x0) at the disc's near edge, sqrt(x1 - x) at its far
 * edge). We therefore:
 *  - tabulate P(x) = 2 pi x R_d(x) once on a fine uniform grid (bounded even where R_d ~ 1/x, as the
 *    PBD profile is near 0) and its running integral C(x) = int_0^x P (exact for the linear P);
 *  - take the wholly-inside rings in one step: int_0^(r_A - r) P = C(r_A - r) (the prefix sum);
 *  - integrate only the partial band x in [x0, x1] = [|r - r_A|, r + r_A] as int P(x) f(x) dx with the
 *    ring fraction f = b / (2 pi x), substituting x = x0 + h (1 - cos t), h = (x1 - x0) / 2, t in
 *    [0, pi]: dx = h sin t dt cancels both square-root endpoints, leaving a smooth integrand for
 *    Gauss-Legendre panels, graded towards t = 0 (x = x0) where R_d peaks or f turns fast.
 * The arc weights are shared by the three channels. Rows (areas) run in parallel with OpenMP. */
#include "sss/kernel.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "kernel/kernel_internal.h"

#define LUT_DEFAULT_SIZE 512
#define LUT_MAX_SIZE 8192
#define LUT_DEFAULT_CUTOFF 1e-7
#define PANEL_NODES 6  /* Gauss-Legendre nodes per t panel in the build */
#define MAX_PANELS 12  /* panels [pi/2, pi], [pi/4, pi/2], ... down to pi/2^12 */
#define EXACT_NODES 16 /* nodes per panel of the slow reference sss_lut_exact */

/* ---- r_max and texel coordinates ------------------------------------------------------------ */

double sss_lut_r_max(const sss_material *m, double source_cutoff)
{
    if (!m) return 0.0;
    if (!(source_cutoff > 0.0)) source_cutoff = LUT_DEFAULT_CUTOFF;
    double r_max = 0.0;
    for (int c = 0; c < 3; c++) {
        /* Maisch & Ropinski 2020, section 7.1: Q(r) = alpha' sigma_t' e^(-sigma_t' r) <= cutoff, and alpha' sigma_t'
         * = sigma_s'; so r = ln(sigma_s' / cutoff) / sigma_t'. */
        double ssp = m->sigma_s[c] * (1.0 - m->g), stp = m->sigma_a[c] + ssp;
        if (!(stp > 0.0) || !(ssp > source_cutoff) || !isfinite(stp)) continue;
        double r = log(ssp / source_cutoff) / stp;
        if (r > r_max) r_max = r;
    }
    return isfinite(r_max) ? r_max : 0.0;
}

static double axis_fraction(sss_lut_axes axes, int i, int n)
{
    double u = (double)i / (double)(n - 1);
    return axes == SSS_LUT_AXES_SQRT ? u * u : u;
}

double sss_lut_texel_r(const sss_lut *lut, int i)
{
    if (!lut || lut->size < 2) return 0.0;
    return lut->r_max * axis_fraction(lut->axes, i, lut->size);
}

double sss_lut_texel_area(const sss_lut *lut, int j)
{
    if (!lut || lut->size < 2) return 0.0;
    return lut->a_max * axis_fraction(lut->axes, j, lut->size);
}

/* Continuous texel coordinate of a value in [0, max], clamped to [0, n - 1]. */
static double axis_coord(sss_lut_axes axes, double v, double max, int n)
{
    double u = max > 0.0 && v > 0.0 ? v / max : 0.0;
    if (!(u < 1.0)) u = 1.0;
    if (axes == SSS_LUT_AXES_SQRT) u = sqrt(u);
    return u * (n - 1);
}

void sss_lut_lookup(const sss_lut *lut, double r, double area, double out[3])
{
    out[0] = out[1] = out[2] = 0.0;
    if (!lut || !lut->texels || lut->size < 2) return;
    int n = lut->size;
    double u = axis_coord(lut->axes, r, lut->r_max, n), v = axis_coord(lut->axes, area, lut->a_max, n);
    int i = (int)u, j = (int)v;
    if (i > n - 2) i = n - 2;
    if (j > n - 2) j = n - 2;
    double fu = u - i, fv = v - j;
    const float *t00 = lut->texels + 3 * ((size_t)j * n + i), *t01 = t00 + 3 * (size_t)n;
    for (int c = 0; c < 3; c++) {
        double a = t00[c] + fu * (t00[c + 3] - t00[c]);
        double b = t01[c] + fu * (t01[c + 3] - t01[c]);
        out[c] = a + fv * (b - a);
    }
}

/* ---- Graded Gauss-Legendre panels in t (x = x0 + h (1 - cos t)) ------------------------------ */

typedef struct panel_rule {
    int per_panel;
    /* Panel k (k < MAX_PANELS) is [pi 2^-(k+1), pi 2^-k]; "tail" K is [0, pi 2^-K]. Per node:
     * om = 1 - cos t, op = 1 + cos t, wsin = Gauss weight * panel half-width * sin t. */
    double om[MAX_PANELS][EXACT_NODES], op[MAX_PANELS][EXACT_NODES], ws[MAX_PANELS][EXACT_NODES];
    double tom[MAX_PANELS + 1][EXACT_NODES], top[MAX_PANELS + 1][EXACT_NODES],
        tws[MAX_PANELS + 1][EXACT_NODES];
} panel_rule;

static void fill_panel(int n, const double *gx, const double *gw, double a, double b, double *om,
                       double *op, double *ws)
{
    for (int g = 0; g < n; g++) {
        double t = 0.5 * (a + b) + 0.5 * (b - a) * gx[g], s = sin(0.5 * t), c = cos(0.5 * t);
        om[g] = 2.0 * s * s; /* 1 - cos t, exact near t = 0 */
        op[g] = 2.0 * c * c; /* 1 + cos t, exact near t = pi */
        ws[g] = gw[g] * 0.5 * (b - a) * sin(t);
    }
}

static void panel_rule_init(panel_rule *pr, int per_panel)
{
    double gx[EXACT_NODES], gw[EXACT_NODES];
    kq_gauss_legendre(per_panel, gx, gw);
    pr->per_panel = per_panel;
    for (int k = 0; k < MAX_PANELS; k++)
        fill_panel(per_panel, gx, gw, KQ_PI * ldexp(1.0, -(k + 1)), KQ_PI * ldexp(1.0, -k), pr->om[k],
                   pr->op[k], pr->ws[k]);
    for (int k = 0; k <= MAX_PANELS; k++)
        fill_panel(per_panel, gx, gw, 0.0, KQ_PI * ldexp(1.0, -k), pr->tom[k], pr->top[k], pr->tws[k]);
}

/* Length scales that decide how finely the band is graded next to x0. */
typedef struct band_scales {
    double feat;  /* the profile's peak at the origin varies on this (kq_profile_length_scale) */
    double decay; /* far from the origin it decays on this (kq_profile_decay_length) */
    double floor; /* nothing shorter matters */
} band_scales;

/* Panels needed to resolve a feature of size s (in x) next to x0 in a band of half-width h: the
 * tail panel [0, pi 2^-K] must not reach beyond t_s / 2, where h (1 - cos t_s) = s. K = 0 (one
 * panel over [0, pi]) when the whole band is shorter than the feature. */
static int panels_for(double s, double h)
{
    if (s >= 2.0 * h) return 0;
    double ts = 2.0 * asin(sqrt(0.5 * s / h)), width = 0.5 * KQ_PI;
    int K = 1;
    while (K < MAX_PANELS && width > 0.5 * ts) {
        K++;
        width *= 0.5;
    }
    return K;
}

/* Rings of the partial band for (r, r_A): fills x and weights w with int P(x) f(x) dx ~ sum w P(x),
 * f = ring fraction inside the disc. Returns the node count (<= (MAX_PANELS + 1) * per_panel). */
static int band_nodes(const panel_rule *pr, double r, double ra, const band_scales *sc, double *x,
                      double *w)
{
    double x0 = fabs(r - ra), x1 = r + ra, h = fmin(r, ra);
    if (!(h > 0.0)) return 0;
    /* When the origin lies inside the disc (f(x0) = 1) the factors below swap: select arithmetically
     * (adding 0 is exact) so that the ring loop has no branches. */
    double in2 = ra > r ? 2.0 * x0 : 0.0, out2 = 2.0 * x0 - in2;
    /* The feature next to x0: near the origin, the turn of f (size ~x0, when the disc's edge passes
     * near the origin) or the profile's peak (size ~feat); further out the profile only decays
     * (size ~decay, but its power-law factors vary on ~x0 / 2). */
    double s = x0 < sc->feat ? fmax(x0, sc->floor) : fmax(sc->feat, fmin(0.5 * x0, sc->decay));
    int K = panels_for(s, h), n = 0, per = pr->per_panel;
    for (int k = 0; k <= K; k++) {
        const double *om = k < K ? pr->om[k] : pr->tom[K], *op = k < K ? pr->op[k] : pr->top[K];
        const double *ws = k < K ? pr->ws[k] : pr->tws[K];
        for (int g = 0; g < per; g++) {
            double xm = h * om[g], xp = h * op[g], xx = x0 + xm;
            /* Half-angle phi of the arc: sin^2(phi/2) = (r_A^2 - (x - r)^2) / (4 r x) and
             * cos^2(phi/2) = ((x + r)^2 - r_A^2) / (4 r x), factored so that no difference of
             * nearly equal numbers is formed; f = phi / pi (Maisch & Ropinski 2020, Eq. 11: b = 2 x phi). */
            double ns = xp * (xm + in2), nc = (xx + x1) * (xm + out2);
            x[n + g] = xx;
            w[n + g] = h * ws[g] * kq_acos_ratio(nc, ns) * (1.0 / KQ_PI);
        }
        n += per;
    }
    return n;
}

/* ---- Tabulated P(x) = 2 pi x R_d(x) and C(x) = int_0^x P ----------------------------------- */

/* Nodes x_k = x_end (k / (n - 1))^2: spacing grows from x_end / (n - 1)^2 at the origin, where the
 * PBD profile turns on a scale of 0.0025 mean free paths (its first tabulated radius, docs/physics.md §2.2),
 * to 2 x_end / (n - 1) at the far end, where every profile is smooth. */
typedef struct lut_table {
    int n;
    double x_end, u_scale; /* u = sqrt(x / x_end) (n - 1) is the continuous node index */
    double *x;             /* n nodes */
    double *inv_dx;        /* n: 1 / (x_(k+1) - x_k) */
    double *p;             /* 3 n, interleaved by channel */
    double *c;             /* 3 n */
} lut_table;

static void table_free(lut_table *t)
{
    free(t->x);
    free(t->inv_dx);
    free(t->p);
    free(t->c);
    memset(t, 0, sizeof *t);
}

static sss_result table_build(const sss_profile *prof, double x_end, int n, lut_table *t, sss_error *err)
{
    memset(t, 0, sizeof *t);
    t->n = n;
    t->x_end = x_end;
    t->u_scale = (n - 1) / sqrt(x_end);
    t->x = malloc(sizeof(double) * (size_t)n);
    t->inv_dx = malloc(sizeof(double) * (size_t)n);
    t->p = malloc(sizeof(double) * 3 * (size_t)n);
    t->c = malloc(sizeof(double) * 3 * (size_t)n);
    if (!t->x || !t->inv_dx || !t->p || !t->c) {
        table_free(t);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "LUT: no memory for a %d-point profile table", n);
    }
    for (int k = 0; k < n; k++) {
        double u = (double)k / (n - 1);
        t->x[k] = x_end * u * u;
    }
    for (int k = 0; k + 1 < n; k++) t->inv_dx[k] = 1.0 / (t->x[k + 1] - t->x[k]);
    t->inv_dx[n - 1] = t->inv_dx[n - 2];
#pragma omp parallel for schedule(static)
    for (int k = 0; k < n; k++) {
        double v[3];
        sss_profile_eval_rgb(prof, t->x[k], v);
        for (int c = 0; c < 3; c++) t->p[3 * k + c] = 2.0 * KQ_PI * t->x[k] * v[c];
    }
    for (int c = 0; c < 3; c++) t->c[c] = 0.0;
    for (int k = 1; k < n; k++) {
        double h = t->x[k] - t->x[k - 1];
        for (int c = 0; c < 3; c++)
            t->c[3 * k + c] = t->c[3 * (k - 1) + c] + 0.5 * h * (t->p[3 * (k - 1) + c] + t->p[3 * k + c]);
    }
    return SSS_OK;
}

static inline int table_cell(const lut_table *t, double x)
{
    int k = (int)(sqrt(x) * t->u_scale);
    if (k > t->n - 2) k = t->n - 2;
    /* sqrt may round across a node: step back if x lies before x_k */
    if (k > 0 && x < t->x[k]) k--;
    return k;
}

/* C(x) of the piecewise-linear P: quadratic inside a cell. */
static void table_cumulative(const lut_table *t, double x, double out[3])
{
    int k = table_cell(t, x);
    double d = x - t->x[k], s = d * t->inv_dx[k];
    const double *p = t->p + 3 * k, *c = t->c + 3 * k;
    for (int ch = 0; ch < 3; ch++) out[ch] = c[ch] + d * (p[ch] + 0.5 * s * (p[ch + 3] - p[ch]));
}

/* A R'_d for r_A > 0 from the table. */
static void disc_integral_table(const lut_table *t, const panel_rule *pr, const band_scales *sc,
                                double r, double ra, double out[3])
{
    double xs[(MAX_PANELS + 1) * EXACT_NODES], ws[(MAX_PANELS + 1) * EXACT_NODES];
    double acc0 = 0.0, acc1 = 0.0, acc2 = 0.0;
    int n = band_nodes(pr, r, ra, sc, xs, ws);
    for (int k = 0; k < n; k++) {
        int i = table_cell(t, xs[k]);
        double f = (xs[k] - t->x[i]) * t->inv_dx[i], w = ws[k];
        const double *p = t->p + 3 * i;
        acc0 += w * (p[0] + f * (p[3] - p[0]));
        acc1 += w * (p[1] + f * (p[4] - p[1]));
        acc2 += w * (p[2] + f * (p[5] - p[2]));
    }
    out[0] = acc0;
    out[1] = acc1;
    out[2] = acc2;
    if (ra > r) { /* rings wholly inside the disc: the prefix sum */
        double cin[3];
        table_cumulative(t, ra - r, cin);
        for (int c = 0; c < 3; c++) out[c] += cin[c];
    }
}

/* ---- The slow reference: the same rings with R_d evaluated directly ------------------------ */

static void p_direct(double x, void *ctx, double out[3])
{
    sss_profile_eval_rgb((const sss_profile *)ctx, x, out);
    for (int c = 0; c < 3; c++) out[c] *= 2.0 * KQ_PI * x;
}

void sss_lut_exact(const sss_profile *profile, double r, double area, double out[3])
{
    out[0] = out[1] = out[2] = 0.0;
    if (!profile || !(r >= 0.0) || !(area >= 0.0) || !isfinite(r) || !isfinite(area)) return;
    if (area == 0.0) {
        sss_profile_eval_rgb(profile, r, out);
        return;
    }
    double ra = sqrt(area / KQ_PI), s_feat = kq_profile_length_scale(profile);
    if (ra > r) { /* the wholly-inside disc of radius r_A - r, graded from the peak at 0 */
        kq_integrate3_graded(p_direct, (void *)profile, 0.0, ra - r, 1e-3 * s_feat, 1e-9, 0.0, out);
    }
    if (r > 0.0) {
        panel_rule pr;
        panel_rule_init(&pr, EXACT_NODES);
        double xs[(MAX_PANELS + 1) * EXACT_NODES], ws[(MAX_PANELS + 1) * EXACT_NODES];
        /* The finest panel resolves 1e-4 of the length scale (the build stops at 1e-3). */
        band_scales sc = {s_feat, kq_profile_decay_length(profile), 1e-4 * s_feat};
        int n = band_nodes(&pr, r, ra, &sc, xs, ws);
        for (int k = 0; k < n; k++) {
            double v[3];
            p_direct(xs[k], (void *)profile, v);
            for (int c = 0; c < 3; c++) out[c] += ws[k] * v[c];
        }
    }
    for (int c = 0; c < 3; c++) out[c] /= area;
}

/* ---- The build ----------------------------------------------------------------------------- */

void sss_lut_free(sss_lut *lut)
{
    if (!lut) return;
    free(lut->texels);
    memset(lut, 0, sizeof *lut);
}

/* r_max for profiles without a source function: where the widest Gaussian of the skin fit falls to
 * `cutoff` of its peak. */
static double gauss6_r_max(const sss_profile *p, double cutoff)
{
    double mm = p->gauss6_mm_per_unit > 0.0 ? p->gauss6_mm_per_unit : 1.0;
    return sqrt(2.0 * sss_gauss6_variance_mm2[SSS_GAUSS6_TERMS - 1] * log(1.0 / cutoff)) / mm;
}

sss_result sss_lut_build(const sss_profile *profile, const sss_lut_desc *desc, sss_lut *out,
                         sss_error *err)
{
    if (!out) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "LUT: output is NULL");
    memset(out, 0, sizeof *out);
    if (!profile) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "LUT: profile is NULL");
    sss_lut_desc d;
    if (desc)
        d = *desc;
    else
        memset(&d, 0, sizeof d);
    if (d.size == 0) d.size = LUT_DEFAULT_SIZE;
    if (d.size < 2 || d.size > LUT_MAX_SIZE)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "LUT: size %d is outside [2, %d]", d.size,
                             LUT_MAX_SIZE);
    if (d.axes != SSS_LUT_AXES_LINEAR && d.axes != SSS_LUT_AXES_SQRT)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "LUT: unknown axes %d", (int)d.axes);
    if (d.source_cutoff == 0.0) d.source_cutoff = LUT_DEFAULT_CUTOFF;
    if (!(d.source_cutoff > 0.0) || !(d.source_cutoff < 1e300))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "LUT: source cut-off %g is not positive",
                             d.source_cutoff);
    if (d.r_max < 0.0 || !isfinite(d.r_max))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "LUT: r_max %g is negative or not finite",
                             d.r_max);
    double r_max = d.r_max;
    if (r_max == 0.0)
        r_max = profile->model == SSS_PROFILE_GAUSS6 ? gauss6_r_max(profile, d.source_cutoff)
                                                     : sss_lut_r_max(&profile->material, d.source_cutoff);
    if (!(r_max > 0.0) || !isfinite(r_max))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                             "LUT: the source function never exceeds the cut-off %g (sigma_s' <= %g in every "
                             "channel), so r_max is 0; give r_max explicitly",
                             d.source_cutoff, d.source_cutoff);

    /* Table of P on [0, 2 r_max] (the band reaches r + r_A <= 2 r_max); its coarsest spacing
     * 2 x_end / n is at most 1/32 of the shortest length scale (linear interpolation error ~ 1e-4 of
     * the curvature there). Panels resolve features down to 1e-3 of that scale (the PBD profile's
     * first tabulated radius is 0.0025 mean free paths). */
    double s_feat = kq_profile_length_scale(profile), x_end = 2.0 * r_max;
    band_scales sc = {s_feat, kq_profile_decay_length(profile), 1e-3 * s_feat};
    double want = ceil(64.0 * x_end / s_feat) + 1.0;
    int nt = want < 4096.0 ? 4096 : want > 262144.0 ? 262144 : (int)want;
    lut_table t;
    sss_result res = table_build(profile, x_end, nt, &t, err);
    if (res != SSS_OK) return res;

    int n = d.size;
    float *tex = malloc(sizeof(float) * 3 * (size_t)n * (size_t)n);
    if (!tex) {
        free(t.p);
        free(t.c);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "LUT: no memory for %d x %d texels", n, n);
    }
    panel_rule pr;
    panel_rule_init(&pr, PANEL_NODES);
    out->size = n;
    out->axes = d.axes;
    out->r_max = r_max;
    out->a_max = KQ_PI * r_max * r_max;
    int bad = 0;
#pragma omp parallel for schedule(dynamic, 2) reduction(| : bad)
    for (int j = 0; j < n; j++) {
        double area = out->a_max * axis_fraction(d.axes, j, n), ra = sqrt(area / KQ_PI);
        float *row = tex + 3 * (size_t)j * n;
        for (int i = 0; i < n; i++) {
            double r = r_max * axis_fraction(d.axes, i, n), v[3];
            if (j == 0) {
                sss_profile_eval_rgb(profile, r, v); /* A -> 0: R'_d = R_d(r) */
            } else if (i == 0) {
                table_cumulative(&t, ra, v); /* disc centred at the origin */
                for (int c = 0; c < 3; c++) v[c] /= area;
            } else {
                disc_integral_table(&t, &pr, &sc, r, ra, v);
                for (int c = 0; c < 3; c++) v[c] /= area;
            }
            for (int c = 0; c < 3; c++) {
                /* Round-off can leave -1e-20 where the profile has vanished: clamp, never negative. */
                float f = (float)(v[c] > 0.0 ? v[c] : 0.0);
                if (!isfinite(f)) bad = 1;
                row[3 * i + c] = f;
            }
        }
    }
    table_free(&t);
    if (bad) {
        free(tex);
        memset(out, 0, sizeof *out);
        return sss_error_set(err, SSS_ERROR_NUMERIC, "LUT: non-finite texel (profile values too large for float)");
    }
    out->texels = tex;
    return SSS_OK;
}
