/* view/rebuild.c — material edits without a frozen window: the edited scene's JSON goes to a worker
 * (view/build_job.c: the loader, then the renderer's LUTs), the window keeps drawing the old scene,
 * and when the worker is done the window thread hands the new scene and its precomputed tables to the
 * renderers (sss_gl_renderer_update_materials: material records and LUT uploads; a new renderer when
 * that is refused). Edits made while a build runs wait as one request: the latest wins, the
 * running build is dropped when it ends. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "view/viewer.h"

static void request_free(view_rebuild_request *q)
{
    free(q->text);
    memset(q, 0, sizeof *q);
}

int view_rebuild_busy(const viewer *v) { return v->build != NULL; }

/* SSS_VIEW_BUILD_DELAY_MS: the worker waits that long first (tests of a slow build). */
static double test_delay(void)
{
    const char *s = getenv("SSS_VIEW_BUILD_DELAY_MS");
    double ms = s ? atof(s) : 0.0;
    return ms > 0.0 && ms < 600000.0 ? ms / 1000.0 : 0.0;
}

static void fail(viewer *v, const view_rebuild_request *q, const sss_error *err)
{
    char *text = view_dup_str(v->live_text);
    if (text) {
        free(v->text);
        v->text = text;
        v->text_size = strlen(text);
    }
    v->medium = v->live_medium;
    v->scale_factor = v->live_scale;
    v->build_err = *err;
    if (q->line) v->build_failed_line = q->line;
    view_message(v, "material change failed: %s", err->message);
}

/* Starts the worker on v->building (the viewer's state when it was requested). */
static void start(viewer *v)
{
    sss_error err = {0};
    char *json = NULL;
    sss_gl_renderer_desc d;
    sss_gl_param_value *params = NULL;
    sss_result res = view_edited_json(v, &json, &err);
    if (res == SSS_OK) res = view_renderer_desc(v, sss_gl_technique_at(v->tech), &d, &params, &err);
    if (res == SSS_OK)
        res = view_build_start(json, v->scene->base_dir, v->scene->name, &d, test_delay(), &v->build, &err);
    free(params);
    free(json);
    v->build_frames = 0;
    v->build_longest_ms = 0.0;
    if (res != SSS_OK) {
        fail(v, &v->building, &err);
        request_free(&v->building);
    }
}

void view_request_rebuild(viewer *v, const char *what, int line)
{
    view_rebuild_request q = {0};
    q.text = view_dup_str(v->text);
    q.medium = v->medium;
    q.scale = v->scale_factor;
    q.line = line;
    q.started = sss_time_seconds();
    snprintf(q.what, sizeof q.what, "%s", what);
    if (!q.text) {
        sss_error err = {0};
        sss_error_set(&err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (material edit)");
        fail(v, &q, &err);
        return;
    }
    view_rebuild_request *slot = v->build ? &v->pending : &v->building;
    request_free(slot);
    *slot = q;
    if (!v->build) start(v);
    else view_message(v, "%s: rebuilding (after the running build)", what);
}

/* The renderer takes scene s in place (same meshes, lights and programs: only materials differ), or,
 * when that fails, a new one is created from it; on failure it keeps drawing the viewer's scene. */
static sss_result update_renderer(viewer *v, const sss_scene *s, const sss_gl_tables *tables, sss_error *err)
{
    sss_error why = {0};
    sss_result res = sss_gl_renderer_update_materials(v->r, s, tables, &why);
    v->rebuild_in_place = res == SSS_OK;
    return res == SSS_OK ? SSS_OK : view_make_renderer_for(v, v->tech, s, tables, err);
}

/* The worker's scene replaces the one on screen; the camera and lights are the window's (they may
 * have moved while the worker ran: only materials differ). */
static sss_result apply(viewer *v, view_build_result *b, sss_error *err)
{
    double start = sss_time_seconds();
    sss_scene *old = v->scene, *s = b->scene;
    s->camera = old->camera;
    s->basis = old->basis;
    for (size_t i = 0; i < s->light_count && i < old->light_count; i++) {
        char *file = s->lights[i].file; /* the same path: the texts differ in materials only */
        s->lights[i] = old->lights[i];
        s->lights[i].file = file;
    }
    sss_result res = update_renderer(v, s, b->tables, err);
    if (res != SSS_OK) return res; /* b still owns s */
    v->scene = s;
    b->scene = old;
    if (v->split_r && sss_gl_renderer_update_materials(v->split_r, s, b->tables, NULL) != SSS_OK)
        view_split_refresh(v); /* it read the old scene */
    v->rebuild_window_ms = 1000.0 * (sss_time_seconds() - start);
    return SSS_OK;
}

static void applied(viewer *v, const view_build_result *b)
{
    view_rebuild_request *q = &v->building;
    free(v->live_text);
    v->live_text = q->text;
    q->text = NULL;
    v->live_medium = q->medium;
    v->live_scale = q->scale;
    v->rebuild_ms = 1000.0 * (sss_time_seconds() - q->started);
    v->rebuild_scene_ms = b->scene_ms;
    v->rebuild_tables_ms = b->tables_ms;
    view_invalidate(v);
    view_message(v,
                 "rebuilt in %.1f ms (worker %.1f ms: scene %.1f ms, tables %.1f ms, while %d frames were drawn, the "
                 "longest %.1f ms; then %s on the window thread %.1f ms; %d older edits dropped): %s",
                 v->rebuild_ms, b->scene_ms + b->tables_ms, b->scene_ms, b->tables_ms, v->build_frames,
                 v->build_longest_ms, v->rebuild_in_place ? "the materials updated in place" : "a new renderer",
                 v->rebuild_window_ms, v->build_dropped, q->what);
    v->build_dropped = 0;
}

void view_poll_rebuild(viewer *v)
{
    if (!v->build || !view_build_poll(v->build)) return;
    sss_error err = {0};
    view_build_result b = {0};
    sss_result res = view_build_finish(v->build, &b, &err);
    v->build = NULL;
    if (v->pending.text) { /* a newer edit waits: this build is stale */
        view_build_result_free(&b);
        request_free(&v->building);
        v->build_dropped++;
        v->building = v->pending;
        memset(&v->pending, 0, sizeof v->pending);
        start(v);
        return;
    }
    if (res == SSS_OK) res = apply(v, &b, &err);
    if (res == SSS_OK) applied(v, &b);
    else fail(v, &v->building, &err);
    view_build_result_free(&b);
    request_free(&v->building);
}

void view_rebuild_free(viewer *v)
{
    if (v->build) view_build_abandon(v->build); /* the worker finishes on its own and frees its job */
    v->build = NULL;
    request_free(&v->building);
    request_free(&v->pending);
    free(v->live_text);
    v->live_text = NULL;
}
