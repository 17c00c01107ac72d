/* reference/ref_profile.c — the radial profile S_r of an object, split at R0 and tabulated for fast
 * lookups (see ref_internal.h for the grid), with the analytic near part and the support radius. */
#include <float.h>
#include <stdlib.h>

#include "reference/ref_internal.h"

sss_result ref_profile_source_init(ref_profile_source *src, const sss_reference_object *obj, sss_error *err)
{
    memset(src, 0, sizeof *src);
    src->kind = obj->profile;
    if (obj->profile == SSS_SCENE_PROFILE_ARTIST) {
        const sss_artist_params *a = &obj->artist;
        if (!(a->s > 0.0) || !isfinite(a->s) || !(a->w >= 0.0 && a->w <= 1.0))
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                                 "artist profile: s must be > 0 and w in [0, 1] (s %g, w %g)", a->s, a->w);
        for (int c = 0; c < 3; c++) {
            if (!(a->near[c] > 0.0 && a->near[c] <= 1.0) || !(a->far[c] > 0.0 && a->far[c] <= 1.0))
                return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                                     "artist profile: near and far must be in (0, 1]");
            if (!(obj->albedo[c] >= 0.0) || !isfinite(obj->albedo[c]))
                return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                                     "artist profile: albedo must be finite and >= 0");
        }
        src->artist = *a;
        memcpy(src->albedo, obj->albedo, sizeof src->albedo);
        return SSS_OK;
    }
    sss_profile_model model = obj->profile == SSS_SCENE_PROFILE_DIPOLE ? SSS_PROFILE_DIPOLE : SSS_PROFILE_PBD;
    return sss_profile_init(&src->profile, model, &obj->optical, obj->table, err);
}

double ref_profile_source_eval(const ref_profile_source *src, int channel, double r)
{
    double v;
    if (src->kind == SSS_SCENE_PROFILE_ARTIST) {
        /* Radially symmetric counterpart of Jimenez et al. 2019, Eq. 6: w G2(sigma_n) + (1 - w) G2(sigma_f). */
        const sss_artist_params *a = &src->artist;
        double sn = a->near[channel] * a->s, sf = a->far[channel] * a->s;
        v = src->albedo[channel] *
            (a->w * sss_gaussian_2d(sn * sn, r) + (1.0 - a->w) * sss_gaussian_2d(sf * sf, r));
    } else {
        v = sss_profile_eval(&src->profile, channel, r);
    }
    return v > 0.0 && isfinite(v) ? v : 0.0;
}

double ref_profile_source_total(const ref_profile_source *src, int channel)
{
    if (src->kind == SSS_SCENE_PROFILE_ARTIST) return src->albedo[channel];
    return sss_profile_total(&src->profile, channel);
}

double ref_profile_source_support(const ref_profile_source *src)
{
    double r = 0.0;
    for (int c = 0; c < 3; c++) {
        double rc;
        if (src->kind == SSS_SCENE_PROFILE_ARTIST) {
            double sf = fmax(src->artist.far[c], src->artist.near[c]) * src->artist.s;
            rc = 12.0 * sf; /* e^(-72): nothing left */
        } else if (src->profile.model == SSS_PROFILE_PBD) {
            const sss_material *m = &src->profile.material;
            double st = m->sigma_a[c] + m->sigma_s[c];
            /* PBRT's table ends at radius[63] optical units; S_r is zero beyond. */
            rc = st > 0.0 ? src->profile.table->radius[SSS_PBD_RADII - 1] / st : 0.0;
        } else {
            const sss_dipole *d = &src->profile.dipole[c];
            /* e^(-60) of the exponential, or a power-law tail (sigma_a = 0) far beyond z_v. */
            rc = 1e6 * d->z_v;
            if (d->sigma_tr > 0.0) rc = fmin(rc, 60.0 / d->sigma_tr + d->z_v);
        }
        if (rc > r && isfinite(rc)) r = rc;
    }
    return r;
}

