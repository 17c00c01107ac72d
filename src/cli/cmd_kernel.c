/* cli/cmd_kernel.c — `sss kernel`: the separable kernels of Jimenez et al. 2019 as text: the importance-sampled
 * taps of the pre-integrated kernel (Eq. 4-5) or of the artist model (Eq. 6), or the rank-N SVD
 * approximation's singular values and vectors. */
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "sss/kernel.h"

#define CMD "kernel"

enum { OPT_ARTIST, OPT_SCALE, OPT_ETA, OPT_MODEL, OPT_TAPS, OPT_RANGE, OPT_METHOD, OPT_RANK, OPT_GRID, OPT_EXTENT };
static const cli_option options[] = {
    {OPT_ARTIST, "--artist", NULL, CLI_ARG_TEXT, "P",
     "artist preset: single-layer, multi-layer or production (Jimenez et al. 2019, Table 2)",
     "single-layer multi-layer production"},
    {OPT_SCALE, "--scale", NULL, CLI_ARG_NUMBER, "S", "millimetres per scene unit (default 1: offsets in mm)", NULL},
    {OPT_ETA, "--eta", NULL, CLI_ARG_NUMBER, "E",
     "relative index of refraction in [" CLI_STR(SSS_ETA_MIN) ", " CLI_STR(SSS_ETA_MAX) "] (default 1.33)", NULL},
    {OPT_MODEL, "--model", NULL, CLI_ARG_TEXT, "M", "profile: pbd (default) or dipole", "pbd dipole"},
    {OPT_TAPS, "--taps", NULL, CLI_ARG_NUMBER, "N", "odd number of taps (default 7)", NULL},
    {OPT_RANGE, "--range", NULL, CLI_ARG_NUMBER, "X", "half-width the taps cover (default: 99.9% of the widest channel)", NULL},
    {OPT_METHOD, "--method", NULL, CLI_ARG_TEXT, "M", "preintegrated, svd or artist", "preintegrated svd artist"},
    {OPT_RANK, "--rank", NULL, CLI_ARG_NUMBER, "R", "svd: terms printed (default 3)", NULL},
    {OPT_GRID, "--grid", NULL, CLI_ARG_NUMBER, "G", "svd: cells per axis (default 64)", NULL},
    {OPT_EXTENT, "--extent", NULL, CLI_ARG_NUMBER, "X",
     "svd: half-width of the grid (default: the radius holding 99.9% of the\n"
     "widest channel's R_d)",
     NULL},
};
const cli_command_spec cli_spec_kernel = {CMD, options, CLI_COUNT(options), CLI_ARG_MEDIUM, NULL};

static void print_usage(FILE *f)
{
    fprintf(f, "usage: sss kernel MEDIUM [--method preintegrated|svd] [OPTIONS]\n"
               "       sss kernel --artist PRESET [OPTIONS]\n"
               "\n"
               "Prints a separable subsurface-scattering kernel (Jimenez et al., Separable Subsurface\n"
               "Scattering). Comment lines start with '#'; then TSV with a header line.\n"
               "  preintegrated  (default for MEDIUM) the taps of a_p(x) = int R_d(sqrt(x^2+y^2)) dy / ||R_d||:\n"
               "                 'offset<TAB>R<TAB>G<TAB>B', one line per tap; each channel's weights sum to 1\n"
               "                 (the comment gives ||R_d||, the total reflectance to apply separately)\n"
               "  artist         (with --artist) the same for the two-Gaussian artist model\n"
               "  svd            singular values of the discretised 2D profile (comments) and the rank-R\n"
               "                 vectors a_k: 'offset<TAB>term<TAB>R<TAB>G<TAB>B', the kernel being\n"
               "                 sum_k sign_k a_k(x) a_k(y) (signs in the comments)\n"
               "\n");
    cli_print_options(f, &cli_spec_kernel);
}

static int print_taps(const char *what, const sss_separable_kernel *k)
{
    printf("# %s kernel, %d taps, range %.9g\n", what, k->taps, k->range);
    printf("# total R G B: %.9g %.9g %.9g\n", k->total[0], k->total[1], k->total[2]);
    printf("offset\tR\tG\tB\n");
    for (int i = 0; i < k->taps; i++)
        printf("%.9g\t%.9g\t%.9g\t%.9g\n", k->offsets[i], k->weights[3 * i], k->weights[3 * i + 1],
               k->weights[3 * i + 2]);
    return CLI_EXIT_OK;
}

static int print_svd(const sss_svd_kernel *k)
{
    int shown = k->rank > 8 ? k->rank : 8;
    if (shown > k->grid) shown = k->grid;
    printf("# rank-%d SVD of R_d on a %d x %d grid of half-width %.9g\n", k->rank, k->grid, k->grid, k->extent);
    const char *names = "RGB";
    for (int c = 0; c < 3; c++) {
        printf("# singular values %c:", names[c]);
        for (int i = 0; i < shown; i++) printf(" %.6g", k->singular_values[c * k->grid + i]);
        printf("\n");
    }
    for (int t = 0; t < k->rank; t++)
        printf("# sign of term %d R G B: %+g %+g %+g\n", t + 1, k->signs[3 * t], k->signs[3 * t + 1],
               k->signs[3 * t + 2]);
    printf("offset\tterm\tR\tG\tB\n");
    double cell = 2.0 * k->extent / k->grid;
    for (int t = 0; t < k->rank; t++)
        for (int x = 0; x < k->grid; x++) {
            const float *v = k->vectors + (size_t)t * 3 * k->grid;
            /* + 0.0 prints -0 as 0 */
            printf("%.9g\t%d\t%.9g\t%.9g\t%.9g\n", -k->extent + (x + 0.5) * cell + 0.0, t + 1, v[x] + 0.0,
                   v[k->grid + x] + 0.0, v[2 * k->grid + x] + 0.0);
        }
    return CLI_EXIT_OK;
}

