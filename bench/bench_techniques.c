/* bench/bench_techniques.c — every technique on one or more scenes, in one run: median ms per pass and
 * per frame (timed frames after warm-up, sss_gl_timing_series) beside the median wall clock of a frame,
 * the frame's ratio to ssss, and GPU memory (the technique's own and the shared frame targets, counted
 * where the GL allocates them; the driver's view where it offers GL_NVX_gpu_memory_info), at 960x540
 * and 1920x1080 by default; --zoom F moves the camera F times its distance from the look-at point
 * (F > 1: the object smaller on screen), so that cost can be seen to follow the object's size.
 *
 * usage: bench_techniques [SCENE.json ...] [--techniques a,b,...] [--frames N] [--warmup N] [--budget S]
 *                         [--size WxH ...] [--zoom F ...] [--tsv FILE] [--json FILE] [--images DIR]
 * A technique may carry parameters as in `sss eval`: NAME:param=value[:param=value] (maisch2020:outer_divisor=2).
 * One renderer per scene and technique, resized to each size (its CPU tables are built once).
 * --budget S: stop timing a technique at one size once S seconds of timed frames have passed (at least 3
 * frames), so that a slow technique cannot use up a fixed time on a GPU machine. --frames 0: no frames,
 * only the GPU memory of each renderer after creation and resizing. --tsv/--json: one row
 * per scene x zoom x technique x size, both files rewritten whole after each row (a run stopped early
 * leaves complete files); bench/gpu/run.sh reads them. --images DIR: the image of every technique at the
 * first size, DIR/<scene>_<technique>.png, to compare a GPU's images with llvmpipe's.
 * Timing method: glFinish + monotonic clock per pass on software GL (llvmpipe), GL_TIME_ELAPSED
 * queries on GPUs (gl/timing.c); the wall clock spans sss_gl_renderer_render, which waits for the
 * frame's query results (or its last glFinish). Default scene: scenes/gl_dragon.json. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sss/gl.h"
#include "sss/scene.h"

#define MAX_LIST 16
#define MAX_SPEC_PARAMS 16
#define MAX_TECHNIQUES 64
#define MIN_BUDGET_FRAMES 3

typedef struct options {
    const char *scenes[MAX_LIST];
    int nscenes;
    char list[1024];
    int frames, warmup, nsizes, sizes[MAX_LIST][2], nzooms;
    double budget, zooms[MAX_LIST];
    const char *tsv, *json, *images;
} options;

typedef struct row {
    const char *scene, *technique;
    int width, height, ok, frames;
    double zoom, wall_ms, create_s;
    char error[600]; /* what failed and sss_error.message */
    sss_gl_timings median; /* pass names are the techniques' static strings */
    size_t per_pixel_bytes, technique_bytes, frame_bytes, renderer_bytes;
    long long nvx_bytes; /* -1: the driver offers no GL_NVX_gpu_memory_info */
} row;

typedef struct run {
    options opt;
    sss_gl_context *ctx;
    sss_gl_context_info info;
    int nvx;
    size_t vidmem_total;
    row *rows;
    int nrows, cap;
} run;


/* ---- Output: TSV and JSON (rewritten whole after every row), the console tables ---------------- */

static void json_string(FILE *f, const char *s)
{
    fputc('"', f);
    for (; s && *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\') fprintf(f, "\\%c", c);
        else if (c < 0x20) fprintf(f, "\\u%04x", c);
        else fputc(c, f);
    }
    fputc('"', f);
}

/* TSV fields may hold no tab or newline: those of error messages become spaces. */
static void tsv_text(FILE *f, const char *s)
{
    for (; s && *s; s++) fputc(*s == '\t' || *s == '\n' || *s == '\r' ? ' ' : *s, f);
}

static const char *TSV_HEADER = "scene\ttechnique\twidth\theight\tzoom\tstatus\tframes\twarmup\ttiming_method\tframe_ms"
                                "\twall_ms\ttechnique_bytes\tframe_bytes\trenderer_bytes\tnvx_bytes\tcreate_s\tpasses\terror\n";

