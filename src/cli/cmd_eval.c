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

enum {
    OPT_OUT, OPT_TECHNIQUES, OPT_RESOLUTIONS, OPT_TIMING_RESOLUTIONS, OPT_WIDTH, OPT_HEIGHT, OPT_FRAMES, OPT_WARMUP,
    OPT_SUPERSAMPLE, OPT_CACHED_REFERENCE, OPT_REFERENCE_DIR, OPT_REFERENCE_QUALITY, OPT_REFERENCE_BOUNCES, OPT_THREADS,
    OPT_SAM_SWEEP, OPT_NO_SAM_SWEEP, OPT_SAM_COUNTS
};
static const cli_option options[] = {
    {OPT_OUT, "--out", "-o", CLI_ARG_DIR, "DIR", "output folder (default out/eval)", NULL},
    {OPT_OUT, "--output", NULL, CLI_ARG_DIR, "DIR", "the same as --out", NULL},
    {OPT_TECHNIQUES, "--techniques", NULL, CLI_ARG_TECHNIQUE, "LIST",
     "comma-separated specs NAME or NAME:param=value[:param=value]\n"
     "(default: every technique of `sss techniques`); supersample=K in a\n"
     "spec sets that spec's antialiasing (maisch2020,maisch2020:supersample=2)",
     NULL},
    {OPT_RESOLUTIONS, "--resolutions", NULL, CLI_ARG_TEXT, "LIST",
     "sizes compared with the reference, WxH,... (default: the camera's);\n"
     "the first one is used for the sheets",
     NULL},
    {OPT_WIDTH, "--width", NULL, CLI_ARG_NUMBER, "W", "with --height: one size WxH for every scene (--resolutions WxH)", NULL},
    {OPT_HEIGHT, "--height", NULL, CLI_ARG_NUMBER, "H", "with --width", NULL},
    {OPT_TIMING_RESOLUTIONS, "--timing-resolutions", NULL, CLI_ARG_TEXT, "LIST",
     "extra sizes where only frame times are measured", NULL},
    {OPT_FRAMES, "--frames", NULL, CLI_ARG_NUMBER, "N", "timed frames per technique; timings are medians (default 5)", NULL},
    {OPT_WARMUP, "--warmup", NULL, CLI_ARG_NUMBER, "W", "frames rendered first and not timed (default 2)", NULL},
    {OPT_SUPERSAMPLE, "--supersample", NULL, CLI_ARG_NUMBER, "K",
     "antialiasing of every technique (`sss render --supersample`): passes at\n"
     "K x the size, box-filtered down; K in 1..4 (default 1: off)",
     NULL},
    {OPT_CACHED_REFERENCE, "--cached-reference", NULL, CLI_ARG_NONE, NULL,
     "use <scene folder>/references/<scene>_<W>x<H>[_t<T>].exr when it exists\n"
     "(and its .json sidecar matches the scene file), else render it",
     NULL},
    {OPT_REFERENCE_DIR, "--reference-dir", NULL, CLI_ARG_DIR, "DIR", "where cached references are looked up instead", NULL},
    {OPT_REFERENCE_QUALITY, "--reference-quality", NULL, CLI_ARG_TEXT, "Q",
     "final (default) or draft, for references that are rendered", "draft final"},
    {OPT_REFERENCE_BOUNCES, "--reference-bounces", NULL, CLI_ARG_NUMBER, "N",
     "the truth: 1 = the single-event integral (`sss reference --bounces 1`,\n"
     "what techniques that model one event converge to), N = N bounces;\n"
     "default: the full transport (bounces until converged)",
     NULL},
    {OPT_THREADS, "--threads", NULL, CLI_ARG_NUMBER, "N", "threads of the reference renderer (default: all cores)", NULL},
    {OPT_THREADS, "--reference-threads", NULL, CLI_ARG_NUMBER, "N", NULL, NULL}, /* the old spelling, still accepted */
    {OPT_SAM_SWEEP, "--sam-sweep", NULL, CLI_ARG_NONE, NULL,
     "RMSE of `sam` against back-side samples n (Maisch & Ropinski 2017, Fig. 10)\n"
     "even when sam is not among the techniques",
     NULL},
    {OPT_NO_SAM_SWEEP, "--no-sam-sweep", NULL, CLI_ARG_NONE, NULL, "never the sam sweep", NULL},
    {OPT_SAM_COUNTS, "--sam-counts", NULL, CLI_ARG_TEXT, "LIST", "the sample counts of the sweep (default 3,10,20,50)", NULL},
};
const cli_command_spec cli_spec_eval = {CMD, options, CLI_COUNT(options), CLI_ARG_FILE, NULL};

