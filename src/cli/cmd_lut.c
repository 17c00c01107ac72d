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

static void print_usage(FILE *f)
{
    fprintf(f,
            "usage: sss lut MEDIUM -o FILE.exr [--scale S] [--eta E] [--size N] [--axes linear|sqrt]\n"
            "               [--model pbd|dipole]\n"
            "\n"
            "Builds the pre-integrated kernel R'_d(r, A) of Maisch & Ropinski 2020 (the average of the\n"
            "diffusion profile R_d over a disc of area A whose centre lies at distance r) and writes it as\n"
            "an N x N float RGB image: x = r axis (column 0: r = 0), y = A axis (row 0: A = 0, i.e. R_d\n"
            "itself). r runs to r_max, where the source function alpha' sigma_t' e^(-sigma_t' r) falls to\n"
            "1e-7, A to pi r_max^2. Prints r_max, A_max and the build time.\n"
            "\n"
            "options:\n"
            "  -o FILE         output image, .exr (32-bit float) or .pfm\n"
            "  --scale S       millimetres per scene unit (default 1: r in mm, A in mm^2)\n"
            "  --eta E         relative index of refraction in [%g, %g] (default 1.33)\n"
            "  --size N        texels per axis, [2, %d] (default 512, as the paper)\n"
            "  --axes A        linear (texel i at r_max i/(N-1), as the paper; default) or sqrt\n"
            "                  (r_max (i/(N-1))^2: denser near r = 0 and A = 0)\n"
            "  --model M       pbd (Photon Beam Diffusion table, as PBRT-v3; default) or dipole\n"
            "\n"
            "media:",
            SSS_ETA_MIN, SSS_ETA_MAX, MAX_SIZE);
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
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--scale") == 0 || strcmp(a, "--eta") == 0) {
            const char *v = cli_option_value(CMD, argc, argv, &i);
            if (!v || !cli_parse_double(CMD, a, v, a[2] == 's' ? &scale : &eta)) return CLI_EXIT_USAGE;
        } else if (strcmp(a, "--size") == 0) {
            const char *v = cli_option_value(CMD, argc, argv, &i);
            if (!v || !cli_parse_int(CMD, a, v, &size)) return CLI_EXIT_USAGE;
        } else if (strcmp(a, "--model") == 0) {
            if (!(model_text = cli_option_value(CMD, argc, argv, &i))) return CLI_EXIT_USAGE;
            if (strcmp(model_text, "pbd") != 0 && strcmp(model_text, "dipole") != 0)
                return cli_usage_error(CMD, "--model expects pbd or dipole, got '%s'", model_text);
        } else if (strcmp(a, "--axes") == 0) {
            if (!(axes_text = cli_option_value(CMD, argc, argv, &i))) return CLI_EXIT_USAGE;
            if (strcmp(axes_text, "linear") != 0 && strcmp(axes_text, "sqrt") != 0)
                return cli_usage_error(CMD, "--axes expects linear or sqrt, got '%s'", axes_text);
        } else if (strcmp(a, "-o") == 0 || strcmp(a, "--output") == 0) {
            if (!(output = cli_option_value(CMD, argc, argv, &i))) return CLI_EXIT_USAGE;
        } else if (a[0] == '-' && a[1] != '\0') {
            return cli_usage_error(CMD, "unknown option '%s'", a);
        } else if (!medium) {
            medium = a;
        } else {
            return cli_usage_error(CMD, "unexpected argument '%s' (one medium only)", a);
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
