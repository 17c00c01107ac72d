/* cli/cmd_profile.c — `sss profile MEDIUM`: prints S_r(r) of a measured medium as TSV
 * (per scene unit^2, before the 1/pi and Fresnel factors; docs/physics.md §2.2), for comparison with PBRT-v3. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "sss/profile.h"

#define CMD "profile"
#define DEFAULT_COUNT 64
#define MAX_COUNT 1000000

enum { OPT_SCALE, OPT_ETA, OPT_MODEL, OPT_R };
static const cli_option options[] = {
    {OPT_SCALE, "--scale", NULL, CLI_ARG_NUMBER, "S", "millimetres per scene unit", NULL, "1 = radii in mm"},
    {OPT_ETA, "--eta", NULL, CLI_ARG_NUMBER, "E",
     "relative index of refraction in [" CLI_STR(SSS_ETA_MIN) ", " CLI_STR(SSS_ETA_MAX) "]", NULL,
     CLI_STR(CLI_DEFAULT_ETA)},
    {OPT_MODEL, "--model", NULL, CLI_ARG_TEXT, "M",
     "pbd (Photon Beam Diffusion table, as PBRT-v3) or dipole\n"
     "(classical dipole of Jensen et al. 2001)",
     "pbd dipole", "pbd"},
    {OPT_R, "--r", NULL, CLI_ARG_TEXT, "R0:R1:N",
     "N radii evenly spaced from R0 to R1 inclusive (N = 1: R0 alone).\n"
     "Default: " CLI_STR(DEFAULT_COUNT) " radii from 0 to the radius holding 99.9% of the plane\n"
     "integral of the widest channel.",
     NULL, NULL},
};
const cli_command_spec cli_spec_profile = {
    CMD, options, CLI_COUNT(options), CLI_ARG_MEDIUM, NULL, "MEDIUM",
    "Prints the radial diffusion profile S_r(r) of a measured medium (Jensen et al. 2001) as TSV:\n"
    "a header line 'r<TAB>R<TAB>G<TAB>B', then one line per radius. Values are per scene unit^2,\n"
    "before the 1/pi and Fresnel factors, as PBRT-v3's TabulatedBSSRDF::Sr returns them (except\n"
    "at r = 0, where this prints the limit r -> 0+ instead of PBRT's 0).\n",
    NULL, NULL};

typedef struct profile_options {
    const char *medium, *model;
    double scale, eta, r0, r1;
    int count, have_range;
} profile_options;

/* Parses "R0:R1:N"; prints a usage error and returns 0 when malformed. */
static int parse_range(const char *text, double *r0, double *r1, int *n)
{
    const char *c1 = strchr(text, ':');
    const char *c2 = c1 ? strchr(c1 + 1, ':') : NULL;
    if (!c1 || !c2 || strchr(c2 + 1, ':')) {
        cli_usage_error(CMD, "--r expects R0:R1:N, got '%s'", text);
        return 0;
    }
    char buf[3][128];
    size_t len[3] = {(size_t)(c1 - text), (size_t)(c2 - c1 - 1), strlen(c2 + 1)};
    const char *start[3] = {text, c1 + 1, c2 + 1};
    for (int k = 0; k < 3; k++) {
        if (len[k] == 0 || len[k] >= sizeof buf[k]) {
            cli_usage_error(CMD, "--r expects R0:R1:N, got '%s'", text);
            return 0;
        }
        memcpy(buf[k], start[k], len[k]);
        buf[k][len[k]] = '\0';
    }
    if (!cli_parse_double(CMD, "--r (R0)", buf[0], r0) || !cli_parse_double(CMD, "--r (R1)", buf[1], r1) ||
        !cli_parse_int(CMD, "--r (N)", buf[2], n))
        return 0;
    if (*r0 < 0.0 || *r1 < 0.0) {
        cli_usage_error(CMD, "--r radii must be >= 0, got '%s'", text);
        return 0;
    }
    if (*n < 1 || *n > MAX_COUNT) {
        cli_usage_error(CMD, "--r count N must be in [1, %d], got %d", MAX_COUNT, *n);
        return 0;
    }
    return 1;
}

static int set_option(void *opts, int id, const char *a, const char *v)
{
    profile_options *o = opts;
    switch (id) {
    case OPT_SCALE:
    case OPT_ETA:
        if (!cli_parse_double(CMD, a, v, id == OPT_SCALE ? &o->scale : &o->eta)) return CLI_EXIT_USAGE;
        break;
    case OPT_MODEL:
        o->model = v;
        if (strcmp(o->model, "pbd") != 0 && strcmp(o->model, "dipole") != 0)
            return cli_usage_error(CMD, "--model expects pbd or dipole, got '%s'", o->model);
        break;
    case OPT_R:
        if (!parse_range(v, &o->r0, &o->r1, &o->count)) return CLI_EXIT_USAGE;
        o->have_range = 1;
        break;
    default: /* CLI_OPERAND */
        if (o->medium) return cli_usage_error(CMD, "unexpected argument '%s' (one medium only)", v);
        o->medium = v;
    }
    return CLI_EXIT_OK;
}

static int profile_parse(int argc, char **argv, profile_options *o)
{
    *o = (profile_options){.model = "pbd", .scale = 1.0, .eta = CLI_DEFAULT_ETA, .count = DEFAULT_COUNT};
    int status = cli_parse(&cli_spec_profile, argc, argv, 1, set_option, o, NULL);
    if (status != CLI_EXIT_OK) return status;
    if (!o->medium) return cli_usage_error(CMD, "missing MEDIUM");
    return CLI_EXIT_OK;
}

static int profile_run(const profile_options *o)
{
    cli_medium_profile mp;
    if (cli_medium_profile_init(CMD, o->medium, o->scale, o->eta, o->model, &mp) != CLI_EXIT_OK) return CLI_EXIT_ERROR;
    const sss_profile *p = &mp.profile;
    double r0 = o->r0, r1 = o->r1;
    if (!o->have_range) {
        r0 = 0.0;
        r1 = sss_profile_reach(p, 0.999);
    }
    printf("r\tR\tG\tB\n");
    for (int k = 0; k < o->count; k++) {
        double r = o->count == 1 ? r0 : r0 + (r1 - r0) * k / (double)(o->count - 1);
        double v[3];
        sss_profile_eval_rgb(p, r, v);
        printf("%.6g\t%.6e\t%.6e\t%.6e\n", r, v[0], v[1], v[2]);
    }
    cli_medium_profile_free(&mp);
    if (fflush(stdout) != 0 || ferror(stdout)) return cli_failf(CMD, "error writing the output");
    return CLI_EXIT_OK;
}

int sss_cmd_profile(int argc, char **argv)
{
    profile_options o;
    int status = profile_parse(argc, argv, &o);
    return status == CLI_EXIT_OK ? profile_run(&o) : status;
}