static void tsv_row(FILE *f, const run *rn, const row *w)
{
    fprintf(f, "%s\t%s\t%d\t%d\t%g\t%s\t%d\t%d\t%s\t", w->scene, w->technique, w->width, w->height, w->zoom,
            w->ok ? "ok" : "failed", w->frames, rn->opt.warmup, w->frames ? w->median.method : "n/a");
    if (w->ok && w->frames) fprintf(f, "%.6f\t%.6f\t", w->median.total_ms, w->wall_ms);
    else fputs("n/a\tn/a\t", f);
    if (w->ok) fprintf(f, "%zu\t%zu\t%zu\t", w->technique_bytes, w->frame_bytes, w->renderer_bytes);
    else fputs("n/a\tn/a\tn/a\t", f);
    if (w->ok && w->nvx_bytes >= 0) fprintf(f, "%lld\t", w->nvx_bytes);
    else fputs("n/a\t", f);
    fprintf(f, "%.3f\t", w->create_s);
    for (int p = 0; w->ok && w->frames && p < w->median.pass_count; p++)
        fprintf(f, "%s%s=%.6f", p ? ";" : "", w->median.passes[p].name, w->median.passes[p].ms);
    fputc('\t', f);
    tsv_text(f, w->error);
    fputc('\n', f);
}

static void json_row(FILE *f, const run *rn, const row *w)
{
    fputs("    {\"scene\": ", f);
    json_string(f, w->scene);
    fputs(", \"technique\": ", f);
    json_string(f, w->technique);
    fprintf(f, ", \"width\": %d, \"height\": %d, \"zoom\": %g, \"status\": \"%s\", \"frames\": %d, \"warmup\": %d", w->width,
            w->height, w->zoom, w->ok ? "ok" : "failed", w->frames, rn->opt.warmup);
    if (w->ok && w->frames) {
        fprintf(f, ",\n     \"frame_ms\": %.6f, \"wall_ms\": %.6f, \"passes\": [", w->median.total_ms, w->wall_ms);
        for (int p = 0; p < w->median.pass_count; p++)
            fprintf(f, "%s{\"name\": \"%s\", \"ms\": %.6f}", p ? ", " : "", w->median.passes[p].name, w->median.passes[p].ms);
        fputs("]", f);
    }
    if (w->ok)
        fprintf(f, ",\n     \"technique_bytes\": %zu, \"frame_bytes\": %zu, \"renderer_bytes\": %zu", w->technique_bytes,
                w->frame_bytes, w->renderer_bytes);
    if (w->ok && w->nvx_bytes >= 0) fprintf(f, ", \"nvx_bytes\": %lld", w->nvx_bytes);
    else fputs(", \"nvx_bytes\": \"n/a\"", f);
    fprintf(f, ", \"create_s\": %.3f, \"error\": ", w->create_s);
    if (w->ok) fputs("null", f);
    else json_string(f, w->error);
    fputc('}', f);
}

static void json_file(FILE *f, const run *rn)
{
    fputs("{\"tool\": \"bench_techniques\", \"gl_renderer\": ", f);
    json_string(f, rn->info.renderer);
    fputs(", \"gl_version\": ", f);
    json_string(f, rn->info.version);
    fputs(", \"gl_platform\": ", f);
    json_string(f, rn->info.platform);
    fprintf(f, ",\n \"software\": %s, \"nvx_gpu_memory_info\": %s, \"video_memory_bytes\": ", rn->info.software ? "true" : "false",
            rn->nvx ? "true" : "false");
    if (rn->nvx) fprintf(f, "%zu", rn->vidmem_total);
    else fputs("\"n/a\"", f);
    fprintf(f, ", \"warmup\": %d, \"frames\": %d, \"budget_s\": %g,\n \"rows\": [\n", rn->opt.warmup, rn->opt.frames,
            rn->opt.budget);
    for (int i = 0; i < rn->nrows; i++) {
        json_row(f, rn, &rn->rows[i]);
        fputs(i + 1 < rn->nrows ? ",\n" : "\n", f);
    }
    fputs(" ]}\n", f);
}

