/* cli/cmd_lut.c — `sss lut MEDIUM -o FILE.exr`: builds the disc-integrated kernel LUT R'_d(r, A) of
 * Maisch & Ropinski 2020 (Eq. 5, sections 7.1-7.2) for a measured medium and writes it as a float RGB image. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "cli/cli.h"
#include "sss/image.h"
#include "sss/kernel.h"

#define CMD "lut"
#define MAX_SIZE 8192

enum { OPT_OUTPUT, OPT_SCALE, OPT_ETA, OPT_MODEL, OPT_SIZE, OPT_AXES };
static const cli_option options[] = {
    {OPT_OUTPUT, "--output", "-o", CLI_ARG_FILE, "FILE", "output image, .exr (32-bit float) or .pfm", NULL},
    {OPT_SCALE, "--scale", NULL, CLI_ARG_NUMBER, "S", "millimetres per scene unit (default 1: r in mm, A in mm^2)", NULL},
    {OPT_ETA, "--eta", NULL, CLI_ARG_NUMBER, "E",
     "relative index of refraction in [" CLI_STR(SSS_ETA_MIN) ", " CLI_STR(SSS_ETA_MAX) "] (default 1.33)", NULL},
    {OPT_MODEL, "--model", NULL, CLI_ARG_TEXT, "M",
     "pbd (Photon Beam Diffusion table, as PBRT-v3; default) or dipole",
     "pbd dipole"},
    {OPT_SIZE, "--size", NULL, CLI_ARG_NUMBER, "N", "texels per axis, [2, " CLI_STR(MAX_SIZE) "] (default 512, as the paper)", NULL},
    {OPT_AXES, "--axes", NULL, CLI_ARG_TEXT, "A",
     "linear (texel i at r_max i/(N-1), as the paper; default) or sqrt\n"
     "(r_max (i/(N-1))^2: denser near r = 0 and A = 0)",
     "linear sqrt"},
};
const cli_command_spec cli_spec_lut = {CMD, options, CLI_COUNT(options), CLI_ARG_MEDIUM, NULL};

static void print_usage(FILE *f)
{
    fprintf(f, "usage: sss lut MEDIUM -o FILE.exr [--scale S] [--eta E] [--size N] [--axes linear|sqrt]\n"
               "               [--model pbd|dipole]\n"
               "\n"
               "Builds the pre-integrated kernel R'_d(r, A) of Maisch & Ropinski 2020 (the average of the\n"
               "diffusion profile R_d over a disc of area A whose centre lies at distance r) and writes it as\n"
               "an N x N float RGB image: x = r axis (column 0: r = 0), y = A axis (row 0: A = 0, i.e. R_d\n"
               "itself). r runs to r_max, where the source function alpha' sigma_t' e^(-sigma_t' r) falls to\n"
               "1e-7, A to pi r_max^2. Prints r_max, A_max and the build time.\n"
               "\n");
    cli_print_options(f, &cli_spec_lut);
    fprintf(f, "\nmedia:");
    for (size_t i = 0; i < sss_measured_medium_count(); i++) fprintf(f, " %s", sss_measured_medium_at(i)->name);
    fprintf(f, " (case-insensitive)\n");
}

/* True for the float formats that keep the LUT's values (.exr, .pfm), case-insensitive. */
static int float_format(const char *path)
{
    const char *dot = strrchr(path, '.'), *slash = strrchr(path, '/');
    if (!dot || (slash && dot < slash)) return 0;
    return strcasecmp(dot + 1, "exr") == 0 || strcasecmp(dot + 1, "pfm") == 0;
}

int sss_cmd_lut(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) {
        print_usage(stdout);
        return CLI_EXIT_OK;
    }
    const char *medium = NULL, *output = NULL, *model_text = "pbd", *axes_text = "linear";
    double scale = 1.0, eta = 1.33;
    int size = 512;
    cli_parser args;
    cli_parser_init(&args, &cli_spec_lut, argc, argv, 1);
    for (int o; (o = cli_next(&args)) != CLI_DONE;) {
        const char *a = args.given, *v = args.value;
        switch (o) {
        case CLI_BAD: return CLI_EXIT_USAGE;
        case OPT_SCALE:
        case OPT_ETA:
            if (!cli_parse_double(CMD, a, v, o == OPT_SCALE ? &scale : &eta)) return CLI_EXIT_USAGE;
            break;
        case OPT_SIZE:
            if (!cli_parse_int(CMD, a, v, &size)) return CLI_EXIT_USAGE;
            break;
        case OPT_MODEL:
            model_text = v;
            if (strcmp(model_text, "pbd") != 0 && strcmp(model_text, "dipole") != 0)
                return cli_usage_error(CMD, "--model expects pbd or dipole, got '%s'", model_text);
            break;
        case OPT_AXES:
            axes_text = v;
            if (strcmp(axes_text, "linear") != 0 && strcmp(axes_text, "sqrt") != 0)
                return cli_usage_error(CMD, "--axes expects linear or sqrt, got '%s'", axes_text);
            break;
        case OPT_OUTPUT: output = v; break;
        default: /* CLI_OPERAND */
            if (medium) return cli_usage_error(CMD, "unexpected argument '%s' (one medium only)", v);
            medium = v;
        }
    }
    if (!medium) return cli_usage_error(CMD, "missing MEDIUM");
    if (!output) return cli_usage_error(CMD, "missing -o FILE (the LUT image to write)");
    /* Checked before the work: a bad size or file type must not cost a build. */
    if (size < 2 || size > MAX_SIZE) return cli_failf(CMD, "--size %d is outside [2, %d]", size, MAX_SIZE);
    if (!float_format(output))
        return cli_failf(CMD, "%s: the LUT needs a float image format (.exr or .pfm)", output);

    sss_error err = {0};
    cli_medium_profile mp;
    if (cli_medium_profile_init(CMD, medium, scale, eta, model_text, &mp) != CLI_EXIT_OK) return CLI_EXIT_ERROR;
    const sss_profile *p = &mp.profile;
    sss_lut_desc desc;
    memset(&desc, 0, sizeof desc);
    desc.size = size;
    desc.axes = strcmp(axes_text, "sqrt") == 0 ? SSS_LUT_AXES_SQRT : SSS_LUT_AXES_LINEAR;
    sss_lut lut;
    double t0 = sss_time_seconds();
    sss_result res = sss_lut_build(p, &desc, &lut, &err);
    double ms = 1e3 * (sss_time_seconds() - t0);
    cli_medium_profile_free(&mp);
    if (res != SSS_OK) return cli_fail(CMD, &err);

    /* Texel (i, j) at texels[3 (j N + i)] is pixel (x = i, y = j): the layout of an image already. */
    sss_image img = {lut.size, lut.size, lut.texels};
    res = sss_image_write(output, &img, 0.0, &err);
    if (res != SSS_OK) {
        sss_lut_free(&lut);
        return cli_fail(CMD, &err);
    }
    printf("wrote %s: %d x %d, %s axes, %s profile\n", output, lut.size, lut.size, axes_text, model_text);
    printf("r_max %.9g\n", lut.r_max);
    printf("A_max %.9g\n", lut.a_max);
    printf("build_ms %.1f\n", ms);
    sss_lut_free(&lut);
    if (fflush(stdout) != 0 || ferror(stdout)) return cli_failf(CMD, "error writing the output");
    return CLI_EXIT_OK;
}
