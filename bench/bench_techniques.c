/* bench/bench_techniques.c — every technique on one scene, in one run: median ms per pass and per
 * frame (5 timed frames after 2 warm-up, sss_gl_timing_series), the frame's ratio to ssss, and GPU
 * memory per pixel, at 960x540 and 1920x1080 by default; --zoom F moves the camera F times its
 * distance from the look-at point (F > 1: the object smaller on screen), so that cost can be seen to
 * follow the object's size.
 *
 * usage: bench_techniques [SCENE.json] [--techniques a,b,...] [--frames N] [--size WxH ...] [--zoom F ...]
 * A technique may carry parameters as in `sss eval`: NAME:param=value[:param=value] (maisch2020:outer_divisor=2).
 * Timing method: glFinish + monotonic clock per pass on software GL (llvmpipe), GL_TIME_ELAPSED
 * queries on GPUs. Default scene: scenes/gl_dragon.json. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sss/gl.h"
#include "sss/scene.h"

#define MAX_LIST 16
#define MAX_SPEC_PARAMS 16

typedef struct result {
    const char *technique;
    sss_gl_timings median;
    size_t per_pixel_bytes;
    int ok;
} result;

/* Splits a spec NAME[:param=value...] into name and parameters; the pointers point into `copy`. */
static int parse_spec(const char *spec, char *copy, size_t cap, sss_gl_param_value *params, int *count)
{
    snprintf(copy, cap, "%s", spec);
    *count = 0;
    char *colon = strchr(copy, ':');
    while (colon) {
        *colon = '\0';
        char *item = colon + 1, *eq = strchr(item, '=');
        colon = strchr(item, ':');
        if (!eq || *count == MAX_SPEC_PARAMS) return 0;
        *eq = '\0';
        params[(*count)++] = (sss_gl_param_value){item, atof(eq + 1)};
    }
    return 1;
}

static int time_technique(sss_gl_context *ctx, const sss_scene *scene, int w, int h, int frames, result *out)
{
    sss_error err = {0};
    sss_gl_renderer_desc d;
    memset(&d, 0, sizeof d);
    char name[256];
    sss_gl_param_value params[MAX_SPEC_PARAMS];
    int nparams = 0;
    if (!parse_spec(out->technique, name, sizeof name, params, &nparams)) {
        fprintf(stderr, "bench_techniques: %s: expected NAME:param=value[:param=value]\n", out->technique);
        out->ok = 0;
        return 0;
    }
    d.technique = name;
    d.params = params;
    d.param_count = nparams;
    d.width = w;
    d.height = h;
    d.timings = 1;
    sss_gl_renderer *r = NULL;
    sss_gl_timing_series series;
    if (sss_gl_timing_series_init(&series, SSS_GL_WARMUP_FRAMES, frames, &err) != SSS_OK ||
        sss_gl_renderer_create(ctx, scene, &d, &r, &err) != SSS_OK) {
        fprintf(stderr, "bench_techniques: %s: %s\n", out->technique, err.message);
        sss_gl_timing_series_free(&series);
        return 0;
    }
    for (int f = 0; f < SSS_GL_WARMUP_FRAMES + frames; f++) {
        sss_gl_timings t;
        if (sss_gl_renderer_render(r, 0.0, &err) != SSS_OK) {
            fprintf(stderr, "bench_techniques: %s: %s\n", out->technique, err.message);
            break;
        }
        sss_gl_renderer_timings(r, &t);
        sss_gl_timing_series_add(&series, &t);
    }
    sss_gl_timing_series_median(&series, &out->median);
    sss_gl_stats st;
    sss_gl_renderer_stats(r, &st);
    out->per_pixel_bytes = st.per_pixel_bytes;
    out->ok = series.timed == frames;
    sss_gl_timing_series_free(&series);
    sss_gl_renderer_destroy(r);
    return out->ok;
}

