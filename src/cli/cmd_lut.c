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
#define DEFAULT_SIZE 512
static const cli_option options[] = {
    {OPT_OUTPUT, "--output", "-o", CLI_ARG_FILE, "FILE", "output image, .exr (32-bit float) or .pfm", NULL, CLI_REQUIRED},
    {OPT_SCALE, "--scale", NULL, CLI_ARG_NUMBER, "S", "millimetres per scene unit", NULL, "1 = r in mm, A in mm^2"},
    {OPT_ETA, "--eta", NULL, CLI_ARG_NUMBER, "E",
     "relative index of refraction in [" CLI_STR(SSS_ETA_MIN) ", " CLI_STR(SSS_ETA_MAX) "]", NULL,
     CLI_STR(CLI_DEFAULT_ETA)},
    {OPT_MODEL, "--model", NULL, CLI_ARG_TEXT, "M", "pbd (Photon Beam Diffusion table, as PBRT-v3) or dipole",
     "pbd dipole", "pbd"},
    {OPT_SIZE, "--size", NULL, CLI_ARG_NUMBER, "N", "texels per axis, [2, " CLI_STR(MAX_SIZE) "]", NULL,
     CLI_STR(DEFAULT_SIZE) ", as the paper"},
    {OPT_AXES, "--axes", NULL, CLI_ARG_TEXT, "A",
     "linear (texel i at r_max i/(N-1), as the paper) or sqrt\n"
     "(r_max (i/(N-1))^2: denser near r = 0 and A = 0)",
     "linear sqrt", "linear"},
};
const cli_command_spec cli_spec_lut = {
    CMD, options, CLI_COUNT(options), CLI_ARG_MEDIUM, NULL, "MEDIUM",
    "Builds the pre-integrated kernel R'_d(r, A) of Maisch & Ropinski 2020 (the average of the\n"
    "diffusion profile R_d over a disc of area A whose centre lies at distance r) and writes it as\n"
    "an N x N float RGB image: x = r axis (column 0: r = 0), y = A axis (row 0: A = 0, i.e. R_d\n"
    "itself). r runs to r_max, where the source function alpha' sigma_t' e^(-sigma_t' r) falls to\n"
    "1e-7, A to pi r_max^2. Prints r_max, A_max and the build time.\n",
    NULL, NULL};

typedef struct lut_options {
    const char *medium, *output, *model, *axes;
    double scale, eta;
    int size;
} lut_options;

/* True for the float formats that keep the LUT's values (.exr, .pfm), case-insensitive. */
static int float_format(const char *path)
{
    const char *dot = strrchr(path, '.'), *slash = strrchr(path, '/');
    if (!dot || (slash && dot < slash)) return 0;
    return strcasecmp(dot + 1, "exr") == 0 || strcasecmp(dot + 1, "pfm") == 0;
}

static int set_option(void *opts, int id, const char *a, const char *v)
{
    lut_options *o = opts;
    switch (id) {
    case OPT_SCALE:
    case OPT_ETA:
        if (!cli_parse_double(CMD, a, v, id == OPT_SCALE ? &o->scale : &o->eta)) return CLI_EXIT_USAGE;
        break;
    case OPT_SIZE:
        if (!cli_parse_int(CMD, a, v, &o->size)) return CLI_EXIT_USAGE;
        break;
    case OPT_MODEL:
        o->model = v;
        if (strcmp(o->model, "pbd") != 0 && strcmp(o->model, "dipole") != 0)
            return cli_usage_error(CMD, "--model expects pbd or dipole, got '%s'", o->model);
        break;
    case OPT_AXES:
        o->axes = v;
        if (strcmp(o->axes, "linear") != 0 && strcmp(o->axes, "sqrt") != 0)
            return cli_usage_error(CMD, "--axes expects linear or sqrt, got '%s'", o->axes);
        break;
    case OPT_OUTPUT: o->output = v; break;
    default: /* CLI_OPERAND */
        if (o->medium) return cli_usage_error(CMD, "unexpected argument '%s' (one medium only)", v);
        o->medium = v;
    }
    return CLI_EXIT_OK;
}

static int lut_parse(int argc, char **argv, lut_options *o)
{
    *o = (lut_options){.model = "pbd", .axes = "linear", .scale = 1.0, .eta = CLI_DEFAULT_ETA,
                       .size = DEFAULT_SIZE};
    int status = cli_parse(&cli_spec_lut, argc, argv, 1, set_option, o, NULL);
    if (status != CLI_EXIT_OK) return status;
    if (!o->medium) return cli_usage_error(CMD, "missing MEDIUM");
    if (!o->output) return cli_usage_error(CMD, "missing -o FILE (the LUT image to write)");
    /* Checked before the work: a bad size or file type must not cost a build. */
    if (o->size < 2 || o->size > MAX_SIZE) return cli_failf(CMD, "--size %d is outside [2, %d]", o->size, MAX_SIZE);
    if (!float_format(o->output))
        return cli_failf(CMD, "%s: the LUT needs a float image format (.exr or .pfm)", o->output);
    return CLI_EXIT_OK;
}

static int lut_run(const lut_options *o)
{
    sss_error err = {0};
    cli_medium_profile mp;
    if (cli_medium_profile_init(CMD, o->medium, o->scale, o->eta, o->model, &mp) != CLI_EXIT_OK) return CLI_EXIT_ERROR;
    sss_lut_desc desc;
    memset(&desc, 0, sizeof desc);
    desc.size = o->size;
    desc.axes = strcmp(o->axes, "sqrt") == 0 ? SSS_LUT_AXES_SQRT : SSS_LUT_AXES_LINEAR;
    sss_lut lut;
    double t0 = sss_time_seconds();
    sss_result res = sss_lut_build(&mp.profile, &desc, &lut, &err);
    double ms = 1e3 * (sss_time_seconds() - t0);
    cli_medium_profile_free(&mp);
    if (res != SSS_OK) return cli_fail(CMD, &err);

    /* Texel (i, j) at texels[3 (j N + i)] is pixel (x = i, y = j): the layout of an image already. */
    sss_image img = {lut.size, lut.size, lut.texels};
    res = sss_image_write(o->output, &img, 0.0, &err);
    if (res != SSS_OK) {
        sss_lut_free(&lut);
        return cli_fail(CMD, &err);
    }
    printf("wrote %s: %d x %d, %s axes, %s profile\n", o->output, lut.size, lut.size, o->axes, o->model);
    printf("r_max %.9g\n", lut.r_max);
    printf("A_max %.9g\n", lut.a_max);
    printf("build_ms %.1f\n", ms);
    sss_lut_free(&lut);
    if (fflush(stdout) != 0 || ferror(stdout)) return cli_failf(CMD, "error writing the output");
    return CLI_EXIT_OK;
}

int sss_cmd_lut(int argc, char **argv)
{
    lut_options o;
    int status = lut_parse(argc, argv, &o);
    return status == CLI_EXIT_OK ? lut_run(&o) : status;
}
