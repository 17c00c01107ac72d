/* view/actions.c — what the viewer's keys do: switch technique (the registry, so new techniques appear
 * by themselves), show the translucency or the screen-space part alone, cycle measured media and the
 * scattering scale, move the light, compute the reference of the current view in the background and
 * the DSSIM of the frame against it, save screenshots. Failures become overlay messages; the viewer
 * keeps the last working state. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "sss/material.h"
#include "view/viewer.h"

const char *const view_buffer_names[VIEW_BUFFER_COUNT] = {"final",        "reflected",         "irradiance",
                                                          "translucency", "translucency_full", "screen"};

void view_message(viewer *v, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(v->message, sizeof v->message, fmt, ap);
    va_end(ap);
    v->message_until = sss_time_seconds() + 5.0;
    if (v->desc->log) v->desc->log(v->desc->log_user, v->message);
}

static int find_param(const sss_gl_param_info *p, int n, const char *name)
{
    for (int i = 0; i < n; i++)
        if (strcmp(p[i].name, name) == 0) return i;
    return -1;
}

static int technique_knows(const sss_gl_technique_info *info, const char *name)
{
    int n = 0;
    const sss_gl_param_info *shared = sss_gl_shared_params(&n);
    return find_param(info->params, info->param_count, name) >= 0 || find_param(shared, n, name) >= 0;
}

/* A param the panel or script set for technique `tech` (NaN when none). */
double view_set_param_value(const viewer *v, const char *tech, const char *name)
{
    double value = NAN;
    size_t tl = strlen(tech);
    for (int i = 0; i < v->set_count; i++) {
        const char *n = v->set_names[i];
        if (strcmp(n, name) == 0) value = v->set_params[i].value;
        else if (strncmp(n, tech, tl) == 0 && n[tl] == '.' && strcmp(n + tl + 1, name) == 0) value = v->set_params[i].value;
    }
    return value;
}

/* The value the user asked for (panel or script, else --param) or the technique's default. */
static double user_value(const viewer *v, const sss_gl_technique_info *info, int index)
{
    double set = view_set_param_value(v, info->name, info->params[index].name);
    if (!isnan(set)) return set;
    for (int i = 0; i < v->desc->param_count; i++)
        if (strcmp(v->desc->params[i].name, info->params[index].name) == 0) return v->desc->params[i].value;
    return info->params[index].default_value;
}

/* The desc of the viewer's renderers of technique `info` at its size: the --param values (those the
 * technique knows, once a renderer runs: switching must not fail on another's), then the panel's and
 * the script's. *params is allocated: free() it. */
sss_result view_renderer_desc(viewer *v, const sss_gl_technique_info *info, sss_gl_renderer_desc *d,
                              sss_gl_param_value **params, sss_error *err)
{
    int shared_count = 0;
    const sss_gl_param_info *shared = sss_gl_shared_params(&shared_count);
    int n = v->desc->param_count, all = info->param_count + shared_count, kept = 0;
    *params = calloc((size_t)(n + all), sizeof **params);
    if (!*params) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (parameters)");
    for (int i = 0; i < n; i++)
        if (!v->r || technique_knows(info, v->desc->params[i].name)) (*params)[kept++] = v->desc->params[i];
    for (int i = 0; i < all; i++) {
        const char *name = i < info->param_count ? info->params[i].name : shared[i - info->param_count].name;
        double set = view_set_param_value(v, info->name, name);
        if (!isnan(set)) (*params)[kept++] = (sss_gl_param_value){name, set};
    }
    memset(d, 0, sizeof *d);
    d->technique = info->name;
    d->width = v->width;
    d->height = v->height;
    d->params = *params;
    d->param_count = kept;
    d->timings = 1;
    d->supersample = v->desc->supersample;
    return SSS_OK;
}

sss_result view_create_renderer(viewer *v, const sss_gl_technique_info *info, const sss_scene *scene,
                                const sss_gl_tables *tables, sss_gl_renderer **out, sss_error *err)
{
    sss_gl_renderer_desc d;
    sss_gl_param_value *params = NULL;
    sss_result res = view_renderer_desc(v, info, &d, &params, err);
    d.tables = tables;
    if (res == SSS_OK) res = sss_gl_renderer_create(v->ctx, scene, &d, out, err);
    free(params);
    return res;
}

