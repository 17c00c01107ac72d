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
#define DEFAULT_TAPS 7
#define DEFAULT_RANK 3
#define DEFAULT_GRID 64
static const cli_option options[] = {
    {OPT_ARTIST, "--artist", NULL, CLI_ARG_TEXT, "P",
     "artist preset instead of MEDIUM: single-layer, multi-layer or production\n"
     "(Jimenez et al. 2019, Table 2)",
     "single-layer multi-layer production", NULL},
    {OPT_SCALE, "--scale", NULL, CLI_ARG_NUMBER, "S", "millimetres per scene unit", NULL, "1 = offsets in mm"},
    {OPT_ETA, "--eta", NULL, CLI_ARG_NUMBER, "E",
     "relative index of refraction in [" CLI_STR(SSS_ETA_MIN) ", " CLI_STR(SSS_ETA_MAX) "]", NULL,
     CLI_STR(CLI_DEFAULT_ETA)},
    {OPT_MODEL, "--model", NULL, CLI_ARG_TEXT, "M", "profile: pbd or dipole", "pbd dipole", "pbd"},
    {OPT_TAPS, "--taps", NULL, CLI_ARG_NUMBER, "N", "odd number of taps", NULL, CLI_STR(DEFAULT_TAPS)},
    {OPT_RANGE, "--range", NULL, CLI_ARG_NUMBER, "X", "half-width the taps cover", NULL, "99.9% of the widest channel"},
    {OPT_METHOD, "--method", NULL, CLI_ARG_TEXT, "M", "preintegrated, svd or artist", "preintegrated svd artist",
     "preintegrated with MEDIUM, artist with --artist"},
    {OPT_RANK, "--rank", NULL, CLI_ARG_NUMBER, "R", "svd: terms printed", NULL, CLI_STR(DEFAULT_RANK)},
    {OPT_GRID, "--grid", NULL, CLI_ARG_NUMBER, "G", "svd: cells per axis", NULL, CLI_STR(DEFAULT_GRID)},
    {OPT_EXTENT, "--extent", NULL, CLI_ARG_NUMBER, "X",
     "svd: half-width of the grid (default: the radius holding 99.9% of the\n"
     "widest channel's R_d)",
     NULL, NULL},
};
const cli_command_spec cli_spec_kernel = {
    CMD, options, CLI_COUNT(options), CLI_ARG_MEDIUM, NULL, "[MEDIUM]",
    "Prints a separable subsurface-scattering kernel (Jimenez et al., Separable Subsurface\n"
    "Scattering). Comment lines start with '#'; then TSV with a header line.\n"
    "  preintegrated  (default for MEDIUM) the taps of a_p(x) = int R_d(sqrt(x^2+y^2)) dy / ||R_d||:\n"
    "                 'offset<TAB>R<TAB>G<TAB>B', one line per tap; each channel's weights sum to 1\n"
    "                 (the comment gives ||R_d||, the total reflectance to apply separately)\n"
    "  artist         (with --artist) the same for the two-Gaussian artist model\n"
    "  svd            singular values of the discretised 2D profile (comments) and the rank-R\n"
    "                 vectors a_k: 'offset<TAB>term<TAB>R<TAB>G<TAB>B', the kernel being\n"
    "                 sum_k sign_k a_k(x) a_k(y) (signs in the comments)\n",
    NULL, NULL};

typedef struct kernel_options {
    const char *medium, *preset, *method, *model;
    double scale, eta, range, extent;
    int taps, rank, grid;
} kernel_options;

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

static int set_option(void *opts, int id, const char *a, const char *v)
{
    kernel_options *o = opts;
    switch (id) {
    case OPT_SCALE:
    case OPT_ETA:
        if (!cli_parse_double(CMD, a, v, id == OPT_SCALE ? &o->scale : &o->eta)) return CLI_EXIT_USAGE;
        break;
    case OPT_RANGE:
    case OPT_EXTENT: /* 0 is the library's "automatic": given on the command line it must be a real width */
        if (!cli_parse_positive(CMD, a, v, id == OPT_RANGE ? &o->range : &o->extent)) return CLI_EXIT_USAGE;
        break;
    case OPT_TAPS:
        if (!cli_parse_int_in(CMD, a, v, 1, INT_MAX, &o->taps)) return CLI_EXIT_USAGE; /* 0: the default 7 */
        break;
    case OPT_RANK:
    case OPT_GRID:
        if (!cli_parse_int(CMD, a, v, id == OPT_RANK ? &o->rank : &o->grid)) return CLI_EXIT_USAGE;
        break;
    case OPT_ARTIST: o->preset = v; break;
    case OPT_METHOD:
        o->method = v;
        if (strcmp(v, "preintegrated") != 0 && strcmp(v, "svd") != 0 && strcmp(v, "artist") != 0)
            return cli_usage_error(CMD, "--method expects preintegrated, svd or artist, got '%s'", v);
        break;
    case OPT_MODEL:
        o->model = v;
        if (strcmp(v, "pbd") != 0 && strcmp(v, "dipole") != 0)
            return cli_usage_error(CMD, "--model expects pbd or dipole, got '%s'", v);
        break;
    default: /* CLI_OPERAND */
        if (o->medium) return cli_usage_error(CMD, "unexpected argument '%s' (one medium only)", v);
        o->medium = v;
    }
    return CLI_EXIT_OK;
}

