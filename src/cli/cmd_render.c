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
#define DEFAULT_FPS 30
static const cli_option options[] = {
    {OPT_OUTPUT, "--output", "-o", CLI_ARG_FILE, "FILE",
     "output image (.png, .hdr, .pfm or .exr by extension); needed unless --window", NULL, NULL},
    {OPT_EXR, "--exr", NULL, CLI_ARG_FILE, "FILE", "also write the linear image as OpenEXR", NULL, NULL},
    {OPT_TECHNIQUE, "--technique", NULL, CLI_ARG_TECHNIQUE, "NAME", "technique (`sss techniques`)", NULL,
     "the scene's render.technique"},
    {OPT_WIDTH, "--width", NULL, CLI_ARG_NUMBER, "W", "image width", NULL, "the scene camera's"},
    {OPT_HEIGHT, "--height", NULL, CLI_ARG_NUMBER, "H", "image height", NULL, "the scene camera's"},
    {OPT_TIME, "--time", NULL, CLI_ARG_NUMBER, "T", "animation time in seconds", NULL, "0"},
    {OPT_FRAMES, "--frames", NULL, CLI_ARG_NUMBER, "N",
     "render N frames (timings are medians over them); progress on stderr", NULL,
     "1, or " CLI_STR(SSS_GL_TIMED_FRAMES) " with --timings/--timings-json"},
    {OPT_ANIMATE, "--animate", NULL, CLI_ARG_NONE, NULL,
     "with --frames: frame k at time T + k / fps, written as a numbered\n"
     "sequence OUT_0000.png, OUT_0001.png, ... (or OUT as a printf pattern\n"
     "with one %d, e.g. frame_%03d.png)",
     NULL, NULL},
    {OPT_FPS, "--fps", NULL, CLI_ARG_NUMBER, "F", "frames per second of --animate", NULL, CLI_STR(DEFAULT_FPS)},
    {OPT_PARAM, "--param", NULL, CLI_ARG_TEXT, "NAME=VALUE",
     "a technique or shared parameter (`sss techniques --params`), repeatable", NULL, NULL},
    {OPT_DATA, "--data", NULL, CLI_ARG_FILE, "FILE",
     "the technique's precomputed data (sam: a .sam file of `sss sam build`)", NULL, NULL},
    {OPT_SUPERSAMPLE, "--supersample", NULL, CLI_ARG_NUMBER, "K",
     "antialiasing: render every pass at K x the width and height (K^2 samples\n"
     "per pixel) and box-filter the linear image down, K in 1.." CLI_STR(SSS_GL_MAX_SUPERSAMPLE) "; costs about\n"
     "K^2 the time; parameters counted in pixels follow K",
     NULL, "1 = off"},
    {OPT_TIMINGS, "--timings", NULL, CLI_ARG_NONE, NULL, "print milliseconds per pass (median over the frames) as a table",
     NULL, NULL},
    {OPT_WARMUP, "--warmup", NULL, CLI_ARG_NUMBER, "W",
     "with timings: W frames rendered first and not timed (the first frames\n"
     "pay shader compilation and first touches)",
     NULL, CLI_STR(SSS_GL_WARMUP_FRAMES)},
    {OPT_TIMINGS_JSON, "--timings-json", NULL, CLI_ARG_FILE, "FILE", "write the timings as JSON", NULL, NULL},
    {OPT_WINDOW, "--window", NULL, CLI_ARG_NONE, NULL,
     "show the frames in a window (needs a display; until it is closed, or\n"
     "for --frames N frames); with -o the last frame is also written",
     NULL, NULL},
};
const cli_command_spec cli_spec_render = {
    CMD, options, CLI_COUNT(options), CLI_ARG_FILE, NULL, "SCENE.json",
    "Renders SCENE.json with a real-time technique on a headless OpenGL 4.5 context (EGL; no display\n"
    "needed) and writes the image: PNG tone-mapped with the scene's exposure (docs/scene-format.md), and with\n"
    "--exr the linear values. Files are written completely or not at all.\n",
    "With --frames N, progress (frames done) goes to stderr when it is a terminal or with --progress.\n"
    "Timings on a software rasteriser (llvmpipe) put glFinish() around every pass and read a monotonic\n"
    "clock; on GPUs they use GL_TIME_ELAPSED queries. The method is printed with the table.\n"
    "Exit status: 0 success, 1 error (scene, GL, output), 2 usage error.\n",
    NULL};

