/* cli/cmd_view.c — `sss view SCENE.json`: the interactive viewer (GLFW window, orbit camera, technique
 * switching, parts alone, media presets, light, animation, screenshots, DSSIM against a background
 * reference), or N frames without input and a screenshot for tests under Xvfb. */
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"
#include "core/file_util.h"
#include "sss/scene.h"
#include "sss/view.h"

#define CMD "view"
#define MAX_FRAMES 100000

enum {
    OPT_TECHNIQUE, OPT_WIDTH, OPT_HEIGHT, OPT_PARAM, OPT_TIME, OPT_ANIMATE, OPT_FRAMES, OPT_SCREENSHOT, OPT_NO_OVERLAY,
    OPT_REFERENCE, OPT_DRAFT_REFERENCE, OPT_SUPERSAMPLE, OPT_INPUT, OPT_SCRIPT
};
static const cli_option options[] = {
    {OPT_TECHNIQUE, "--technique", NULL, CLI_ARG_TECHNIQUE, "NAME", "first technique", NULL,
     "the scene's render.technique"},
    {OPT_WIDTH, "--width", NULL, CLI_ARG_NUMBER, "W", "window width", NULL, "the scene camera's"},
    {OPT_HEIGHT, "--height", NULL, CLI_ARG_NUMBER, "H", "window height", NULL, "the scene camera's"},
    {OPT_PARAM, "--param", NULL, CLI_ARG_TEXT, "NAME=VALUE",
     "a technique or shared parameter, repeatable (kept across technique\n"
     "switches for the techniques that have it)",
     NULL, NULL},
    {OPT_TIME, "--time", NULL, CLI_ARG_NUMBER, "T", "animation time of the first frame", NULL, "0"},
    {OPT_ANIMATE, "--animate", NULL, CLI_ARG_NONE, NULL, "start with the animation playing (--frames: 30 frames per second)",
     NULL, NULL},
    {OPT_FRAMES, "--frames", NULL, CLI_ARG_NUMBER, "N", "render N frames without input, then exit", NULL, NULL},
    {OPT_SCREENSHOT, "--screenshot", NULL, CLI_ARG_FILE, "FILE",
     "with --frames: write the last frame as PNG (the window's image without\n"
     "the overlay, the same image as `sss render` of that view)",
     NULL, NULL},
    {OPT_SCREENSHOT, "--output", "-o", CLI_ARG_FILE, "FILE", "the same as --screenshot", NULL, NULL},
    {OPT_NO_OVERLAY, "--no-overlay", NULL, CLI_ARG_NONE, NULL, "start with the panel hidden (O toggles it)", NULL, NULL},
    {OPT_SCRIPT, "--script", NULL, CLI_ARG_FILE, "FILE",
     "run the panel actions of FILE, one per line, then exit (docs/viewer.md):\n"
     "technique NAME, param [TECH.]NAME VALUE, material OBJ FIELD VALUE...,\n"
     "light I position|intensity|colour VALUE..., buffer NAME,\n"
     "split off|reference|TECH [POS], errormap on|off, panel on|off,\n"
     "reference [draft], key EVENT, frames N, screenshot FILE.png",
     NULL, NULL},
    {OPT_REFERENCE, "--reference", NULL, CLI_ARG_NONE, NULL,
     "render the CPU reference of the first view in the background at once;\n"
     "with --frames, wait for it and print the DSSIM of the last frame",
     NULL, NULL},
    {OPT_DRAFT_REFERENCE, "--draft-reference", NULL, CLI_ARG_NONE, NULL, "references at draft quality (faster, noisier)",
     NULL, NULL},
    {OPT_SUPERSAMPLE, "--supersample", NULL, CLI_ARG_NUMBER, "K",
     "antialiasing (`sss render --supersample`): K x K samples per pixel,\n"
     "K in 1..4; about K^2 the frame time",
     NULL, "1 = off"},
    {OPT_INPUT, "--input", NULL, CLI_ARG_TEXT, "EVENTS",
     "with --frames: input events, one per frame, comma-separated (tests):\n"
     "keys (tab, shift+tab, 1, 2, 3, b, m, shift+m, +, -, l, shift+l, space,\n"
     "s, c, o, h), orbit:DX:DY and pan:DX:DY (drags in pixels, y down),\n"
     "zoom:STEPS (wheel)",
     NULL, NULL},
};

static void print_keys(FILE *f) { fprintf(f, "\nkeys and mouse:\n%s", sss_view_help_text()); }

