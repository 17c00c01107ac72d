/* cli/cmd_eval.c — `sss eval SCENE.json... --out DIR`: every technique against the CPU reference on each
 * scene (sss/eval.h): results.json/.csv, comparison sheets, plots and report.html; a progress bar with
 * ETA on a terminal, plain lines otherwise; a summary table on stdout. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include "cli/cli.h"
#include "core/text.h"
#include "sss/eval.h"
#include "sss/gl.h"

#define CMD "eval"
#define MAX_LIST 256
#define MAX_IMAGES 16

enum {
    OPT_OUT, OPT_TECHNIQUES, OPT_RESOLUTIONS, OPT_TIMING_RESOLUTIONS, OPT_WIDTH, OPT_HEIGHT, OPT_FRAMES, OPT_WARMUP, OPT_FRAME_BUDGET,
    OPT_SUPERSAMPLE, OPT_CACHED_REFERENCE, OPT_REFERENCE_DIR, OPT_REFERENCE_QUALITY, OPT_REFERENCE_BOUNCES, OPT_REFERENCE_NOISE, OPT_BOTH_TRUTHS, OPT_THREADS,
    OPT_SAM_SWEEP, OPT_NO_SAM_SWEEP, OPT_SAM_COUNTS, OPT_IMAGES
};
static const cli_option options[] = {
    {OPT_OUT, "--out", "-o", CLI_ARG_DIR, "DIR", "output folder", NULL, "out/eval"},
    {OPT_OUT, "--output", NULL, CLI_ARG_DIR, "DIR", "the same as --out", NULL, NULL},
    {OPT_TECHNIQUES, "--techniques", NULL, CLI_ARG_TECHNIQUE, "LIST",
     "comma-separated specs NAME or NAME:param=value[:param=value]\n"
     "(default: every technique of `sss techniques`); supersample=K in a\n"
     "spec sets that spec's antialiasing (maisch2020,maisch2020:supersample=2)",
     NULL, NULL},
    {OPT_RESOLUTIONS, "--resolutions", NULL, CLI_ARG_TEXT, "LIST",
     "sizes compared with the reference, WxH,... (default: the camera's);\n"
     "the first one is used for the sheets",
     NULL, NULL},
    {OPT_WIDTH, "--width", NULL, CLI_ARG_NUMBER, "W", "with --height: one size WxH for every scene (--resolutions WxH)",
     NULL, NULL},
    {OPT_HEIGHT, "--height", NULL, CLI_ARG_NUMBER, "H", "with --width", NULL, NULL},
    {OPT_TIMING_RESOLUTIONS, "--timing-resolutions", NULL, CLI_ARG_TEXT, "LIST",
     "extra sizes where only frame times are measured", NULL, NULL},
    {OPT_FRAMES, "--frames", NULL, CLI_ARG_NUMBER, "N", "timed frames per technique; timings are medians", NULL, "5"},
    {OPT_WARMUP, "--warmup", NULL, CLI_ARG_NUMBER, "W", "frames rendered first and not timed", NULL, "2"},
    {OPT_FRAME_BUDGET, "--frame-budget", NULL, CLI_ARG_NUMBER, "S",
     "a technique's timed frames stop after S seconds (at least one); one whose\n"
     "first warm-up frame alone takes longer is timed on that frame (no warm-up)",
     NULL, "none"},
    {OPT_SUPERSAMPLE, "--supersample", NULL, CLI_ARG_NUMBER, "K",
     "antialiasing of every technique (`sss render --supersample`): passes at\n"
     "K x the size, box-filtered down; K in 1..4",
     NULL, "1 = off"},
    {OPT_CACHED_REFERENCE, "--cached-reference", NULL, CLI_ARG_NONE, NULL,
     "use <scene folder>/references/<scene>_<W>x<H>[_t<T>].exr when it exists\n"
     "(and its .json sidecar matches the scene file), else render it",
     NULL, NULL},
    {OPT_REFERENCE_DIR, "--reference-dir", NULL, CLI_ARG_DIR, "DIR", "where cached references are looked up instead", NULL,
     NULL},
    {OPT_REFERENCE_QUALITY, "--reference-quality", NULL, CLI_ARG_TEXT, "Q",
     "final or draft, for references that are rendered", "draft final", "final"},
    {OPT_REFERENCE_BOUNCES, "--reference-bounces", NULL, CLI_ARG_NUMBER, "N",
     "the truth: 1 = the single-event integral (`sss reference --bounces 1`,\n"
     "what techniques that model one event converge to), N = N bounces;\n"
     "default: the full transport (bounces until converged)",
     NULL, NULL},
    {OPT_REFERENCE_NOISE, "--reference-noise", NULL, CLI_ARG_NONE, NULL,
     "a second reference (seed 1) at the first size: the largest change of a\n"
     "technique's DSSIM or FLIP between the two is the scene's noise, and the\n"
     "report marks a best technique only when it leads by more (cached as\n"
     "<scene>_seed1_<W>x<H>[_t<T>].exr)",
     NULL, NULL},
    {OPT_BOTH_TRUTHS, "--both-truths", NULL, CLI_ARG_NONE, NULL,
     "score every technique against two truths side by side: the full transport\n"
     "(the default) and the single-event integral (bounces 1: light from the\n"
     "lights only), rendered at the same quality and cached as\n"
     "<scene>_bounces1_<W>x<H>[_t<T>].exr; the difference is the light between\n"
     "surfaces, which no technique models unless its interreflection is on",
     NULL, NULL},
    {OPT_THREADS, "--threads", NULL, CLI_ARG_NUMBER, "N", "threads of the reference renderer", NULL, "all cores"},
    /* the old spelling, still accepted */
    {OPT_THREADS, "--reference-threads", NULL, CLI_ARG_NUMBER, "N", NULL, NULL, NULL},
    {OPT_SAM_SWEEP, "--sam-sweep", NULL, CLI_ARG_NONE, NULL,
     "RMSE of `sam` against back-side samples n (Maisch & Ropinski 2017, Fig. 10)\n"
     "even when sam is not among the techniques",
     NULL, NULL},
    {OPT_NO_SAM_SWEEP, "--no-sam-sweep", NULL, CLI_ARG_NONE, NULL, "never the sam sweep", NULL, NULL},
    {OPT_SAM_COUNTS, "--sam-counts", NULL, CLI_ARG_TEXT, "LIST", "the sample counts of the sweep", NULL, "3,10,20,50"},
    {OPT_IMAGES, "--images", NULL, CLI_ARG_TEXT, "NAME=PATTERN",
     "images of another renderer scored like a technique, marked external;\n"
     "{scene} in PATTERN is the scene file's name without .json; EXR, PFM,\n"
     "HDR linear, PNG sRGB; the scene's size; repeat for more (at most 16)",
     NULL, NULL},
};
const cli_command_spec cli_spec_eval = {
    CMD, options, CLI_COUNT(options), CLI_ARG_FILE, NULL, "SCENE.json[@T]...",
    "Renders every technique and the CPU reference for each scene, compares them (DSSIM, FLIP, PSNR,\n"
    "RMSE on the tone-mapped 8-bit images), times every pass (median of N frames) and writes to DIR:\n"
    "results.json (schema docs/results.schema.json), results.csv, sheet_<scene>.png (reference,\n"
    "techniques, their DSSIM and FLIP maps with colour bars, zoomed crops), crops_<scene>_<k>.png,\n"
    "plot_dssim.png, plot_flip.png, plot_passes.png, plot_resolution.png (per scene),\n"
    "plot_sam_rmse.png (when the SAM sweep ran) and report.html (self-contained; docs/eval.md\n"
    "says how to read it). A technique that fails is reported as failed with its error, not\n"
    "dropped. A summary table goes to stdout.\n"
    "SCENE.json@T evaluates an animated scene at time T seconds (default 0).\n",
    "--reference-threads, the old spelling of --threads, is still accepted.\n"
    "Progress goes to stderr when it is a terminal (a bar with the time left) or with --progress\n"
    "(otherwise a line per stage); notes too, unless --quiet.\n"
    "References rendered during the run are saved to DIR/references/ (half-float EXR + .json\n"
    "sidecar) so that they can be committed next to the scene.\n"
    "Exit status: 0 results written (also when techniques failed), 1 error, 2 usage error.\n",
    NULL};