typedef struct render_options {
    const char *scene_path, *out, *exr, *technique, *json, *data;
    int width, height, frames, frames_given, animate, timings, window, supersample, warmup;
    double time0, fps;
    cli_params params;
    cli_common common;
} render_options;

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

static int set_number(render_options *o, int id, const char *a, const char *v)
{
    switch (id) {
    case OPT_WIDTH:
    case OPT_HEIGHT:
        if (!cli_parse_size(CMD, a, v, id == OPT_WIDTH ? &o->width : &o->height)) return CLI_EXIT_USAGE;
        break;
    case OPT_TIME:
        if (!cli_parse_double(CMD, a, v, &o->time0)) return CLI_EXIT_USAGE;
        break;
    case OPT_FRAMES:
        if (!cli_parse_int(CMD, a, v, &o->frames)) return CLI_EXIT_USAGE;
        if (o->frames < 1 || o->frames > MAX_FRAMES) return cli_usage_error(CMD, "--frames must be in 1..%d", MAX_FRAMES);
        o->frames_given = 1;
        break;
    case OPT_FPS:
        if (!cli_parse_double(CMD, a, v, &o->fps)) return CLI_EXIT_USAGE;
        if (!(o->fps > 0.0)) return cli_usage_error(CMD, "--fps must be > 0");
        break;
    case OPT_WARMUP:
        if (!cli_parse_int(CMD, a, v, &o->warmup)) return CLI_EXIT_USAGE;
        if (o->warmup < 0 || o->warmup > MAX_FRAMES) return cli_usage_error(CMD, "--warmup must be in 0..%d", MAX_FRAMES);
        break;
    default: /* OPT_SUPERSAMPLE */
        if (!cli_parse_supersample(CMD, a, v, &o->supersample)) return CLI_EXIT_USAGE;
    }
    return CLI_EXIT_OK;
}

static int set_option(void *opts, int id, const char *a, const char *v)
{
    render_options *o = opts;
    switch (id) {
    case OPT_OUTPUT: o->out = v; break;
    case OPT_EXR: o->exr = v; break;
    case OPT_TECHNIQUE: o->technique = v; break;
    case OPT_ANIMATE: o->animate = 1; break;
    case OPT_TIMINGS: o->timings = 1; break;
    case OPT_TIMINGS_JSON: o->json = v; break;
    case OPT_DATA: o->data = v; break;
    case OPT_WINDOW: o->window = 1; break;
    case OPT_PARAM:
        if (!cli_params_add(CMD, &o->params, v)) return CLI_EXIT_USAGE;
        break;
    case CLI_OPERAND:
        if (o->scene_path) return cli_usage_error(CMD, "unexpected argument '%s'", v);
        o->scene_path = v;
        break;
    default: return set_number(o, id, a, v);
    }
    return CLI_EXIT_OK;
}

/* -o and --exr: a frame pattern only with --animate, and the formats they are written in. */
static int check_output_names(const render_options *o)
{
    const char *names[2] = {o->out, o->exr}, *flags[2] = {"-o", "--exr"};
    for (int k = 0; k < 2; k++)
        if (names[k] && !valid_pattern(names[k]))
            return cli_usage_error(CMD, "%s '%s': a frame pattern needs exactly one %%d (width at most %d; %%%% for '%%')",
                                   flags[k], names[k], PATTERN_WIDTH_MAX);
    for (int k = 0; k < 2; k++)
        if (names[k] && !o->animate && strchr(names[k], '%'))
            return cli_usage_error(CMD, "%s holds a %%d pattern but --animate is not set", flags[k]);
    char ext[16];
    if (o->exr) {
        sss_path_extension(o->exr, ext, sizeof ext);
        if (strcmp(ext, "exr") != 0) return cli_usage_error(CMD, "--exr needs a .exr file name, got '%s'", o->exr);
    }
    if (o->out) {
        sss_path_extension(o->out, ext, sizeof ext);
        if (strcmp(ext, "png") && strcmp(ext, "exr") && strcmp(ext, "hdr") && strcmp(ext, "pfm"))
            return cli_usage_error(CMD, "-o: unknown image format '%s' (png, exr, hdr, pfm)", o->out);
    }
    return CLI_EXIT_OK;
}