int sss_cmd_kernel(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) {
        print_usage(stdout);
        return CLI_EXIT_OK;
    }
    const char *medium = NULL, *preset = NULL, *method = NULL, *model_text = "pbd";
    double scale = 1.0, eta = 1.33, range = 0.0, extent = 0.0;
    int taps = 7, rank = 3, grid = 64;
    cli_parser args;
    cli_parser_init(&args, &cli_spec_kernel, argc, argv, 1);
    for (int o; (o = cli_next(&args)) != CLI_DONE;) {
        const char *a = args.given, *v = args.value;
        switch (o) {
        case CLI_BAD: return CLI_EXIT_USAGE;
        case OPT_SCALE:
        case OPT_ETA:
            if (!cli_parse_double(CMD, a, v, o == OPT_SCALE ? &scale : &eta)) return CLI_EXIT_USAGE;
            break;
        case OPT_RANGE:
        case OPT_EXTENT: /* 0 is the library's "automatic": given on the command line it must be a real width */
            if (!cli_parse_positive(CMD, a, v, o == OPT_RANGE ? &range : &extent)) return CLI_EXIT_USAGE;
            break;
        case OPT_TAPS:
            if (!cli_parse_int_in(CMD, a, v, 1, INT_MAX, &taps)) return CLI_EXIT_USAGE; /* 0: the default 7 */
            break;
        case OPT_RANK:
        case OPT_GRID:
            if (!cli_parse_int(CMD, a, v, o == OPT_RANK ? &rank : &grid)) return CLI_EXIT_USAGE;
            break;
        case OPT_ARTIST: preset = v; break;
        case OPT_METHOD:
            method = v;
            if (strcmp(method, "preintegrated") != 0 && strcmp(method, "svd") != 0 && strcmp(method, "artist") != 0)
                return cli_usage_error(CMD, "--method expects preintegrated, svd or artist, got '%s'", method);
            break;
        case OPT_MODEL:
            model_text = v;
            if (strcmp(model_text, "pbd") != 0 && strcmp(model_text, "dipole") != 0)
                return cli_usage_error(CMD, "--model expects pbd or dipole, got '%s'", model_text);
            break;
        default: /* CLI_OPERAND */
            if (medium) return cli_usage_error(CMD, "unexpected argument '%s' (one medium only)", v);
            medium = v;
        }
    }
    if (medium && preset) return cli_usage_error(CMD, "give a MEDIUM or --artist PRESET, not both");
    if (!medium && !preset) return cli_usage_error(CMD, "missing MEDIUM (or --artist PRESET)");
    if (!method) method = preset ? "artist" : "preintegrated";
    if (preset && strcmp(method, "artist") != 0)
        return cli_usage_error(CMD, "--method %s needs a MEDIUM, not --artist", method);
    if (!preset && strcmp(method, "artist") == 0) return cli_usage_error(CMD, "--method artist needs --artist PRESET");

    sss_error err = {0};
    if (preset) {
        sss_artist_params ap;
        if (sss_artist_preset(preset, &ap, &err) != SSS_OK) return cli_fail(CMD, &err);
        if (!(scale > 0.0)) return cli_failf(CMD, "--scale %g is not positive", scale);
        ap.s /= scale; /* the presets' s is in mm */
        sss_separable_kernel k;
        if (sss_kernel_artist(&ap, taps, &k, &err) != SSS_OK) return cli_fail(CMD, &err);
        print_taps("artist", &k);
        sss_separable_kernel_free(&k);
    } else {
        cli_medium_profile mp;
        if (cli_medium_profile_init(CMD, medium, scale, eta, model_text, &mp) != CLI_EXIT_OK) return CLI_EXIT_ERROR;
        const sss_profile *p = &mp.profile;
        sss_result res = SSS_OK;
        if (strcmp(method, "svd") == 0) {
            if (!(extent > 0.0))
                for (int c = 0; c < 3; c++) extent = fmax(extent, sss_profile_radius_for_fraction(p, c, 0.999));
            sss_svd_kernel k;
            res = sss_kernel_svd(p, grid, extent, rank, &k, &err);
            if (res == SSS_OK) print_svd(&k);
            sss_svd_kernel_free(&k);
        } else {
            sss_separable_kernel k;
            res = sss_kernel_preintegrated(p, taps, range, &k, &err);
            if (res == SSS_OK) print_taps("pre-integrated", &k);
            sss_separable_kernel_free(&k);
        }
        cli_medium_profile_free(&mp);
        if (res != SSS_OK) return cli_fail(CMD, &err);
    }
    if (fflush(stdout) != 0 || ferror(stdout)) return cli_failf(CMD, "error writing the output");
    return CLI_EXIT_OK;
}
