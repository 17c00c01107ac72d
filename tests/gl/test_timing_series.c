/* tests/gl/test_timing_series.c — the bookkeeping behind every reported frame time (sss render
 * --timings, sss eval, sss view, bench_gl): frames of known, injected cost go in; the warm-up frames
 * must not count, the median is per pass over the timed frames, a pass run twice in a frame adds up,
 * a pass missing from a frame counts 0 ms there, and a full series keeps the latest frames. No clock
 * is read: the costs are made up. */
#include <string.h>

#include "check.h"
#include "sss/gl.h"

/* One frame: pass names and costs (a name may repeat), the total as the renderer reports it. */
static sss_gl_timings frame(int n, const char *const *names, const double *ms)
{
    sss_gl_timings t;
    memset(&t, 0, sizeof t);
    t.method = "injected";
    for (int i = 0; i < n; i++) {
        t.passes[i].name = names[i];
        t.passes[i].ms = ms[i];
        t.total_ms += ms[i];
    }
    t.pass_count = n;
    return t;
}

static double pass_ms(const sss_gl_timings *t, const char *name)
{
    for (int i = 0; i < t->pass_count; i++)
        if (strcmp(t->passes[i].name, name) == 0) return t->passes[i].ms;
    return -1.0;
}

static void test_warmup_and_median(void)
{
    sss_gl_timing_series s;
    sss_error err = {0};
    CHECK(sss_gl_timing_series_init(&s, 2, 5, &err) == SSS_OK);
    const char *names[] = {"gbuffer", "screen_space", "screen_space"};
    /* two warm-up frames 100x slower, as a first frame on llvmpipe is */
    for (int k = 0; k < 2; k++) {
        sss_gl_timings w = frame(3, names, (double[]){1000, 2000, 2000});
        sss_gl_timing_series_add(&s, &w);
    }
    sss_gl_timings empty;
    sss_gl_timing_series_median(&s, &empty);
    CHECK(s.timed == 0 && empty.pass_count == 0);
    const double gbuffer[5] = {10, 14, 11, 9, 13}, screen[5] = {3, 5, 4, 2, 6};
    for (int k = 0; k < 5; k++) {
        /* screen_space runs twice: 3 + 1 etc.; a late pass appears in frames 3 and 4 only */
        const char *n4[] = {"gbuffer", "screen_space", "screen_space", "late"};
        sss_gl_timings f = frame(k >= 3 ? 4 : 3, n4, (double[]){gbuffer[k], screen[k], 1.0, 50.0});
        sss_gl_timing_series_add(&s, &f);
    }
    sss_gl_timings m;
    sss_gl_timing_series_median(&s, &m);
    CHECK(s.timed == 5 && m.pass_count == 3);
    CHECK_NEAR(pass_ms(&m, "gbuffer"), 11.0, 1e-12);          /* median of 9..14 */
    CHECK_NEAR(pass_ms(&m, "screen_space"), 5.0, 1e-12);      /* median of {4, 6, 5, 3, 7} */
    CHECK_NEAR(pass_ms(&m, "late"), 0.0, 1e-12);              /* {0, 0, 0, 50, 50} */
    /* totals per frame: 14, 20, 16, 62, 70 -> 20 */
    CHECK_NEAR(m.total_ms, 20.0, 1e-12);
    CHECK(strcmp(m.method, "injected") == 0);
    /* a sixth frame replaces the oldest: gbuffer {14, 11, 9, 13, 100} -> 13 */
    sss_gl_timings f6 = frame(1, names, (double[]){100});
    sss_gl_timing_series_add(&s, &f6);
    sss_gl_timing_series_median(&s, &m);
    CHECK(s.timed == 5);
    CHECK_NEAR(pass_ms(&m, "gbuffer"), 13.0, 1e-12);
    CHECK_NEAR(pass_ms(&m, "late"), 0.0, 1e-12); /* {0, 0, 50, 50, 0} */
    sss_gl_timing_series_free(&s);
}

static void test_errors(void)
{
    sss_gl_timing_series s;
    sss_error err = {0};
    CHECK(sss_gl_timing_series_init(&s, -1, 5, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(sss_gl_timing_series_init(&s, 2, 0, &err) == SSS_ERROR_INVALID_ARGUMENT);
    /* a zeroed series takes frames without effect */
    sss_gl_timing_series z;
    memset(&z, 0, sizeof z);
    const char *names[] = {"gbuffer"};
    sss_gl_timings f = frame(1, names, (double[]){1});
    sss_gl_timing_series_add(&z, &f);
    sss_gl_timings m;
    sss_gl_timing_series_median(&z, &m);
    CHECK(m.pass_count == 0);
    sss_gl_timing_series_free(&z);
}

int main(void)
{
    test_warmup_and_median();
    test_errors();
    return CHECK_DONE();
}
