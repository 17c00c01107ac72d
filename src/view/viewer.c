/* view/viewer.c — sss_view_run: the window, the frame loop (render when something changed or the
 * animation plays, show the final image or a buffer, screenshot from the back buffer, then the overlay,
 * then swap) and the fixed-frame mode for tests. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <epoxy/gl.h>

#include "core/file_util.h"
#include "scene/scene_files.h"
#include "view/panel.h"
#include "view/script.h"
#include "view/viewer.h"

#define OVERLAY_TEXT_SIZE 8192
#define FRAMES_MODE_FPS 30.0

static void sleep_ms(int ms)
{
    struct timespec ts = {ms / 1000, (long)(ms % 1000) * 1000000L};
    nanosleep(&ts, NULL);
}

static void check_size(viewer *v)
{
    int fw = 0, fh = 0;
    sss_gl_window_size(v->ctx, &fw, &fh);
    if (fw < 1 || fh < 1 || (fw == v->width && fh == v->height)) return; /* minimised or unchanged */
    sss_error err = {0};
    if (sss_gl_renderer_resize(v->r, fw, fh, &err) != SSS_OK) {
        view_message(v, "resize: %s", err.message);
        return;
    }
    v->width = fw;
    v->height = fh;
    v->scene->camera.width = fw;
    v->scene->camera.height = fh;
    if (v->split_r) view_split_refresh(v);
    view_camera_changed(v);
}

/* The split view or the error map, composed on the CPU from the final image; 0 when neither is on or
 * its other half (the reference, the second technique) is not there yet. */
static int show_composed(viewer *v, sss_error *err, sss_result *res)
{
    int want_ref = v->errormap || v->split == VIEW_SPLIT_REFERENCE;
    if ((!v->errormap && !v->split) || (want_ref && !v->ref) || (v->split == VIEW_SPLIT_TECHNIQUE && !v->split_r))
        return 0;
    double exposure = v->errormap ? 0.0 : v->scene->render.exposure;
    if (v->composed_gen == v->image_gen && v->composed_ref == v->ref) {
        *res = view_gl_redraw_image(&v->gl, exposure, v->width, v->height, err);
        return 1;
    }
    if (v->frame_img.width != v->width || v->frame_img.height != v->height) {
        sss_image_free(&v->frame_img);
        if ((*res = sss_image_create(&v->frame_img, v->width, v->height, err)) != SSS_OK) return 1;
    }
    if ((*res = sss_gl_renderer_read(v->r, &v->frame_img, err)) != SSS_OK) return 1;
    const sss_image *shown = &v->frame_img;
    if (v->errormap) {
        sss_image_metrics m;
        sss_image_free(&v->map_img);
        *res = sss_image_compare(&v->frame_img, v->ref, v->scene->render.exposure, &m, &v->map_img, err);
        double before = v->error_range;
        if (*res == SSS_OK) *res = view_error_map(&v->map_img, &v->composed_img, &v->error_range, err);
        if (*res == SSS_OK && v->error_range != before) /* the scale of the colour bar, also without the panel */
            view_message(v, "error map: DSSIM %.6f, colour bar from 0 (left) to %g (right)", m.dssim, v->error_range);
        shown = &v->composed_img;
    } else {
        const sss_image *other = v->ref;
        if (v->split == VIEW_SPLIT_TECHNIQUE) {
            if (v->other_img.width != v->width || v->other_img.height != v->height) {
                sss_image_free(&v->other_img);
                *res = sss_image_create(&v->other_img, v->width, v->height, err);
            }
            if (*res == SSS_OK) *res = sss_gl_renderer_read(v->split_r, &v->other_img, err);
            other = &v->other_img;
        }
        if (*res == SSS_OK) *res = view_compose_split(&v->frame_img, other, v->split_pos, &v->composed_img, err);
        shown = &v->composed_img;
    }
    if (*res == SSS_OK) *res = view_gl_draw_image(&v->gl, shown, exposure, v->width, v->height, err);
    v->composed_gen = v->image_gen;
    v->composed_ref = v->ref;
    return 1;
}