sss_result view_make_renderer(viewer *v, int tech, sss_error *err)
{
    return view_make_renderer_for(v, tech, v->scene, NULL, err);
}

sss_result view_make_renderer_for(viewer *v, int tech, const sss_scene *scene, const sss_gl_tables *tables,
                                  sss_error *err)
{
    const sss_gl_technique_info *info = sss_gl_technique_at(tech);
    if (!info) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "no technique %d", tech);
    sss_gl_renderer *r = NULL;
    sss_result res = view_create_renderer(v, info, scene, tables, &r, err);
    if (res == SSS_OK) {
        sss_gl_timing_series_free(&v->timing_series);
        res = sss_gl_timing_series_init(&v->timing_series, SSS_GL_WARMUP_FRAMES, SSS_GL_TIMED_FRAMES, err);
        if (res != SSS_OK) sss_gl_renderer_destroy(r);
    }
    if (res != SSS_OK) return res;
    sss_gl_renderer_destroy(v->r);
    v->r = r;
    v->tech = tech;
    v->need_render = 1;
    /* the part switches of the new technique */
    int p = find_param(info->params, info->param_count, "screen_space");
    int q = find_param(info->params, info->param_count, "translucency");
    if (p >= 0 && q >= 0) {
        sss_gl_renderer_set_param(r, "screen_space", v->part == PART_TRANSLUCENCY ? 0.0 : user_value(v, info, p), NULL);
        sss_gl_renderer_set_param(r, "translucency", v->part == PART_SCREEN ? 0.0 : user_value(v, info, q), NULL);
        v->part_buffer = NULL;
    } else if (v->part == PART_TRANSLUCENCY) {
        v->part_buffer = "translucency_full";
    } else if (v->part == PART_SCREEN && strcmp(info->name, "screen") != 0) {
        v->part_buffer = "screen";
    } else {
        v->part_buffer = NULL;
    }
    return SSS_OK;
}

void view_switch_technique(viewer *v, int tech, int quiet)
{
    sss_error err = {0};
    const sss_gl_technique_info *info = sss_gl_technique_at(tech);
    if (view_make_renderer(v, tech, &err) != SSS_OK)
        view_message(v, "technique %s failed: %s", info ? info->name : "?", err.message);
    else if (!quiet)
        view_message(v, "technique %s", info->name);
}

void view_apply_part(viewer *v, int part)
{
    int back = v->part_saved_tech;
    v->part = part;
    v->part_saved_tech = -1;
    if (back >= 0 && back != v->tech) view_switch_technique(v, back, 1);
    else view_switch_technique(v, v->tech, 1); /* re-applies the switches */
    static const char *const names[3] = {"all parts", "translucency alone", "screen-space part alone"};
    view_message(v, "%s%s%s%s", names[part], v->part_buffer ? " (through the technique's buffer " : "",
                 v->part_buffer ? v->part_buffer : "", v->part_buffer ? ")" : "");
}

/* A part shown through a buffer could not be read: try the next way (translucency -> the
 * low-resolution buffer; screen -> the "screen" technique), else give up with a message. */
static void part_buffer_failed(viewer *v)
{
    const char *name = sss_gl_technique_at(v->tech)->name;
    if (v->part == PART_TRANSLUCENCY && v->part_buffer && strcmp(v->part_buffer, "translucency_full") == 0) {
        v->part_buffer = "translucency";
        return;
    }
    v->part_buffer = NULL;
    if (v->part == PART_SCREEN) {
        for (int i = 0; i < sss_gl_technique_count(); i++)
            if (strcmp(sss_gl_technique_at(i)->name, "screen") == 0 && i != v->tech) {
                int saved = v->tech;
                view_switch_technique(v, i, 1);
                if (v->tech == i) {
                    v->part_saved_tech = saved;
                    view_message(v, "%s has no screen-space switch: showing technique screen", name);
                    return;
                }
            }
    }
    view_message(v, "technique %s exposes no %s part (no switch, no buffer)", name,
                 v->part == PART_SCREEN ? "screen-space" : "translucency");
    v->part = PART_ALL;
}

