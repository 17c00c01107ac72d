/* bench/bench_gl.c — per-pass timings of a real-time technique (default maisch2020) on a scene (default
 * scenes/gl_dragon.json: the 100k-triangle dragon, 11k-triangle splat mesh, two point lights) at
 * 960x540 and 1920x1080: median ms per pass over the timed frames (default 5) after 2 warm-up frames
 * (sss_gl_timing_series), the ratio of each pass and of the whole frame to the screen-space pass, and the GPU memory per pixel and per splat.
 *
 * usage: bench_gl [SCENE.json] [--technique NAME] [--frames N] [--size WxH ...] [NAME=VALUE ...]
 * Timing method: glFinish + monotonic clock per pass on software GL (llvmpipe), GL_TIME_ELAPSED
 * queries on GPUs (printed). Set LP_NUM_THREADS to choose llvmpipe's thread count. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sss/common.h"
#include "sss/gl.h"
#include "sss/scene.h"

#define MAX_FRAMES 64
#define MAX_SIZES 8
#define MAX_PARAMS 32

static int run(sss_gl_context *ctx, const sss_scene *scene, const char *technique, int w, int h, int frames,
               const sss_gl_param_value *params, int nparams)
{
    sss_error err = {0};
    sss_gl_renderer_desc d;
    memset(&d, 0, sizeof d);
    d.technique = technique;
    d.width = w;
    d.height = h;
    d.timings = 1;
    d.params = params;
    d.param_count = nparams;
    sss_gl_renderer *r = NULL;
    double t0 = sss_time_seconds();
    if (sss_gl_renderer_create(ctx, scene, &d, &r, &err) != SSS_OK) {
        fprintf(stderr, "bench_gl: %s\n", err.message);
        return 1;
    }
    double setup = sss_time_seconds() - t0;
    sss_gl_timing_series series;
    if (sss_gl_timing_series_init(&series, SSS_GL_WARMUP_FRAMES, frames, &err) != SSS_OK) {
        fprintf(stderr, "bench_gl: %s\n", err.message);
        sss_gl_renderer_destroy(r);
        return 1;
    }
    sss_gl_timings t;
    for (int f = 0; f < SSS_GL_WARMUP_FRAMES + frames; f++) { /* the series drops the warm-up frames */
        if (sss_gl_renderer_render(r, 0.0, &err) != SSS_OK) {
            fprintf(stderr, "bench_gl: %s\n", err.message);
            sss_gl_timing_series_free(&series);
            sss_gl_renderer_destroy(r);
            return 1;
        }
        sss_gl_renderer_timings(r, &t);
        sss_gl_timing_series_add(&series, &t);
    }
    sss_gl_timing_series_median(&series, &t);
    sss_gl_timing_series_free(&series);
    sss_gl_stats st;
    sss_gl_renderer_stats(r, &st);
    int npass = t.pass_count;
    double screen = 0.0;
    for (int p = 0; p < npass; p++)
        if (strcmp(t.passes[p].name, "screen_space") == 0) screen = t.passes[p].ms;
    double tot = t.total_ms;
    printf("\n%s %dx%d, median of %d frames after %d warm-up, %s; setup (upload, LUTs, programs) %.0f ms\n",
           technique ? technique : scene->render.technique, w, h, frames, SSS_GL_WARMUP_FRAMES, t.method, 1e3 * setup);
    printf("  %-16s %12s %14s\n", "pass", "median ms", "/ screen_space");
    for (int p = 0; p < npass; p++)
        printf("  %-16s %12.1f %14.2f\n", t.passes[p].name, t.passes[p].ms, screen > 0.0 ? t.passes[p].ms / screen : 0.0);
    printf("  %-16s %12.1f %14.2f\n", "total", tot, screen > 0.0 ? tot / screen : 0.0);
    printf("  memory: %zu bytes of screen-sized targets per pixel, %zu bytes per splat (%u of %u splats drawn),\n"
           "          textures %.1f MB (LUTs %.1f MB), buffers %.1f MB\n",
           st.per_pixel_bytes, st.per_splat_bytes, st.splat_drawn, st.splat_total, st.texture_bytes / 1048576.0,
           st.lut_bytes / 1048576.0, st.buffer_bytes / 1048576.0);
    sss_gl_renderer_destroy(r);
    return 0;
}

int main(int argc, char **argv)
{
    const char *path = "scenes/gl_dragon.json", *technique = NULL;
    int frames = SSS_GL_TIMED_FRAMES, nsizes = 0, sizes[MAX_SIZES][2];
    sss_gl_param_value params[MAX_PARAMS];
    char names[MAX_PARAMS][64];
    int nparams = 0;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--technique") == 0 && i + 1 < argc) {
            technique = argv[++i];
        } else if (strcmp(argv[i], "--frames") == 0 && i + 1 < argc) {
            frames = atoi(argv[++i]);
            if (frames < 1 || frames > MAX_FRAMES) {
                fprintf(stderr, "bench_gl: --frames must be in 1..%d\n", MAX_FRAMES);
                return 2;
            }
        } else if (strcmp(argv[i], "--size") == 0 && i + 1 < argc && nsizes < MAX_SIZES) {
            if (sscanf(argv[++i], "%dx%d", &sizes[nsizes][0], &sizes[nsizes][1]) != 2) {
                fprintf(stderr, "bench_gl: --size expects WxH\n");
                return 2;
            }
            nsizes++;
        } else if (strchr(argv[i], '=') && nparams < MAX_PARAMS) {
            const char *eq = strchr(argv[i], '=');
            size_t n = (size_t)(eq - argv[i]) < sizeof names[0] - 1 ? (size_t)(eq - argv[i]) : sizeof names[0] - 1;
            memcpy(names[nparams], argv[i], n);
            names[nparams][n] = '\0';
            params[nparams].name = names[nparams];
            params[nparams].value = atof(eq + 1);
            nparams++;
        } else if (argv[i][0] != '-') {
            path = argv[i];
        } else {
            fprintf(stderr, "usage: bench_gl [SCENE.json] [--technique NAME] [--frames N] [--size WxH ...] "
                            "[NAME=VALUE ...]\n");
            return 2;
        }
    }
    if (nsizes == 0) {
        sizes[0][0] = 960, sizes[0][1] = 540;
        sizes[1][0] = 1920, sizes[1][1] = 1080;
        nsizes = 2;
    }
    sss_error err = {0};
    sss_scene scene;
    if (sss_scene_load(path, NULL, &scene, &err) != SSS_OK) {
        fprintf(stderr, "bench_gl: %s\n", err.message);
        return 1;
    }
    sss_gl_context *ctx = NULL;
    if (sss_gl_context_create(NULL, &ctx, &err) != SSS_OK) {
        fprintf(stderr, "bench_gl: %s\n", err.message);
        sss_scene_free(&scene);
        return 1;
    }
    sss_gl_context_info info;
    sss_gl_context_get_info(ctx, &info);
    printf("bench_gl: %s on %s (%s)\n", path, info.renderer, info.version);
    int status = 0;
    for (int i = 0; i < nsizes && !status; i++)
        status = run(ctx, &scene, technique, sizes[i][0], sizes[i][1], frames, params, nparams);
    sss_gl_context_destroy(ctx);
    sss_scene_free(&scene);
    return status;
}
