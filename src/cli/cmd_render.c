/* cli/cmd_render.c — `sss render SCENE.json -o OUT.png`: renders a scene with a real-time technique on a
 * headless OpenGL context (EGL) and writes the image; optional EXR, per-pass timings (table or JSON),
 * animation time and numbered sequences, technique parameters, or a window (GLFW) instead of files. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "core/file_util.h"
#include "sss/gl.h"
#include "sss/image.h"
#include "sss/scene.h"

#define CMD "render"
#define MAX_FRAMES 100000

enum {
    OPT_OUTPUT, OPT_EXR, OPT_TECHNIQUE, OPT_WIDTH, OPT_HEIGHT, OPT_TIME, OPT_FRAMES, OPT_ANIMATE, OPT_FPS, OPT_PARAM,
    OPT_DATA, OPT_SUPERSAMPLE, OPT_TIMINGS, OPT_WARMUP, OPT_TIMINGS_JSON, OPT_WINDOW
};
static const cli_option options[] = {
    {OPT_OUTPUT, "--output", "-o", CLI_ARG_FILE, "FILE", "output image (.png, .hdr, .pfm or .exr by extension)", NULL},
    {OPT_EXR, "--exr", NULL, CLI_ARG_FILE, "FILE", "also write the linear image as OpenEXR", NULL},
    {OPT_TECHNIQUE, "--technique", NULL, CLI_ARG_TECHNIQUE, "NAME",
     "technique (default: the scene's render.technique); `sss techniques`", NULL},
    {OPT_WIDTH, "--width", NULL, CLI_ARG_NUMBER, "W", "image width (default: the scene camera's)", NULL},
    {OPT_HEIGHT, "--height", NULL, CLI_ARG_NUMBER, "H", "image height (default: the scene camera's)", NULL},
    {OPT_TIME, "--time", NULL, CLI_ARG_NUMBER, "T", "animation time in seconds (default 0)", NULL},
    {OPT_FRAMES, "--frames", NULL, CLI_ARG_NUMBER, "N",
     "render N frames (timings are medians over them; default 1, or " CLI_STR(SSS_GL_TIMED_FRAMES) " with\n"
     "--timings/--timings-json); progress on stderr",
     NULL},
    {OPT_ANIMATE, "--animate", NULL, CLI_ARG_NONE, NULL,
     "with --frames: frame k at time T + k / fps, written as a numbered\n"
     "sequence OUT_0000.png, OUT_0001.png, ... (or OUT as a printf pattern\n"
     "with one %d, e.g. frame_%03d.png)",
     NULL},
    {OPT_FPS, "--fps", NULL, CLI_ARG_NUMBER, "F", "frames per second of --animate (default 30)", NULL},
    {OPT_PARAM, "--param", NULL, CLI_ARG_TEXT, "NAME=VALUE",
     "a technique or shared parameter (`sss techniques --params`), repeatable", NULL},
    {OPT_DATA, "--data", NULL, CLI_ARG_FILE, "FILE",
     "the technique's precomputed data (sam: a .sam file of `sss sam build`)", NULL},
    {OPT_SUPERSAMPLE, "--supersample", NULL, CLI_ARG_NUMBER, "K",
     "antialiasing: render every pass at K x the width and height (K^2 samples\n"
     "per pixel) and box-filter the linear image down, K in 1.." CLI_STR(SSS_GL_MAX_SUPERSAMPLE) " (default 1:\n"
     "off); costs about K^2 the time; parameters counted in pixels follow K",
     NULL},
    {OPT_TIMINGS, "--timings", NULL, CLI_ARG_NONE, NULL, "print milliseconds per pass (median over the frames) as a table",
     NULL},
    {OPT_WARMUP, "--warmup", NULL, CLI_ARG_NUMBER, "W",
     "with timings: W frames rendered first and not timed (default " CLI_STR(SSS_GL_WARMUP_FRAMES) ": the\n"
     "first frames pay shader compilation and first touches)",
     NULL},
    {OPT_TIMINGS_JSON, "--timings-json", NULL, CLI_ARG_FILE, "FILE", "write the timings as JSON", NULL},
    {OPT_WINDOW, "--window", NULL, CLI_ARG_NONE, NULL,
     "show the frames in a window (needs a display; until it is closed, or\n"
     "for --frames N frames); with -o the last frame is also written",
     NULL},
};
const cli_command_spec cli_spec_render = {CMD, options, CLI_COUNT(options), CLI_ARG_FILE, NULL};

static void print_usage(FILE *f)
{
    fprintf(f,
            "usage: sss render SCENE.json -o OUT.png [--exr OUT.exr] [--technique NAME] [--width W --height H]\n"
            "                  [--time T] [--frames N [--animate] [--fps F]] [--param NAME=VALUE ...]\n"
            "                  [--supersample K] [--timings] [--timings-json FILE] [--warmup W] [--window]\n"
            "                  [--quiet | --progress]\n"
            "\n"
            "Renders SCENE.json with a real-time technique on a headless OpenGL 4.5 context (EGL; no display\n"
            "needed) and writes the image: PNG tone-mapped with the scene's exposure (docs/scene-format.md), and with\n"
            "--exr the linear values. Files are written completely or not at all.\n"
            "\n");
    cli_print_options(f, &cli_spec_render);
    fprintf(f,
            "\n"
            "With --frames N, progress (frames done) goes to stderr when it is a terminal or with --progress.\n"
            "Timings on a software rasteriser (llvmpipe) put glFinish() around every pass and read a monotonic\n"
            "clock; on GPUs they use GL_TIME_ELAPSED queries. The method is printed with the table.\n"
            "Exit status: 0 success, 1 error (scene, GL, output), 2 usage error.\n");
}

/* Frame file name: a printf pattern with one %d, else "_%04d" inserted before the extension. */
static int frame_path(const char *out, int k, char *buf, size_t cap)
{
    const char *pct = strchr(out, '%');
    if (pct) {
        int n = snprintf(buf, cap, out, k);
        return n > 0 && (size_t)n < cap;
    }
    const char *slash = strrchr(out, '/');
    const char *dot = strrchr(out, '.');
    if (!dot || (slash && dot < slash)) dot = out + strlen(out);
    int n = snprintf(buf, cap, "%.*s_%04d%s", (int)(dot - out), out, k, dot);
    return n > 0 && (size_t)n < cap;
}

