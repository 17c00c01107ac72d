/* eval/eval_tech.c — one technique at one size: renderer set-up time, N timed frames (median per
 * pass and of the totals), read-back, statistics; failures recorded in the entry. Also the progress
 * bookkeeping and the SAM sweep's parameter lookup. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "eval/eval_internal.h"

/* ---- Progress -------------------------------------------------------------------------------- */

void eval_progress_update(eval_progress *p, double step_fraction, const char *stage)
{
    if (stage) snprintf(p->stage, sizeof p->stage, "%s", stage);
    if (!p->cb || !p->cb->progress) return;
    if (step_fraction < 0) step_fraction = 0;
    if (step_fraction > 1) step_fraction = 1;
    double f = p->total > 0 ? (p->done + step_fraction * p->step) / p->total : 1.0;
    p->cb->progress(p->cb->user, f > 1 ? 1 : f, p->stage);
}

void eval_progress_finish_step(eval_progress *p)
{
    p->done += p->step;
    p->step = 0;
}

void eval_note(eval_progress *p, const char *fmt, ...)
{
    if (!p || !p->cb || !p->cb->note) return;
    char msg[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    p->cb->note(p->cb->user, msg);
}

/* ---- One technique at one size ----------------------------------------------------------------- */

void eval_fail_entry(sss_eval_entry *e, const char *msg)
{
    e->ok = 0;
    snprintf(e->error, sizeof e->error, "%s", msg && msg[0] ? msg : "unknown error");
}

/* One frame: its GPU timings and its wall seconds (render call to return, glFinish included). */
static int render_frame(eval_gl *rc, sss_gl_renderer *r, double t, sss_gl_timings *tm, double *seconds,
                        sss_error *err)
{
    double t0 = sss_time_seconds();
    if (sss_gl_renderer_render(r, t, err) != SSS_OK) return 0;
    *seconds = sss_time_seconds() - t0;
    sss_gl_renderer_timings(r, tm);
    if (tm->method) rc->method = tm->method;
    return 1;
}

/* The warm-up and timed frames into series (made with rc->warmup_frames to drop). Under a frame budget
 * (sss_eval_desc.frame_budget_s) the timed frames stop once they have taken it, and a first warm-up
 * frame that alone took longer becomes the one timed frame: a slow technique costs one frame, not
 * warm-up + frames of them, and its entry says it had no warm-up. */
static int render_frames(eval_gl *rc, sss_gl_renderer *r, double t, int frames, const char *stage,
                         sss_gl_timing_series *series, sss_eval_entry *e, sss_error *err)
{
    double budget = rc->frame_budget_s, timed_s = 0, s = 0;
    char st[256];
    for (int f = 0; f < series->warmup + frames; f++) {
        if (budget > 0 && series->timed > 0 && timed_s >= budget) break;
        int warm = f < series->warmup, total = series->warmup + frames;
        if (warm) snprintf(st, sizeof st, "%s: warm-up frame %d/%d", stage, f + 1, series->warmup);
        else snprintf(st, sizeof st, "%s: frame %d/%d", stage, f - series->warmup + 1, frames);
        eval_progress_update(rc->prog, (1.0 + f) / (total + 1.0), st);
        sss_gl_timings tm;
        if (!render_frame(rc, r, t, &tm, &s, err)) return 0;
        if (f == 0 && warm && budget > 0 && s > budget) {
            series->warmup = 0; /* nothing added yet: the first frame is the timed one */
            warm = 0;
        }
        if (!warm) timed_s += s;
        sss_gl_timing_series_add(series, &tm);
        e->frames = series->timed;
        e->warmup_frames = series->warmup;
    }
    return 1;
}

sss_result eval_run_technique(eval_gl *rc, const sss_scene *view, double t, const eval_spec *spec, int nparams,
                              int frames, sss_eval_entry *e, const char *stage)
{
    e->ok = 0;
    e->frames = 0;
    e->warmup_frames = 0;
    if (!rc->gl) {
        eval_fail_entry(e, rc->gl_error);
        return SSS_OK;
    }
    sss_error err = {0};
    /* "supersample" in a spec is the renderer's SSAA factor, not a technique parameter */
    sss_gl_param_value params[EVAL_MAX_SPEC_PARAMS + 1];
    int np = 0, k = rc->supersample > 0 ? rc->supersample : 1;
    for (int i = 0; i < nparams && i < EVAL_MAX_SPEC_PARAMS + 1; i++) {
        if (strcmp(spec->params[i].name, "supersample") != 0) {
            params[np++] = spec->params[i];
            continue;
        }
        double v = spec->params[i].value;
        if (v != floor(v) || v < 0 || v > SSS_GL_MAX_SUPERSAMPLE) {
            char msg[128];
            snprintf(msg, sizeof msg, "supersample = %g must be an integer in 1..%d (0: 1, off)", v,
                     SSS_GL_MAX_SUPERSAMPLE);
            eval_fail_entry(e, msg);
            return SSS_OK;
        }
        k = v == 0 ? 1 : (int)v;
    }
    e->supersample = k;
    sss_gl_renderer_desc rd;
    memset(&rd, 0, sizeof rd);
    rd.technique = spec->name;
    rd.width = view->camera.width;
    rd.height = view->camera.height;
    rd.params = params;
    rd.param_count = np;
    rd.timings = 1;
    rd.supersample = k;
    char st[256];
    snprintf(st, sizeof st, "%s: set-up", stage);
    eval_progress_update(rc->prog, 0.0, st);
    sss_gl_renderer *r = NULL;
    double t0 = sss_time_seconds();
    if (sss_gl_renderer_create(rc->gl, view, &rd, &r, &err) != SSS_OK) {
        eval_fail_entry(e, err.message);
        return SSS_OK;
    }
    e->precompute_ms = 1000.0 * (sss_time_seconds() - t0);
    if (sss_gl_kernel_cut_warnings(view, &rd, e->warning, sizeof e->warning) > 0 && e->kind == SSS_EVAL_QUALITY)
        eval_note(rc->prog, "warning: %s: %s", stage, e->warning);
    sss_gl_timing_series series;
    if (sss_gl_timing_series_init(&series, rc->warmup_frames, frames, &err) != SSS_OK) {
        sss_gl_renderer_destroy(r);
        return sss_error_set(NULL, err.code, "%s", err.message);
    }
    sss_image img = {0};
    int ok = sss_image_create(&img, rd.width, rd.height, &err) == SSS_OK;
    if (ok) ok = render_frames(rc, r, t, frames, stage, &series, e, &err);
    if (ok) ok = sss_gl_renderer_read(r, &img, &err) == SSS_OK;
    if (ok && rc->object_ids && !rc->object_ids->pixels &&
        sss_gl_renderer_read_buffer(r, "object_id", rc->object_ids, NULL) != SSS_OK)
        sss_image_free(rc->object_ids); /* no silhouette crops: not an error of the technique */
    if (ok) {
        sss_gl_timings median;
        sss_gl_timing_series_median(&series, &median);
        e->ok = 1;
        e->total_ms = median.total_ms;
        e->pass_count = median.pass_count;
        for (int j = 0; j < median.pass_count; j++) {
            snprintf(e->passes[j].name, sizeof e->passes[j].name, "%s", median.passes[j].name);
            e->passes[j].ms = median.passes[j].ms;
        }
        sss_gl_renderer_stats(r, &e->stats);
        e->has_stats = 1;
        e->image = img;
        img.pixels = NULL;
    } else {
        eval_fail_entry(e, err.message);
    }
    sss_image_free(&img);
    sss_gl_timing_series_free(&series);
    sss_gl_renderer_destroy(r);
    return SSS_OK;
}

/* ---- The SAM sweep --------------------------------------------------------------------------- */

const int eval_default_sam_counts[EVAL_DEFAULT_SAM_COUNTS] = {3, 10, 20, 50};

/* The sam technique's back-side sample count (Maisch & Ropinski 2017, 4.1: n = 3): a parameter named like one of
 * these, else an integer parameter whose name or doc mentions the back side. */
const sss_gl_param_info *eval_find_sam_param(const sss_gl_technique_info *t)
{
    /* not "samples": sam's Monte Carlo pairs per form factor */
    static const char *const names[] = {"back_samples", "back_side_samples", "backside_samples", "n_back", "n"};
    for (size_t k = 0; k < sizeof names / sizeof names[0]; k++)
        for (int i = 0; i < t->param_count; i++)
            if (strcmp(t->params[i].name, names[k]) == 0 && t->params[i].type == SSS_GL_PARAM_INT) return &t->params[i];
    for (int i = 0; i < t->param_count; i++)
        if (t->params[i].type == SSS_GL_PARAM_INT &&
            (strstr(t->params[i].name, "back") || (t->params[i].doc && strstr(t->params[i].doc, "back"))))
            return &t->params[i];
    return NULL;
}

