/* gl/renderer.c — the renderer object: parameters, shared programs and passes, the frame loop, read
 * back, timings and statistics. Techniques plug in through gl_technique (gl_internal.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl/gl_internal.h"

/* ---- Parameters ----------------------------------------------------------------------------- */

static int find_param(const sss_gl_param_info *params, int count, const char *name)
{
    for (int i = 0; i < count; i++)
        if (strcmp(params[i].name, name) == 0) return i;
    return -1;
}

static sss_result check_value(const sss_gl_param_info *p, double v, sss_error *err)
{
    if (!isfinite(v) || v < p->min_value || v > p->max_value)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "parameter %s = %g is outside [%g, %g] (%s)", p->name,
                             v, p->min_value, p->max_value, p->doc);
    if (p->type != SSS_GL_PARAM_FLOAT && v != floor(v))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "parameter %s must be %s, got %g", p->name,
                             p->type == SSS_GL_PARAM_BOOL ? "0 or 1" : "an integer", v);
    return SSS_OK;
}

/* Unknown names: the message lists what the technique and the shared table accept. */
static sss_result unknown_param(const sss_gl_renderer *r, const char *name, sss_error *err)
{
    char list[400] = "";
    size_t at = 0;
    for (int i = 0; i < r->tech->info.param_count && at < sizeof list; i++)
        at += (size_t)snprintf(list + at, sizeof list - at, "%s%s", i ? ", " : "", r->tech->info.params[i].name);
    int n = 0;
    const sss_gl_param_info *sp = sss_gl_shared_params(&n);
    for (int i = 0; i < n && at < sizeof list; i++)
        at += (size_t)snprintf(list + at, sizeof list - at, ", %s", sp[i].name);
    return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "technique %s has no parameter '%s' (known: %s)",
                         r->tech->info.name, name, list);
}

static sss_result set_param_value(sss_gl_renderer *r, const char *name, double value, int *scene_level,
                                  sss_error *err);

/* preset: every parameter back to its default, then (paper) the technique's published values. */
static sss_result apply_preset(sss_gl_renderer *r, double preset, sss_error *err)
{
    for (int i = 0; i < r->tech->info.param_count; i++) r->params[i] = r->tech->info.params[i].default_value;
    int n = 0;
    const sss_gl_param_info *sp = sss_gl_shared_params(&n);
    for (int i = 0; i < n; i++) r->shared[i] = sp[i].default_value;
    r->shared[GL_P_PRESET] = preset;
    sss_result res = SSS_OK;
    for (int i = 0; preset == SSS_GL_PRESET_PAPER && i < r->tech->paper_count && res == SSS_OK; i++)
        res = set_param_value(r, r->tech->paper[i].name, r->tech->paper[i].value, NULL, err);
    return res;
}

/* Sets a parameter value; *scene_level tells whether scene resources depend on it. */
static sss_result set_param_value(sss_gl_renderer *r, const char *name, double value, int *scene_level,
                                  sss_error *err)
{
    if (!name) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "parameter name is NULL");
    int i = find_param(r->tech->info.params, r->tech->info.param_count, name);
    if (i >= 0) {
        sss_result res = check_value(&r->tech->info.params[i], value, err);
        if (res != SSS_OK) return res;
        r->params[i] = value;
        if (scene_level) *scene_level = 0;
        return SSS_OK;
    }
    int n = 0;
    const sss_gl_param_info *sp = sss_gl_shared_params(&n);
    i = find_param(sp, n, name);
    if (i < 0) return unknown_param(r, name, err);
    sss_result res = check_value(&sp[i], value, err);
    if (res != SSS_OK) return res;
    if (scene_level) *scene_level = i != GL_P_SHADOW_BIAS;
    if (i == GL_P_PRESET) return apply_preset(r, value, err);
    r->shared[i] = value;
    return SSS_OK;
}

double sss_gl_renderer_get_param(const sss_gl_renderer *r, const char *name)
{
    if (!r || !name) return NAN;
    int i = find_param(r->tech->info.params, r->tech->info.param_count, name);
    if (i >= 0) return r->params[i];
    int n = 0;
    const sss_gl_param_info *sp = sss_gl_shared_params(&n);
    i = find_param(sp, n, name);
    return i >= 0 ? r->shared[i] : NAN;
}

