/* gl/core/lut_cascade.c — the kernel LUT of a subsurface material as the GPU scene holds it: a cascade
 * of disc-integrated tables R'_d(r, A) (Maisch & Ropinski 2020, section 7.1), normalised for upload; and a
 * set of cascades computed ahead (sss_gl_tables holds one), found by what a cascade depends on: the
 * material's optics, profile model and PBD table, and the shared LUT parameters. CPU only. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gl/core/gl_core.h"

/* The kernel LUT of a material as a cascade of `levels` tables (one array layer each): level l covers
 * r in [0, r_max / 16^l] and A in [0, pi (r_max / 16^l)^2]. One table spanning the longest channel's
 * r_max resolves areas only down to ~1e-4 A_max (sqrt axes, 512 texels): with r_max set by a weakly
 * absorbing red channel, pixel-sized areas of the short green and blue kernels fell into its first
 * rows and a flat, uniformly lit plane came out up to 4x too bright. The finer levels fix that; the
 * lookup (common.glsl lut_rd) takes the finest level that contains both r and A. */
static sss_result build_luts(const double *shared, const sss_scene_material *m, sss_lut *luts, int levels,
                             sss_error *err)
{
    const sss_profile *prof = &m->rd;
    sss_lut_desc d;
    memset(&d, 0, sizeof d);
    d.size = (int)shared[GL_P_LUT_SIZE];
    d.axes = (int)shared[GL_P_LUT_AXES] ? SSS_LUT_AXES_SQRT : SSS_LUT_AXES_LINEAR;
    d.source_cutoff = shared[GL_P_LUT_CUTOFF];
    double rm = sss_lut_r_max(&m->optical, d.source_cutoff);
    double energy = shared[GL_P_LUT_ENERGY];
    if (energy > 0.0) {
        /* The source-function rule of Maisch & Ropinski 2020 (section 7.1) uses sigma_t' alone and cuts weakly
         * absorbing channels far inside their diffusion tail (Skimmilk red: r_max = 32 mm against an
         * e-folding length of 18 mm; the back-lit dragon lost 25% of its red). r_max is therefore the
         * larger of that rule and the radius holding `energy` of every channel's plane integral. */
        double e = sss_profile_reach(prof, energy);
        if (e > rm) rm = e;
    }
    if (!(rm > 0.0) || !isfinite(rm))
        return sss_error_set(err, SSS_ERROR_NUMERIC, "no finite kernel radius for the material");
    for (int l = 0; l < levels; l++) {
        d.r_max = rm / pow(16.0, l);
        sss_result res = sss_lut_build(prof, &d, &luts[l], err);
        if (res != SSS_OK) {
            for (int k = 0; k < l; k++) sss_lut_free(&luts[k]);
            return res;
        }
    }
    return SSS_OK;
}

/* One level's texels as RGBA32F holding R'_d / (the level's largest value), the scale kept apart. Not
 * RGBA16F: a layer spans the blue peak R_d(0) and the red tail at r_max, more than the 1e8 the
 * half-float range holds (tried: the back-lit dragon lost 20% of its red). */
static sss_result normalise_level(const sss_lut *lut, float *rgba, float *scale, sss_error *err)
{
    size_t n = (size_t)lut->size * lut->size;
    double mx = 0.0;
    for (size_t i = 0; i < 3 * n; i++) {
        double v = lut->texels[i];
        if (!isfinite(v) || v < 0.0)
            return sss_error_set(err, SSS_ERROR_NUMERIC, "kernel LUT holds a negative or non-finite value");
        if (v > mx) mx = v;
    }
    *scale = mx > 0.0 ? (float)mx : 1.0f;
    for (size_t i = 0; i < n; i++) {
        for (int c = 0; c < 3; c++) rgba[4 * i + c] = (float)(lut->texels[3 * i + c] / *scale);
        rgba[4 * i + 3] = 0.0f;
    }
    return SSS_OK;
}

