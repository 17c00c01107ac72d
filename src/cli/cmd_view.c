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
    {OPT_TECHNIQUE, "--technique", NULL, CLI_ARG_TECHNIQUE, "NAME", "first technique (default: the scene's render.technique)",
     NULL},
    {OPT_WIDTH, "--width", NULL, CLI_ARG_NUMBER, "W", "window width (default: the scene camera's)", NULL},
    {OPT_HEIGHT, "--height", NULL, CLI_ARG_NUMBER, "H", "window height (default: the scene camera's)", NULL},
    {OPT_PARAM, "--param", NULL, CLI_ARG_TEXT, "NAME=VALUE",
     "a technique or shared parameter, repeatable (kept across technique\n"
     "switches for the techniques that have it)",
     NULL},
    {OPT_TIME, "--time", NULL, CLI_ARG_NUMBER, "T", "animation time of the first frame (default 0)", NULL},
    {OPT_ANIMATE, "--animate", NULL, CLI_ARG_NONE, NULL, "start with the animation playing (--frames: 30 frames per second)",
     NULL},
    {OPT_FRAMES, "--frames", NULL, CLI_ARG_NUMBER, "N", "render N frames without input, then exit", NULL},
    {OPT_SCREENSHOT, "--screenshot", NULL, CLI_ARG_FILE, "FILE",
     "with --frames: write the last frame as PNG (the window's image without\n"
     "the overlay, the same image as `sss render` of that view)",
     NULL},
    {OPT_SCREENSHOT, "--output", "-o", CLI_ARG_FILE, "FILE", "the same as --screenshot", NULL},
    {OPT_NO_OVERLAY, "--no-overlay", NULL, CLI_ARG_NONE, NULL, "start with the panel hidden (O toggles it)", NULL},
    {OPT_SCRIPT, "--script", NULL, CLI_ARG_FILE, "FILE",
     "run the panel actions of FILE, one per line, then exit (docs/viewer.md):\n"
     "technique NAME, param [TECH.]NAME VALUE, material OBJ FIELD VALUE...,\n"
     "light I position|intensity|colour VALUE..., buffer NAME,\n"
     "split off|reference|TECH [POS], errormap on|off, panel on|off,\n"
     "reference [draft], key EVENT, frames N, screenshot FILE.png",
     NULL},
    {OPT_REFERENCE, "--reference", NULL, CLI_ARG_NONE, NULL,
     "render the CPU reference of the first view in the background at once;\n"
     "with --frames, wait for it and print the DSSIM of the last frame",
     NULL},
    {OPT_DRAFT_REFERENCE, "--draft-reference", NULL, CLI_ARG_NONE, NULL, "references at draft quality (faster, noisier)",
     NULL},
    {OPT_SUPERSAMPLE, "--supersample", NULL, CLI_ARG_NUMBER, "K",
     "antialiasing (`sss render --supersample`): K x K samples per pixel,\n"
     "K in 1..4 (default 1: off); about K^2 the frame time",
     NULL},
    {OPT_INPUT, "--input", NULL, CLI_ARG_TEXT, "EVENTS",
     "with --frames: input events, one per frame, comma-separated (tests):\n"
     "keys (tab, shift+tab, 1, 2, 3, b, m, shift+m, +, -, l, shift+l, space,\n"
     "s, c, o, h), orbit:DX:DY and pan:DX:DY (drags in pixels, y down),\n"
     "zoom:STEPS (wheel)",
     NULL},
};
const cli_command_spec cli_spec_view = {CMD, options, CLI_COUNT(options), CLI_ARG_FILE, NULL};