/* The image under the overlay: the technique's final frame, or a buffer (a part alone, the B key). */
static sss_result show_image(viewer *v, sss_error *err)
{
    const char *want = v->part_buffer ? v->part_buffer : v->buffer ? view_buffer_names[v->buffer] : NULL;
    double exposure = v->scene->render.exposure;
    sss_result composed = SSS_OK;
    if (!want && !v->need_render && show_composed(v, err, &composed)) return composed;
    if (want && v->shown_gen == v->image_gen && v->shown_name == want)
        return view_gl_redraw_image(&v->gl, exposure, v->width, v->height, err);
    if (want) {
        sss_image img = {0};
        if (view_buffer_to_show(v, &img)) {
            sss_result res = view_gl_draw_image(&v->gl, &img, exposure, v->width, v->height, err);
            sss_image_free(&img);
            v->shown_gen = v->image_gen;
            v->shown_name = v->part_buffer ? v->part_buffer : view_buffer_names[v->buffer];
            return res;
        }
    }
    if (v->need_render) { /* a fresh renderer (technique switched just now) has no frame yet */
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
        return SSS_OK;
    }
    return sss_gl_renderer_present(v->r, err);
}

static sss_result draw_overlay(viewer *v, sss_error *err)
{
    char *text = malloc(OVERLAY_TEXT_SIZE);
    if (!text) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (overlay)");
    view_overlay_text(v, text, OVERLAY_TEXT_SIZE);
    view_text t = {0};
    float scale = v->width >= 1600 ? 2.0f : 1.0f;
    sss_result res = view_text_build(&t, text, 4.0f, 4.0f, scale, err);
    if (res == SSS_OK) res = view_gl_draw_text(&v->gl, &t, v->width, v->height, err);
    view_text_free(&t);
    free(text);
    return res;
}

/* The technique's frame (and the split view's second technique's) when something changed or in a
 * fixed-frame run, whose render failure ends the run (interactively it becomes a message). */
static sss_result render(viewer *v, int fixed, int *rendered, sss_error *err)
{
    *rendered = 0;
    if (!v->need_render && !fixed) return SSS_OK;
    sss_error rerr = {0};
    if (sss_gl_renderer_render(v->r, v->t, &rerr) != SSS_OK) {
        v->need_render = 0;
        if (fixed) {
            *err = rerr;
            return rerr.code;
        }
        view_message(v, "render: %s", rerr.message);
    } else {
        sss_gl_timings frame;
        sss_gl_renderer_timings(v->r, &frame);
        sss_gl_timing_series_add(&v->timing_series, &frame);
        sss_gl_timing_series_median(&v->timing_series, &v->timings);
        v->image_gen++;
        v->need_render = 0;
        *rendered = 1;
    }
    if (v->split_r && sss_gl_renderer_render(v->split_r, v->t, &rerr) != SSS_OK) {
        view_message(v, "split view: %s", rerr.message);
        v->split = VIEW_SPLIT_OFF;
        view_split_refresh(v);
    }
    return SSS_OK;
}

/* The S key's sss-view-NNNN.png, from the back buffer before the overlay is drawn. */
static void key_screenshot(viewer *v)
{
    v->act_screenshot = 0;
    char name[64];
    sss_error serr = {0};
    if (!view_next_screenshot_name(name, sizeof name)) view_message(v, "screenshot: sss-view-0000..9999.png all exist");
    else if (view_save_screenshot(v, name, &serr) != SSS_OK) view_message(v, "%s", serr.message);
    else view_message(v, "saved %s", name);
}

/* The panel or the text overlay, timed (v->overlay_ms); a failure hides it interactively. */
static sss_result draw_ui(viewer *v, int fixed, sss_error *err)
{
    if (fixed) glFinish(); /* scripts time the panel alone: the frame's own work done first */
    double overlay_start = sss_time_seconds();
    sss_result res = SSS_OK;
    if (v->overlay && v->panel) res = view_panel_draw(v, err);
    else if (v->overlay) res = draw_overlay(v, err);
    if (fixed) glFinish();
    v->overlay_ms = v->overlay ? 1000.0 * (sss_time_seconds() - overlay_start) : 0.0;
    if (res != SSS_OK && !fixed) {
        view_message(v, "%s", err->message);
        v->overlay = 0;
        res = SSS_OK;
    }
    return res;
}