static void print_usage(FILE *f)
{
    fprintf(f,
            "usage: sss eval SCENE.json[@T]... [--out DIR] [--techniques A,B:param=value,...]\n"
            "                [--resolutions WxH,... | --width W --height H] [--timing-resolutions WxH,...]\n"
            "                [--frames N] [--warmup W] [--cached-reference] [--reference-dir DIR]\n"
            "                [--reference-quality draft|final] [--reference-bounces N] [--threads N]\n"
            "                [--sam-sweep | --no-sam-sweep] [--sam-counts 3,10,20,50] [--supersample K]\n"
            "                [--quiet | --progress]\n"
            "\n"
            "Renders every technique and the CPU reference for each scene, compares them (DSSIM, FLIP, PSNR,\n"
            "RMSE on the tone-mapped 8-bit images), times every pass (median of N frames) and writes to DIR:\n"
            "results.json (schema docs/results.schema.json), results.csv, sheet_<scene>.png (reference,\n"
            "techniques, their DSSIM and FLIP maps with colour bars, zoomed crops), crops_<scene>_<k>.png,\n"
            "plot_dssim.png, plot_flip.png, plot_passes.png, plot_resolution.png (per scene),\n"
            "plot_sam_rmse.png (when the SAM sweep ran) and report.html (self-contained; docs/eval.md\n"
            "says how to read it). A technique that fails is reported as failed with its error, not\n"
            "dropped. A summary table goes to stdout.\n"
            "SCENE.json@T evaluates an animated scene at time T seconds (default 0).\n"
            "\n");
    cli_print_options(f, &cli_spec_eval);
    fprintf(f,
            "\n"
            "--reference-threads, the old spelling of --threads, is still accepted.\n"
            "Progress goes to stderr when it is a terminal (a bar with the time left) or with --progress\n"
            "(otherwise a line per stage); notes too, unless --quiet.\n"
            "References rendered during the run are saved to DIR/references/ (half-float EXR + .json\n"
            "sidecar) so that they can be committed next to the scene.\n"
            "Exit status: 0 results written (also when techniques failed), 1 error, 2 usage error.\n");
}

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
    printf("%-22s %-26s %-7s %9s %8s %8s %8s %11s\n", "scene", "technique", "status", "DSSIM", "FLIP", "PSNR", "RMSE",
           "ms/frame");
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
        if (e->ok) snprintf(ms, sizeof ms, "%.1f", e->total_ms);
        printf("%-22.22s %-26.26s %-7s %9s %8s %8s %8s %11s\n", esc(res->scenes[e->scene].name, b1),
               esc(e->label, b2), e->ok ? "ok" : "FAILED", d, fl, p, r, ms);
    }
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

