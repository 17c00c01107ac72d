/* tests/gl/gl_test_util.h — helpers of the GL tests: one headless context per process, rendering a
 * scene file with parameters to an image, comparing with cached CPU-reference images. */
#ifndef SSS_GL_TEST_UTIL_H
#define SSS_GL_TEST_UTIL_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "sss/gl.h"
#include "sss/image.h"
#include "sss/material.h"
#include "sss/scene.h"

static inline sss_gl_context *gt_ctx(void)
{
    static sss_gl_context *ctx;
    if (!ctx) {
        sss_error err = {0};
        if (sss_gl_context_create(NULL, &ctx, &err) != SSS_OK) {
            fprintf(stderr, "no headless GL context: %s\n", err.message);
            exit(1);
        }
    }
    return ctx;
}

static inline int gt_load(const char *name, sss_scene *scene)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/scenes/%s", SSS_SOURCE_DIR, name);
    sss_error err = {0};
    if (sss_scene_load(path, NULL, scene, &err) != SSS_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 0;
    }
    return 1;
}

/* A renderer description: technique (NULL: the scene's), parameters, supersampling factor k (0: off).
 * The cached references of these tests are the single-event integral (tests/data/gl/README.md), what
 * the techniques model: the description adds interreflection=0 (the light between surfaces,
 * docs/interreflection.md) unless the parameters name it. The parameters live in one of 16 static
 * copies, used in turn: a description stays valid for the next 15 calls (tests hold two or three). */
static inline sss_gl_renderer_desc gt_desc(const char *technique, const sss_gl_param_value *params, int nparams, int k)
{
    static sss_gl_param_value copies[16][64];
    static int next;
    sss_gl_param_value *with_off = copies[next];
    next = (next + 1) % 16;
    sss_gl_renderer_desc d;
    memset(&d, 0, sizeof d);
    d.technique = technique;
    d.params = params;
    d.param_count = nparams;
    d.supersample = k;
    int named = 0;
    for (int i = 0; i < nparams; i++) named |= strcmp(params[i].name, "interreflection") == 0;
    if (!named && nparams < 63) {
        for (int i = 0; i < nparams; i++) with_off[i] = params[i];
        with_off[nparams].name = "interreflection";
        with_off[nparams].value = 0.0;
        d.params = with_off;
        d.param_count = nparams + 1;
    }
    return d;
}

/* Renders with technique (NULL: the scene's), "name=value" parameters and supersampling factor k
 * (sss_gl_renderer_desc.supersample; 0: off) at the camera's size; out is created. */
static inline int gt_render_k(const sss_scene *scene, const char *technique, double time,
                              const sss_gl_param_value *params, int nparams, int k, sss_image *out)
{
    sss_error err = {0};
    sss_gl_renderer_desc d = gt_desc(technique, params, nparams, k);
    sss_gl_renderer *r = NULL;
    memset(out, 0, sizeof *out);
    if (sss_gl_renderer_create(gt_ctx(), scene, &d, &r, &err) != SSS_OK ||
        sss_gl_renderer_render(r, time, &err) != SSS_OK ||
        sss_image_create(out, scene->camera.width, scene->camera.height, &err) != SSS_OK ||
        sss_gl_renderer_read(r, out, &err) != SSS_OK) {
        fprintf(stderr, "%s, supersample %d: render failed: %s\n", technique ? technique : "scene's technique", k,
                err.message);
        sss_gl_renderer_destroy(r);
        sss_image_free(out);
        return 0;
    }
    sss_gl_renderer_destroy(r);
    return 1;
}

/* Renders one frame with technique and reads its internal buffers names[0..count) (see
 * sss_gl_renderer_read_buffer) into out[0..count), which are created; 0 (all freed) on failure. */
