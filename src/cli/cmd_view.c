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
#define MAX_PARAMS 64
#define MAX_FRAMES 100000

static void print_usage(FILE *f)
{
    fprintf(f,
            "usage: sss view SCENE.json [--technique NAME] [--width W --height H] [--param NAME=VALUE ...]\n"
            "                [--time T] [--animate] [--frames N [--screenshot FILE.png]] [--no-overlay]\n"
            "                [--reference] [--draft-reference] [--supersample K] [--input EVENTS]\n"
            "                [--script FILE]\n"
            "\n"
            "Shows SCENE.json in a window with a real-time technique (needs a display; without one use\n"
            "`sss render`, or run under `xvfb-run -a`). A panel (Dear ImGui) lists the techniques and\n"
            "their parameters, materials, lights, frame time per pass, buffers, the split view and the\n"
            "error map; the window title shows the frame time.\n"
            "\n"
            "options:\n"
            "  --technique NAME    first technique (default: the scene's render.technique)\n"
            "  --width W, --height H  window size (default: the scene camera's)\n"
            "  --param NAME=VALUE  a technique or shared parameter, repeatable (kept across technique\n"
            "                      switches for the techniques that have it)\n"
            "  --time T            animation time of the first frame (default 0)\n"
            "  --animate           start with the animation playing (--frames: 30 frames per second)\n"
            "  --frames N          render N frames without input, then exit\n"
            "  --screenshot FILE   with --frames: write the last frame as PNG (the window's image without\n"
            "                      the overlay, the same image as `sss render` of that view)\n"
            "  --no-overlay        start with the panel hidden (O toggles it)\n"
            "  --script FILE       run the panel actions of FILE, one per line, then exit (docs/viewer.md):\n"
            "                      technique NAME, param [TECH.]NAME VALUE, material OBJ FIELD VALUE...,\n"
            "                      light I position|intensity|colour VALUE..., buffer NAME,\n"
            "                      split off|reference|TECH [POS], errormap on|off, panel on|off,\n"
            "                      reference [draft], key EVENT, frames N, screenshot FILE.png\n"
            "  --reference         render the CPU reference of the first view in the background at once;\n"
            "                      with --frames, wait for it and print the DSSIM of the last frame\n"
            "  --draft-reference   references at draft quality (faster, noisier)\n"
            "  --supersample K     antialiasing (`sss render --supersample`): K x K samples per pixel,\n"
            "                      K in 1..4 (default 1: off); about K^2 the frame time\n"
            "  --input EVENTS      with --frames: input events, one per frame, comma-separated (tests):\n"
            "                      keys (tab, shift+tab, 1, 2, 3, b, m, shift+m, +, -, l, shift+l, space,\n"
            "                      s, c, o, h), orbit:DX:DY and pan:DX:DY (drags in pixels, y down),\n"
            "                      zoom:STEPS (wheel)\n"
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
    sss_gl_param_value params[MAX_PARAMS];
    char names[MAX_PARAMS][64];
    int nparams = 0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v;
        if (strcmp(a, "--technique") == 0) {
            if (!(d.technique = cli_option_value(CMD, argc, argv, &i))) return CLI_EXIT_USAGE;
        } else if (strcmp(a, "--width") == 0 || strcmp(a, "--height") == 0) {
            int *dst = a[2] == 'w' ? &d.width : &d.height;
            if (!(v = cli_option_value(CMD, argc, argv, &i)) || !cli_parse_int(CMD, a, v, dst)) return CLI_EXIT_USAGE;
            if (*dst < 1 || *dst > SSS_SCENE_MAX_IMAGE_SIZE)
                return cli_usage_error(CMD, "%s must be in 1..%d", a, SSS_SCENE_MAX_IMAGE_SIZE);
        } else if (strcmp(a, "--time") == 0) {
            if (!(v = cli_option_value(CMD, argc, argv, &i)) || !cli_parse_double(CMD, a, v, &d.time)) return CLI_EXIT_USAGE;
        } else if (strcmp(a, "--frames") == 0) {
            if (!(v = cli_option_value(CMD, argc, argv, &i)) || !cli_parse_int(CMD, a, v, &d.frames)) return CLI_EXIT_USAGE;
            if (d.frames < 1 || d.frames > MAX_FRAMES) return cli_usage_error(CMD, "--frames must be in 1..%d", MAX_FRAMES);
        } else if (strcmp(a, "--screenshot") == 0) {
            if (!(d.screenshot = cli_option_value(CMD, argc, argv, &i))) return CLI_EXIT_USAGE;
        } else if (strcmp(a, "--script") == 0) {
            if (!(d.script = cli_option_value(CMD, argc, argv, &i))) return CLI_EXIT_USAGE;
        } else if (strcmp(a, "--input") == 0) {
            if (!(d.input = cli_option_value(CMD, argc, argv, &i))) return CLI_EXIT_USAGE;
        } else if (strcmp(a, "--animate") == 0) {
            d.animate = 1;
        } else if (strcmp(a, "--no-overlay") == 0) {
            d.no_overlay = 1;
        } else if (strcmp(a, "--reference") == 0) {
            d.reference = 1;
        } else if (strcmp(a, "--draft-reference") == 0) {
            d.reference_draft = 1;
        } else if (strcmp(a, "--supersample") == 0) {
            if (!(v = cli_option_value(CMD, argc, argv, &i)) || !cli_parse_int(CMD, a, v, &d.supersample))
                return CLI_EXIT_USAGE;
            if (d.supersample < 1 || d.supersample > SSS_GL_MAX_SUPERSAMPLE)
                return cli_usage_error(CMD, "--supersample must be in 1..%d (the antialiasing factor per axis; 1: off), got %d",
                                       SSS_GL_MAX_SUPERSAMPLE, d.supersample);
        } else if (strcmp(a, "--param") == 0) {
            if (!(v = cli_option_value(CMD, argc, argv, &i))) return CLI_EXIT_USAGE;
            const char *eq = strchr(v, '=');
            if (!eq || eq == v || (size_t)(eq - v) >= sizeof names[0])
                return cli_usage_error(CMD, "--param expects NAME=VALUE, got '%s'", v);
            if (nparams >= MAX_PARAMS) return cli_usage_error(CMD, "at most %d --param options", MAX_PARAMS);
            memcpy(names[nparams], v, (size_t)(eq - v));
            names[nparams][eq - v] = '\0';
            params[nparams].name = names[nparams];
            sss_error perr = {0};
            if (sss_gl_param_parse(names[nparams], eq + 1, &params[nparams].value, &perr) != SSS_OK)
                return cli_usage_error(CMD, "--param: %s", perr.message);
            nparams++;
        } else if (a[0] == '-' && a[1]) {
            return cli_usage_error(CMD, "unknown option '%s'", a);
        } else if (!d.scene_path) {
            d.scene_path = a;
        } else {
            return cli_usage_error(CMD, "unexpected argument '%s'", a);
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
    d.params = params;
    d.param_count = nparams;
    d.log = print_message;
    sss_error err = {0};
    if (sss_view_run(&d, &err) != SSS_OK) return cli_fail(CMD, &err);
    return CLI_EXIT_OK;
}