sss_result gl_lut_cascade_build(const double *shared, const sss_scene_material *m, gl_lut_cascade *out,
                                sss_error *err)
{
    memset(out, 0, sizeof *out);
    int levels = (int)shared[GL_P_LUT_LEVELS];
    sss_lut *luts = calloc((size_t)levels, sizeof *luts);
    if (!luts) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (kernel LUT)");
    sss_result res = build_luts(shared, m, luts, levels, err);
    if (res != SSS_OK) {
        free(luts);
        return res;
    }
    size_t texels = (size_t)luts[0].size * luts[0].size;
    out->size = luts[0].size;
    out->levels = levels;
    out->r_max = luts[0].r_max;
    out->a_max = luts[0].a_max;
    out->axes = luts[0].axes;
    out->rgba = malloc(sizeof *out->rgba * 4 * texels * (size_t)levels);
    out->scales = calloc((size_t)levels, sizeof *out->scales);
    if (!out->rgba || !out->scales) res = sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (kernel LUT)");
    for (int l = 0; l < levels && res == SSS_OK; l++)
        res = normalise_level(&luts[l], out->rgba + 4 * texels * (size_t)l, &out->scales[l], err);
    for (int l = 0; l < levels; l++) sss_lut_free(&luts[l]);
    free(luts);
    if (res != SSS_OK) gl_lut_cascade_free(out);
    return res;
}

void gl_lut_cascade_free(gl_lut_cascade *c)
{
    free(c->rgba);
    free(c->scales);
    memset(c, 0, sizeof *c);
}


struct gl_lut_key {
    sss_material optical;
    sss_profile_model model;
    const sss_pbd_table *table;
    double size, axes, cutoff, energy, levels;
};

static void key_of(const double *shared, const sss_scene_material *m, gl_lut_key *k)
{
    memset(k, 0, sizeof *k);
    k->optical = m->optical;
    k->model = sss_scene_material_profile_model(m);
    k->table = m->table;
    k->size = shared[GL_P_LUT_SIZE];
    k->axes = shared[GL_P_LUT_AXES];
    k->cutoff = shared[GL_P_LUT_CUTOFF];
    k->energy = shared[GL_P_LUT_ENERGY];
    k->levels = shared[GL_P_LUT_LEVELS];
}

static int same_key(const gl_lut_key *a, const gl_lut_key *b)
{
    return memcmp(&a->optical, &b->optical, sizeof a->optical) == 0 && a->model == b->model &&
           a->table == b->table && a->size == b->size && a->axes == b->axes && a->cutoff == b->cutoff &&
           a->energy == b->energy && a->levels == b->levels;
}

static int find_key(const gl_lut_set *set, const gl_lut_key *k)
{
    for (int i = 0; i < set->count; i++)
        if (same_key(&set->keys[i], k)) return i;
    return -1;
}

static sss_result add_material(gl_lut_set *set, const double *shared, const sss_scene_material *m, sss_error *err)
{
    gl_lut_key k;
    key_of(shared, m, &k);
    if (find_key(set, &k) >= 0) return SSS_OK;
    sss_result res = gl_lut_cascade_build(shared, m, &set->cascades[set->count], err);
    if (res != SSS_OK) return res;
    set->keys[set->count++] = k;
    return SSS_OK;
}

sss_result gl_lut_set_build(gl_lut_set *set, const sss_scene *scene, const double *shared, sss_error *err)
{
    memset(set, 0, sizeof *set);
    size_t n = scene->object_count ? scene->object_count : 1;
    set->keys = calloc(n, sizeof *set->keys);
    set->cascades = calloc(n, sizeof *set->cascades);
    if (!set->keys || !set->cascades) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (tables)");
    sss_result res = SSS_OK;
    for (size_t i = 0; i < scene->object_count && res == SSS_OK; i++)
        if (scene->objects[i].material.type == SSS_SCENE_MATERIAL_SUBSURFACE) {
            res = add_material(set, shared, &scene->objects[i].material, err);
            if (res != SSS_OK) sss_error_prefix(err, "kernel LUT");
        }
    return res;
}

void gl_lut_set_free(gl_lut_set *set)
{
    for (int i = 0; set->cascades && i < set->count; i++) gl_lut_cascade_free(&set->cascades[i]);
    free(set->keys);
    free(set->cascades);
    memset(set, 0, sizeof *set);
}

const gl_lut_cascade *gl_lut_set_find(const gl_lut_set *set, const double *shared, const sss_scene_material *m)
{
    if (!set) return NULL;
    gl_lut_key k;
    key_of(shared, m, &k);
    int i = find_key(set, &k);
    return i >= 0 ? &set->cascades[i] : NULL;
}