#define PATTERN_WIDTH_MAX 32 /* frame numbers have at most 6 digits; a wider field only pads */

/* Accepts a name without '%', or a printf pattern with exactly one %d-style conversion (optionally
 * zero-padded to a width <= PATTERN_WIDTH_MAX) and %% escapes: with no conversion every frame would
 * go to one file, and a width beyond int makes snprintf fail. */
static int valid_pattern(const char *s)
{
    if (!strchr(s, '%')) return 1;
    int conv = 0;
    for (const char *p = strchr(s, '%'); p; p = strchr(p, '%')) {
        p++;
        if (*p == '%') {
            p++;
            continue;
        }
        int width = 0;
        for (; *p >= '0' && *p <= '9'; p++)
            if ((width = 10 * width + (*p - '0')) > PATTERN_WIDTH_MAX) return 0;
        if (*p != 'd') return 0;
        conv++;
        p++;
    }
    return conv == 1;
}

static sss_result write_timings_json(const char *path, const char *technique, int w, int h, int supersample,
                                     int warmup, int frames, const char *renderer, const sss_gl_timings *median,
                                     sss_error *err)
{
    char tmp[4096];
    FILE *f = sss_atomic_open(path, tmp, sizeof tmp, err);
    if (!f) return err ? err->code : SSS_ERROR_IO;
    fprintf(f, "{\n  \"technique\": \"%s\",\n  \"width\": %d,\n  \"height\": %d,\n  \"supersample\": %d,\n",
            technique, w, h, supersample);
    fprintf(f, "  \"warmup_frames\": %d,\n  \"frames\": %d,\n", warmup, frames);
    fprintf(f, "  \"method\": \"%s\",\n  \"renderer\": \"", median->method);
    for (const char *c = renderer; *c; c++)
        if (*c == '"' || *c == '\\') fprintf(f, "\\%c", *c);
        else if ((unsigned char)*c >= 0x20) fputc(*c, f);
    fprintf(f, "\",\n  \"passes\": [\n");
    for (int i = 0; i < median->pass_count; i++)
        fprintf(f, "    {\"name\": \"%s\", \"median_ms\": %.4f}%s\n", median->passes[i].name, median->passes[i].ms,
                i + 1 < median->pass_count ? "," : "");
    fprintf(f, "  ],\n  \"total_median_ms\": %.4f\n}\n", median->total_ms);
    return sss_atomic_close(f, tmp, path, err);
}

