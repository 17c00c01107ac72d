/* gl/tech_ssss_kernel.c — the CPU side of the separable subsurface scattering techniques: for every
 * subsurface material, the 1D taps of each separable term and the transmittance profile T(s), packed
 * as described in tech_ssss.h.
 *
 *  - ssss: one term. Pre-integrated a_p / ||R_d||_1 (Jimenez et al. 2019, Eq. 4-5) or the artist model a_m
 *    (Eq. 6), both importance-sampled at the dominant channel's quantiles (section 7) by the kernel
 *    module, or the guided rank-1 a_s (Appendix A, Eq. 8-9) discretised here the same way. The taps'
 *    weights sum to 1 per channel; the multiplier is the total reflectance ||R_d||_1.
 *  - ssss-gauss6: six terms, the normalised 1D Gaussians of d'Eon et al.'s skin fit (variances in mm^2
 *    converted with the material's scale, mm per scene unit); the vertical pass carries the term's
 *    weight, and the multiplier is the material's total diffuse reflectance (the weights sum to 1).
 *  - ssss-svd: rank N, the SVD factors of the discretised profile as uniform taps on its grid; term k
 *    is sign_k a_k(x) a_k(y). The sum is normalised to the profile's total (Jimenez et al. 2019, section 3: the
 *    truncated SVD loses energy, "even if energy conservation is enforced by normalizing").
 * T(s) = integral of R_d(sqrt(r^2 + s^2)) over the plane = 2 pi int_s^inf R_d(rho) rho d rho: the light
 * leaving the front of a slab of thickness s lit uniformly at its back (Jimenez et al. 2010, whose
 * reference code sums the six Gaussians' e^(-s^2 / 2 v)); for Gaussian models the same closed form. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl/techniques/ssss/tech_ssss.h"
#include "sss/profile.h"

#define ENERGY_RANGE 0.999   /* kernel ranges and T(s) tables span this fraction of the energy */
/* Cells of the guided optimisation (the kernel module integrates R_d over each cell, so any grid
 * works; 128 cells resolve the near part of the kernel for the 7-31 taps drawn from it). */
#define GUIDED_GRID 128
#define T_STEPS 4096         /* quadrature steps of T(s) */

static const char *const preset_names[4] = {NULL, "single-layer", "multi-layer", "production"};

void ssss_kernel_data_free(ssss_kernel_data *d)
{
    if (!d) return;
    free(d->block);
    free(d->trans);
    memset(d, 0, sizeof *d);
}


/* RMS width of a term's taps per channel (the sigma of the depth correction for kernels that are not
 * Gaussians): sqrt(sum |w| x^2 / sum |w|). */
static void rms_width(const float *offsets, const float *weights, int taps, double out[3])
{
    for (int c = 0; c < 3; c++) {
        double s0 = 0.0, s2 = 0.0;
        for (int k = 0; k < taps; k++) {
            double w = fabs(weights[3 * k + c]);
            s0 += w;
            s2 += w * offsets[k] * offsets[k];
        }
        out[c] = s0 > 0.0 ? sqrt(s2 / s0) : 0.0;
    }
}

/* ---- T(s) ----------------------------------------------------------------------------------- */

/* T(s) / T(0) of a radial profile on SSSS_TRANS_SIZE points of [0, s_max]: trapezoids of
 * 2 pi rho R_d(rho) on rho = s_end (i / T_STEPS)^2 (dense where the PBD profile peaks). */
