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

sss_result eval_run_technique(eval_gl *rc, const sss_scene *view, double t, const eval_spec *spec, int nparams,
                              int frames, sss_eval_entry *e, const char *stage)
{
    e->ok = 0;
    e->frames = 0;
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
    double *series = calloc((size_t)(SSS_GL_MAX_PASSES + 1) * (size_t)frames, sizeof *series);
    const char *names[SSS_GL_MAX_PASSES];
    int counts[SSS_GL_MAX_PASSES] = {0};
    int npass = 0;
    if (!series) {
        sss_gl_renderer_destroy(r);
        return sss_error_set(NULL, SSS_ERROR_OUT_OF_MEMORY, "out of memory");
    }
    double *totals = series + (size_t)SSS_GL_MAX_PASSES * (size_t)frames;
    sss_image img = {0};
    int ok = sss_image_create(&img, rd.width, rd.height, &err) == SSS_OK;
    for (int f = 0; ok && f < frames; f++) {
        snprintf(st, sizeof st, "%s: frame %d/%d", stage, f + 1, frames);
        eval_progress_update(rc->prog, (1.0 + f) / (frames + 1.0), st);
        if (sss_gl_renderer_render(r, t, &err) != SSS_OK) {
            ok = 0;
            break;
        }
        sss_gl_timings tm;
        sss_gl_renderer_timings(r, &tm);
        if (tm.method) rc->method = tm.method;
        totals[f] = tm.total_ms;
        for (int p = 0; p < tm.pass_count; p++) {
            int j = 0;
            while (j < npass && strcmp(names[j], tm.passes[p].name) != 0) j++;
            if (j == npass) {
                if (npass >= SSS_GL_MAX_PASSES) continue;
                names[npass++] = tm.passes[p].name;
            }
            /* a pass name repeated within a frame adds up */
            if (counts[j] == f + 1) series[(size_t)j * (size_t)frames + (size_t)f] += tm.passes[p].ms;
            else {
                series[(size_t)j * (size_t)frames + (size_t)f] = tm.passes[p].ms;
                counts[j] = f + 1;
            }
        }
        e->frames = f + 1;
    }
    if (ok) ok = sss_gl_renderer_read(r, &img, &err) == SSS_OK;
    if (ok) {
        e->ok = 1;
        e->total_ms = sss_median(totals, frames);
        e->pass_count = npass;
        for (int j = 0; j < npass; j++) {
            snprintf(e->passes[j].name, sizeof e->passes[j].name, "%s", names[j]);
            /* frames in which the pass did not run count as 0 ms */
            e->passes[j].ms = sss_median(series + (size_t)j * (size_t)frames, frames);
        }
        sss_gl_renderer_stats(r, &e->stats);
        e->has_stats = 1;
        e->image = img;
        img.pixels = NULL;
    } else {
        eval_fail_entry(e, err.message);
    }
    sss_image_free(&img);
    free(series);
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