/* Writes path through path.tmp and a rename, so a reader never sees half a file. */
static int write_file(const char *path, const run *rn, int json)
{
    char tmp[1024];
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    FILE *f = fopen(tmp, "w");
    if (!f) {
        fprintf(stderr, "bench_techniques: cannot write %s\n", tmp);
        return 0;
    }
    if (json) json_file(f, rn);
    else {
        fputs(TSV_HEADER, f);
        for (int i = 0; i < rn->nrows; i++) tsv_row(f, rn, &rn->rows[i]);
    }
    int ok = fclose(f) == 0 && rename(tmp, path) == 0;
    if (!ok) fprintf(stderr, "bench_techniques: cannot write %s\n", path);
    return ok;
}

static int write_outputs(const run *rn)
{
    int ok = 1;
    if (rn->opt.tsv) ok &= write_file(rn->opt.tsv, rn, 0);
    if (rn->opt.json) ok &= write_file(rn->opt.json, rn, 1);
    return ok;
}

static void print_row(const row *w)
{
    if (!w->ok || !w->frames) return;
    fprintf(stderr, "  %s %s %dx%d: %.3f ms (wall %.3f), %d frames\n", w->scene, w->technique, w->width, w->height,
            w->median.total_ms, w->wall_ms, w->frames);
}

/* The rows from `first` on (one scene and zoom), one table per size. */
static void print_tables(const run *rn, int first)
{
    for (int s = 0; s < rn->opt.nsizes; s++) {
        const row *rows[MAX_TECHNIQUES];
        int n = 0;
        double ssss = 0.0;
        for (int i = first; i < rn->nrows && n < MAX_TECHNIQUES; i++)
            if (rn->rows[i].width == rn->opt.sizes[s][0] && rn->rows[i].height == rn->opt.sizes[s][1]) {
                rows[n++] = &rn->rows[i];
                if (rn->rows[i].ok && strcmp(rn->rows[i].technique, "ssss") == 0) ssss = rn->rows[i].median.total_ms;
            }
        if (!n) continue;
        printf("\n%s %dx%d, zoom %g: median of up to %d frames after %d warm-up (%s)\n", rows[0]->scene, rows[0]->width,
               rows[0]->height, rows[0]->zoom, rn->opt.frames, rn->opt.warmup, rows[0]->ok ? rows[0]->median.method : "-");
        printf("  %-14s %10s %10s %8s %8s %9s  %s\n", "technique", "frame ms", "wall ms", "/ ssss", "B/pixel", "own MiB",
               "passes (ms)");
        for (int i = 0; i < n; i++) {
            const row *w = rows[i];
            if (!w->ok) {
                printf("  %-14s %10s  %s\n", w->technique, "failed", w->error);
                continue;
            }
            printf("  %-14s %10.3f %10.3f %8.2f %8zu %9.2f ", w->technique, w->median.total_ms, w->wall_ms,
                   ssss > 0.0 ? w->median.total_ms / ssss : 0.0, w->per_pixel_bytes, w->technique_bytes / 1048576.0);
            for (int p = 0; p < w->median.pass_count; p++) printf(" %s %.3f", w->median.passes[p].name, w->median.passes[p].ms);
            printf("\n");
        }
    }
    fflush(stdout);
}

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

static void fail(row *out, const char *what, const char *message)
{
    out->ok = 0;
    snprintf(out->error, sizeof out->error, "%s: %s", what, message);
    fprintf(stderr, "bench_techniques: %s %s %dx%d: %s: %s\n", out->scene, out->technique, out->width, out->height,
            what, message);
}