/* One frame: the queued keys and a finished rebuild first, then render, show, screenshots (the back
 * buffer before the overlay and the swap; a script's after the panel), the overlay, swap. Failures
 * end a fixed-frame run; interactively they become a message. */
static sss_result frame(viewer *v, int fixed, const char *screenshot, sss_error *err)
{
    double entered = sss_time_seconds();
    int building = view_rebuild_busy(v), rendered = 0;
    check_size(v);
    view_cmd_keys(v);
    view_poll_rebuild(v);
    if (v->playing && !fixed) {
        double now = glfwGetTime();
        v->t += now - v->wall_last;
        v->wall_last = now;
        view_invalidate(v);
    }
    double start = sss_time_seconds();
    sss_result res = render(v, fixed, &rendered, err);
    if (res != SSS_OK) return res;
    view_poll_reference(v);
    view_update_dssim(v);
    if ((res = show_image(v, err)) != SSS_OK) {
        if (fixed) return res;
        view_message(v, "%s", err->message);
    }
    if (screenshot && (res = view_save_screenshot(v, screenshot, err)) != SSS_OK) return res;
    if (v->act_screenshot) key_screenshot(v);
    if ((res = draw_ui(v, fixed, err)) != SSS_OK) return res;
    if (v->shot_path) { /* a script's screenshot: the window as shown, the panel included */
        res = view_save_screenshot(v, v->shot_path, err);
        v->shot_path = NULL;
        if (res != SSS_OK) return res;
    }
    sss_gl_window_swap(v->ctx);
    if (rendered) v->frame_ms = 1000.0 * (sss_time_seconds() - start);
    v->frame_wall_ms = 1000.0 * (sss_time_seconds() - entered);
    if (building && view_rebuild_busy(v)) v->build_frames++; /* drawn while the worker ran */
    if (building && v->frame_wall_ms > v->build_longest_ms) v->build_longest_ms = v->frame_wall_ms;
    view_update_title(v);
    return SSS_OK;
}

/* The next comma-separated event of a script into buf; returns the rest (NULL at the end). */
static const char *next_event(const char *s, char *buf, size_t cap)
{
    if (!s || !*s) return NULL;
    const char *comma = strchr(s, ',');
    size_t n = comma ? (size_t)(comma - s) : strlen(s);
    if (n >= cap) n = cap - 1;
    memcpy(buf, s, n);
    buf[n] = '\0';
    return comma ? comma + 1 : s + strlen(s);
}

static sss_result check_input(viewer *v, const char *input, sss_error *err)
{
    char ev[64];
    int count = 0;
    for (const char *s = next_event(input, ev, sizeof ev); s; s = next_event(s, ev, sizeof ev), count++)
        if (!view_input_event(v, ev, 0))
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                                 "input event '%s' is unknown (keys such as tab, shift+m, l, +; orbit:DX:DY, "
                                 "pan:DX:DY, zoom:STEPS)",
                                 ev);
    if (count > v->desc->frames)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                             "%d input events but %d frames: one input event is applied per frame", count,
                             v->desc->frames);
    return SSS_OK;
}

static sss_result run_fixed(viewer *v, sss_error *err)
{
    const sss_view_desc *d = v->desc;
    const char *script = d->input;
    char ev[64];
    if (d->reference) view_request_reference(v, d->reference_draft);
    for (int k = 0; k < d->frames; k++) {
        glfwPollEvents();
        if ((script = next_event(script, ev, sizeof ev))) view_input_event(v, ev, 1);
        if (v->playing && k > 0) { /* fixed steps: frame k of an animation from the start is at T + k / fps */
            v->t += 1.0 / FRAMES_MODE_FPS;
            view_invalidate(v);
        }
        if (k == d->frames - 1)
            while (v->job && !view_ref_poll(v->job, NULL, NULL)) { /* the DSSIM belongs to the last frame */
                glfwPollEvents();
                sleep_ms(50);
            }
        sss_result res = frame(v, 1, k == d->frames - 1 ? d->screenshot : NULL, err);
        if (res != SSS_OK) return res;
        while (view_rebuild_busy(v)) { /* one event per frame: an edit's build applies before the next */
            glfwPollEvents();
            sleep_ms(10);
            view_poll_rebuild(v);
        }
        if (glfwWindowShouldClose(v->window)) break;
    }
    if (d->reference) {
        if (v->ref && v->dssim_gen) view_message(v, "DSSIM of the last frame vs the %s reference: %.6f",
                                                 v->ref_draft ? "draft" : "final", v->dssim);
        else return sss_error_set(err, SSS_ERROR_NUMERIC, "no DSSIM: %s", v->message);
    }
    return SSS_OK;
}