int sss_cmd_eval(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) {
        print_usage(stdout);
        return CLI_EXIT_OK;
    }
    const char *out_dir = "out/eval";
    const char **scenes = calloc((size_t)argc, sizeof *scenes);
    char *tech_text = NULL;
    char *techs[MAX_LIST];
    int nscenes = 0, quiet = 0, status = CLI_EXIT_USAGE;
    sss_eval_desc desc;
    memset(&desc, 0, sizeof desc);
    sss_eval_size *sizes = NULL, *tsizes = NULL, one_size = {0};
    int sam_counts[64];
    char save_dir[2048];
    sss_eval_results res;
    memset(&res, 0, sizeof res);
    if (!scenes) return cli_failf(CMD, "out of memory");
    cli_parser args;
    cli_parser_init(&args, &cli_spec_eval, argc, argv, 1);
    for (int o; (o = cli_next(&args)) != CLI_DONE;) {
        const char *a = args.given, *v = args.value;
        sss_error perr = {0};
        if (o == CLI_BAD) {
            goto done;
        } else if (o == OPT_OUT) {
            out_dir = v;
        } else if (o == OPT_TECHNIQUES) {
            free(tech_text);
            tech_text = strdup(v);
            if (!tech_text) {
                status = cli_failf(CMD, "out of memory");
                goto done;
            }
            int n = split_list(tech_text, techs, MAX_LIST);
            if (n <= 0) {
                cli_usage_error(CMD, "--techniques needs a comma-separated list (at most %d)", MAX_LIST);
                goto done;
            }
            for (int k = 0; k < n; k++) {
                if (sss_eval_check_spec(techs[k], &perr) != SSS_OK) {
                    cli_usage_error(CMD, "--techniques: %s", perr.message);
                    goto done;
                }
            }
            desc.techniques = (const char *const *)techs;
            desc.technique_count = n;
        } else if (o == OPT_RESOLUTIONS || o == OPT_TIMING_RESOLUTIONS) {
            int timing = o == OPT_TIMING_RESOLUTIONS;
            sss_eval_size **dst = timing ? &tsizes : &sizes;
            free(*dst);
            int n = 0;
            if (sss_eval_parse_sizes(v, dst, &n, &perr) != SSS_OK) {
                cli_usage_error(CMD, "%s: %s", a, perr.message);
                goto done;
            }
            if (!timing && n > 8) {
                cli_usage_error(CMD, "--resolutions: at most 8 sizes");
                goto done;
            }
            if (timing) desc.timing_resolution_count = n;
            else desc.resolution_count = n;
        } else if (o == OPT_WIDTH || o == OPT_HEIGHT) {
            if (!cli_parse_size(CMD, a, v, o == OPT_WIDTH ? &one_size.width : &one_size.height)) goto done;
        } else if (o == OPT_FRAMES) {
            if (!cli_parse_int(CMD, a, v, &desc.frames)) goto done;
            if (desc.frames < 1 || desc.frames > 10000) {
                cli_usage_error(CMD, "--frames must be in 1..10000");
                goto done;
            }
        } else if (o == OPT_WARMUP) {
            if (!cli_parse_int(CMD, a, v, &desc.warmup_frames)) goto done;
            if (desc.warmup_frames < 0 || desc.warmup_frames > 10000) {
                cli_usage_error(CMD, "--warmup must be in 0..10000");
                goto done;
            }
            if (desc.warmup_frames == 0) desc.warmup_frames = -1; /* the library's "none" */
        } else if (o == OPT_SUPERSAMPLE) {
            if (!cli_parse_supersample(CMD, a, v, &desc.supersample)) goto done;
        } else if (o == OPT_CACHED_REFERENCE) {
            desc.cached_reference = 1;
        } else if (o == OPT_REFERENCE_DIR) {
            desc.reference_dir = v;
        } else if (o == OPT_REFERENCE_QUALITY) {
            if (strcmp(v, "final") == 0) desc.reference_quality = SSS_REFERENCE_FINAL;
            else if (strcmp(v, "draft") == 0) desc.reference_quality = SSS_REFERENCE_DRAFT;
            else {
                cli_usage_error(CMD, "--reference-quality must be draft or final, got '%s'", v);
                goto done;
            }
        } else if (o == OPT_REFERENCE_BOUNCES) {
            if (!cli_parse_int(CMD, a, v, &desc.reference_bounces)) goto done;
            if (desc.reference_bounces < 1 || desc.reference_bounces > SSS_REFERENCE_MAX_BOUNCES) {
                cli_usage_error(CMD, "--reference-bounces must be in 1..%d, got %d", SSS_REFERENCE_MAX_BOUNCES,
                                desc.reference_bounces);
                goto done;
            }
        } else if (o == OPT_THREADS) {
            if (!cli_parse_int(CMD, a, v, &desc.reference_threads)) goto done;
            if (desc.reference_threads < 1 || desc.reference_threads > 4096) {
                cli_usage_error(CMD, "%s must be in 1..4096", a);
                goto done;
            }
        } else if (o == OPT_SAM_SWEEP) {
            desc.sam_sweep = 1;
        } else if (o == OPT_NO_SAM_SWEEP) {
            desc.sam_sweep = -1;
        } else if (o == OPT_SAM_COUNTS) {
            char buf[512];
            snprintf(buf, sizeof buf, "%s", v);
            char *items[64];
            int n = split_list(buf, items, 64);
            if (n <= 0) {
                cli_usage_error(CMD, "--sam-counts needs a comma-separated list of at most 64 counts");
                goto done;
            }
            for (int k = 0; k < n; k++) {
                if (!cli_parse_int(CMD, a, items[k], &sam_counts[k])) goto done;
                if (sam_counts[k] < 1) {
                    cli_usage_error(CMD, "--sam-counts: counts must be >= 1");
                    goto done;
                }
            }
            desc.sam_counts = sam_counts;
            desc.sam_count_count = n;
        } else { /* CLI_OPERAND */
            scenes[nscenes++] = v;
        }
    }
    quiet = args.quiet;
    for (int k = 0; k < desc.technique_count && !quiet; k++) /* run and reported as failed, not refused */
        warn_unknown_technique(techs[k]);
    if ((one_size.width > 0) != (one_size.height > 0)) {
        cli_usage_error(CMD, "--width and --height go together (one size for every scene)");
        goto done;
    }
    if (one_size.width > 0) {
        if (sizes) {
            cli_usage_error(CMD, "--width/--height and --resolutions exclude each other");
            goto done;
        }
        char text[64];
        snprintf(text, sizeof text, "%dx%d", one_size.width, one_size.height);
        sss_error perr = {0};
        if (sss_eval_parse_sizes(text, &sizes, &desc.resolution_count, &perr) != SSS_OK) {
            cli_usage_error(CMD, "--width/--height: %s", perr.message);
            goto done;
        }
    }
    if (nscenes == 0) {
        cli_usage_error(CMD, "expects at least one scene file");
        goto done;
    }
    desc.resolutions = sizes;
    desc.timing_resolutions = tsizes;
    snprintf(save_dir, sizeof save_dir, "%s/references", out_dir);
    desc.save_references_dir = save_dir;

    progress_state ps;
    memset(&ps, 0, sizeof ps);
    ps.tty = isatty(fileno(stderr));
    ps.quiet = quiet;
    ps.show = cli_show_progress(&args);
    ps.start = sss_time_seconds();
    sss_eval_callbacks cb = {on_progress, on_note, &ps};
    sss_error err = {0};
    sss_result r = sss_eval_run(scenes, nscenes, &desc, &cb, &res, &err);
    if (ps.tty && ps.bar_shown) fputc('\n', stderr);
    if (r != SSS_OK) {
        status = cli_fail(CMD, &err);
        goto done;
    }
    if (sss_eval_write_all(&res, out_dir, &err) != SSS_OK) {
        status = cli_fail(CMD, &err);
        goto done;
    }
    print_summary(&res, out_dir);
    status = CLI_EXIT_OK;
done:
    sss_eval_results_free(&res);
    free(sizes);
    free(tsizes);
    free(tech_text);
    free(scenes);
    return status;
}