static int kernel_parse(int argc, char **argv, kernel_options *o)
{
    *o = (kernel_options){.model = "pbd", .scale = 1.0, .eta = CLI_DEFAULT_ETA, .taps = DEFAULT_TAPS,
                          .rank = DEFAULT_RANK, .grid = DEFAULT_GRID};
    int status = cli_parse(&cli_spec_kernel, argc, argv, 1, set_option, o, NULL);
    if (status != CLI_EXIT_OK) return status;
    if (o->medium && o->preset) return cli_usage_error(CMD, "give a MEDIUM or --artist PRESET, not both");
    if (!o->medium && !o->preset) return cli_usage_error(CMD, "missing MEDIUM (or --artist PRESET)");
    if (!o->method) o->method = o->preset ? "artist" : "preintegrated";
    if (o->preset && strcmp(o->method, "artist") != 0)
        return cli_usage_error(CMD, "--method %s needs a MEDIUM, not --artist", o->method);
    if (!o->preset && strcmp(o->method, "artist") == 0)
        return cli_usage_error(CMD, "--method artist needs --artist PRESET");
    return CLI_EXIT_OK;
}

static int run_artist(const kernel_options *o)
{
    sss_error err = {0};
    sss_artist_params ap;
    if (sss_artist_preset(o->preset, &ap, &err) != SSS_OK) return cli_fail(CMD, &err);
    if (!(o->scale > 0.0)) return cli_failf(CMD, "--scale %g is not positive", o->scale);
    ap.s /= o->scale; /* the presets' s is in mm */
    sss_separable_kernel k;
    if (sss_kernel_artist(&ap, o->taps, &k, &err) != SSS_OK) return cli_fail(CMD, &err);
    print_taps("artist", &k);
    sss_separable_kernel_free(&k);
    return CLI_EXIT_OK;
}

static int run_medium(const kernel_options *o)
{
    sss_error err = {0};
    cli_medium_profile mp;
    if (cli_medium_profile_init(CMD, o->medium, o->scale, o->eta, o->model, &mp) != CLI_EXIT_OK) return CLI_EXIT_ERROR;
    const sss_profile *p = &mp.profile;
    sss_result res = SSS_OK;
    if (strcmp(o->method, "svd") == 0) {
        double extent = o->extent;
        if (!(extent > 0.0)) extent = sss_profile_reach(p, 0.999);
        sss_svd_kernel k;
        res = sss_kernel_svd(p, o->grid, extent, o->rank, &k, &err);
        if (res == SSS_OK) print_svd(&k);
        sss_svd_kernel_free(&k);
    } else {
        sss_separable_kernel k;
        res = sss_kernel_preintegrated(p, o->taps, o->range, &k, &err);
        if (res == SSS_OK) print_taps("pre-integrated", &k);
        sss_separable_kernel_free(&k);
    }
    cli_medium_profile_free(&mp);
    return res == SSS_OK ? CLI_EXIT_OK : cli_fail(CMD, &err);
}

static int kernel_run(const kernel_options *o)
{
    int status = o->preset ? run_artist(o) : run_medium(o);
    if (status != CLI_EXIT_OK) return status;
    if (fflush(stdout) != 0 || ferror(stdout)) return cli_failf(CMD, "error writing the output");
    return CLI_EXIT_OK;
}

int sss_cmd_kernel(int argc, char **argv)
{
    kernel_options o;
    int status = kernel_parse(argc, argv, &o);
    return status == CLI_EXIT_OK ? kernel_run(&o) : status;
}