/* ---- Creation ------------------------------------------------------------------------------- */

/* A pass over the caller's frame (frame.external) has no G-buffer, illumination or window of its own. */
static sss_result build_programs(sss_gl_renderer *r, sss_error *err)
{
    int own = !r->frame.external;
    sss_result res = gl_program_vf("shadow.vert.glsl", "shadow.frag.glsl", NULL, &r->prog_shadow, err);
    if (res == SSS_OK && own) res = gl_program_vf("gbuffer.vert.glsl", "gbuffer.frag.glsl", NULL, &r->prog_gbuffer, err);
    if (res == SSS_OK && own)
        res = gl_program_vf("fullscreen.vert.glsl", "illumination.frag.glsl", NULL, &r->prog_illum, err);
    if (res == SSS_OK)
        res = gl_program_compute("mip_reduce.comp.glsl",
                                 (r->tech->needs & GL_NEED_NORMAL_MIPS) ? "#define WITH_NORMALS 1\n" : NULL,
                                 &r->prog_reduce, err);
    if (res == SSS_OK && own)
        res = gl_program_vf("fullscreen.vert.glsl", "present.frag.glsl", NULL, &r->prog_present, err);
    return res;
}

static sss_result build_scene(sss_gl_renderer *r, sss_error *err)
{
    sss_result res = gl_scene_upload(r, err);
    if (res == SSS_OK) res = gl_lights_record_kinds(r, err);
    /* as a pass, only techniques that light the registered meshes themselves need lights and shadow maps */
    if (res == SSS_OK && (!r->frame.external || (r->tech->needs & GL_NEED_LIGHTS))) res = gl_lights_build(r, err);
    if (res == SSS_OK && (r->tech->needs & GL_NEED_SPLAT_MESHES)) res = gl_scene_prepare_splats(r, err);
    return res;
}

sss_result gl_runtime_technique_create(sss_gl_renderer *r, sss_error *err)
{
    r->tech_state = calloc(1, r->tech->state_size ? r->tech->state_size : 1);
    if (!r->tech_state) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (technique state)");
    sss_result res = SSS_OK;
    if (r->tech->create) GL_MEM_ACCOUNT(r->tech_gpu_bytes, res = r->tech->create(r, r->tech_state, err));
    if (res != SSS_OK) sss_error_prefix(err, r->tech->info.name);
    return res;
}

void gl_runtime_technique_destroy(sss_gl_renderer *r)
{
    if (r->tech_state && r->tech->destroy) GL_MEM_ACCOUNT(r->tech_gpu_bytes, r->tech->destroy(r, r->tech_state));
    free(r->tech_state);
    r->tech_state = NULL;
}

sss_result gl_materials_read_at_render(sss_gl_renderer *r, void *state, sss_error *err)
{
    (void)r, (void)state, (void)err;
    return SSS_OK;
}

sss_result gl_runtime_rebuild_if_dirty(sss_gl_renderer *r, sss_error *err)
{
    if (!r->scene_dirty) return SSS_OK;
    gl_runtime_technique_destroy(r);
    gl_scene_free(&r->gs);
    r->scene_dirty = 0;
    sss_result res = build_scene(r, err);
    if (res == SSS_OK) res = gl_runtime_technique_create(r, err);
    if (res != SSS_OK) r->scene_dirty = 1;
    return res;
}

/* The frame targets: the renderer's own, or (a pass) the slots for the caller's textures. */
static sss_result create_frame(sss_gl_renderer *r, sss_error *err)
{
    int normal_mips = (r->tech->needs & GL_NEED_NORMAL_MIPS) != 0;
    if (r->frame.external) return gl_frame_create_external(&r->frame, r->width, r->height, normal_mips, err);
    return gl_frame_create(&r->frame, r->width, r->height, normal_mips, err);
}

sss_result sss_gl_renderer_create(sss_gl_context *ctx, const sss_scene *scene, const sss_gl_renderer_desc *desc,
                                  sss_gl_renderer **out, sss_error *err)
{
    if (!out) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sss_gl_renderer_create: out is NULL");
    *out = NULL;
    if (!ctx || !scene) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sss_gl_renderer_create: no context or scene");
    return gl_runtime_create(ctx, scene, desc, 0, out, err);
}