typedef struct progress_state {
    int tty, quiet, show; /* show: the progress (cli_show_progress); quiet: no notes either */
    double start;
    char last[256];
    int bar_shown;
} progress_state;

/* Stage without the per-frame suffix, for the plain (non-terminal) lines. */
static void major_stage(const char *stage, char *out, size_t cap)
{
    snprintf(out, cap, "%s", stage ? stage : "");
    const char *cut[] = {": frame ", ": set-up"};
    for (int i = 0; i < 2; i++) {
        char *p = strstr(out, cut[i]);
        if (p) *p = '\0';
    }
    char *paren = strstr(out, ": reference (");
    if (paren) paren[strlen(": reference")] = '\0';
}

static void on_progress(void *user, double fraction, const char *stage)
{
    progress_state *p = user;
    if (!p->show) return;
    if (p->tty) {
        double elapsed = sss_time_seconds() - p->start;
        char eta[32] = "--:--";
        if (fraction > 0.01 && fraction < 1) {
            int s = (int)(elapsed * (1.0 - fraction) / fraction + 0.5);
            snprintf(eta, sizeof eta, "%d:%02d", s / 60, s % 60);
        } else if (fraction >= 1) {
            snprintf(eta, sizeof eta, "0:00");
        }
        char bar[26];
        int filled = (int)(25.0 * fraction);
        for (int i = 0; i < 25; i++) bar[i] = i < filled ? '#' : '.';
        bar[25] = '\0';
        /* one line: the stage is cut to the terminal's width so that \r keeps overwriting it */
        struct winsize ws;
        int cols = ioctl(fileno(stderr), TIOCGWINSZ, &ws) == 0 && ws.ws_col > 0 ? ws.ws_col : 80;
        int room = cols - 1 - (27 + 5 + 4 + 10 + 2);
        if (room < 0) room = 0;
        char shown[SSS_TEXT_ESCAPE_MAX * 256 + 1]; /* the stage names scenes: escaped like every message */
        sss_text_escape(stage ? stage : "", stage ? strnlen(stage, 256) : 0, shown);
        fprintf(stderr, "\r\033[K[%s] %3d%% ETA %s  %.*s", bar, (int)(100.0 * fraction), eta, room, shown);
        fflush(stderr);
        p->bar_shown = 1;
    } else {
        char major[256];
        major_stage(stage, major, sizeof major);
        if (strcmp(major, p->last) != 0) {
            snprintf(p->last, sizeof p->last, "%s", major);
            char shown[SSS_TEXT_ESCAPE_MAX * sizeof major + 1];
            sss_text_escape(major, strlen(major), shown);
            fprintf(stderr, "[%3d%%] %s\n", (int)(100.0 * fraction), shown);
        }
    }
}

