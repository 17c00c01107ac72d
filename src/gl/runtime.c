/* gl/runtime.c — a technique at work on a GL core (runtime.h): creation, the technique's context and
 * life, parameter and size changes, a frame's steps. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gl/runtime.h"

/* ---- Creation --------------------------------------------------------------------------------- */

sss_result gl_runtime_init(gl_runtime *rt, sss_gl_context *ctx, const sss_scene *scene,
                           const sss_gl_renderer_desc *desc_in, int external, sss_error *err)
{
    memset(rt, 0, sizeof *rt);
    sss_gl_renderer_desc desc;
    memset(&desc, 0, sizeof desc);
    if (desc_in) desc = *desc_in;
    sss_result res = gl_params_technique(scene, &desc, &rt->tech, err);
    if (res != SSS_OK) return res;
    int width = desc.width > 0 ? desc.width : scene->camera.width;
    int height = desc.height > 0 ? desc.height : scene->camera.height;
    if (width < 1 || height < 1 || width > ctx->max_texture_size || height > ctx->max_texture_size ||
        width > SSS_SCENE_MAX_IMAGE_SIZE || height > SSS_SCENE_MAX_IMAGE_SIZE)
        return sss_error_set(err, SSS_ERROR_LIMIT, "image size %dx%d outside 1..%d", width, height,
                             ctx->max_texture_size < SSS_SCENE_MAX_IMAGE_SIZE ? ctx->max_texture_size
                                                                             : SSS_SCENE_MAX_IMAGE_SIZE);
    int k = desc.supersample == 0 ? 1 : desc.supersample;
    res = gl_ssaa_check(ctx, width, height, k, err);
    if (res != SSS_OK) return res;
    rt->data_file = desc.data_file;
    res = gl_params_from_desc(rt->tech, &desc, rt->params, rt->core.shared, err);
    if (res != SSS_OK) return res;
    gl_core_init(&rt->core, ctx, scene, rt->tech->reads, external, width, height, k, desc.timings);
    return SSS_OK;
}

void gl_runtime_ctx(const gl_runtime *rt, gl_tech_ctx *c)
{
    const gl_core *core = &rt->core;
    memset(c, 0, sizeof *c);
    c->gl = core->ctx;
    c->scene = core->scene;
    c->gs = &core->gs;
    c->frame = core->frame;
    unsigned reads = rt->tech->reads;
    if (!(reads & GL_READ_POSITION)) c->frame.pos = 0;
    if (!(reads & GL_READ_NORMAL)) c->frame.nrm = 0;
    if (!(reads & GL_READ_ALBEDO)) c->frame.albedo = 0;
    if (!(reads & GL_READ_DEPTH) || core->external) c->frame.depth = 0;
    if (!(reads & GL_READ_IRRADIANCE)) c->frame.irr = 0;
    if (!(reads & GL_READ_REFLECTED)) c->frame.refl = 0;
    c->frame.fbo_gbuffer = c->frame.fbo_light = 0; /* the renderer's own passes write them */
    c->view = &core->view;
    c->timer = (gl_timer *)&core->timer;
    c->width = core->width;
    c->height = core->height;
    c->supersample = core->supersample;
    c->params = rt->params;
    c->data_file = rt->data_file;
    c->tables_data = gl_tables_technique_data(rt->tables, rt->tech, core->scene, rt->data_file, rt->params);
    c->frame_rendered = rt->frame_rendered;
    c->vao_empty = core->vao_empty;
    c->prog_mips = core->prog_reduce;
}

sss_result gl_runtime_technique_create(gl_runtime *rt, sss_error *err)
{
    rt->state = calloc(1, rt->tech->state_size ? rt->tech->state_size : 1);
    if (!rt->state) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (technique state)");
    sss_result res = SSS_OK;
    gl_tech_ctx c;
    gl_runtime_ctx(rt, &c);
    if (rt->tech->create) GL_MEM_ACCOUNT(rt->tech_gpu_bytes, res = rt->tech->create(&c, rt->state, err));
    if (res != SSS_OK) sss_error_prefix(err, rt->tech->info.name);
    return res;
}