/* Bytes the driver has handed out since `before` (GL_NVX_gpu_memory_info), or -1 without it. */
static long long nvx_used(run *rn, size_t before)
{
    size_t total = 0, available = 0;
    if (!rn->nvx || !sss_gl_context_video_memory(rn->ctx, &total, &available)) return -1;
    return (long long)before - (long long)available;
}

/* Warm-up and timed frames of r at its current size into out (medians, memory). */
/* Warm-up and timed frames of r at its current size into out (medians); 0 after a failure. */
static int time_frames(run *rn, sss_gl_renderer *r, row *out)
{
    sss_error err = {0};
    sss_gl_timing_series series;
    double *wall = calloc((size_t)rn->opt.frames, sizeof *wall);
    if (!wall || sss_gl_timing_series_init(&series, rn->opt.warmup, rn->opt.frames, &err) != SSS_OK) {
        free(wall);
        fail(out, "timing", wall ? err.message : "out of memory");
        return 0;
    }
    double t_first = 0.0;
    int ok = 1;
    for (int f = 0; f < rn->opt.warmup + rn->opt.frames; f++) {
        double t0 = sss_time_seconds();
        if (sss_gl_renderer_render(r, 0.0, &err) != SSS_OK) {
            fail(out, "render", err.message);
            ok = 0;
            break;
        }
        if (f >= rn->opt.warmup) wall[f - rn->opt.warmup] = 1e3 * (sss_time_seconds() - t0);
        if (f == rn->opt.warmup) t_first = t0;
        sss_gl_timings t;
        sss_gl_renderer_timings(r, &t);
        sss_gl_timing_series_add(&series, &t);
        if (rn->opt.budget > 0.0 && series.timed >= MIN_BUDGET_FRAMES && sss_time_seconds() - t_first > rn->opt.budget)
            break;
    }
    sss_gl_timing_series_median(&series, &out->median);
    out->frames = series.timed;
    out->wall_ms = series.timed > 0 ? sss_median(wall, series.timed) : 0.0;
    sss_gl_timing_series_free(&series);
    free(wall);
    return ok && out->frames > 0;
}

/* The frames (none with --frames 0: memory only), then what r holds on the GPU. */
static void measure(run *rn, sss_gl_renderer *r, size_t bytes_before, size_t nvx_before, row *out)
{
    out->ok = rn->opt.frames == 0 || time_frames(rn, r, out);
    sss_gl_stats st;
    sss_gl_renderer_stats(r, &st);
    out->per_pixel_bytes = st.per_pixel_bytes;
    sss_gl_renderer_gpu_memory(r, &out->technique_bytes, &out->frame_bytes);
    out->renderer_bytes = sss_gl_allocated_bytes() - bytes_before;
    out->nvx_bytes = nvx_used(rn, nvx_before);
}

static row *new_row(run *rn, const char *scene, const char *technique, int s, double zoom)
{
    if (rn->nrows == rn->cap) {
        int cap = rn->cap ? 2 * rn->cap : 64;
        row *grown = realloc(rn->rows, (size_t)cap * sizeof *grown);
        if (!grown) return NULL;
        rn->rows = grown;
        rn->cap = cap;
    }
    row *out = &rn->rows[rn->nrows++];
    memset(out, 0, sizeof *out);
    out->scene = scene;
    out->technique = technique;
    out->width = rn->opt.sizes[s][0];
    out->height = rn->opt.sizes[s][1];
    out->zoom = zoom;
    out->nvx_bytes = -1;
    return out;
}