const cli_command_spec cli_spec_view = {
    CMD, options, CLI_COUNT(options), CLI_ARG_FILE, NULL, "SCENE.json",
    "Shows SCENE.json in a window with a real-time technique (needs a display; without one use\n"
    "`sss render`, or run under `xvfb-run -a`). A panel (Dear ImGui) lists the techniques and\n"
    "their parameters, materials, lights, frame time per pass, buffers, the split view and the\n"
    "error map; the window title shows the frame time. The viewer's messages go to stdout (none\n"
    "with --quiet).\n",
    "Exit status: 0 success, 1 error (scene, no display, GL, screenshot), 2 usage error.\n", print_keys};

static void print_message(void *user, const char *message)
{
    (void)user;
    printf("sss view: %s\n", message);
    fflush(stdout);
}

typedef struct view_options {
    sss_view_desc d; /* its params point into params */
    cli_params params;
    cli_common common;
} view_options;

static int set_option(void *opts, int id, const char *a, const char *v)
{
    view_options *o = opts;
    sss_view_desc *d = &o->d;
    switch (id) {
    case OPT_TECHNIQUE: d->technique = v; break;
    case OPT_WIDTH:
    case OPT_HEIGHT:
        if (!cli_parse_size(CMD, a, v, id == OPT_WIDTH ? &d->width : &d->height)) return CLI_EXIT_USAGE;
        break;
    case OPT_TIME:
        if (!cli_parse_double(CMD, a, v, &d->time)) return CLI_EXIT_USAGE;
        break;
    case OPT_FRAMES:
        if (!cli_parse_int(CMD, a, v, &d->frames)) return CLI_EXIT_USAGE;
        if (d->frames < 1 || d->frames > MAX_FRAMES) return cli_usage_error(CMD, "--frames must be in 1..%d", MAX_FRAMES);
        break;
    case OPT_SCREENSHOT: d->screenshot = v; break;
    case OPT_INPUT: d->input = v; break;
    case OPT_SCRIPT: d->script = v; break;
    case OPT_ANIMATE: d->animate = 1; break;
    case OPT_NO_OVERLAY: d->no_overlay = 1; break;
    case OPT_REFERENCE: d->reference = 1; break;
    case OPT_DRAFT_REFERENCE: d->reference_draft = 1; break;
    case OPT_SUPERSAMPLE:
        if (!cli_parse_supersample(CMD, a, v, &d->supersample)) return CLI_EXIT_USAGE;
        break;
    case OPT_PARAM:
        if (!cli_params_add(CMD, &o->params, v)) return CLI_EXIT_USAGE;
        break;
    default: /* CLI_OPERAND */
        if (d->scene_path) return cli_usage_error(CMD, "unexpected argument '%s'", v);
        d->scene_path = v;
    }
    return CLI_EXIT_OK;
}

static int view_parse(int argc, char **argv, view_options *o)
{
    memset(o, 0, sizeof *o);
    sss_view_desc *d = &o->d;
    int status = cli_parse(&cli_spec_view, argc, argv, 1, set_option, o, &o->common);
    if (status != CLI_EXIT_OK) return status;
    if (!d->scene_path) return cli_usage_error(CMD, "missing SCENE.json");
    if (d->screenshot && d->frames < 1) return cli_usage_error(CMD, "--screenshot needs --frames N");
    if (d->input && d->frames < 1) return cli_usage_error(CMD, "--input needs --frames N");
    if (d->script && (d->frames || d->input || d->screenshot))
        return cli_usage_error(CMD, "--script replaces --frames, --input and --screenshot (use its frames, key "
                                    "and screenshot lines)");
    if (d->screenshot) {
        char ext[16];
        sss_path_extension(d->screenshot, ext, sizeof ext);
        if (strcmp(ext, "png") != 0)
            return cli_usage_error(CMD, "--screenshot needs a .png file name, got '%s'", d->screenshot);
    }
    d->params = o->params.values;
    d->param_count = o->params.count;
    d->log = o->common.quiet ? NULL : print_message;
    if (d->technique && cli_check_technique(CMD, d->technique) != CLI_EXIT_OK) return CLI_EXIT_ERROR;
    return CLI_EXIT_OK;
}

static int view_run(const view_options *o)
{
    sss_error err = {0};
    if (sss_view_run(&o->d, &err) != SSS_OK) return cli_fail(CMD, &err);
    return CLI_EXIT_OK;
}

int sss_cmd_view(int argc, char **argv)
{
    view_options o;
    int status = view_parse(argc, argv, &o);
    return status == CLI_EXIT_OK ? view_run(&o) : status;
}
