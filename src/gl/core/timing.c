/* gl/timing.c — per-pass timings.
 *
 * On software rasterisers (llvmpipe) GL_TIME_ELAPSED reports nonsense (GL-NOTES.md: 21 ms for a 4.1 s
 * pass), so each pass is bracketed by glFinish() and the monotonic clock; on real GPUs timer queries
 * measure without stalling the pipeline. With timing disabled nothing is inserted.
 */
#include <string.h>

#include "gl/core/gl_base.h"

void gl_timer_init(gl_timer *t, int enabled, int software)
{
    memset(t, 0, sizeof *t);
    t->enabled = enabled;
    t->use_queries = enabled && !software;
    t->open = -1;
    if (t->use_queries) glGenQueries(SSS_GL_MAX_PASSES, t->queries);
}

void gl_timer_free(gl_timer *t)
{
    if (t->use_queries && t->queries[0]) glDeleteQueries(SSS_GL_MAX_PASSES, t->queries);
    memset(t, 0, sizeof *t);
    t->open = -1;
}

void gl_timer_frame_begin(gl_timer *t)
{
    t->count = 0;
    t->open = -1;
    if (t->enabled && !t->use_queries) glFinish(); /* work queued before the frame is not ours */
}

void gl_timer_begin(gl_timer *t, const char *name)
{
    if (!t->enabled || t->count >= SSS_GL_MAX_PASSES) return;
    if (t->open >= 0) gl_timer_end(t);
    int i = t->count++;
    t->names[i] = name;
    t->ms[i] = 0.0;
    t->open = i;
    if (t->use_queries) glBeginQuery(GL_TIME_ELAPSED, t->queries[i]);
    else t->t0 = sss_time_seconds();
}

void gl_timer_end(gl_timer *t)
{
    if (!t->enabled || t->open < 0) return;
    if (t->use_queries) {
        glEndQuery(GL_TIME_ELAPSED);
    } else {
        glFinish();
        t->ms[t->open] = 1e3 * (sss_time_seconds() - t->t0);
    }
    t->open = -1;
}

void gl_timer_frame_end(gl_timer *t)
{
    if (!t->enabled) return;
    if (t->open >= 0) gl_timer_end(t);
    if (!t->use_queries) return;
    for (int i = 0; i < t->count; i++) {
        GLuint64 ns = 0;
        glGetQueryObjectui64v(t->queries[i], GL_QUERY_RESULT, &ns);
        t->ms[i] = (double)ns * 1e-6;
    }
}