void gl_runtime_technique_destroy(gl_runtime *rt)
{
    if (rt->state && rt->tech->destroy) GL_MEM_ACCOUNT(rt->tech_gpu_bytes, rt->tech->destroy(rt->state));
    free(rt->state);
    rt->state = NULL;
}

static sss_result technique_resize(gl_runtime *rt, sss_error *err)
{
    if (!rt->state || !rt->tech->resize) return SSS_OK;
    gl_tech_ctx c;
    gl_runtime_ctx(rt, &c);
    sss_result res;
    GL_MEM_ACCOUNT(rt->tech_gpu_bytes, res = rt->tech->resize(&c, rt->state, err));
    return res;
}

sss_result gl_runtime_create_gl(gl_runtime *rt, const sss_gl_tables *tables, sss_error *err)
{
    while (glGetError() != GL_NO_ERROR) {}
    rt->tables = tables;
    sss_result res = gl_core_create_gl(&rt->core, gl_tables_luts(tables), err);
    if (res == SSS_OK) res = gl_runtime_technique_create(rt, err);
    rt->tables = NULL;
    if (res == SSS_OK) res = gl_check(rt->core.ctx, "renderer creation", err);
    return res;
}

void gl_runtime_free(gl_runtime *rt)
{
    gl_runtime_technique_destroy(rt);
    gl_core_free(&rt->core);
}

/* ---- Changes ------------------------------------------------------------------------------------ */

sss_result gl_runtime_set_param(gl_runtime *rt, const char *name, double value, sss_error *err)
{
    int scene_level = 0;
    sss_result res = gl_params_set_value(rt->tech, rt->params, rt->core.shared, name, value, &scene_level, err);
    if (res != SSS_OK) return res;
    if (scene_level) {
        rt->scene_dirty = 1;
        return SSS_OK;
    }
    sss_gl_context_make_current(rt->core.ctx);
    return technique_resize(rt, err);
}

double gl_runtime_get_param(const gl_runtime *rt, const char *name)
{
    return gl_params_get(rt->tech, rt->params, rt->core.shared, name);
}

sss_result gl_runtime_resize(gl_runtime *rt, int width, int height, int k, sss_error *err)
{
    const gl_core *core = &rt->core;
    if (width < 1 || height < 1 || width > core->ctx->max_texture_size || height > core->ctx->max_texture_size)
        return sss_error_set(err, SSS_ERROR_LIMIT, "image size %dx%d outside 1..%d", width, height,
                             core->ctx->max_texture_size);
    sss_result res = gl_ssaa_check(core->ctx, width, height, k, err);
    if (res != SSS_OK) return res;
    if (width == core->out_width && height == core->out_height && k == core->supersample) return SSS_OK;
    sss_gl_context_make_current(core->ctx);
    rt->frame_rendered = 0;
    res = gl_core_resize(&rt->core, width, height, k, err);
    if (res == SSS_OK) res = technique_resize(rt, err);
    return res;
}

sss_result gl_runtime_rebuild_if_dirty(gl_runtime *rt, sss_error *err)
{
    if (!rt->scene_dirty) return SSS_OK;
    gl_runtime_technique_destroy(rt);
    rt->core.luts = gl_tables_luts(rt->tables);
    sss_result res = gl_core_rebuild_scene(&rt->core, rt->core.scene, err);
    rt->core.luts = NULL;
    if (res == SSS_OK) res = gl_runtime_technique_create(rt, err);
    rt->scene_dirty = res != SSS_OK;
    return res;
}

sss_result gl_runtime_update_lights(gl_runtime *rt, sss_error *err)
{
    if (!sss_gl_context_make_current(rt->core.ctx))
        return sss_error_set(err, SSS_ERROR_UNSUPPORTED, "update_lights: cannot make the GL context current");
    return gl_lights_update(&rt->core, err);
}