static void on_note(void *user, const char *msg)
{
    progress_state *p = user;
    if (p->quiet) return;
    if (p->tty && p->bar_shown) fputs("\r\033[K", stderr);
    cli_message(CMD, "%s", msg);
}

/* A spec whose technique is unknown runs (and fails, in the results); a likely typo gets a warning. */
static void warn_unknown_technique(const char *spec)
{
    char name[64];
    snprintf(name, sizeof name, "%.*s", (int)strcspn(spec, ":"), spec);
    if (sss_gl_technique_find(name)) return;
    const char *names[64];
    const char *s = cli_suggest(name, names, cli_technique_names(names, 64));
    if (s) cli_message(CMD, "warning: unknown technique '%s'; did you mean '%s'?", name, s);
}

/* Splits a comma-separated list in place. */
static int split_list(char *text, char **items, int max)
{
    int n = 0;
    for (char *tok = strtok(text, ","); tok; tok = strtok(NULL, ",")) {
        if (n >= max) return -1;
        items[n++] = tok;
    }
    return n;
}

/* s with its control characters escaped (core/text.h) into buf, the input cut to fit cap: scene
 * names come from file names, errors and labels from data, and none may reach a terminal raw. */
#define ESC_CAP (SSS_TEXT_ESCAPE_MAX * 256 + 1)
static const char *esc(const char *s, char buf[ESC_CAP])
{
    sss_text_escape(s, strnlen(s, 256), buf);
    return buf;
}