static void wait_reference(viewer *v)
{
    while (v->job && !view_ref_poll(v->job, NULL, NULL)) {
        glfwPollEvents();
        sleep_ms(50);
    }
}

/* A material edit of the script that failed in the worker: the script stops (at that edit's line). */
static sss_result script_build_error(viewer *v, sss_error *err)
{
    if (!v->build_failed_line) return SSS_OK;
    *err = v->build_err;
    return err->code;
}

/* Frames until the material edits in the background are applied: the window keeps drawing. */
static sss_result wait_rebuild(viewer *v, int *frames, double *longest_ms, sss_error *err)
{
    *frames = 0;
    *longest_ms = 0.0;
    sss_result res = SSS_OK;
    while (res == SSS_OK && view_rebuild_busy(v)) {
        glfwPollEvents();
        res = frame(v, 1, NULL, err);
        (*frames)++;
        if (v->frame_wall_ms > *longest_ms) *longest_ms = v->frame_wall_ms;
    }
    if (res == SSS_OK) res = script_build_error(v, err);
    return res;
}

/* A script's `frames N` (N frames, their median times reported) or `screenshot F` (one frame, the
 * window as shown written after the edits and the reference in the background are done). */
static sss_result script_frames(viewer *v, const view_command *c, sss_error *err)
{
    int n = c->kind == VIEW_CMD_FRAMES ? c->index : 1;
    sss_result res = SSS_OK;
    if (c->kind == VIEW_CMD_SCREENSHOT) {
        int waited = 0;
        double longest = 0.0;
        res = wait_rebuild(v, &waited, &longest, err);
        wait_reference(v);
        v->shot_path = c->text;
    }
    double *ms = calloc(2 * (size_t)n, sizeof *ms), *overlay_ms = ms + n;
    if (!ms) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (frame times)");
    for (int k = 0; k < n && res == SSS_OK; k++) {
        glfwPollEvents();
        res = frame(v, 1, NULL, err);
        ms[k] = v->frame_ms;
        overlay_ms[k] = v->overlay_ms;
        if (res == SSS_OK) res = script_build_error(v, err);
    }
    if (res == SSS_OK && c->kind == VIEW_CMD_SCREENSHOT) view_message(v, "saved %s", c->text);
    else if (res == SSS_OK) /* wall time from render to swap, the panel (when shown) included */
        view_message(v, "%d frames: median frame time %.2f ms, of which %s %.2f ms", n, sss_median(ms, n),
                     v->overlay ? (v->panel ? "panel" : "text overlay") : "hidden panel", sss_median(overlay_ms, n));
    free(ms);
    return res;
}

/* One line of a script: frames and waits run here (they draw), input events go to input.c, the
 * other actions to commands.c. */
static sss_result script_line(viewer *v, const view_command *c, sss_error *err)
{
    sss_result res = SSS_OK;
    if (c->kind == VIEW_CMD_FRAMES || c->kind == VIEW_CMD_SCREENSHOT) {
        res = script_frames(v, c, err);
    } else if (c->kind == VIEW_CMD_WAIT) {
        int frames = 0;
        double longest = 0.0;
        res = wait_rebuild(v, &frames, &longest, err);
        if (res == SSS_OK)
            view_message(v, "wait: %d frames drawn until the material edits were applied (longest %.1f ms)", frames,
                         longest);
    } else if (c->kind == VIEW_CMD_KEY) {
        if (!view_input_event(v, c->name, 1))
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "key: unknown input event '%s'", c->name);
        view_cmd_keys(v);
    } else {
        v->script_line = c->line;
        res = view_cmd_run(v, c, err);
        v->script_line = 0;
    }
    return res;
}

/* --script: each line's action; a failure stops the script, naming its line (for a material edit
 * that failed in the worker, the edit's line). */
