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

static void print_usage(FILE *f)
{
    fprintf(f,
            "usage: sss profile MEDIUM [--scale S] [--eta E] [--model pbd|dipole] [--r R0:R1:N]\n"
            "\n"
            "Prints the radial diffusion profile S_r(r) of a measured medium (Jensen et al. 2001) as TSV:\n"
            "a header line 'r<TAB>R<TAB>G<TAB>B', then one line per radius. Values are per scene unit^2,\n"
            "before the 1/pi and Fresnel factors, as PBRT-v3's TabulatedBSSRDF::Sr returns them (except\n"
            "at r = 0, where this prints the limit r -> 0+ instead of PBRT's 0).\n"
            "\n"
            "options:\n"
            "  --scale S       millimetres per scene unit (default 1: radii in mm)\n"
            "  --eta E         relative index of refraction in [%g, %g] (default 1.33)\n"
            "  --model M       pbd (Photon Beam Diffusion table, as PBRT-v3; default) or dipole\n"
            "                  (classical dipole of Jensen et al. 2001)\n"
            "  --r R0:R1:N     N radii evenly spaced from R0 to R1 inclusive (N = 1: R0 alone).\n"
            "                  Default: %d radii from 0 to the radius holding 99.9%% of the plane\n"
            "                  integral of the widest channel.\n"
            "\n"
            "media:",
            SSS_ETA_MIN, SSS_ETA_MAX, DEFAULT_COUNT);
    for (size_t i = 0; i < sss_measured_medium_count(); i++)
        fprintf(f, " %s", sss_measured_medium_at(i)->name);
    fprintf(f, " (case-insensitive)\n");
}

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

int sss_cmd_profile(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) {
        print_usage(stdout);
        return CLI_EXIT_OK;
    }
    const char *medium = NULL, *model_text = "pbd";
    double scale = 1.0, eta = 1.33, r0 = 0.0, r1 = 0.0;
    int count = DEFAULT_COUNT, have_range = 0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--scale") == 0 || strcmp(a, "--eta") == 0) {
            const char *v = cli_option_value(CMD, argc, argv, &i);
            if (!v || !cli_parse_double(CMD, a, v, a[2] == 's' ? &scale : &eta)) return CLI_EXIT_USAGE;
        } else if (strcmp(a, "--model") == 0) {
            if (!(model_text = cli_option_value(CMD, argc, argv, &i))) return CLI_EXIT_USAGE;
            if (strcmp(model_text, "pbd") != 0 && strcmp(model_text, "dipole") != 0)
                return cli_usage_error(CMD, "--model expects pbd or dipole, got '%s'", model_text);
        } else if (strcmp(a, "--r") == 0) {
            const char *v = cli_option_value(CMD, argc, argv, &i);
            if (!v || !parse_range(v, &r0, &r1, &count)) return CLI_EXIT_USAGE;
            have_range = 1;
        } else if (a[0] == '-' && a[1] != '\0') {
            return cli_usage_error(CMD, "unknown option '%s'", a);
        } else if (!medium) {
            medium = a;
        } else {
            return cli_usage_error(CMD, "unexpected argument '%s' (one medium only)", a);
        }
    }
    if (!medium) return cli_usage_error(CMD, "missing MEDIUM");

    cli_medium_profile mp;
    if (cli_medium_profile_init(CMD, medium, scale, eta, model_text, &mp) != CLI_EXIT_OK) return CLI_EXIT_ERROR;
    const sss_profile *p = &mp.profile;

    if (!have_range) {
        r0 = 0.0;
        r1 = 0.0;
        for (int c = 0; c < 3; c++) r1 = fmax(r1, sss_profile_radius_for_fraction(p, c, 0.999));
    }

    printf("r\tR\tG\tB\n");
    for (int k = 0; k < count; k++) {
        double r = count == 1 ? r0 : r0 + (r1 - r0) * k / (double)(count - 1);
        double v[3];
        sss_profile_eval_rgb(p, r, v);
        printf("%.6g\t%.6e\t%.6e\t%.6e\n", r, v[0], v[1], v[2]);
    }
    cli_medium_profile_free(&mp);
    if (fflush(stdout) != 0 || ferror(stdout)) return cli_failf(CMD, "error writing the output");
    return CLI_EXIT_OK;
}