static sss_result trans_from_profile(const sss_profile *p, float *row, double *s_max, sss_error *err)
{
    double s_end = sss_profile_reach(p, 1.0 - 1e-6);
    *s_max = sss_profile_reach(p, ENERGY_RANGE);
    if (!(s_end > 0.0) || !(*s_max > 0.0))
        return sss_error_set(err, SSS_ERROR_NUMERIC, "transmittance: the profile has no finite radius");
    double *cum = malloc(sizeof(double) * 3 * (T_STEPS + 1)); /* integral from rho_i to s_end */
    if (!cum) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "transmittance: out of memory");
    double prev[3], rho_prev = s_end;
    sss_profile_eval_rgb(p, s_end, prev);
    for (int c = 0; c < 3; c++) {
        prev[c] *= 2.0 * M_PI * s_end;
        cum[3 * T_STEPS + c] = 0.0;
    }
    for (int i = T_STEPS - 1; i >= 0; i--) {
        double t = (double)i / T_STEPS, rho = s_end * t * t, v[3];
        sss_profile_eval_rgb(p, rho, v);
        for (int c = 0; c < 3; c++) {
            v[c] *= 2.0 * M_PI * rho;
            cum[3 * i + c] = cum[3 * (i + 1) + c] + 0.5 * (v[c] + prev[c]) * (rho_prev - rho);
            prev[c] = v[c];
        }
        rho_prev = rho;
    }
    for (int j = 0; j < SSSS_TRANS_SIZE; j++) {
        double s = *s_max * j / (SSSS_TRANS_SIZE - 1);
        double t = sqrt(fmin(s / s_end, 1.0)) * T_STEPS; /* rho index of s */
        int i = (int)t;
        if (i >= T_STEPS) i = T_STEPS - 1;
        double f = t - i;
        for (int c = 0; c < 3; c++) {
            double v = (1.0 - f) * cum[3 * i + c] + f * cum[3 * (i + 1) + c];
            row[4 * j + c] = cum[c] > 0.0 ? (float)(v / cum[c]) : 0.0f;
        }
        row[4 * j + 3] = 1.0f;
    }
    free(cum);
    return SSS_OK;
}

/* T(s) / T(0) of a 2D Gaussian mixture: sum_i w_i e^(-s^2 / 2 v_i) / sum_i w_i (per channel). */
static void trans_from_gaussians(int n, const double *var, const double (*w)[3], float *row, double *s_max)
{
    double vmax = 0.0;
    for (int i = 0; i < n; i++) vmax = fmax(vmax, var[i]);
    *s_max = 3.72 * sqrt(vmax); /* e^(-s^2 / 2 v) = 1e-3 */
    for (int j = 0; j < SSSS_TRANS_SIZE; j++) {
        double s = *s_max * j / (SSSS_TRANS_SIZE - 1);
        for (int c = 0; c < 3; c++) {
            double num = 0.0, den = 0.0;
            for (int i = 0; i < n; i++) {
                num += w[i][c] * (var[i] > 0.0 ? exp(-s * s / (2.0 * var[i])) : (s == 0.0));
                den += w[i][c];
            }
            row[4 * j + c] = den > 0.0 ? (float)(num / den) : 0.0f;
        }
        row[4 * j + 3] = 1.0f;
    }
}

/* ---- Guided kernel taps ----------------------------------------------------------------------- */

/* Integral of the piecewise-constant density d (grid cells of width h from -extent) over [x0, x1]. */
static double cell_integral(const double *d, int grid, double extent, double x0, double x1)
{
    double h = 2.0 * extent / grid, sum = 0.0;
    x0 = fmax(x0, -extent);
    x1 = fmin(x1, extent);
    for (int i = 0; i < grid && x1 > x0; i++) {
        double a = -extent + i * h, b = a + h;
        double lo = fmax(a, x0), hi = fmin(b, x1);
        if (hi > lo) sum += d[i] * (hi - lo);
    }
    return sum;
}

/* Importance-sampled taps of a density tabulated on cells (3 * grid values): offsets at the dominant
 * channel's quantiles (k + 1/2) / taps, weights = each channel's integral over the tap's interval
 * (midpoints; the outer taps reach the grid's ends) over the channel's integral (integral[c]). */