static int render_parse(int argc, char **argv, render_options *o)
{
    memset(o, 0, sizeof *o);
    o->frames = 1;
    o->supersample = 1;
    o->warmup = SSS_GL_WARMUP_FRAMES;
    o->fps = DEFAULT_FPS;
    int status = cli_parse(&cli_spec_render, argc, argv, 1, set_option, o, &o->common);
    if (status != CLI_EXIT_OK) return status;
    if (!o->scene_path) return cli_usage_error(CMD, "missing SCENE.json");
    if ((o->timings || o->json) && !o->frames_given) o->frames = SSS_GL_TIMED_FRAMES;
    if (!o->out && !o->window) return cli_usage_error(CMD, "missing -o OUT.png (or --window)");
    if (o->animate && !o->frames_given && !o->window) return cli_usage_error(CMD, "--animate needs --frames N");
    if (o->window && !o->frames_given && (o->out || o->exr))
        return cli_usage_error(CMD, "--window with -o/--exr needs --frames N (which frame to write)");
    if ((status = check_output_names(o)) != CLI_EXIT_OK) return status;
    if (o->technique && cli_check_technique(CMD, o->technique) != CLI_EXIT_OK) return CLI_EXIT_ERROR;
    return CLI_EXIT_OK;
}

/* What a run holds: the scene, the GL context and renderer, the timings, the image read back. */
typedef struct render_job {
    const render_options *o;
    sss_scene scene;
    sss_gl_context *ctx;
    sss_gl_renderer *r;
    int timed, w, h;          /* timings wanted; the image size */
    sss_gl_timing_series series;
    sss_image img;
    cli_progress progress;
    int total, done_frames;   /* for the progress: every frame rendered, warm-up too */
} render_job;

/* The context (a window with --window) and the renderer of o's technique, size and parameters. */
static sss_result open_renderer(render_job *j, sss_error *err)
{
    const render_options *o = j->o;
    sss_gl_context_desc cdesc;
    memset(&cdesc, 0, sizeof cdesc);
    cdesc.platform = o->window ? SSS_GL_PLATFORM_WINDOW : SSS_GL_PLATFORM_HEADLESS;
    cdesc.window_width = o->width ? o->width : j->scene.camera.width;
    cdesc.window_height = o->height ? o->height : j->scene.camera.height;
    cdesc.window_title = o->scene_path;
    sss_result res = sss_gl_context_create(&cdesc, &j->ctx, err);
    if (res != SSS_OK) return res;
    sss_gl_renderer_desc rdesc;
    memset(&rdesc, 0, sizeof rdesc);
    rdesc.technique = o->technique;
    rdesc.width = o->width;
    rdesc.height = o->height;
    rdesc.params = o->params.values;
    rdesc.param_count = o->params.count;
    rdesc.timings = j->timed = o->timings || o->json;
    rdesc.data_file = o->data;
    rdesc.supersample = o->supersample;
    /* progress over every frame rendered (warm-up too); a window shows its own frames */
    cli_progress_init(&j->progress, &o->common);
    j->progress.active = j->progress.active && !o->window && o->frames > 1;
    j->total = o->frames + (j->timed ? o->warmup : 0);
    if (j->timed && (res = sss_gl_timing_series_init(&j->series, o->warmup, o->frames, err)) != SSS_OK) return res;
    if ((res = sss_gl_renderer_create(j->ctx, &j->scene, &rdesc, &j->r, err)) != SSS_OK) return res;
    sss_gl_renderer_size(j->r, &j->w, &j->h);
    return sss_image_create(&j->img, j->w, j->h, err);
}

/* One frame at time t, shown in the window when present; its timings join the series when timed; the
 * progress counts it when stage is given. */
static sss_result render_one(render_job *j, double t, int present, int timed, const char *stage, sss_error *err)
{
    sss_result res = sss_gl_renderer_render(j->r, t, err);
    if (res == SSS_OK && present) {
        if ((res = sss_gl_renderer_present(j->r, err)) == SSS_OK) sss_gl_window_swap(j->ctx);
    }
    if (res != SSS_OK) return res;
    if (timed) {
        sss_gl_timings last = {0};
        sss_gl_renderer_timings(j->r, &last);
        sss_gl_timing_series_add(&j->series, &last);
    }
    if (stage) cli_progress_update(&j->progress, (double)++j->done_frames / j->total, stage);
    return SSS_OK;
}