static void print_summary(const sss_eval_results *res, const char *out_dir)
{
    char b1[ESC_CAP], b2[ESC_CAP], b3[ESC_CAP];
    int two = res->both_truths;
    if (two) /* which truth each group of columns scores against */
        printf("%-61s %-35s %s\n", "", res->reference_bounces ? "---- vs the main truth ----" : "----- vs full transport -----",
               "-- vs single event --");
    printf("%-22s %-30s %-7s %9s %8s %8s %8s%s %11s\n", "scene", "technique", "status", "DSSIM", "FLIP", "PSNR", "RMSE",
           two ? "    DSSIM     FLIP" : "", "ms/frame");
    int cut = 0; /* entries timed on fewer frames than asked (--frame-budget) */
    for (int i = 0; i < res->entry_count; i++) {
        const sss_eval_entry *e = &res->entries[i];
        if (e->kind != SSS_EVAL_QUALITY) continue;
        int pw = res->scenes[e->scene].references[0].width, ph = res->scenes[e->scene].references[0].height;
        if (e->width != pw || e->height != ph) continue;
        char d[16] = "-", fl[16] = "-", p[16] = "-", r[16] = "-", ms[24] = "-";
        if (e->has_metrics) {
            snprintf(d, sizeof d, "%.4f", e->metrics.dssim);
            snprintf(fl, sizeof fl, "%.4f", e->metrics.flip);
            if (isfinite(e->metrics.psnr)) snprintf(p, sizeof p, "%.2f", e->metrics.psnr);
            else snprintf(p, sizeof p, "inf");
            snprintf(r, sizeof r, "%.3f", e->metrics.rmse);
        }
        if (e->external) snprintf(ms, sizeof ms, "external");
        else if (e->ok) {
            int fewer = e->frames < res->frames || e->warmup_frames < res->warmup_frames;
            snprintf(ms, sizeof ms, "%.1f%s", e->total_ms, fewer ? "*" : "");
            cut += fewer;
        }
        char single[32] = "";
        if (two && e->has_single_event)
            snprintf(single, sizeof single, " %8.4f %8.4f", e->single_event.dssim, e->single_event.flip);
        else if (two) snprintf(single, sizeof single, " %8s %8s", "-", "-");
        printf("%-22.22s %-30.30s %-7s %9s %8s %8s %8s%s %11s\n", esc(res->scenes[e->scene].name, b1),
               esc(e->label, b2), e->ok ? "ok" : "FAILED", d, fl, p, r, single, ms);
    }
    if (cut)
        printf("* fewer frames than asked (--frame-budget %g s); without warm-up where the first frame took longer:\n"
               "  its time then includes one-off costs (results.json: frames, warmup_frames)\n",
               res->frame_budget_s);
    int failed = 0;
    for (int i = 0; i < res->entry_count; i++) failed += !res->entries[i].ok;
    if (failed) {
        printf("\n%d failed run%s:\n", failed, failed == 1 ? "" : "s");
        for (int i = 0; i < res->entry_count; i++) {
            const sss_eval_entry *e = &res->entries[i];
            if (!e->ok)
                printf("  %s / %s (%dx%d): %.200s\n", esc(res->scenes[e->scene].name, b1), esc(e->label, b2), e->width,
                       e->height, esc(e->error, b3));
        }
    }
    for (int s = 0; s < res->scene_count; s++)
        for (int k = 0; k < res->scenes[s].reference_count; k++) {
            const sss_eval_reference *r = &res->scenes[s].references[k];
            if (r->source == SSS_EVAL_REF_NONE)
                printf("reference %s %dx%d unavailable: %s\n", esc(res->scenes[s].name, b1), r->width, r->height,
                       esc(r->error, b2));
        }
    printf("\n%d scene%s, %d technique%s, %.1f s; timings: %s\n", res->scene_count, res->scene_count == 1 ? "" : "s",
           res->label_count, res->label_count == 1 ? "" : "s", res->seconds,
           esc(res->timing_method[0] ? res->timing_method : (res->gl_ok ? "-" : res->gl_error), b1));
    printf("wrote %s/report.html (and results.json, results.csv, sheets, plots)\n", esc(out_dir, b2));
}