sss_result gl_technique_for(const sss_scene *scene, const sss_gl_renderer_desc *desc, const gl_technique **out,
                            sss_error *err)
{
    const char *name = desc->technique ? desc->technique : scene->render.technique;
    if (!name || !name[0]) name = SSS_SCENE_DEFAULT_TECHNIQUE;
    *out = gl_technique_lookup(name);
    if (*out) return SSS_OK;
    char list[256] = "";
    size_t at = 0;
    for (int i = 0; i < sss_gl_technique_count() && at < sizeof list; i++)
        at += (size_t)snprintf(list + at, sizeof list - at, "%s%s", i ? ", " : "", sss_gl_technique_at(i)->name);
    if (desc->technique)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "unknown technique '%s' (known: %s)", name, list);
    return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "%s: render.technique: unknown technique '%s' (known: %s)",
                         scene->name ? scene->name : "scene", name, list);
}

sss_result gl_params_from_desc(sss_gl_renderer *r, const sss_gl_renderer_desc *desc, sss_error *err)
{
    const gl_technique *tech = r->tech;
    if (tech->info.param_count > GL_MAX_PARAMS)
        return sss_error_set(err, SSS_ERROR_LIMIT, "technique %s declares too many parameters", tech->info.name);
    for (int i = 0; i < tech->info.param_count; i++) r->params[i] = tech->info.params[i].default_value;
    int n = 0;
    const sss_gl_param_info *sp = sss_gl_shared_params(&n);
    for (int i = 0; i < n; i++) r->shared[i] = sp[i].default_value;
    /* the preset first, so that the parameters given with it override it */
    sss_result res = SSS_OK;
    for (int pass = 0; pass < 2; pass++)
        for (int i = 0; i < desc->param_count && res == SSS_OK; i++) {
            int is_preset = desc->params[i].name && strcmp(desc->params[i].name, sp[GL_P_PRESET].name) == 0;
            if (is_preset == (pass == 0)) res = set_param_value(r, desc->params[i].name, desc->params[i].value, NULL, err);
        }
    return res;
}

/* Everything of a new renderer that needs the GL; r->tables is read here only (scene and technique). */
static sss_result create_gl_parts(sss_gl_renderer *r, const sss_gl_tables *tables, sss_error *err)
{
    while (glGetError() != GL_NO_ERROR) {}
    r->tables = tables;
    sss_result res = build_programs(r, err);
    if (res == SSS_OK) {
        glCreateBuffers(1, &r->ubo_frame);
        glNamedBufferStorage(r->ubo_frame, (GLsizeiptr)gl_frame_ubo_size(), NULL, GL_DYNAMIC_STORAGE_BIT);
        glCreateVertexArrays(1, &r->vao_empty);
        res = build_scene(r, err);
    }
    if (res == SSS_OK) GL_MEM_ACCOUNT(r->frame_gpu_bytes, res = create_frame(r, err));
    if (res == SSS_OK) GL_MEM_ACCOUNT(r->frame_gpu_bytes, res = gl_ssaa_resize(r, err));
    if (res == SSS_OK) res = gl_runtime_technique_create(r, err);
    r->tables = NULL;
    if (res == SSS_OK) res = gl_check(r->ctx, "renderer creation", err);
    return res;
}