static void print_table(result *res, int n, int w, int h, double zoom, int frames)
{
    double ssss = 0.0;
    for (int i = 0; i < n; i++)
        if (res[i].ok && strcmp(res[i].technique, "ssss") == 0) ssss = res[i].median.total_ms;
    printf("\n%dx%d, zoom %g: median of %d frames after %d warm-up (%s)\n", w, h, zoom, frames, SSS_GL_WARMUP_FRAMES,
           n > 0 && res[0].ok ? res[0].median.method : "-");
    printf("  %-14s %10s %8s %8s  %s\n", "technique", "frame ms", "/ ssss", "B/pixel", "passes (ms)");
    for (int i = 0; i < n; i++) {
        if (!res[i].ok) {
            printf("  %-14s %10s\n", res[i].technique, "failed");
            continue;
        }
        printf("  %-14s %10.1f %8.2f %8zu ", res[i].technique, res[i].median.total_ms,
               ssss > 0.0 ? res[i].median.total_ms / ssss : 0.0, res[i].per_pixel_bytes);
        for (int p = 0; p < res[i].median.pass_count; p++)
            printf(" %s %.1f", res[i].median.passes[p].name, res[i].median.passes[p].ms);
        printf("\n");
    }
}

/* The scene's camera moved zoom times as far from its look-at point. */
static void zoom_camera(sss_scene *scene, const double position[3], double zoom)
{
    for (int k = 0; k < 3; k++)
        scene->camera.position[k] = scene->camera.look_at[k] + (position[k] - scene->camera.look_at[k]) * zoom;
}

static int parse_args(int argc, char **argv, const char **path, char *list, size_t cap, int *frames,
                      int sizes[][2], int *nsizes, double *zooms, int *nzooms)
{
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(a, "--techniques") == 0 && v) {
            snprintf(list, cap, "%s", v);
        } else if (strcmp(a, "--frames") == 0 && v) {
            *frames = atoi(v);
            if (*frames < 1 || *frames > 1000) return 0;
        } else if (strcmp(a, "--size") == 0 && v && *nsizes < MAX_LIST) {
            if (sscanf(v, "%dx%d", &sizes[*nsizes][0], &sizes[*nsizes][1]) != 2) return 0;
            (*nsizes)++;
        } else if (strcmp(a, "--zoom") == 0 && v && *nzooms < MAX_LIST) {
            zooms[*nzooms] = atof(v);
            if (!(zooms[(*nzooms)++] > 0.0)) return 0;
        } else if (a[0] != '-') {
            *path = a;
            continue;
        } else {
            return 0;
        }
        i++;
    }
    return 1;
}

int main(int argc, char **argv)
{
    const char *path = "scenes/gl_dragon.json";
    char list[1024] = "";
    int frames = SSS_GL_TIMED_FRAMES, nsizes = 0, sizes[MAX_LIST][2], nzooms = 0;
    double zooms[MAX_LIST];
    if (!parse_args(argc, argv, &path, list, sizeof list, &frames, sizes, &nsizes, zooms, &nzooms)) {
        fprintf(stderr, "usage: bench_techniques [SCENE.json] [--techniques a,b,...] [--frames N] [--size WxH ...] "
                        "[--zoom F ...]\n");
        return 2;
    }
    if (nsizes == 0) {
        sizes[0][0] = 960, sizes[0][1] = 540, sizes[1][0] = 1920, sizes[1][1] = 1080;
        nsizes = 2;
    }
    if (nzooms == 0) zooms[nzooms++] = 1.0;
    result res[64];
    int n = 0;
    if (list[0]) {
        for (char *tok = strtok(list, ","); tok && n < 64; tok = strtok(NULL, ",")) res[n++].technique = tok;
    } else {
        for (int i = 0; i < sss_gl_technique_count() && n < 64; i++) res[n++].technique = sss_gl_technique_at(i)->name;
    }
    sss_error err = {0};
    sss_scene scene;
    sss_gl_context *ctx = NULL;
    if (sss_scene_load(path, NULL, &scene, &err) != SSS_OK || sss_gl_context_create(NULL, &ctx, &err) != SSS_OK) {
        fprintf(stderr, "bench_techniques: %s\n", err.message);
        return 1;
    }
    sss_gl_context_info info;
    sss_gl_context_get_info(ctx, &info);
    printf("bench_techniques: %s on %s (%s)\n", path, info.renderer, info.version);
    double position[3] = {scene.camera.position[0], scene.camera.position[1], scene.camera.position[2]};
    for (int z = 0; z < nzooms; z++) {
        zoom_camera(&scene, position, zooms[z]);
        for (int s = 0; s < nsizes; s++) {
            for (int i = 0; i < n; i++) time_technique(ctx, &scene, sizes[s][0], sizes[s][1], frames, &res[i]);
            print_table(res, n, sizes[s][0], sizes[s][1], zooms[z], frames);
            fflush(stdout);
        }
    }
    sss_gl_context_destroy(ctx);
    sss_scene_free(&scene);
    return 0;
}
