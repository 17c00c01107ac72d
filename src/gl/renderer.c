/* gl/renderer.c — sss_gl_renderer (sss/gl.h): a runtime (runtime.h) whose frame holds the renderer's
 * own G-buffer and illumination (own_passes.c); read back, present, timings and statistics. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gl/gl_test.h"
#include "gl/own_passes.h"

struct sss_gl_renderer {
    gl_runtime rt;
    gl_own_programs own; /* G-buffer, illumination, present */
};

/* ---- Creation ------------------------------------------------------------------------------- */

sss_result sss_gl_renderer_create(sss_gl_context *ctx, const sss_scene *scene, const sss_gl_renderer_desc *desc,
                                  sss_gl_renderer **out, sss_error *err)
{
    if (!out) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sss_gl_renderer_create: out is NULL");
    *out = NULL;
    if (!ctx || !scene)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sss_gl_renderer_create: no context or scene");
    sss_gl_renderer *r = calloc(1, sizeof *r);
    if (!r) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (renderer)");
    sss_result res = gl_runtime_init(&r->rt, ctx, scene, desc, 0, err);
    if (res == SSS_OK && !sss_gl_context_make_current(ctx))
        res = sss_error_set(err, SSS_ERROR_UNSUPPORTED, "cannot make the GL context current");
    if (res != SSS_OK) {
        free(r);
        return res;
    }
    res = gl_own_programs_build(&r->own, err);
    if (res == SSS_OK) res = gl_runtime_create_gl(&r->rt, desc ? desc->tables : NULL, err);
    if (res != SSS_OK) {
        sss_gl_renderer_destroy(r);
        return res;
    }
    *out = r;
    return SSS_OK;
}

void sss_gl_renderer_destroy(sss_gl_renderer *r)
{
    if (!r) return;
    sss_gl_context_make_current(r->rt.core.ctx);
    gl_runtime_free(&r->rt);
    gl_own_programs_free(&r->own);
    free(r);
}

/* ---- Changes -------------------------------------------------------------------------------- */

sss_result sss_gl_renderer_set_param(sss_gl_renderer *r, const char *name, double value, sss_error *err)
{
    if (!r) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "renderer is NULL");
    return gl_runtime_set_param(&r->rt, name, value, err);
}

double sss_gl_renderer_get_param(const sss_gl_renderer *r, const char *name)
{
    return r && name ? gl_runtime_get_param(&r->rt, name) : NAN;
}

sss_result sss_gl_renderer_update_lights(sss_gl_renderer *r, sss_error *err)
{
    if (!r) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "update_lights: no renderer");
    return gl_runtime_update_lights(&r->rt, err);
}

sss_result sss_gl_renderer_update_materials(sss_gl_renderer *r, const sss_scene *scene, const sss_gl_tables *tables,
                                            sss_error *err)
{
    if (!r) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "update_materials: no renderer");
    return gl_runtime_update_materials(&r->rt, scene, tables, err);
}

sss_result sss_gl_renderer_resize(sss_gl_renderer *r, int width, int height, sss_error *err)
{
    if (!r) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "renderer is NULL");
    return gl_runtime_resize(&r->rt, width, height, r->rt.core.supersample, err);
}

void sss_gl_renderer_size(const sss_gl_renderer *r, int *width, int *height)
{
    if (width) *width = r ? r->rt.core.out_width : 0;
    if (height) *height = r ? r->rt.core.out_height : 0;
}

sss_result sss_gl_renderer_set_supersample(sss_gl_renderer *r, int supersample, sss_error *err)
{
    if (!r) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "renderer is NULL");
    return gl_runtime_resize(&r->rt, r->rt.core.out_width, r->rt.core.out_height, supersample == 0 ? 1 : supersample,
                             err);
}

int sss_gl_renderer_get_supersample(const sss_gl_renderer *r) { return r ? r->rt.core.supersample : 0; }

/* ---- Frames --------------------------------------------------------------------------------- */

/* The frame: the renderer's G-buffer, the shadow maps, its illumination with the light between surfaces
 * (interreflection.c), the mip chains (each when the
 * technique reads what it makes), then the technique. */
static sss_result render_frame(sss_gl_renderer *r, double time, sss_error *err)
{
    gl_runtime *rt = &r->rt;
    gl_core *core = &rt->core;
    sss_result res = gl_runtime_rebuild_if_dirty(rt, err); /* the camera's depth range needs the bounds */
    if (res != SSS_OK) return res;
    gl_camera cam;
    gl_core_scene_camera(core, &cam);
    res = gl_runtime_frame_begin(rt, &cam, time, err);
    if (res != SSS_OK) return res;
    unsigned reads = rt->tech->reads;
    if (reads & (GL_READ_GBUFFER | GL_READ_DEPTH | GL_READ_ILLUMINATION))
        res = gl_own_gbuffer(core, &r->own, err);
    if (res == SSS_OK && (reads & (GL_READ_ILLUMINATION | GL_READ_LIGHTS))) res = gl_core_shadows(core, err);
    if (res == SSS_OK && (reads & GL_READ_ILLUMINATION)) res = gl_own_illumination(core, &r->own, err);
    if (res == SSS_OK && gl_bounce_enabled(core)) res = gl_bounce_frame(core, err);
    if (res == SSS_OK && (reads & GL_READ_MIPS)) res = gl_core_mipmaps(core, err);
    return gl_runtime_frame_finish(rt, res, err);
}