int view_buffer_to_show(viewer *v, sss_image *out)
{
    for (int attempt = 0; attempt < 4; attempt++) {
        const char *name = v->part_buffer ? v->part_buffer : v->buffer > 0 ? view_buffer_names[v->buffer] : NULL;
        if (!name) return 0;
        sss_error err = {0};
        if (sss_gl_renderer_read_buffer(v->r, name, out, &err) == SSS_OK) return 1;
        if (v->part_buffer) {
            part_buffer_failed(v);
        } else {
            view_message(v, "%s", err.message);
            v->buffer = 0;
        }
    }
    return 0;
}

/* ---- Scene edits ---------------------------------------------------------------------------- */

void view_invalidate(viewer *v)
{
    free(v->view_key);
    v->view_key = NULL;
    v->ref = NULL;
    v->dssim_gen = 0;
    v->need_render = 1;
}

void view_camera_changed(viewer *v)
{
    sss_camera_basis b;
    if (sss_camera_basis_init(&v->scene->camera, &b, NULL) == SSS_OK) v->scene->basis = b;
    view_invalidate(v);
}

/* The split renderer again after the scene or size changed (none when the split is not a technique). */
void view_split_refresh(viewer *v)
{
    sss_gl_renderer_destroy(v->split_r);
    v->split_r = NULL;
    if (v->split != VIEW_SPLIT_TECHNIQUE) return;
    sss_error err = {0};
    if (view_create_renderer(v, sss_gl_technique_at(v->split_tech), v->scene, NULL, &v->split_r, &err) != SSS_OK) {
        view_message(v, "split view: %s", err.message);
        v->split = VIEW_SPLIT_OFF;
    }
    v->composed_gen = 0;
}

void view_light_changed(viewer *v)
{
    /* The renderer re-reads the moved light (shadow maps follow at the next frame); only if that is
     * refused (it never is for a moved light) is it rebuilt on the same scene. */
    sss_error err = {0};
    if (!v->r || sss_gl_renderer_update_lights(v->r, &err) != SSS_OK) {
        err.message[0] = 0;
        if (view_make_renderer(v, v->tech, &err) != SSS_OK) view_message(v, "light: %s", err.message);
    }
    if (v->split_r && sss_gl_renderer_update_lights(v->split_r, NULL) != SSS_OK) view_split_refresh(v);
    view_invalidate(v);
}

sss_result view_edited_json(viewer *v, char **json, sss_error *err)
{
    view_edits e;
    memset(&e, 0, sizeof e);
    e.camera = &v->scene->camera;
    e.light0 = v->has_light ? &v->scene->lights[0] : NULL;
    e.medium = v->medium;
    e.scale_factor = v->scale_factor;
    return view_scene_json(v->text, v->text_size, v->scene->name, &e, json, err);
}

/* ---- Reference and DSSIM -------------------------------------------------------------------- */

sss_result view_current_key(viewer *v, char **key, char **json, sss_error *err)
{
    *key = NULL;
    char *j = NULL;
    sss_result res = view_edited_json(v, &j, err);
    if (res != SSS_OK) return res;
    size_t n = strlen(j) + 64;
    *key = malloc(n);
    if (!*key) {
        free(j);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (view key)");
    }
    snprintf(*key, n, "%s|t=%.17g", j, v->t);
    if (json) *json = j;
    else free(j);
    return SSS_OK;
}

static char *quality_key(const char *key, int draft)
{
    size_t n = strlen(key) + 8;
    char *k = malloc(n);
    if (k) snprintf(k, n, "%s|%s", key, draft ? "draft" : "final");
    return k;
}