typedef struct eval_options {
    const char *out_dir;
    const char **scenes; /* argc entries */
    int nscenes;
    char *tech_text;     /* --techniques, split in place into techs */
    char *techs[MAX_LIST];
    sss_eval_size *sizes, *tsizes, one_size;
    int sam_counts[64];
    sss_eval_image_source images[MAX_IMAGES];
    char save_dir[2048];
    sss_eval_desc desc;  /* points into the fields above */
    cli_common common;
} eval_options;

static void eval_options_free(eval_options *o)
{
    free(o->sizes);
    free(o->tsizes);
    free(o->tech_text);
    free(o->scenes);
    for (int j = 0; j < o->desc.image_count; j++) free((char *)o->images[j].name);
}

static int set_techniques(eval_options *o, const char *v)
{
    free(o->tech_text);
    o->tech_text = strdup(v);
    if (!o->tech_text) return cli_failf(CMD, "out of memory");
    int n = split_list(o->tech_text, o->techs, MAX_LIST);
    if (n <= 0) return cli_usage_error(CMD, "--techniques needs a comma-separated list (at most %d)", MAX_LIST);
    for (int k = 0; k < n; k++) {
        sss_error perr = {0};
        if (sss_eval_check_spec(o->techs[k], &perr) != SSS_OK)
            return cli_usage_error(CMD, "--techniques: %s", perr.message);
    }
    o->desc.techniques = (const char *const *)o->techs;
    o->desc.technique_count = n;
    return CLI_EXIT_OK;
}

static int set_sizes(eval_options *o, int timing, const char *a, const char *v)
{
    sss_eval_size **dst = timing ? &o->tsizes : &o->sizes;
    free(*dst);
    int n = 0;
    sss_error perr = {0};
    if (sss_eval_parse_sizes(v, dst, &n, &perr) != SSS_OK) return cli_usage_error(CMD, "%s: %s", a, perr.message);
    if (!timing && n > 8) return cli_usage_error(CMD, "--resolutions: at most 8 sizes");
    if (timing) o->desc.timing_resolution_count = n;
    else o->desc.resolution_count = n;
    return CLI_EXIT_OK;
}

static int set_sam_counts(eval_options *o, const char *a, const char *v)
{
    char buf[512];
    snprintf(buf, sizeof buf, "%s", v);
    char *items[64];
    int n = split_list(buf, items, 64);
    if (n <= 0) return cli_usage_error(CMD, "--sam-counts needs a comma-separated list of at most 64 counts");
    for (int k = 0; k < n; k++) {
        if (!cli_parse_int(CMD, a, items[k], &o->sam_counts[k])) return CLI_EXIT_USAGE;
        if (o->sam_counts[k] < 1) return cli_usage_error(CMD, "--sam-counts: counts must be >= 1");
    }
    o->desc.sam_counts = o->sam_counts;
    o->desc.sam_count_count = n;
    return CLI_EXIT_OK;
}