/* Writes r's image (the scene's exposure) as DIR/<scene file stem>_<technique>.png. */
static void save_image(run *rn, sss_gl_renderer *r, const sss_scene *scene, row *out)
{
    const char *base = strrchr(out->scene, '/');
    base = base ? base + 1 : out->scene;
    char path[1024], name[256];
    snprintf(name, sizeof name, "%.*s_%s", (int)strcspn(base, "."), base, out->technique);
    for (char *c = name; *c; c++)
        if (*c == ':' || *c == '=') *c = '-';
    snprintf(path, sizeof path, "%s/%s.png", rn->opt.images, name);
    sss_image img;
    sss_error err = {0};
    if (sss_image_create(&img, out->width, out->height, &err) != SSS_OK || sss_gl_renderer_read(r, &img, &err) != SSS_OK ||
        sss_image_write(path, &img, scene->render.exposure, &err) != SSS_OK)
        fail(out, "image", err.message);
    sss_image_free(&img);
}

/* One renderer of `spec` on `scene`, timed at every size; a row per size. */
static void bench_technique(run *rn, const char *path, const sss_scene *scene, const char *spec, double zoom)
{
    char name[256];
    sss_gl_param_value params[MAX_SPEC_PARAMS];
    int nparams = 0, ok = parse_spec(spec, name, sizeof name, params, &nparams);
    sss_gl_renderer_desc d;
    memset(&d, 0, sizeof d);
    d.technique = name;
    d.params = params;
    d.param_count = nparams;
    d.width = rn->opt.sizes[0][0];
    d.height = rn->opt.sizes[0][1];
    d.timings = 1;
    size_t bytes_before = sss_gl_allocated_bytes(), nvx_total = 0, nvx_before = 0;
    if (rn->nvx) sss_gl_context_video_memory(rn->ctx, &nvx_total, &nvx_before);
    sss_error err = {0};
    sss_gl_renderer *r = NULL;
    double t0 = sss_time_seconds();
    if (ok && sss_gl_renderer_create(rn->ctx, scene, &d, &r, &err) != SSS_OK) ok = 0;
    double create_s = sss_time_seconds() - t0;
    for (int s = 0; s < rn->opt.nsizes; s++) {
        row *out = new_row(rn, path, spec, s, zoom);
        if (!out) break;
        out->create_s = create_s;
        if (!r) fail(out, "create", ok || err.message[0] ? err.message : "expected NAME:param=value[:param=value]");
        else if (s > 0 && sss_gl_renderer_resize(r, out->width, out->height, &err) != SSS_OK) fail(out, "resize", err.message);
        else measure(rn, r, bytes_before, nvx_before, out);
        if (r && out->ok && out->frames && s == 0 && rn->opt.images) save_image(rn, r, scene, out);
        write_outputs(rn);
        print_row(out);
    }
    sss_gl_renderer_destroy(r);
}

/* The scene's camera moved zoom times as far from its look-at point. */
static void zoom_camera(sss_scene *scene, const double position[3], double zoom)
{
    for (int k = 0; k < 3; k++)
        scene->camera.position[k] = scene->camera.look_at[k] + (position[k] - scene->camera.look_at[k]) * zoom;
}

static int bench_scene(run *rn, const char *path, char **techniques, int n)
{
    sss_error err = {0};
    sss_scene scene;
    if (sss_scene_load(path, NULL, &scene, &err) != SSS_OK) {
        fprintf(stderr, "bench_techniques: %s\n", err.message);
        return 0;
    }
    double position[3] = {scene.camera.position[0], scene.camera.position[1], scene.camera.position[2]};
    for (int z = 0; z < rn->opt.nzooms; z++) {
        zoom_camera(&scene, position, rn->opt.zooms[z]);
        int first = rn->nrows;
        for (int i = 0; i < n; i++) bench_technique(rn, path, &scene, techniques[i], rn->opt.zooms[z]);
        print_tables(rn, first);
    }
    sss_scene_free(&scene);
    return 1;
}

static int parse_count(const char *v, int lo, int *out)
{
    char *end = NULL;
    long x = strtol(v, &end, 10);
    if (!*v || *end || x < lo || x > 100000) return 0;
    *out = (int)x;
    return 1;
}