void view_request_reference(viewer *v, int draft)
{
    double progress = 0.0;
    if (v->job) {
        view_ref_poll(v->job, &progress, NULL);
        view_message(v, "a reference is being rendered (%.0f%%)", 100.0 * progress);
        return;
    }
    sss_error err = {0};
    char *key = NULL, *json = NULL;
    if (view_current_key(v, &key, &json, &err) != SSS_OK) {
        view_message(v, "reference: %s", err.message);
        return;
    }
    char *qk = quality_key(key, draft);
    free(key);
    if (!qk) {
        free(json);
        view_message(v, "reference: out of memory");
        return;
    }
    if (view_ref_cache_find(&v->cache, qk)) {
        free(json);
        free(qk);
        view_invalidate(v);
        view_message(v, "the reference of this view is cached");
        return;
    }
    if (view_ref_start(json, v->scene->base_dir, v->scene->name, v->t, draft, &v->job, &err) != SSS_OK) {
        free(qk);
        view_message(v, "reference: %s", err.message);
    } else {
        v->job_key = qk;
        view_message(v, "rendering the %s reference of this view in the background", draft ? "draft" : "final");
    }
    free(json);
}

void view_poll_reference(viewer *v)
{
    if (!v->job || !view_ref_poll(v->job, NULL, NULL)) return;
    sss_error err = {0};
    sss_image img = {0};
    sss_result res = view_ref_finish(v->job, &img, &err);
    v->job = NULL;
    if (res == SSS_OK) res = view_ref_cache_put(&v->cache, v->job_key, &img, &err);
    free(v->job_key);
    v->job_key = NULL;
    if (res != SSS_OK) view_message(v, "reference failed: %s", err.message);
    else view_message(v, "reference ready");
    free(v->view_key); /* look the current view up again */
    v->view_key = NULL;
    v->ref = NULL;
    v->dssim_gen = 0;
}

void view_update_dssim(viewer *v)
{
    if (!v->view_key) {
        sss_error err = {0};
        if (view_current_key(v, &v->view_key, NULL, &err) != SSS_OK) return;
        v->ref = NULL;
        for (int draft = 0; draft <= 1 && !v->ref; draft++) {
            char *qk = quality_key(v->view_key, draft);
            if (qk) v->ref = view_ref_cache_find(&v->cache, qk);
            if (v->ref) v->ref_draft = draft;
            free(qk);
        }
    }
    if (!v->ref || v->dssim_gen == v->image_gen || !v->image_gen) return;
    sss_error err = {0};
    if (v->frame_img.width != v->width || v->frame_img.height != v->height) {
        sss_image_free(&v->frame_img);
        if (sss_image_create(&v->frame_img, v->width, v->height, &err) != SSS_OK) return;
    }
    sss_image_metrics m;
    if (sss_gl_renderer_read(v->r, &v->frame_img, &err) != SSS_OK ||
        sss_image_compare(&v->frame_img, v->ref, v->scene->render.exposure, &m, NULL, &err) != SSS_OK) {
        view_message(v, "DSSIM: %s", err.message);
        v->ref = NULL;
        return;
    }
    v->dssim = m.dssim;
    v->dssim_gen = v->image_gen;
}

/* ---- Screenshots ---------------------------------------------------------------------------- */

int view_next_screenshot_name(char *buf, size_t cap)
{
    for (int i = 0; i < 10000; i++) {
        snprintf(buf, cap, "sss-view-%04d.png", i);
        if (access(buf, F_OK) != 0) return 1;
    }
    return 0;
}

sss_result view_check_outputs(const viewer *v, const char *const *paths, size_t count, sss_error *err)
{
    sss_io_set io = {0};
    for (size_t i = 0; i < v->files.input_count; i++) sss_io_add_input(&io, v->files.inputs[i]);
    for (size_t i = 0; i < count; i++) sss_io_add_output(&io, paths[i]);
    sss_result res = sss_io_check(&io, err);
    sss_io_free(&io);
    return res;
}

sss_result view_save_screenshot(const viewer *v, const char *path, sss_error *err)
{
    sss_result res = view_check_outputs(v, &path, 1, err);
    return res == SSS_OK ? view_gl_screenshot(v->width, v->height, path, err) : res;
}