/* 4-point Gauss-Legendre on [a, b] of S_c(r) 2 pi r (minus the constant s0 when given). */
static void gl4(const ref_profile_source *src, double a, double b, const double *s0, double out[3])
{
    static const double x[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
    static const double w[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};
    double mid = 0.5 * (a + b), half = 0.5 * (b - a);
    out[0] = out[1] = out[2] = 0.0;
    for (int k = 0; k < 4; k++) {
        double r = mid + half * x[k];
        for (int c = 0; c < 3; c++) {
            double s = ref_profile_source_eval(src, c, r) - (s0 ? s0[c] : 0.0);
            out[c] += w[k] * half * s * 2.0 * REF_PI * r;
        }
    }
}

#define SUBSTEPS_PER_OCTAVE 32

sss_result ref_profile_build(ref_profile *p, const ref_profile_source *src, double r0, double max_r,
                             sss_error *err)
{
    memset(p, 0, sizeof *p);
    if (!(r0 > 0.0) || !isfinite(r0) || !(max_r > 0.0) || !isfinite(max_r))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "reference: bad profile radii (R0 %g, max %g)",
                             r0, max_r);
    /* Keep the float grid sane: at most 2^100 between R0 and the cut. */
    if (max_r > r0 * 1e30) max_r = r0 * 1e30;
    p->r0 = (float)r0;
    p->inv_r0 = 1.0f / p->r0;
    r0 = p->r0;
    for (int c = 0; c < 3; c++) {
        p->s0[c] = ref_profile_source_eval(src, c, r0);
        p->total[c] = ref_profile_source_total(src, c);
    }

    /* Near part: int_0^R0 (S_r - S_r(R0)) 2 pi r dr in bins of 1/8 octave down to R0 2^-32 (S_r is
     * bounded at 0, so what lies below is far below double precision of the sum). */
    p->near_edge[0] = 0.0;
    for (int j = 1; j <= REF_NEAR_BINS; j++) p->near_edge[j] = r0 * exp2(-(double)(REF_NEAR_BINS - j) / 8.0);
    p->near_cdf[0] = 0.0;
    for (int j = 0; j < REF_NEAR_BINS; j++) {
        double v[3], a = p->near_edge[j], b = p->near_edge[j + 1], w = 0.0;
        gl4(src, a, b, p->s0, v);
        for (int c = 0; c < 3; c++) {
            p->near_mass[j][c] = v[c];
            p->near[c] += v[c];
            w += fabs(v[c]);
        }
        p->near_cdf[j + 1] = p->near_cdf[j] + w;
    }
    double below_r0[3]; /* int_0^R0 S_r 2 pi r dr, for the support criterion */
    for (int c = 0; c < 3; c++) below_r0[c] = p->near[c] + REF_PI * r0 * r0 * p->s0[c];

    /* Far part: cumulative integral on a log grid from R0 to the support, to find where the tail
     * beyond holds less than 1e-6 of the whole (per channel). */
    double support = ref_profile_source_support(src);
    double r_hi = fmax(support, 2.0 * r0);
    int octaves = (int)ceil(log2(r_hi / r0));
    if (octaves < 1) octaves = 1;
    if (octaves > 100) octaves = 100;
    size_t steps = (size_t)octaves * SUBSTEPS_PER_OCTAVE;
    double *cum = malloc(sizeof(double) * 3 * (steps + 1));
    if (!cum) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "reference: out of memory (profile)");
    cum[0] = cum[1] = cum[2] = 0.0;
    for (size_t j = 0; j < steps; j++) {
        double a = r0 * exp2((double)j / SUBSTEPS_PER_OCTAVE), b = r0 * exp2((double)(j + 1) / SUBSTEPS_PER_OCTAVE);
        double v[3];
        gl4(src, a, b, NULL, v);
        for (int c = 0; c < 3; c++) cum[3 * (j + 1) + c] = cum[3 * j + c] + v[c];
    }
    size_t cut = steps;
    for (size_t j = 0; j <= steps; j++) {
        int ok = 1;
        for (int c = 0; c < 3; c++) {
            double whole = below_r0[c] + cum[3 * steps + c];
            double tail = cum[3 * steps + c] - cum[3 * j + c];
            if (tail > 1e-6 * whole) ok = 0;
        }
        if (ok) {
            cut = j;
            break;
        }
    }
    double r_cut = r0 * exp2((double)cut / SUBSTEPS_PER_OCTAVE);
    if (r_cut > max_r) r_cut = max_r;
    if (r_cut < r0 * 1.01) r_cut = r0 * 1.01;
    p->r_cut = (float)r_cut;

    /* The table: entries up to the octave position of r_cut, plus one zero entry. */
    float x = (float)(r_cut / r0);
    uint32_t bits;
    memcpy(&bits, &x, sizeof bits);
    uint32_t last = (bits >> 15) - (127u << 8) + 1; /* first entry beyond r_cut */
    p->n = last + 1;
    p->table = calloc((size_t)p->n * 4, sizeof(float));
    if (!p->table) {
        free(cum);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "reference: out of memory (profile)");
    }
    double *rr = malloc(sizeof(double) * p->n);
    double *sv = malloc(sizeof(double) * 3 * p->n);
    if (!rr || !sv) {
        free(rr);
        free(sv);
        free(cum);
        ref_profile_free(p);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "reference: out of memory (profile)");
    }
    for (uint32_t i = 0; i < p->n; i++) {
        rr[i] = r0 * ldexp(1.0 + (i & 255u) / 256.0, (int)(i >> 8));
        for (int c = 0; c < 3; c++)
            sv[3 * i + c] = (i < last && rr[i] <= r_cut * 1.0000001) || i == 0
                                ? ref_profile_source_eval(src, c, rr[i]) : 0.0;
    }
    /* Criterion length l(r) = min over channels of sqrt(S / (|S''| + 2 |S'| / r)): the monopole error
     * of a node of size s is about (s / l)^2 / 40 (second moment of its points against the Hessian
     * of S(|x - x_o|), whose eigenvalues are S'' and S'/r twice). A channel counts only where it still
     * matters: where a ring of width r, 2 pi r^2 S(r), holds at least 1e-4 of its plane integral
     * (so a fast-decaying blue does not dictate the nodes far out where only red remains).
     * Finite differences on the (non-uniform) grid. */
    for (uint32_t i = 0; i < p->n; i++) {
        double len = (double)FLT_MAX;
        if (i + 1 < p->n) {
            uint32_t im = i > 0 ? i - 1 : 0, ip = i + 1;
            double hm = rr[i] - rr[im], hp = rr[ip] - rr[i];
            for (int c = 0; c < 3; c++) {
                double s = sv[3 * i + c];
                double whole = below_r0[c] + cum[3 * steps + c];
                if (!(s > 0.0) || !(2.0 * REF_PI * rr[i] * rr[i] * s >= 1e-4 * whole)) continue;
                double d1, d2;
                if (i == 0) {
                    d1 = (sv[3 * ip + c] - s) / hp;
                    d2 = 0.0;
                } else {
                    double sm = sv[3 * im + c], sp = sv[3 * ip + c];
                    d1 = (sp - sm) / (hp + hm);
                    d2 = 2.0 * (hm * sp - (hm + hp) * s + hp * sm) / (hm * hp * (hm + hp));
                }
                double curv = fabs(d2) + 2.0 * fabs(d1) / rr[i];
                if (curv > 0.0) {
                    double l = sqrt(s / curv);
                    if (l < len) len = l;
                }
            }
        }
        /* A floor against kinks of the clamped table: never ask for nodes below 1/50 of the radius. */
        if (len < 0.02 * rr[i]) len = 0.02 * rr[i];
        for (int c = 0; c < 3; c++) p->table[4 * i + c] = (float)sv[3 * i + c];
        p->table[4 * i + 3] = (float)fmin(len, (double)FLT_MAX);
    }
    free(rr);
    free(sv);
    free(cum);
    return SSS_OK;
}

void ref_profile_free(ref_profile *p)
{
    if (!p) return;
    free(p->table);
    memset(p, 0, sizeof *p);
}