sss_result gl_runtime_create(sss_gl_context *ctx, const sss_scene *scene, const sss_gl_renderer_desc *desc_in,
                             int external, sss_gl_renderer **out, sss_error *err)
{
    sss_gl_renderer_desc desc;
    memset(&desc, 0, sizeof desc);
    if (desc_in) desc = *desc_in;
    const gl_technique *tech = NULL;
    sss_result res = gl_technique_for(scene, &desc, &tech, err);
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
    if (!sss_gl_context_make_current(ctx))
        return sss_error_set(err, SSS_ERROR_UNSUPPORTED, "cannot make the GL context current");
    sss_gl_renderer *r = calloc(1, sizeof *r);
    if (!r) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (renderer)");
    r->ctx = ctx;
    r->scene = scene;
    r->tech = tech;
    r->frame.external = external;
    r->data_file = desc.data_file;
    r->supersample = k;
    r->out_width = width;
    r->out_height = height;
    r->width = width * k;
    r->height = height * k;
    res = gl_params_from_desc(r, &desc, err);
    gl_timer_init(&r->timer, desc.timings, ctx->software);
    if (res == SSS_OK) res = create_gl_parts(r, desc.tables, err);
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
    sss_gl_context_make_current(r->ctx);
    gl_runtime_technique_destroy(r);
    gl_ssaa_free(r);
    gl_frame_free(&r->frame);
    gl_scene_free(&r->gs);
    GLuint progs[5] = {r->prog_gbuffer, r->prog_shadow, r->prog_illum, r->prog_reduce, r->prog_present};
    for (int i = 0; i < 5; i++)
        if (progs[i]) glDeleteProgram(progs[i]);
    if (r->ubo_frame) glDeleteBuffers(1, &r->ubo_frame);
    if (r->vao_empty) glDeleteVertexArrays(1, &r->vao_empty);
    gl_timer_free(&r->timer);
    free(r);
}

sss_result sss_gl_renderer_set_param(sss_gl_renderer *r, const char *name, double value, sss_error *err)
{
    if (!r) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "renderer is NULL");
    int scene_level = 0;
    sss_result res = set_param_value(r, name, value, &scene_level, err);
    if (res != SSS_OK) return res;
    if (scene_level) r->scene_dirty = 1;
    else if (r->tech->resize && r->tech_state) {
        sss_gl_context_make_current(r->ctx);
        GL_MEM_ACCOUNT(r->tech_gpu_bytes, res = r->tech->resize(r, r->tech_state, err));
    }
    return res;
}

sss_result sss_gl_renderer_update_lights(sss_gl_renderer *r, sss_error *err)
{
    if (!r) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "update_lights: no renderer");
    if (!sss_gl_context_make_current(r->ctx))
        return sss_error_set(err, SSS_ERROR_UNSUPPORTED, "update_lights: cannot make the GL context current");
    return gl_lights_update(r, err);
}

/* New output size and SSAA factor (already checked): frame targets at k x the size, the output image,
 * the technique's targets. */
static sss_result apply_size(sss_gl_renderer *r, int width, int height, int k, sss_error *err)
{
    if (width == r->out_width && height == r->out_height && k == r->supersample) return SSS_OK;
    sss_gl_context_make_current(r->ctx);
    int external = r->frame.external;
    GL_MEM_ACCOUNT(r->frame_gpu_bytes, gl_frame_free(&r->frame));
    r->frame.external = external;
    r->supersample = k;
    r->out_width = width;
    r->out_height = height;
    r->width = width * k;
    r->height = height * k;
    r->frame_rendered = 0;
    sss_result res = SSS_OK;
    GL_MEM_ACCOUNT(r->frame_gpu_bytes, res = create_frame(r, err));
    if (res == SSS_OK) GL_MEM_ACCOUNT(r->frame_gpu_bytes, res = gl_ssaa_resize(r, err));
    if (res == SSS_OK && r->tech->resize)
        GL_MEM_ACCOUNT(r->tech_gpu_bytes, res = r->tech->resize(r, r->tech_state, err));
    return res;
}

sss_result sss_gl_renderer_resize(sss_gl_renderer *r, int width, int height, sss_error *err)
{
    if (!r) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "renderer is NULL");
    if (width < 1 || height < 1 || width > r->ctx->max_texture_size || height > r->ctx->max_texture_size)
        return sss_error_set(err, SSS_ERROR_LIMIT, "image size %dx%d outside 1..%d", width, height,
                             r->ctx->max_texture_size);
    sss_result res = gl_ssaa_check(r->ctx, width, height, r->supersample, err);
    if (res != SSS_OK) return res;
    return apply_size(r, width, height, r->supersample, err);
}

void sss_gl_renderer_size(const sss_gl_renderer *r, int *width, int *height)
{
    if (width) *width = r ? r->out_width : 0;
    if (height) *height = r ? r->out_height : 0;
}