static int parse_option(options *o, const char *a, const char *v)
{
    if (strcmp(a, "--techniques") == 0) snprintf(o->list, sizeof o->list, "%s", v);
    else if (strcmp(a, "--frames") == 0) return parse_count(v, 0, &o->frames);
    else if (strcmp(a, "--warmup") == 0) return parse_count(v, 0, &o->warmup);
    else if (strcmp(a, "--budget") == 0) return (o->budget = atof(v)) > 0.0;
    else if (strcmp(a, "--tsv") == 0) o->tsv = v;
    else if (strcmp(a, "--json") == 0) o->json = v;
    else if (strcmp(a, "--images") == 0) o->images = v;
    else if (strcmp(a, "--size") == 0 && o->nsizes < MAX_LIST) {
        int *wh = o->sizes[o->nsizes++];
        return sscanf(v, "%dx%d", &wh[0], &wh[1]) == 2 && wh[0] > 0 && wh[1] > 0;
    } else if (strcmp(a, "--zoom") == 0 && o->nzooms < MAX_LIST)
        return (o->zooms[o->nzooms++] = atof(v)) > 0.0;
    else return 0;
    return 1;
}

static int parse_args(int argc, char **argv, options *o)
{
    memset(o, 0, sizeof *o);
    o->frames = SSS_GL_TIMED_FRAMES;
    o->warmup = SSS_GL_WARMUP_FRAMES;
    for (int i = 1; i < argc; i++) {
        if (argv[i][0] != '-') {
            if (o->nscenes == MAX_LIST) return 0;
            o->scenes[o->nscenes++] = argv[i];
        } else if (i + 1 >= argc || !parse_option(o, argv[i], argv[i + 1])) {
            return 0;
        } else {
            i++;
        }
    }
    if (o->nscenes == 0) o->scenes[o->nscenes++] = "scenes/gl_dragon.json";
    if (o->nsizes == 0) {
        o->sizes[0][0] = 960, o->sizes[0][1] = 540, o->sizes[1][0] = 1920, o->sizes[1][1] = 1080;
        o->nsizes = 2;
    }
    if (o->nzooms == 0) o->zooms[o->nzooms++] = 1.0;
    return 1;
}

int main(int argc, char **argv)
{
    run rn;
    memset(&rn, 0, sizeof rn);
    if (!parse_args(argc, argv, &rn.opt)) {
        fprintf(stderr, "usage: bench_techniques [SCENE.json ...] [--techniques a,b,...] [--frames N] [--warmup N] "
                        "[--budget S] [--size WxH ...] [--zoom F ...] [--tsv FILE] [--json FILE] [--images DIR]\n");
        return 2;
    }
    char *techniques[MAX_TECHNIQUES];
    int n = 0;
    if (rn.opt.list[0]) {
        for (char *tok = strtok(rn.opt.list, ","); tok && n < MAX_TECHNIQUES; tok = strtok(NULL, ",")) techniques[n++] = tok;
    } else {
        for (int i = 0; i < sss_gl_technique_count() && n < MAX_TECHNIQUES; i++)
            techniques[n++] = (char *)sss_gl_technique_at(i)->name;
    }
    sss_error err = {0};
    if (sss_gl_context_create(NULL, &rn.ctx, &err) != SSS_OK) {
        fprintf(stderr, "bench_techniques: %s\n", err.message);
        return 1;
    }
    sss_gl_context_get_info(rn.ctx, &rn.info);
    size_t available = 0;
    rn.nvx = sss_gl_context_video_memory(rn.ctx, &rn.vidmem_total, &available);
    printf("bench_techniques: %s (%s, %s)\n", rn.info.renderer, rn.info.version, rn.info.platform);
    int ok = write_outputs(&rn);
    for (int s = 0; ok && s < rn.opt.nscenes; s++) ok = bench_scene(&rn, rn.opt.scenes[s], techniques, n);
    for (int i = 0; i < rn.nrows; i++) ok = ok && rn.rows[i].ok;
    free(rn.rows);
    sss_gl_context_destroy(rn.ctx);
    return ok ? 0 : 1;
}