/* Frame k's image to -o and --exr (with --animate under its frame's name). */
static sss_result write_frame(render_job *j, int k, sss_error *err)
{
    const render_options *o = j->o;
    sss_result res = sss_gl_renderer_read(j->r, &j->img, err);
    const char *targets[2] = {o->out, o->exr};
    double exposures[2] = {j->scene.render.exposure, 0.0};
    for (int t = 0; t < 2 && res == SSS_OK; t++) {
        if (!targets[t]) continue;
        char path[4096];
        if (o->animate && !frame_path(targets[t], k, path, sizeof path))
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "output name too long: %s", targets[t]);
        res = sss_image_write(o->animate ? path : targets[t], &j->img, exposures[t], err);
    }
    return res;
}

/* The warm-up (timed runs), then the frames: until the window closes with --window and no --frames. */
static sss_result render_frames(render_job *j, sss_error *err)
{
    const render_options *o = j->o;
    sss_result res = SSS_OK;
    for (int k = 0; j->timed && k < o->warmup && res == SSS_OK; k++)
        res = render_one(j, o->time0, 0, 1, "warm-up", err);
    for (int k = 0; res == SSS_OK && (k < o->frames || (o->window && !o->frames_given)); k++) {
        if (o->window && sss_gl_window_should_close(j->ctx)) break;
        char stage[32];
        snprintf(stage, sizeof stage, "frame %d/%d", k + 1, o->frames);
        res = render_one(j, o->animate ? o->time0 + k / o->fps : o->time0, o->window, j->timed && k < o->frames,
                         k < o->frames ? stage : NULL, err);
        int write_now = (o->out || o->exr) && k < o->frames && (o->animate || k == o->frames - 1);
        if (res == SSS_OK && write_now) res = write_frame(j, k, err);
    }
    return res;
}

/* The median timings: a table on stdout (--timings), JSON (--timings-json). */
static sss_result report_timings(render_job *j, sss_error *err)
{
    const render_options *o = j->o;
    sss_gl_timings median;
    sss_gl_timing_series_median(&j->series, &median);
    if (!j->timed || median.pass_count == 0) return SSS_OK;
    sss_gl_context_info info;
    sss_gl_context_get_info(j->ctx, &info);
    const char *tname = o->technique ? o->technique : j->scene.render.technique;
    int timed = j->series.timed;
    if (o->timings) {
        char ssaa[48] = "";
        if (o->supersample > 1)
            snprintf(ssaa, sizeof ssaa, " (supersample %d: %dx%d)", o->supersample, j->w * o->supersample,
                     j->h * o->supersample);
        printf("technique %s, %dx%d%s, median of %d frame%s after %d warm-up, %s on %s\n",
               sss_gl_technique_find(tname) ? tname : "?", j->w, j->h, ssaa, timed, timed == 1 ? "" : "s", o->warmup,
               median.method, info.renderer);
        printf("%-20s %12s\n", "pass", "median ms");
        for (int k = 0; k < median.pass_count; k++) printf("%-20s %12.3f\n", median.passes[k].name, median.passes[k].ms);
        printf("%-20s %12.3f\n", "total", median.total_ms);
    }
    if (!o->json) return SSS_OK;
    return write_timings_json(o->json, tname, j->w, j->h, o->supersample, o->warmup, timed, info.renderer, &median, err);
}

static int render_run(const render_options *o)
{
    render_job j;
    memset(&j, 0, sizeof j);
    j.o = o;
    sss_error err = {0};
    if (sss_scene_load(o->scene_path, NULL, &j.scene, &err) != SSS_OK) return cli_fail(CMD, &err);
    int status = check_outputs(o->out, o->exr, o->json, o->animate, o->frames, o->data, &j.scene);
    if (status == CLI_EXIT_OK) {
        sss_result res = open_renderer(&j, &err);
        if (res == SSS_OK) res = render_frames(&j, &err);
        cli_progress_end(&j.progress);
        if (res == SSS_OK) res = report_timings(&j, &err);
        if (res != SSS_OK) status = cli_fail(CMD, &err);
    }
    sss_gl_timing_series_free(&j.series);
    sss_image_free(&j.img);
    sss_gl_renderer_destroy(j.r);
    sss_gl_context_destroy(j.ctx);
    sss_scene_free(&j.scene);
    return status;
}

int sss_cmd_render(int argc, char **argv)
{
    render_options o;
    int status = render_parse(argc, argv, &o);
    return status == CLI_EXIT_OK ? render_run(&o) : status;
}