sss_result sss_gl_renderer_set_supersample(sss_gl_renderer *r, int supersample, sss_error *err)
{
    if (!r) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "renderer is NULL");
    int k = supersample == 0 ? 1 : supersample;
    sss_result res = gl_ssaa_check(r->ctx, r->out_width, r->out_height, k, err);
    if (res != SSS_OK) return res;
    return apply_size(r, r->out_width, r->out_height, k, err);
}

int sss_gl_renderer_get_supersample(const sss_gl_renderer *r) { return r ? gl_supersample(r) : 0; }

/* ---- Frames --------------------------------------------------------------------------------- */

sss_result sss_gl_renderer_render(sss_gl_renderer *r, double time, sss_error *err)
{
    if (!r) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "renderer is NULL");
    if (!isfinite(time)) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "render time %g is not finite", time);
    sss_gl_context_make_current(r->ctx);
    r->frame_rendered = 0;
    sss_result res = gl_runtime_rebuild_if_dirty(r, err); /* the camera's depth range needs the bounds */
    if (res != SSS_OK) return res;
    r->time = time;
    gl_camera cam;
    gl_camera_from_scene(r, &cam);
    res = gl_frame_run(r, &cam, time, err);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (res == SSS_OK) res = gl_check(r->ctx, "the end of the frame", err);
    if (res == SSS_OK) r->frame_rendered = 1;
    return res;
}

sss_result sss_gl_renderer_read(sss_gl_renderer *r, sss_image *out, sss_error *err)
{
    if (!r || !out || !out->pixels)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sss_gl_renderer_read: no renderer or image");
    if (out->width != r->out_width || out->height != r->out_height)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "read-back image is %dx%d, the renderer %dx%d",
                             out->width, out->height, r->out_width, r->out_height);
    if (!r->frame_rendered) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "no frame rendered yet");
    sss_gl_context_make_current(r->ctx);
    sss_image tmp;
    sss_result res = gl_read_texture_rgb(gl_output_texture(r), 0, r->out_width, r->out_height, &tmp, err);
    if (res != SSS_OK) return res;
    size_t bad = sss_image_count_nonfinite(&tmp);
    if (bad) {
        sss_image_free(&tmp);
        return sss_error_set(err, SSS_ERROR_NUMERIC, "technique %s produced %zu NaN/Inf values",
                             r->tech->info.name, bad);
    }
    memcpy(out->pixels, tmp.pixels, sizeof(float) * 3 * (size_t)r->out_width * (size_t)r->out_height);
    sss_image_free(&tmp);
    return gl_check(r->ctx, "the read-back", err);
}

/* The G-buffer's object id + 1 (0: background), from the alpha of the normal target, in all three channels. */
static sss_result read_object_ids(const sss_gl_renderer *r, sss_image *out, sss_error *err)
{
    int w = r->frame.width, h = r->frame.height;
    if (!r->frame.nrm)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "technique %s has no G-buffer", r->tech->info.name);
    sss_result res = sss_image_create(out, w, h, err);
    if (res != SSS_OK) return res;
    size_t n = (size_t)w * (size_t)h;
    float *rgba = malloc(n * 4 * sizeof(float));
    if (!rgba) {
        sss_image_free(out);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (read-back of %dx%d)", w, h);
    }
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glGetTextureImage(r->frame.nrm, 0, GL_RGBA, GL_FLOAT, (GLsizei)(n * 4 * sizeof(float)), rgba);
    for (int y = 0; y < h; y++) /* GL rows run bottom-up */
        for (int x = 0; x < w; x++)
            for (int c = 0; c < 3; c++)
                out->pixels[((size_t)y * (size_t)w + (size_t)x) * 3 + (size_t)c] =
                    rgba[((size_t)(h - 1 - y) * (size_t)w + (size_t)x) * 4 + 3];
    free(rgba);
    res = gl_check(r->ctx, "the object id read-back", err);
    if (res != SSS_OK) sss_image_free(out);
    return res;
}