static sss_result run_script(viewer *v, const view_script *script, sss_error *err)
{
    for (int i = 0; i < script->count; i++) {
        const view_command *c = &script->commands[i];
        sss_error cerr = {0};
        sss_result res = script_line(v, c, &cerr);
        if (res != SSS_OK) {
            v->shot_path = NULL;
            int line = v->build_failed_line ? v->build_failed_line : c->line;
            return sss_error_set(err, res, "%s:%d: %s", v->desc->script, line, cerr.message);
        }
    }
    int frames = 0;
    double longest = 0.0;
    sss_error cerr = {0};
    if (wait_rebuild(v, &frames, &longest, &cerr) == SSS_OK) return SSS_OK; /* the last edits applied */
    return sss_error_set(err, cerr.code, "%s:%d: %s", v->desc->script, v->build_failed_line, cerr.message);
}

static void run_interactive(viewer *v)
{
    view_install_callbacks(v);
    if (v->desc->reference) view_request_reference(v, v->desc->reference_draft);
    while (!glfwWindowShouldClose(v->window)) {
        int busy = v->need_render || v->playing || v->act_tech || v->act_part || v->act_buffer || v->act_medium ||
                   v->act_light || v->act_reference || v->act_screenshot || v->act_scale != 0.0;
        if (busy) glfwPollEvents();
        else glfwWaitEventsTimeout(view_rebuild_busy(v) ? 0.05 : v->job ? 0.25 : v->panel && v->overlay ? 0.1 : 1.0); /* ImGui settles in a few frames */
        sss_error err = {0};
        frame(v, 0, NULL, &err);
    }
}

/* The viewer's inputs, and its planned outputs (--screenshot, the script's screenshot lines, in
 * order) checked against them and each other before the window opens: a refused script writes
 * nothing. */
static sss_result check_files(viewer *v, const view_script *script, sss_error *err)
{
    const sss_view_desc *d = v->desc;
    scene_add_inputs(&v->files, v->scene);
    sss_io_add_input(&v->files, d->script);
    const char **planned = calloc((size_t)script->count + 1, sizeof *planned);
    if (!planned) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (screenshots)");
    size_t n = 0;
    sss_result res = SSS_OK;
    if (d->screenshot) {
        planned[n++] = d->screenshot;
        res = view_check_outputs(v, planned, n, err);
    }
    for (int i = 0; res == SSS_OK && i < script->count; i++) {
        const view_command *c = &script->commands[i];
        if (c->kind != VIEW_CMD_SCREENSHOT) continue;
        planned[n++] = c->text;
        sss_error cerr = {0};
        if ((res = view_check_outputs(v, planned, n, &cerr)) != SSS_OK)
            sss_error_set(err, res, "%s:%d: screenshot: %s", d->script, c->line, cerr.message);
    }
    free(planned);
    return res;
}

static int technique_index(const char *name)
{
    for (int i = 0; i < sss_gl_technique_count(); i++)
        if (strcmp(sss_gl_technique_at(i)->name, name) == 0) return i;
    return -1;
}

/* The scene (loaded, and its text for edits), the first technique, the --input events and the
 * script (its key events too), the files: all checked before a window opens. */
static sss_result load_inputs(viewer *v, view_script *script, sss_error *err)
{
    const sss_view_desc *desc = v->desc;
    sss_result res = sss_scene_load(desc->scene_path, NULL, v->scene, err);
    if (res == SSS_OK) res = sss_read_file(desc->scene_path, SSS_SCENE_MAX_FILE_SIZE, &v->text, &v->text_size, err);
    if (res != SSS_OK) return res;
    const char *tname = desc->technique ? desc->technique : v->scene->render.technique;
    if ((v->tech = technique_index(tname)) < 0) {
        char list[256] = "";
        size_t at = 0;
        for (int i = 0; i < sss_gl_technique_count() && at < sizeof list; i++)
            at += (size_t)snprintf(list + at, sizeof list - at, "%s%s", i ? ", " : "", sss_gl_technique_at(i)->name);
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "unknown technique '%s' (known: %s)", tname, list);
    }
    if (desc->input && (res = check_input(v, desc->input, err)) != SSS_OK) return res;
    if (desc->script && (res = view_script_load(desc->script, script, err)) != SSS_OK) return res;
    for (int i = 0; i < script->count; i++)
        if (script->commands[i].kind == VIEW_CMD_KEY && !view_input_event(v, script->commands[i].name, 0))
            return sss_error_set(err, SSS_ERROR_PARSE, "%s:%d: key: unknown input event '%s'", desc->script,
                                 script->commands[i].line, script->commands[i].name);
    return check_files(v, script, err);
}

