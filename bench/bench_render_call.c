/* bench/bench_render_call.c — the C side of the Python module's overhead (bench/bench_python.py): median
 * ms of one frame as a program gets it, sss_gl_renderer_render + sss_gl_renderer_read into an image,
 * after warm-up frames, on one renderer (no pass timings: no glFinish per pass).
 *
 * usage: bench_render_call SCENE.json TECHNIQUE WIDTH HEIGHT FRAMES [NAME=VALUE ...]
 * Prints "median_ms M" (and min/max) on stdout. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"
#include "sss/gl.h"
#include "sss/scene.h"

#define WARMUP 5
#define MAX_PARAMS 16

typedef struct frame_ctx {
    sss_gl_renderer *r;
    sss_image img;
    int failed;
} frame_ctx;

static void frame(void *user)
{
    frame_ctx *f = user;
    sss_error err = {0};
    if (sss_gl_renderer_render(f->r, 0.0, &err) != SSS_OK || sss_gl_renderer_read(f->r, &f->img, &err) != SSS_OK) {
        if (!f->failed) fprintf(stderr, "bench_render_call: %s\n", err.message);
        f->failed = 1;
    }
}

int main(int argc, char **argv)
{
    if (argc < 6 || argc - 6 > MAX_PARAMS) {
        fprintf(stderr, "usage: bench_render_call SCENE.json TECHNIQUE WIDTH HEIGHT FRAMES [NAME=VALUE ...]\n");
        return 2;
    }
    sss_gl_param_value params[MAX_PARAMS];
    char names[MAX_PARAMS][64];
    int nparams = 0;
    for (int i = 6; i < argc; i++, nparams++) {
        const char *eq = strchr(argv[i], '=');
        if (!eq || (size_t)(eq - argv[i]) >= sizeof names[0]) return fprintf(stderr, "bad NAME=VALUE: %s\n", argv[i]), 2;
        memcpy(names[nparams], argv[i], (size_t)(eq - argv[i]));
        names[nparams][eq - argv[i]] = '\0';
        params[nparams].name = names[nparams];
        params[nparams].value = atof(eq + 1);
    }
    sss_error err = {0};
    sss_scene scene;
    if (sss_scene_load(argv[1], NULL, &scene, &err) != SSS_OK) return fprintf(stderr, "%s\n", err.message), 1;
    sss_gl_context_desc cdesc;
    memset(&cdesc, 0, sizeof cdesc);
    sss_gl_renderer_desc d;
    memset(&d, 0, sizeof d);
    d.technique = argv[2];
    d.width = atoi(argv[3]);
    d.height = atoi(argv[4]);
    d.params = params;
    d.param_count = nparams;
    int frames = atoi(argv[5]);
    sss_gl_context *ctx = NULL;
    frame_ctx f = {0};
    int status = 1;
    if (sss_gl_context_create(&cdesc, &ctx, &err) == SSS_OK && sss_gl_renderer_create(ctx, &scene, &d, &f.r, &err) == SSS_OK &&
        sss_image_create(&f.img, d.width, d.height, &err) == SSS_OK) {
        for (int i = 0; i < WARMUP; i++) frame(&f);
        bench_run("render + read", frames > 0 ? frames : 1, frame, &f);
        status = f.failed;
    } else {
        fprintf(stderr, "bench_render_call: %s\n", err.message);
    }
    sss_image_free(&f.img);
    sss_gl_renderer_destroy(f.r);
    sss_gl_context_destroy(ctx);
    sss_scene_free(&scene);
    return status;
}