static void print_usage(FILE *f)
{
    fprintf(f,
            "usage: sss view SCENE.json [--technique NAME] [--width W --height H] [--param NAME=VALUE ...]\n"
            "                [--time T] [--animate] [--frames N [--screenshot FILE.png]] [--no-overlay]\n"
            "                [--reference] [--draft-reference] [--supersample K] [--input EVENTS] [--quiet]\n"
            "                [--script FILE]\n"
            "\n"
            "Shows SCENE.json in a window with a real-time technique (needs a display; without one use\n"
            "`sss render`, or run under `xvfb-run -a`). A panel (Dear ImGui) lists the techniques and\n"
            "their parameters, materials, lights, frame time per pass, buffers, the split view and the\n"
            "error map; the window title shows the frame time. The viewer's messages go to stdout (none\n"
            "with --quiet).\n"
            "\n");
    cli_print_options(f, &cli_spec_view);
    fprintf(f,
            "\n"
            "keys and mouse:\n%s"
            "\n"
            "Exit status: 0 success, 1 error (scene, no display, GL, screenshot), 2 usage error.\n",
            sss_view_help_text());
}

static void print_message(void *user, const char *message)
{
    (void)user;
    printf("sss view: %s\n", message);
    fflush(stdout);
}

int sss_cmd_view(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) {
        print_usage(stdout);
        return CLI_EXIT_OK;
    }
    sss_view_desc d;
    memset(&d, 0, sizeof d);
    cli_params params;
    params.count = 0;
    cli_parser args;
    cli_parser_init(&args, &cli_spec_view, argc, argv, 1);
    for (int o; (o = cli_next(&args)) != CLI_DONE;) {
        const char *a = args.given, *v = args.value;
        switch (o) {
        case CLI_BAD: return CLI_EXIT_USAGE;
        case OPT_TECHNIQUE: d.technique = v; break;
        case OPT_WIDTH:
        case OPT_HEIGHT:
            if (!cli_parse_size(CMD, a, v, o == OPT_WIDTH ? &d.width : &d.height)) return CLI_EXIT_USAGE;
            break;
        case OPT_TIME:
            if (!cli_parse_double(CMD, a, v, &d.time)) return CLI_EXIT_USAGE;
            break;
        case OPT_FRAMES:
            if (!cli_parse_int(CMD, a, v, &d.frames)) return CLI_EXIT_USAGE;
            if (d.frames < 1 || d.frames > MAX_FRAMES) return cli_usage_error(CMD, "--frames must be in 1..%d", MAX_FRAMES);
            break;
        case OPT_SCREENSHOT: d.screenshot = v; break;
        case OPT_INPUT: d.input = v; break;
        case OPT_SCRIPT: d.script = v; break;
        case OPT_ANIMATE: d.animate = 1; break;
        case OPT_NO_OVERLAY: d.no_overlay = 1; break;
        case OPT_REFERENCE: d.reference = 1; break;
        case OPT_DRAFT_REFERENCE: d.reference_draft = 1; break;
        case OPT_SUPERSAMPLE:
            if (!cli_parse_supersample(CMD, a, v, &d.supersample)) return CLI_EXIT_USAGE;
            break;
        case OPT_PARAM:
            if (!cli_params_add(CMD, &params, v)) return CLI_EXIT_USAGE;
            break;
        default: /* CLI_OPERAND */
            if (d.scene_path) return cli_usage_error(CMD, "unexpected argument '%s'", v);
            d.scene_path = v;
        }
    }
    if (!d.scene_path) return cli_usage_error(CMD, "missing SCENE.json");
    if (d.screenshot && d.frames < 1) return cli_usage_error(CMD, "--screenshot needs --frames N");
    if (d.input && d.frames < 1) return cli_usage_error(CMD, "--input needs --frames N");
    if (d.script && (d.frames || d.input || d.screenshot))
        return cli_usage_error(CMD, "--script replaces --frames, --input and --screenshot (use its frames, key "
                                    "and screenshot lines)");
    if (d.screenshot) {
        char ext[16];
        sss_path_extension(d.screenshot, ext, sizeof ext);
        if (strcmp(ext, "png") != 0) return cli_usage_error(CMD, "--screenshot needs a .png file name, got '%s'", d.screenshot);
    }
    d.params = params.values;
    d.param_count = params.count;
    d.log = args.quiet ? NULL : print_message;
    if (d.technique && cli_check_technique(CMD, d.technique) != CLI_EXIT_OK) return CLI_EXIT_ERROR;
    sss_error err = {0};
    if (sss_view_run(&d, &err) != SSS_OK) return cli_fail(CMD, &err);
    return CLI_EXIT_OK;
}