/* --images NAME=PATTERN (v lives as long as argv). */
static int add_images(eval_options *o, const char *v)
{
    const char *eq = strchr(v, '=');
    if (!eq || eq == v || !eq[1]) return cli_usage_error(CMD, "--images needs NAME=PATTERN, got '%s'", v);
    if (o->desc.image_count >= MAX_IMAGES) return cli_usage_error(CMD, "--images: at most %d", MAX_IMAGES);
    char *name = strndup(v, (size_t)(eq - v));
    if (!name) return cli_failf(CMD, "out of memory");
    o->images[o->desc.image_count].name = name;
    o->images[o->desc.image_count].pattern = eq + 1;
    o->desc.images = o->images;
    o->desc.image_count++;
    return CLI_EXIT_OK;
}

/* An integer option's value in min..max, else the usage error "NAME must be in min..max". */
static int set_int(const char *a, const char *v, int min, int max, const char *shown, int *out)
{
    if (!cli_parse_int(CMD, a, v, out)) return CLI_EXIT_USAGE;
    if (*out < min || *out > max) return cli_usage_error(CMD, "%s must be in %d..%d", shown, min, max);
    return CLI_EXIT_OK;
}

static int set_reference_option(eval_options *o, int id, const char *a, const char *v)
{
    sss_eval_desc *d = &o->desc;
    switch (id) {
    case OPT_CACHED_REFERENCE: d->cached_reference = 1; break;
    case OPT_REFERENCE_NOISE: d->reference_noise = 1; break;
    case OPT_BOTH_TRUTHS: d->both_truths = 1; break;
    case OPT_REFERENCE_DIR: d->reference_dir = v; break;
    case OPT_REFERENCE_QUALITY:
        if (strcmp(v, "final") == 0) d->reference_quality = SSS_REFERENCE_FINAL;
        else if (strcmp(v, "draft") == 0) d->reference_quality = SSS_REFERENCE_DRAFT;
        else return cli_usage_error(CMD, "--reference-quality must be draft or final, got '%s'", v);
        break;
    case OPT_REFERENCE_BOUNCES:
        if (!cli_parse_int(CMD, a, v, &d->reference_bounces)) return CLI_EXIT_USAGE;
        if (d->reference_bounces < 1 || d->reference_bounces > SSS_REFERENCE_MAX_BOUNCES)
            return cli_usage_error(CMD, "--reference-bounces must be in 1..%d, got %d", SSS_REFERENCE_MAX_BOUNCES,
                                   d->reference_bounces);
        break;
    default: /* OPT_THREADS */
        return set_int(a, v, 1, 4096, a, &d->reference_threads);
    }
    return CLI_EXIT_OK;
}

static int set_option(void *opts, int id, const char *a, const char *v)
{
    eval_options *o = opts;
    sss_eval_desc *d = &o->desc;
    switch (id) {
    case OPT_OUT: o->out_dir = v; return CLI_EXIT_OK;
    case OPT_TECHNIQUES: return set_techniques(o, v);
    case OPT_RESOLUTIONS:
    case OPT_TIMING_RESOLUTIONS: return set_sizes(o, id == OPT_TIMING_RESOLUTIONS, a, v);
    case OPT_WIDTH:
    case OPT_HEIGHT:
        return cli_parse_size(CMD, a, v, id == OPT_WIDTH ? &o->one_size.width : &o->one_size.height) ? CLI_EXIT_OK
                                                                                                     : CLI_EXIT_USAGE;
    case OPT_FRAMES: return set_int(a, v, 1, 10000, "--frames", &d->frames);
    case OPT_WARMUP: {
        int status = set_int(a, v, 0, 10000, "--warmup", &d->warmup_frames);
        if (d->warmup_frames == 0) d->warmup_frames = -1; /* the library's "none" */
        return status;
    }
    case OPT_FRAME_BUDGET:
        if (!cli_parse_positive(CMD, a, v, &d->frame_budget_s)) return CLI_EXIT_USAGE;
        return d->frame_budget_s <= 1e6 ? CLI_EXIT_OK : cli_usage_error(CMD, "--frame-budget must be at most 1e6 seconds");
    case OPT_SUPERSAMPLE: return cli_parse_supersample(CMD, a, v, &d->supersample) ? CLI_EXIT_OK : CLI_EXIT_USAGE;
    case OPT_SAM_SWEEP: d->sam_sweep = 1; return CLI_EXIT_OK;
    case OPT_NO_SAM_SWEEP: d->sam_sweep = -1; return CLI_EXIT_OK;
    case OPT_SAM_COUNTS: return set_sam_counts(o, a, v);
    case OPT_IMAGES: return add_images(o, v);
    case CLI_OPERAND: o->scenes[o->nscenes++] = v; return CLI_EXIT_OK;
    default: return set_reference_option(o, id, a, v);
    }
}