static void taps_from_density(const double *dens, int grid, double extent, int taps, float *offsets, float *weights,
                              double integral[3])
{
    int dom = 0;
    double widest = -1.0, h = 2.0 * extent / grid;
    for (int c = 0; c < 3; c++) {
        double s0 = 0.0, s2 = 0.0;
        for (int i = 0; i < grid; i++) {
            double x = -extent + (i + 0.5) * h, a = fabs(dens[c * grid + i]);
            s0 += a;
            s2 += a * x * x;
        }
        integral[c] = cell_integral(dens + c * grid, grid, extent, -extent, extent);
        double w = s0 > 0.0 ? s2 / s0 : 0.0;
        if (w > widest) {
            widest = w;
            dom = c;
        }
    }
    const double *d = dens + dom * grid;
    double total = 0.0;
    for (int i = 0; i < grid; i++) total += fabs(d[i]) * h;
    int mid = taps / 2;
    offsets[mid] = 0.0f;
    for (int k = mid + 1; k < taps; k++) {
        /* the right half: |d| accumulated from 0 reaches (q - 1/2) of the total at the quantile q */
        double target = ((k + 0.5) / taps - 0.5) * total, acc = 0.0, x = extent;
        for (int i = grid / 2; i < grid; i++) {
            double a = -extent + i * h, b = a + h, lo = fmax(a, 0.0), m = fabs(d[i]) * (b - lo);
            if (acc + m >= target && m > 0.0) {
                x = lo + (target - acc) / fabs(d[i]);
                break;
            }
            acc += m;
        }
        offsets[k] = (float)x;
        offsets[taps - 1 - k] = (float)-x;
    }
    for (int k = 0; k < taps; k++) {
        double lo = k == 0 ? -extent : 0.5 * ((double)offsets[k - 1] + offsets[k]);
        double hi = k == taps - 1 ? extent : 0.5 * ((double)offsets[k] + offsets[k + 1]);
        for (int c = 0; c < 3; c++) {
            double w = cell_integral(dens + c * grid, grid, extent, lo, hi);
            weights[3 * k + c] = integral[c] != 0.0 ? (float)(w / integral[c]) : 0.0f;
        }
    }
}

/* ---- One material ------------------------------------------------------------------------------ */

typedef struct term_out {
    int taps;
    float *offsets, *wh, *wv; /* taps, 3 taps, 3 taps */
    double range, sigma[3];
} term_out;

typedef struct material_out {
    int enabled;
    double mult[3], t0[3], trans_scale[3], s_max;
    float trans[SSSS_TRANS_SIZE * 4];
    term_out *terms;
} material_out;

static sss_result term_alloc(term_out *t, int taps, sss_error *err)
{
    t->taps = taps;
    t->offsets = calloc((size_t)taps, sizeof(float));
    t->wh = calloc(3 * (size_t)taps, sizeof(float));
    t->wv = calloc(3 * (size_t)taps, sizeof(float));
    if (!t->offsets || !t->wh || !t->wv) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "ssss: out of memory");
    return SSS_OK;
}

/* A separable kernel as one term with equal horizontal and vertical weights. */
static sss_result term_from_kernel(term_out *t, const sss_separable_kernel *k, sss_error *err)
{
    sss_result res = term_alloc(t, k->taps, err);
    if (res != SSS_OK) return res;
    memcpy(t->offsets, k->offsets, sizeof(float) * (size_t)k->taps);
    memcpy(t->wh, k->weights, sizeof(float) * 3 * (size_t)k->taps);
    memcpy(t->wv, k->weights, sizeof(float) * 3 * (size_t)k->taps);
    t->range = k->range;
    rms_width(t->offsets, t->wh, t->taps, t->sigma);
    return SSS_OK;
}

/* Table 2 presets are in mm: divide s by the material's scale (mm per scene unit). */
static sss_result artist_params(const sss_scene_material *sm, int preset, sss_artist_params *ap, sss_error *err)
{
    if (preset == 0 && sm->profile == SSS_SCENE_PROFILE_ARTIST) {
        *ap = sm->artist;
        return SSS_OK;
    }
    sss_result res = sss_artist_preset(preset_names[preset ? preset : 3], ap, err);
    if (res == SSS_OK) ap->s /= sm->scale > 0.0 ? sm->scale : 1.0;
    return res;
}