sss_result sss_gl_renderer_render(sss_gl_renderer *r, double time, sss_error *err)
{
    if (!r) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "renderer is NULL");
    if (!isfinite(time)) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "render time %g is not finite", time);
    sss_gl_context_make_current(r->rt.core.ctx);
    sss_result res = render_frame(r, time, err);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (res == SSS_OK) res = gl_check(r->rt.core.ctx, "the end of the frame", err);
    if (res != SSS_OK) r->rt.frame_rendered = 0;
    return res;
}

/* ---- Results -------------------------------------------------------------------------------- */

sss_result sss_gl_renderer_read(sss_gl_renderer *r, sss_image *out, sss_error *err)
{
    if (!r || !out || !out->pixels)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sss_gl_renderer_read: no renderer or image");
    const gl_core *core = &r->rt.core;
    if (out->width != core->out_width || out->height != core->out_height)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "read-back image is %dx%d, the renderer %dx%d",
                             out->width, out->height, core->out_width, core->out_height);
    if (!r->rt.frame_rendered) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "no frame rendered yet");
    sss_gl_context_make_current(core->ctx);
    sss_image tmp;
    sss_result res = gl_read_texture_rgb(gl_core_output(core), 0, core->out_width, core->out_height, &tmp, err);
    if (res != SSS_OK) return res;
    size_t bad = sss_image_count_nonfinite(&tmp);
    if (bad) {
        sss_image_free(&tmp);
        return sss_error_set(err, SSS_ERROR_NUMERIC, "technique %s produced %zu NaN/Inf values",
                             r->rt.tech->info.name, bad);
    }
    memcpy(out->pixels, tmp.pixels, sizeof(float) * 3 * (size_t)core->out_width * (size_t)core->out_height);
    sss_image_free(&tmp);
    return gl_check(core->ctx, "the read-back", err);
}

sss_result sss_gl_renderer_read_buffer(sss_gl_renderer *r, const char *name, sss_image *out, sss_error *err)
{
    if (out) memset(out, 0, sizeof *out);
    if (!r || !name || !out) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "read_buffer: bad arguments");
    if (!r->rt.frame_rendered) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "no frame rendered yet");
    const gl_core *core = &r->rt.core;
    sss_gl_context_make_current(core->ctx);
    GLuint tex = 0;
    if (strcmp(name, "final") == 0) tex = gl_core_output(core);
    else if (strcmp(name, "supersampled") == 0) tex = core->frame.final;
    else if (strcmp(name, "reflected") == 0) tex = core->frame.refl;
    else if (strcmp(name, "irradiance") == 0) tex = core->frame.irr;
    else if (strcmp(name, "object_id") == 0) return gl_own_read_object_ids(core, out, err);
    else tex = gl_runtime_target(&r->rt, name);
    if (!tex)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "technique %s has no buffer '%s'",
                             r->rt.tech->info.name, name);
    GLint w = 0, h = 0;
    glGetTextureLevelParameteriv(tex, 0, GL_TEXTURE_WIDTH, &w);
    glGetTextureLevelParameteriv(tex, 0, GL_TEXTURE_HEIGHT, &h);
    return gl_read_texture_rgb(tex, 0, w, h, out, err);
}

sss_result sss_gl_renderer_present(sss_gl_renderer *r, sss_error *err)
{
    if (!r) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "renderer is NULL");
    return gl_own_present(&r->rt.core, &r->own, err);
}

void sss_gl_renderer_timings(const sss_gl_renderer *r, sss_gl_timings *out)
{
    gl_runtime_timings(r ? &r->rt : NULL, out);
}

void sss_gl_renderer_stats(sss_gl_renderer *r, sss_gl_stats *out) { gl_runtime_stats(r ? &r->rt : NULL, out); }

void sss_gl_renderer_gpu_memory(const sss_gl_renderer *r, size_t *technique_bytes, size_t *frame_bytes)
{
    if (technique_bytes) *technique_bytes = r && r->rt.tech_gpu_bytes > 0 ? (size_t)r->rt.tech_gpu_bytes : 0;
    if (frame_bytes) *frame_bytes = r && r->rt.core.frame_gpu_bytes > 0 ? (size_t)r->rt.core.frame_gpu_bytes : 0;
}

/* ---- For the tests (gl_test.h) ---------------------------------------------------------------- */

const gl_core *gl_test_renderer_core(const sss_gl_renderer *r) { return &r->rt.core; }

void *gl_test_renderer_state(const sss_gl_renderer *r) { return r->rt.state; }