sss_result sss_gl_renderer_read_buffer(sss_gl_renderer *r, const char *name, sss_image *out, sss_error *err)
{
    if (out) memset(out, 0, sizeof *out);
    if (!r || !name || !out) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "read_buffer: bad arguments");
    if (!r->frame_rendered) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "no frame rendered yet");
    sss_gl_context_make_current(r->ctx);
    GLuint tex = 0;
    if (strcmp(name, "final") == 0) tex = gl_output_texture(r);
    else if (strcmp(name, "supersampled") == 0) tex = r->frame.final;
    else if (strcmp(name, "reflected") == 0) tex = r->frame.refl;
    else if (strcmp(name, "irradiance") == 0) tex = r->frame.irr;
    else if (strcmp(name, "object_id") == 0) return read_object_ids(r, out, err);
    else if (r->tech->buffer) tex = r->tech->buffer(r, r->tech_state, name);
    if (!tex)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "technique %s has no buffer '%s'", r->tech->info.name,
                             name);
    GLint w = 0, h = 0;
    glGetTextureLevelParameteriv(tex, 0, GL_TEXTURE_WIDTH, &w);
    glGetTextureLevelParameteriv(tex, 0, GL_TEXTURE_HEIGHT, &h);
    return gl_read_texture_rgb(tex, 0, w, h, out, err);
}

sss_result sss_gl_renderer_present(sss_gl_renderer *r, sss_error *err)
{
    if (!r) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "renderer is NULL");
    if (!r->ctx->window) return sss_error_set(err, SSS_ERROR_UNSUPPORTED, "present needs a window context");
    int w = 0, h = 0;
    sss_gl_window_size(r->ctx, &w, &h);
    if (w < 1 || h < 1) return SSS_OK;
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, w, h);
    glUseProgram(r->prog_present);
    glBindTextureUnit(0, gl_output_texture(r));
    glUniform2f(glGetUniformLocation(r->prog_present, "u_scale"), (float)r->out_width / w, (float)r->out_height / h);
    gl_draw_fullscreen(r);
    return gl_check(r->ctx, "present", err);
}

void sss_gl_renderer_timings(const sss_gl_renderer *r, sss_gl_timings *out)
{
    if (!out) return;
    memset(out, 0, sizeof *out);
    out->method = "off";
    if (!r || !r->timer.enabled) return;
    out->method = r->timer.use_queries ? "GL_TIME_ELAPSED queries" : "glFinish + monotonic clock";
    out->pass_count = r->timer.count;
    for (int i = 0; i < r->timer.count; i++) {
        out->passes[i].name = r->timer.names[i];
        out->passes[i].ms = r->timer.ms[i];
        out->total_ms += r->timer.ms[i];
    }
}

void sss_gl_renderer_stats(sss_gl_renderer *r, sss_gl_stats *out)
{
    if (!out) return;
    memset(out, 0, sizeof *out);
    if (!r) return;
    out->texture_bytes = r->gs.texture_bytes + r->gs.lut_bytes + r->frame.bytes + r->ssaa_bytes;
    out->buffer_bytes = r->gs.buffer_bytes + r->gs.record_bytes;
    out->lut_bytes = r->gs.lut_bytes;
    out->luts_precomputed = r->gs.luts_precomputed;
    /* per render pixel here and in the technique's stats, then per output pixel (k^2 of them) */
    out->per_pixel_bytes = r->frame.bytes / ((size_t)r->width * (size_t)r->height);
    out->splat_total = r->gs.splat_total;
    out->material_count = r->gs.material_count;
    out->light_count = r->gs.light_count;
    out->virtual_light_count = r->gs.vpl_count;
    out->object_count = (int)r->scene->object_count;
    if (r->tech->stats && r->tech_state) r->tech->stats(r, r->tech_state, out);
    size_t k = (size_t)gl_supersample(r);
    out->per_pixel_bytes = out->per_pixel_bytes * k * k + r->ssaa_bytes / ((size_t)r->out_width * (size_t)r->out_height);
}

void sss_gl_renderer_gpu_memory(const sss_gl_renderer *r, size_t *technique_bytes, size_t *frame_bytes)
{
    if (technique_bytes) *technique_bytes = r && r->tech_gpu_bytes > 0 ? (size_t)r->tech_gpu_bytes : 0;
    if (frame_bytes) *frame_bytes = r && r->frame_gpu_bytes > 0 ? (size_t)r->frame_gpu_bytes : 0;
}