static sss_result build_separable(const sss_scene_material *sm, const sss_profile *prof, const ssss_kernel_opts *o,
                                  material_out *m, sss_error *err)
{
    int kind = o->kernel;
    if (kind == SSSS_KERNEL_AUTO)
        kind = sm->profile == SSS_SCENE_PROFILE_ARTIST ? SSSS_KERNEL_ARTIST : SSSS_KERNEL_PREINTEGRATED;
    sss_separable_kernel k;
    memset(&k, 0, sizeof k);
    sss_result res = SSS_OK;
    if (kind == SSSS_KERNEL_PREINTEGRATED) {
        res = sss_kernel_preintegrated(prof, o->taps, 0.0, &k, err);
        if (res == SSS_OK) res = term_from_kernel(&m->terms[0], &k, err);
        for (int c = 0; c < 3; c++) m->mult[c] = m->t0[c] = k.total[c];
        if (res == SSS_OK) res = trans_from_profile(prof, m->trans, &m->s_max, err);
    } else if (kind == SSSS_KERNEL_ARTIST) {
        sss_artist_params ap;
        res = artist_params(sm, o->preset, &ap, err);
        if (res == SSS_OK) res = sss_kernel_artist(&ap, o->taps, &k, err);
        if (res == SSS_OK) res = term_from_kernel(&m->terms[0], &k, err);
        /* The artist kernel is normalised (Eq. 6): the energy is the material's total reflectance.
         * Its depth correction uses sigma_max = sigma_f (Eq. 7); its T(s) is the two-Gaussian mixture. */
        double var[2], w[2][3];
        for (int c = 0; c < 3; c++) {
            m->mult[c] = m->t0[c] = sm->albedo[c];
            m->terms[0].sigma[c] = fmax(ap.near[c], ap.far[c]) * ap.s;
            w[0][c] = ap.w;
            w[1][c] = 1.0 - ap.w;
        }
        if (res == SSS_OK) {
            /* each channel's own pair of widths */
            double smax = 0.0;
            for (int c = 0; c < 3; c++) smax = fmax(smax, 3.72 * fmax(ap.near[c], ap.far[c]) * ap.s);
            m->s_max = smax;
            for (int j = 0; j < SSSS_TRANS_SIZE; j++) {
                double s = smax * j / (SSSS_TRANS_SIZE - 1);
                for (int c = 0; c < 3; c++) {
                    var[0] = pow(ap.near[c] * ap.s, 2.0);
                    var[1] = pow(ap.far[c] * ap.s, 2.0);
                    double v = 0.0;
                    for (int g = 0; g < 2; g++)
                        v += w[g][c] * (var[g] > 0.0 ? exp(-s * s / (2.0 * var[g])) : (s == 0.0));
                    m->trans[4 * j + c] = (float)v;
                }
                m->trans[4 * j + 3] = 1.0f;
            }
        }
    } else {
        /* guided rank-1 (Appendix A): b is given in mm^-2, the grid is in scene units */
        double extent = sss_profile_reach(prof, ENERGY_RANGE), scale = sm->scale > 0.0 ? sm->scale : 1.0;
        double *a = malloc(sizeof(double) * 3 * GUIDED_GRID);
        if (!a) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "ssss: out of memory");
        res = sss_kernel_guided(prof, GUIDED_GRID, extent, o->guide_k, o->guide_b_mm * scale * scale, a, err);
        if (res == SSS_OK) res = term_alloc(&m->terms[0], o->taps, err);
        if (res == SSS_OK) {
            term_out *t = &m->terms[0];
            double integral[3];
            taps_from_density(a, GUIDED_GRID, extent, o->taps, t->offsets, t->wh, integral);
            memcpy(t->wv, t->wh, sizeof(float) * 3 * (size_t)t->taps);
            t->range = extent;
            rms_width(t->offsets, t->wh, t->taps, t->sigma);
            /* Eq. 8's constraint: ||a_s||_1^2 = ||R_d||_1 */
            for (int c = 0; c < 3; c++) {
                m->mult[c] = integral[c] * integral[c];
                m->t0[c] = sss_profile_total(prof, c);
            }
            res = trans_from_profile(prof, m->trans, &m->s_max, err);
        }
        free(a);
    }
    sss_separable_kernel_free(&k);
    return res;
}