/* Refuses, before rendering, an output (every frame's with --animate) that is an input's file. */
static int check_outputs(const char *out, const char *exr, const char *json, int animate, int frames,
                         const char *data, const sss_scene *scene)
{
    const char *fixed[3] = {animate ? NULL : out, animate ? NULL : exr, json};
    if (cli_check_outputs(CMD, fixed, 3, &data, 1, scene) != CLI_EXIT_OK) return CLI_EXIT_ERROR;
    const char *targets[2] = {out, exr};
    for (int k = 0; animate && k < frames; k++)
        for (int o = 0; o < 2; o++) {
            char path[4096];
            if (!targets[o]) continue;
            if (!frame_path(targets[o], k, path, sizeof path)) return cli_failf(CMD, "output name too long: %s", targets[o]);
            const char *frame = path;
            if (cli_check_outputs(CMD, &frame, 1, &data, 1, scene) != CLI_EXIT_OK) return CLI_EXIT_ERROR;
        }
    return CLI_EXIT_OK;
}

int sss_cmd_render(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) {
        print_usage(stdout);
        return CLI_EXIT_OK;
    }
    const char *scene_path = NULL, *out = NULL, *exr = NULL, *technique = NULL, *json = NULL, *data = NULL;
    int width = 0, height = 0, frames = 1, animate = 0, timings = 0, window = 0, frames_given = 0, supersample = 1;
    int warmup = SSS_GL_WARMUP_FRAMES;
    double time0 = 0.0, fps = 30.0;
    cli_params params;
    params.count = 0;
    cli_parser args;
    cli_parser_init(&args, &cli_spec_render, argc, argv, 1);
    for (int o; (o = cli_next(&args)) != CLI_DONE;) {
        const char *a = args.given, *v = args.value;
        switch (o) {
        case CLI_BAD: return CLI_EXIT_USAGE;
        case OPT_OUTPUT: out = v; break;
        case OPT_EXR: exr = v; break;
        case OPT_TECHNIQUE: technique = v; break;
        case OPT_WIDTH:
        case OPT_HEIGHT:
            if (!cli_parse_size(CMD, a, v, o == OPT_WIDTH ? &width : &height)) return CLI_EXIT_USAGE;
            break;
        case OPT_TIME:
            if (!cli_parse_double(CMD, a, v, &time0)) return CLI_EXIT_USAGE;
            break;
        case OPT_FRAMES:
            if (!cli_parse_int(CMD, a, v, &frames)) return CLI_EXIT_USAGE;
            if (frames < 1 || frames > MAX_FRAMES) return cli_usage_error(CMD, "--frames must be in 1..%d", MAX_FRAMES);
            frames_given = 1;
            break;
        case OPT_FPS:
            if (!cli_parse_double(CMD, a, v, &fps)) return CLI_EXIT_USAGE;
            if (!(fps > 0.0)) return cli_usage_error(CMD, "--fps must be > 0");
            break;
        case OPT_ANIMATE: animate = 1; break;
        case OPT_TIMINGS: timings = 1; break;
        case OPT_WARMUP:
            if (!cli_parse_int(CMD, a, v, &warmup)) return CLI_EXIT_USAGE;
            if (warmup < 0 || warmup > MAX_FRAMES) return cli_usage_error(CMD, "--warmup must be in 0..%d", MAX_FRAMES);
            break;
        case OPT_TIMINGS_JSON: json = v; break;
        case OPT_SUPERSAMPLE:
            if (!cli_parse_supersample(CMD, a, v, &supersample)) return CLI_EXIT_USAGE;
            break;
        case OPT_DATA: data = v; break;
        case OPT_WINDOW: window = 1; break;
        case OPT_PARAM:
            if (!cli_params_add(CMD, &params, v)) return CLI_EXIT_USAGE;
            break;
        default: /* CLI_OPERAND */
            if (scene_path) return cli_usage_error(CMD, "unexpected argument '%s'", v);
            scene_path = v;
        }
    }
    if (!scene_path) return cli_usage_error(CMD, "missing SCENE.json");
    if ((timings || json) && !frames_given) frames = SSS_GL_TIMED_FRAMES;
    if (!out && !window) return cli_usage_error(CMD, "missing -o OUT.png (or --window)");
    if (animate && !frames_given && !window) return cli_usage_error(CMD, "--animate needs --frames N");
    if (window && !frames_given && (out || exr))
        return cli_usage_error(CMD, "--window with -o/--exr needs --frames N (which frame to write)");
    if (out && !valid_pattern(out))
        return cli_usage_error(CMD, "-o '%s': a frame pattern needs exactly one %%d (width at most %d; %%%% for '%%')",
                               out, PATTERN_WIDTH_MAX);
    if (exr && !valid_pattern(exr))
        return cli_usage_error(CMD, "--exr '%s': a frame pattern needs exactly one %%d (width at most %d; %%%% for '%%')",
                               exr, PATTERN_WIDTH_MAX);
    if (out && !animate && strchr(out, '%')) return cli_usage_error(CMD, "-o holds a %%d pattern but --animate is not set");
    if (exr && !animate && strchr(exr, '%')) return cli_usage_error(CMD, "--exr holds a %%d pattern but --animate is not set");
    if (exr) {
        char ext[16];
        sss_path_extension(exr, ext, sizeof ext);
        if (strcmp(ext, "exr") != 0) return cli_usage_error(CMD, "--exr needs a .exr file name, got '%s'", exr);
    }
    if (out) {
        char ext[16];
        sss_path_extension(out, ext, sizeof ext);
        if (strcmp(ext, "png") && strcmp(ext, "exr") && strcmp(ext, "hdr") && strcmp(ext, "pfm"))
            return cli_usage_error(CMD, "-o: unknown image format '%s' (png, exr, hdr, pfm)", out);
    }

    if (technique && cli_check_technique(CMD, technique) != CLI_EXIT_OK) return CLI_EXIT_ERROR;

    sss_error err = {0};
    sss_scene scene;
    if (sss_scene_load(scene_path, NULL, &scene, &err) != SSS_OK) return cli_fail(CMD, &err);
    if (check_outputs(out, exr, json, animate, frames, data, &scene) != CLI_EXIT_OK) {
        sss_scene_free(&scene);
        return CLI_EXIT_ERROR;
    }
    sss_gl_context_desc cdesc;
    memset(&cdesc, 0, sizeof cdesc);
    cdesc.platform = window ? SSS_GL_PLATFORM_WINDOW : SSS_GL_PLATFORM_HEADLESS;
    cdesc.window_width = width ? width : scene.camera.width;
    cdesc.window_height = height ? height : scene.camera.height;
    cdesc.window_title = scene_path;
    sss_gl_context *ctx = NULL;
    if (sss_gl_context_create(&cdesc, &ctx, &err) != SSS_OK) {
        sss_scene_free(&scene);
        return cli_fail(CMD, &err);
    }
    sss_gl_renderer_desc rdesc;
    memset(&rdesc, 0, sizeof rdesc);
    rdesc.technique = technique;
    rdesc.width = width;
    rdesc.height = height;
    rdesc.params = params.values;
    rdesc.param_count = params.count;
    rdesc.timings = timings || json;
    rdesc.data_file = data;
    rdesc.supersample = supersample;
    sss_gl_renderer *r = NULL;
    int status = CLI_EXIT_OK;
    /* progress over every frame rendered (warm-up too); a window shows its own frames */
    cli_progress progress;
    cli_progress_init(&progress, &args);
    progress.active = progress.active && !window && frames > 1;
    sss_gl_timing_series series = {0};
    sss_image img = {0};
    if (rdesc.timings && sss_gl_timing_series_init(&series, warmup, frames, &err) != SSS_OK) {
        status = cli_fail(CMD, &err);
        goto done;
    }
    if (sss_gl_renderer_create(ctx, &scene, &rdesc, &r, &err) != SSS_OK) {
        status = cli_fail(CMD, &err);
        goto done;
    }
    int w, h;
    sss_gl_renderer_size(r, &w, &h);
    if (sss_image_create(&img, w, h, &err) != SSS_OK) {
        status = cli_fail(CMD, &err);
        goto done;
    }
    sss_gl_timings last = {0};
    int total = frames + (rdesc.timings ? warmup : 0), done_frames = 0;
    char stage[32] = "warm-up";
    for (int k = 0; rdesc.timings && k < warmup; k++) {
        if (sss_gl_renderer_render(r, time0, &err) != SSS_OK) {
            status = cli_fail(CMD, &err);
            goto done;
        }
        sss_gl_renderer_timings(r, &last);
        sss_gl_timing_series_add(&series, &last);
        cli_progress_update(&progress, (double)++done_frames / total, stage);
    }
    for (int k = 0; k < frames || (window && !frames_given); k++) {
        double t = animate ? time0 + k / fps : time0;
        if (window && sss_gl_window_should_close(ctx)) break;
        if (sss_gl_renderer_render(r, t, &err) != SSS_OK) {
            status = cli_fail(CMD, &err);
            goto done;
        }
        if (window) {
            if (sss_gl_renderer_present(r, &err) != SSS_OK) {
                status = cli_fail(CMD, &err);
                goto done;
            }
            sss_gl_window_swap(ctx);
        }
        if (rdesc.timings && k < frames) {
            sss_gl_renderer_timings(r, &last);
            sss_gl_timing_series_add(&series, &last);
        }
        snprintf(stage, sizeof stage, "frame %d/%d", k + 1, frames);
        if (k < frames) cli_progress_update(&progress, (double)++done_frames / total, stage);
        if (!out && !exr) continue;
        int write_now = k < frames && (animate || k == frames - 1);
        if (!write_now) continue;
        if (sss_gl_renderer_read(r, &img, &err) != SSS_OK) {
            status = cli_fail(CMD, &err);
            goto done;
        }
        char path[4096];
        const char *targets[2] = {out, exr};
        double exposures[2] = {scene.render.exposure, 0.0};
        for (int o = 0; o < 2; o++) {
            if (!targets[o]) continue;
            const char *p = targets[o];
            if (animate) {
                if (!frame_path(targets[o], k, path, sizeof path)) {
                    status = cli_failf(CMD, "output name too long: %s", targets[o]);
                    goto done;
                }
                p = path;
            }
            if (sss_image_write(p, &img, exposures[o], &err) != SSS_OK) {
                status = cli_fail(CMD, &err);
                goto done;
            }
        }
    }
    cli_progress_end(&progress);
    sss_gl_timings median;
    sss_gl_timing_series_median(&series, &median);
    if (rdesc.timings && median.pass_count > 0) {
        sss_gl_context_info info;
        sss_gl_context_get_info(ctx, &info);
        if (timings) {
            const char *tname = technique ? technique : scene.render.technique;
            char ssaa[48] = "";
            if (supersample > 1) snprintf(ssaa, sizeof ssaa, " (supersample %d: %dx%d)", supersample, w * supersample,
                                          h * supersample);
            printf("technique %s, %dx%d%s, median of %d frame%s after %d warm-up, %s on %s\n",
                   sss_gl_technique_find(tname) ? tname : "?", w, h, ssaa, series.timed, series.timed == 1 ? "" : "s",
                   warmup, median.method, info.renderer);
            printf("%-20s %12s\n", "pass", "median ms");
            for (int j = 0; j < median.pass_count; j++) printf("%-20s %12.3f\n", median.passes[j].name, median.passes[j].ms);
            printf("%-20s %12.3f\n", "total", median.total_ms);
        }
        if (json && write_timings_json(json, technique ? technique : scene.render.technique, w, h, supersample, warmup,
                                       series.timed, info.renderer, &median, &err) != SSS_OK) {
            status = cli_fail(CMD, &err);
            goto done;
        }
    }
done:
    if (status != CLI_EXIT_OK) cli_progress_end(&progress);
    sss_gl_timing_series_free(&series);
    sss_image_free(&img);
    sss_gl_renderer_destroy(r);
    sss_gl_context_destroy(ctx);
    sss_scene_free(&scene);
    return status;
}