static inline int gt_render_buffers(const sss_scene *scene, const char *technique, const sss_gl_param_value *params,
                                    int nparams, const char *const *names, sss_image *out, int count)
{
    sss_error err = {0};
    sss_gl_renderer_desc d = gt_desc(technique, params, nparams, 0);
    sss_gl_renderer *r = NULL;
    memset(out, 0, (size_t)count * sizeof *out);
    int ok = sss_gl_renderer_create(gt_ctx(), scene, &d, &r, &err) == SSS_OK &&
             sss_gl_renderer_render(r, 0.0, &err) == SSS_OK;
    for (int i = 0; ok && i < count; i++) ok = sss_gl_renderer_read_buffer(r, names[i], &out[i], &err) == SSS_OK;
    if (!ok) {
        fprintf(stderr, "%s: render or buffer read failed: %s\n", technique, err.message);
        for (int i = 0; i < count; i++) sss_image_free(&out[i]);
    }
    sss_gl_renderer_destroy(r);
    return ok;
}

/* gt_render_k without supersampling. */
static inline int gt_render(const sss_scene *scene, const char *technique, double time, const sss_gl_param_value *params,
                     int nparams, sss_image *out)
{
    return gt_render_k(scene, technique, time, params, nparams, 0, out);
}

static inline int gt_read_ref(const char *name, sss_image *out)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/gl/%s", SSS_TEST_DATA, name);
    sss_error err = {0};
    if (sss_image_read(path, out, &err) != SSS_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 0;
    }
    return 1;
}

static inline double gt_dssim(const sss_image *a, const sss_image *b)
{
    sss_image_metrics m;
    sss_error err = {0};
    if (sss_image_compare(a, b, 0.0, &m, NULL, &err) != SSS_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 1.0;
    }
    return m.dssim;
}

/* Renders technique with parameters and returns its DSSIM against ref; a failed render, or NaN/Inf in
 * the image, fails the test (CHECK) and returns 1. */
static inline double gt_technique_dssim(const sss_scene *scene, const sss_image *ref, const char *tech,
                                        const sss_gl_param_value *params, int nparams)
{
    sss_image img;
    if (!gt_render(scene, tech, 0.0, params, nparams, &img)) {
        CHECK_MSG(0, "%s failed to render", tech);
        return 1.0;
    }
    CHECK_MSG(sss_image_count_nonfinite(&img) == 0, "%s wrote NaN or Inf", tech);
    double d = gt_dssim(&img, ref);
    sss_image_free(&img);
    return d;
}

/* gt_technique_dssim on a committed scene (scenes/) against its cached reference (tests/data/gl/),
 * printed; with bound > 0 it must lie below it. Returns the DSSIM (1 on failure). */
static inline double gt_scene_dssim(const char *file, const char *ref_name, const char *technique, double bound)
{
    sss_scene scene;
    sss_image ref;
    if (!gt_load(file, &scene)) {
        CHECK(0);
        return 1.0;
    }
    double d = 1.0;
    if (gt_read_ref(ref_name, &ref)) {
        d = gt_technique_dssim(&scene, &ref, technique, NULL, 0);
        sss_image_free(&ref);
    } else {
        CHECK(0);
    }
    printf("%s, %s: DSSIM %.4f\n", file, technique, d);
    if (bound > 0.0) CHECK_MSG(d < bound, "%s %s: DSSIM %g >= %g", file, technique, d, bound);
    sss_scene_free(&scene);
    return d;
}

/* F_t at normal incidence into a material (PBRT-v3's dielectric Fresnel); *co gets the exit factor
 * c_o = F_t / (pi c) of docs/physics.md §1 for a view along the normal. */
static inline double gt_normal_transmission(const sss_scene_material *m, double *co)
{
    double eta = m->optical.eta, ft = 1.0 - sss_fresnel_dielectric(1.0, 1.0, eta);
    if (co) *co = ft / (M_PI * sss_bssrdf_normalization(eta));
    return ft;
}

static inline void gt_mean(const sss_image *a, double mean[3])
{
    mean[0] = mean[1] = mean[2] = 0.0;
    size_t n = (size_t)a->width * a->height;
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < 3; c++) mean[c] += a->pixels[3 * i + c];
    for (int c = 0; c < 3; c++) mean[c] /= (double)n;
}

#endif