/* ---- Frames ------------------------------------------------------------------------------------- */

sss_result gl_runtime_frame_begin(gl_runtime *rt, const gl_camera *cam, double time, sss_error *err)
{
    rt->frame_rendered = 0;
    sss_result res = gl_runtime_rebuild_if_dirty(rt, err);
    if (res != SSS_OK) return res;
    double cutoff = rt->tech->grazing_cutoff ? rt->tech->grazing_cutoff(rt->params) : 0.2;
    gl_core_frame_begin(&rt->core, cam, time, cutoff);
    return SSS_OK;
}

sss_result gl_runtime_frame_finish(gl_runtime *rt, sss_result so_far, sss_error *err)
{
    gl_timer_end(&rt->core.timer);
    sss_result res = so_far;
    if (res == SSS_OK) {
        gl_tech_ctx c;
        gl_runtime_ctx(rt, &c);
        GL_MEM_ACCOUNT(rt->tech_gpu_bytes, res = rt->tech->render(&c, rt->state, err));
    }
    if (res == SSS_OK) res = gl_ssaa_resolve(&rt->core, err);
    gl_timer_frame_end(&rt->core.timer);
    if (res == SSS_OK) rt->frame_rendered = 1;
    return res;
}

/* ---- Results ------------------------------------------------------------------------------------ */

GLuint gl_runtime_target(const gl_runtime *rt, const char *name)
{
    if (!rt->state || !rt->tech->target || !rt->tech->targets) return 0;
    for (const char *const *t = rt->tech->targets; *t; t++)
        if (strcmp(*t, name) == 0) return rt->tech->target(rt->state, name);
    return 0;
}

void gl_runtime_timings(const gl_runtime *rt, sss_gl_timings *out)
{
    if (!out) return;
    memset(out, 0, sizeof *out);
    out->method = "off";
    if (!rt || !rt->core.timer.enabled) return;
    const gl_timer *t = &rt->core.timer;
    out->method = t->use_queries ? "GL_TIME_ELAPSED queries" : "glFinish + monotonic clock";
    out->pass_count = t->count;
    for (int i = 0; i < t->count; i++) {
        out->passes[i].name = t->names[i];
        out->passes[i].ms = t->ms[i];
        out->total_ms += t->ms[i];
    }
}

void gl_runtime_stats(const gl_runtime *rt, sss_gl_stats *out)
{
    if (!out) return;
    memset(out, 0, sizeof *out);
    if (!rt) return;
    const gl_core *core = &rt->core;
    const gl_scene *gs = &core->gs;
    out->texture_bytes = gs->texture_bytes + gs->mat.lut_bytes + core->frame.bytes + core->ssaa_bytes;
    out->buffer_bytes = gs->buffer_bytes + gs->mat.record_bytes;
    out->lut_bytes = gs->mat.lut_bytes;
    out->luts_precomputed = gs->mat.luts_precomputed;
    /* per render pixel here and in the technique's stats, then per output pixel (k^2 of them) */
    out->per_pixel_bytes = core->frame.bytes / ((size_t)core->width * (size_t)core->height);
    out->splat_total = gs->splat_total;
    out->material_count = gs->mat.count;
    out->light_count = gs->light_count;
    out->virtual_light_count = gs->vpl_count;
    out->object_count = (int)core->scene->object_count;
    out->splat_fragments = -1;
    if (rt->tech->stats && rt->state) {
        gl_tech_ctx c;
        gl_runtime_ctx(rt, &c);
        rt->tech->stats(&c, rt->state, out);
    }
    size_t k = (size_t)core->supersample;
    out->per_pixel_bytes =
        out->per_pixel_bytes * k * k + core->ssaa_bytes / ((size_t)core->out_width * (size_t)core->out_height);
}
