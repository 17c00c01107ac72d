/* gl/timing_series.c — per-pass medians over frames after warm-up (sss/gl.h, sss_gl_timing_series). */
#include <stdlib.h>
#include <string.h>

#include "sss/gl.h"

sss_result sss_gl_timing_series_init(sss_gl_timing_series *s, int warmup, int timed_frames, sss_error *err)
{
    memset(s, 0, sizeof *s);
    if (warmup < 0 || timed_frames < 1)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                             "timing: %d warm-up and %d timed frames (need >= 0 and >= 1)", warmup, timed_frames);
    s->ms = calloc((size_t)(SSS_GL_MAX_PASSES + 1) * (size_t)timed_frames, sizeof *s->ms);
    if (!s->ms) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "timing: out of memory (%d frames)", timed_frames);
    s->warmup = warmup;
    s->capacity = timed_frames;
    return SSS_OK;
}

static int pass_slot(sss_gl_timing_series *s, const char *name)
{
    for (int j = 0; j < s->pass_count; j++)
        if (strcmp(s->pass_names[j], name) == 0) return j;
    if (s->pass_count >= SSS_GL_MAX_PASSES) return -1;
    s->pass_names[s->pass_count] = name;
    return s->pass_count++;
}

/* Makes room for one more timed frame by dropping the oldest (a full series keeps the latest). */
static void drop_oldest(sss_gl_timing_series *s)
{
    for (int row = 0; row <= SSS_GL_MAX_PASSES; row++) {
        double *r = s->ms + (size_t)row * s->capacity;
        memmove(r, r + 1, (size_t)(s->capacity - 1) * sizeof *r);
        r[s->capacity - 1] = 0.0;
    }
    s->timed--;
}

void sss_gl_timing_series_add(sss_gl_timing_series *s, const sss_gl_timings *frame)
{
    if (s->capacity < 1 || s->added++ < s->warmup) return;
    if (s->timed == s->capacity) drop_oldest(s);
    int f = s->timed++;
    if (frame->method) s->method = frame->method;
    for (int p = 0; p < frame->pass_count; p++) {
        int j = pass_slot(s, frame->passes[p].name);
        if (j >= 0) s->ms[(size_t)j * s->capacity + f] += frame->passes[p].ms;
    }
    s->ms[(size_t)SSS_GL_MAX_PASSES * s->capacity + f] = frame->total_ms;
}

void sss_gl_timing_series_median(const sss_gl_timing_series *s, sss_gl_timings *out)
{
    memset(out, 0, sizeof *out);
    out->method = s->method ? s->method : "off";
    if (s->timed < 1) return;
    double *tmp = malloc((size_t)s->timed * sizeof *tmp);
    if (!tmp) return;
    out->pass_count = s->pass_count;
    for (int j = 0; j <= s->pass_count; j++) {
        int row = j < s->pass_count ? j : SSS_GL_MAX_PASSES;
        memcpy(tmp, s->ms + (size_t)row * s->capacity, (size_t)s->timed * sizeof *tmp);
        double med = sss_median(tmp, s->timed);
        if (j < s->pass_count) {
            out->passes[j].name = s->pass_names[j];
            out->passes[j].ms = med;
        } else {
            out->total_ms = med;
        }
    }
    free(tmp);
}

void sss_gl_timing_series_free(sss_gl_timing_series *s)
{
    free(s->ms);
    memset(s, 0, sizeof *s);
}