static sss_result build_gauss6(const sss_scene_material *sm, const ssss_kernel_opts *o, material_out *m,
                               sss_error *err)
{
    double scale = sm->scale > 0.0 ? sm->scale : 1.0, var[SSS_GAUSS6_TERMS], w[SSS_GAUSS6_TERMS][3];
    sss_result res = SSS_OK;
    for (int i = 0; i < SSS_GAUSS6_TERMS && res == SSS_OK; i++) {
        var[i] = sss_gauss6_variance_mm2[i] / (scale * scale);
        for (int c = 0; c < 3; c++) w[i][c] = sss_gauss6_weight[c][i];
        /* a normalised 1D Gaussian of this variance, importance-sampled like the artist kernel */
        sss_artist_params g;
        memset(&g, 0, sizeof g);
        g.s = sqrt(var[i]);
        g.w = 1.0;
        for (int c = 0; c < 3; c++) g.near[c] = g.far[c] = 1.0;
        sss_separable_kernel k;
        res = sss_kernel_artist(&g, o->taps, &k, err);
        if (res != SSS_OK) break;
        term_out *t = &m->terms[i];
        res = term_from_kernel(t, &k, err);
        sss_separable_kernel_free(&k);
        if (res != SSS_OK) break;
        for (int j = 0; j < t->taps; j++)
            for (int c = 0; c < 3; c++) t->wv[3 * j + c] *= (float)w[i][c];
        /* Eq. 7 is exact for a Gaussian: its own sigma */
        for (int c = 0; c < 3; c++) t->sigma[c] = g.s;
    }
    if (res != SSS_OK) return res;
    for (int c = 0; c < 3; c++) m->mult[c] = m->t0[c] = sm->albedo[c];
    trans_from_gaussians(SSS_GAUSS6_TERMS, var, (const double (*)[3])w, m->trans, &m->s_max);
    return SSS_OK;
}

static sss_result build_svd(const sss_profile *prof, const ssss_kernel_opts *o, material_out *m, sss_error *err)
{
    double extent = sss_profile_reach(prof, ENERGY_RANGE);
    sss_svd_kernel k;
    sss_result res = sss_kernel_svd(prof, o->grid, extent, o->rank, &k, err);
    if (res != SSS_OK) return res;
    double h = 2.0 * extent / o->grid, approx[3] = {0, 0, 0};
    for (int t = 0; t < o->rank && res == SSS_OK; t++) {
        term_out *tm = &m->terms[t];
        res = term_alloc(tm, o->grid, err);
        if (res != SSS_OK) break;
        for (int i = 0; i < o->grid; i++) {
            tm->offsets[i] = (float)(-extent + (i + 0.5) * h);
            for (int c = 0; c < 3; c++) {
                float v = k.vectors[((size_t)t * 3 + c) * o->grid + i];
                tm->wh[3 * i + c] = v;
                tm->wv[3 * i + c] = k.signs[t * 3 + c] * v;
            }
        }
        tm->range = extent;
        rms_width(tm->offsets, tm->wh, tm->taps, tm->sigma);
        for (int c = 0; c < 3; c++) {
            double s = 0.0;
            for (int i = 0; i < o->grid; i++) s += tm->wh[3 * i + c];
            approx[c] += k.signs[t * 3 + c] * s * s;
        }
    }
    sss_svd_kernel_free(&k);
    if (res != SSS_OK) return res;
    /* normalise the rank-N sum to the profile's total; the weights then carry the energy */
    for (int c = 0; c < 3; c++) {
        double total = sss_profile_total(prof, c), f = approx[c] > 0.0 ? total / approx[c] : 0.0;
        for (int t = 0; t < o->rank; t++)
            for (int i = 0; i < o->grid; i++) m->terms[t].wv[3 * i + c] *= (float)f;
        m->mult[c] = 1.0;
        m->t0[c] = total;
    }
    return trans_from_profile(prof, m->trans, &m->s_max, err);
}

static sss_result build_material(const sss_scene_material *sm, const ssss_kernel_opts *o, material_out *m,
                                 sss_error *err)
{
    sss_result res;
    if (o->variant == SSSS_VARIANT_SEPARABLE) res = build_separable(sm, &sm->rd, o, m, err);
    else if (o->variant == SSSS_VARIANT_GAUSS6) res = build_gauss6(sm, o, m, err);
    else res = build_svd(&sm->rd, o, m, err);
    if (res != SSS_OK) return res;
    /* The T(s) table is relative to T(0), the model's total reflectance (t0); the passes multiply by
     * mult afterwards, so the transmitted irradiance enters with T(0) / mult. */
    for (int c = 0; c < 3; c++) m->trans_scale[c] = m->mult[c] > 0.0 ? m->t0[c] / m->mult[c] : 0.0;
    m->enabled = 1;
    return SSS_OK;
}

/* ---- Packing ----------------------------------------------------------------------------------- */