/* The window (its GL context) at the asked size, the first renderer, the overlay's GL objects. */
static sss_result open_window(viewer *v, sss_error *err)
{
    const sss_view_desc *desc = v->desc;
    v->has_light = v->scene->light_count > 0;
    v->home = v->scene->camera;
    sss_gl_context_desc cd;
    memset(&cd, 0, sizeof cd);
    cd.platform = SSS_GL_PLATFORM_WINDOW;
    cd.window_width = desc->width > 0 ? desc->width : v->scene->camera.width;
    cd.window_height = desc->height > 0 ? desc->height : v->scene->camera.height;
    cd.window_title = desc->scene_path;
    sss_result res = sss_gl_context_create(&cd, &v->ctx, err);
    if (res != SSS_OK) return res;
    v->window = glfwGetCurrentContext(); /* the context's window: it was just made current */
    sss_gl_window_size(v->ctx, &v->width, &v->height);
    if (v->width < 1 || v->height < 1) v->width = cd.window_width, v->height = cd.window_height;
    v->scene->camera.width = v->width;
    v->scene->camera.height = v->height;
    view_camera_changed(v);
    res = view_make_renderer(v, v->tech, err);
    v->live_text = view_dup_str(v->text);
    v->live_medium = v->medium;
    v->live_scale = v->scale_factor;
    if (res == SSS_OK && !v->live_text) res = sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (scene text)");
    if (res == SSS_OK) res = view_gl_init(&v->gl, err);
    return res;
}

static void viewer_free(viewer *v)
{
    view_rebuild_free(v);
    if (v->job) view_ref_abandon(v->job); /* the worker finishes on its own and frees its job */
    free(v->job_key);
    view_ref_cache_free(&v->cache);
    free(v->view_key);
    sss_image_free(&v->frame_img);
    sss_image_free(&v->other_img);
    sss_image_free(&v->composed_img);
    sss_image_free(&v->map_img);
    if (v->ctx) {
        sss_gl_context_make_current(v->ctx);
        view_panel_destroy(v);
        view_gl_free(&v->gl);
    }
    sss_gl_renderer_destroy(v->split_r);
    sss_gl_renderer_destroy(v->r);
    sss_gl_timing_series_free(&v->timing_series);
    sss_gl_context_destroy(v->ctx);
    sss_scene_free(v->scene);
    free(v->scene);
    free(v->text);
    sss_io_free(&v->files);
}

sss_result sss_view_run(const sss_view_desc *desc, sss_error *err)
{
    if (!desc || !desc->scene_path) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sss_view_run: no scene");
    if (desc->frames < 0 || (desc->screenshot && desc->frames < 1))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "a screenshot needs a number of frames >= 1");
    viewer v;
    memset(&v, 0, sizeof v);
    v.desc = desc;
    v.medium = -1;
    v.scale_factor = 1.0;
    v.drag_button = -1;
    v.part_saved_tech = -1;
    v.split_pos = 0.5;
    v.overlay = !desc->no_overlay;
    v.t = desc->time;
    v.playing = desc->animate;
    v.scene = calloc(1, sizeof *v.scene);
    if (!v.scene) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (scene)");
    view_script script = {0};
    sss_result res = load_inputs(&v, &script, err);
    if (res == SSS_OK) res = open_window(&v, err);
    if (res == SSS_OK) {
        sss_error perr = {0};
        if (view_panel_create(&v, &perr) != SSS_OK) view_message(&v, "panel: %s (the text overlay instead)", perr.message);
        if (desc->script) res = run_script(&v, &script, err);
        else if (desc->frames > 0) res = run_fixed(&v, err);
        else run_interactive(&v);
    }
    view_script_free(&script);
    viewer_free(&v);
    return res;
}