/* --width/--height: one size for every scene, as --resolutions WxH. */
static int check_sizes(eval_options *o)
{
    if ((o->one_size.width > 0) != (o->one_size.height > 0))
        return cli_usage_error(CMD, "--width and --height go together (one size for every scene)");
    if (o->one_size.width > 0) {
        if (o->sizes) return cli_usage_error(CMD, "--width/--height and --resolutions exclude each other");
        char text[64];
        snprintf(text, sizeof text, "%dx%d", o->one_size.width, o->one_size.height);
        sss_error perr = {0};
        if (sss_eval_parse_sizes(text, &o->sizes, &o->desc.resolution_count, &perr) != SSS_OK)
            return cli_usage_error(CMD, "--width/--height: %s", perr.message);
    }
    return CLI_EXIT_OK;
}

/* o is freed with eval_options_free, also on failure. */
static int eval_parse(int argc, char **argv, eval_options *o)
{
    memset(o, 0, sizeof *o);
    o->out_dir = "out/eval";
    o->scenes = calloc((size_t)argc, sizeof *o->scenes);
    if (!o->scenes) return cli_failf(CMD, "out of memory");
    int status = cli_parse(&cli_spec_eval, argc, argv, 1, set_option, o, &o->common);
    if (status != CLI_EXIT_OK) return status;
    for (int k = 0; k < o->desc.technique_count && !o->common.quiet; k++) /* run and reported as failed, not refused */
        warn_unknown_technique(o->techs[k]);
    if ((status = check_sizes(o)) != CLI_EXIT_OK) return status;
    if (o->nscenes == 0) return cli_usage_error(CMD, "expects at least one scene file");
    if (o->desc.both_truths && o->desc.reference_bounces == 1)
        return cli_usage_error(CMD, "--both-truths adds the single-event truth to the full transport; with "
                                    "--reference-bounces 1 both would be the single-event truth");
    o->desc.resolutions = o->sizes;
    o->desc.timing_resolutions = o->tsizes;
    snprintf(o->save_dir, sizeof o->save_dir, "%s/references", o->out_dir);
    o->desc.save_references_dir = o->save_dir;
    return CLI_EXIT_OK;
}

static int eval_run(const eval_options *o)
{
    progress_state ps;
    memset(&ps, 0, sizeof ps);
    ps.tty = isatty(fileno(stderr));
    ps.quiet = o->common.quiet;
    ps.show = cli_show_progress(&o->common);
    ps.start = sss_time_seconds();
    sss_eval_callbacks cb = {on_progress, on_note, &ps};
    sss_eval_results res;
    memset(&res, 0, sizeof res);
    sss_error err = {0};
    sss_result r = sss_eval_run(o->scenes, o->nscenes, &o->desc, &cb, &res, &err);
    if (ps.tty && ps.bar_shown) fputc('\n', stderr);
    if (r == SSS_OK) r = sss_eval_write_all(&res, o->out_dir, &err);
    if (r == SSS_OK) print_summary(&res, o->out_dir);
    sss_eval_results_free(&res);
    return r == SSS_OK ? CLI_EXIT_OK : cli_fail(CMD, &err);
}

int sss_cmd_eval(int argc, char **argv)
{
    eval_options o;
    int status = eval_parse(argc, argv, &o);
    if (status == CLI_EXIT_OK) status = eval_run(&o);
    eval_options_free(&o);
    return status;
}