sss_result ssss_kernel_build(const gl_tech_ctx *ctx, const ssss_kernel_opts *o, ssss_kernel_data *out,
                             sss_error *err)
{
    memset(out, 0, sizeof *out);
    const gl_scene *gs = ctx->gs;
    const sss_scene *scene = ctx->scene;
    int T = o->variant == SSSS_VARIANT_GAUSS6 ? SSS_GAUSS6_TERMS : o->variant == SSSS_VARIANT_SVD ? o->rank : 1;
    if (o->variant != SSSS_VARIANT_SVD && o->taps % 2 == 0)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                             "taps = %d must be odd (one tap at the centre, the rest in symmetric pairs)", o->taps);
    int nm = gs->mat.count;
    material_out *mats = calloc((size_t)(nm ? nm : 1), sizeof *mats);
    term_out *terms = calloc((size_t)(nm ? nm : 1) * (size_t)T, sizeof *terms);
    sss_result res = mats && terms ? SSS_OK : sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "ssss: out of memory");
    int tap_vec4 = 0, rows = 0;
    for (int mi = 0; mi < nm && res == SSS_OK; mi++) {
        mats[mi].terms = terms + (size_t)mi * T;
        if (!gs->mat.items[mi].subsurface) continue;
        for (size_t i = 0; i < scene->object_count && i < (size_t)gs->object_count; i++) {
            if (gs->objects[i].material != mi) continue;
            res = build_material(&scene->objects[i].material, o, &mats[mi], err);
            if (res != SSS_OK) {
                char what[64];
                snprintf(what, sizeof what, "objects[%zu].material", i);
                sss_error_prefix(err, what);
            }
            break;
        }
        if (!mats[mi].enabled) continue;
        for (int t = 0; t < T; t++) tap_vec4 += 2 * mats[mi].terms[t].taps;
        rows++;
    }
    if (res == SSS_OK) {
        out->terms = T;
        out->materials = nm;
        int head = 1 + nm * (SSSS_MAT_VEC4 + 2 * T);
        out->vec4_count = head + tap_vec4;
        out->trans_rows = rows ? rows : 1;
        out->block = calloc((size_t)out->vec4_count * 4, sizeof(float));
        out->trans = calloc((size_t)out->trans_rows * SSSS_TRANS_SIZE * 4, sizeof(float));
        if (!out->block || !out->trans) res = sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "ssss: out of memory");
    }
    if (res == SSS_OK) {
        float *b = out->block;
        b[0] = (float)T;
        b[1] = (float)nm;
        int next = 1 + nm * (SSSS_MAT_VEC4 + 2 * T), row = 0;
        for (int mi = 0; mi < nm; mi++) {
            const material_out *m = &mats[mi];
            float *v = b + 4 * (1 + mi * (SSSS_MAT_VEC4 + 2 * T));
            if (!m->enabled) continue;
            for (int c = 0; c < 3; c++) {
                v[c] = (float)m->mult[c];
                v[4 + c] = (float)m->trans_scale[c];
            }
            v[3] = 1.0f;
            v[7] = (float)row;
            v[8] = (float)m->s_max;
            memcpy(out->trans + (size_t)row * SSSS_TRANS_SIZE * 4, m->trans, sizeof m->trans);
            row++;
            for (int t = 0; t < T; t++) {
                const term_out *tm = &m->terms[t];
                float *h = v + 4 * (SSSS_MAT_VEC4 + 2 * t);
                h[0] = (float)next;
                h[1] = (float)tm->taps;
                h[2] = (float)tm->range;
                for (int c = 0; c < 3; c++) h[4 + c] = (float)tm->sigma[c];
                for (int k = 0; k < tm->taps; k++) {
                    float *tap = b + 4 * (next + 2 * k);
                    for (int c = 0; c < 3; c++) {
                        tap[c] = tm->wh[3 * k + c];
                        tap[4 + c] = tm->wv[3 * k + c];
                    }
                    tap[3] = tm->offsets[k];
                }
                next += 2 * tm->taps;
            }
        }
        for (int i = 0; i < out->vec4_count * 4; i++)
            if (!isfinite(out->block[i])) res = sss_error_set(err, SSS_ERROR_NUMERIC, "ssss: non-finite kernel data");
    }
    for (int i = 0; terms && i < nm * T; i++) {
        free(terms[i].offsets);
        free(terms[i].wh);
        free(terms[i].wv);
    }
    free(terms);
    free(mats);
    if (res != SSS_OK) ssss_kernel_data_free(out);
    return res;
}
