/* cli/cli.h — shared helpers of the `sss` command-line tool: option parsing and error reporting.
 * Exit codes: 0 success, 1 an error in the inputs or the work, 2 a usage error. */
#ifndef SSS_CLI_H
#define SSS_CLI_H

#include "sss/common.h"
#include "sss/profile.h"

enum { CLI_EXIT_OK = 0, CLI_EXIT_ERROR = 1, CLI_EXIT_USAGE = 2 };

/* Subcommands: argv[0] is the subcommand's name ("profile"), options follow. */
int sss_cmd_profile(int argc, char **argv);
int sss_cmd_lut(int argc, char **argv);
int sss_cmd_kernel(int argc, char **argv);
int sss_cmd_compare(int argc, char **argv);
int sss_cmd_mesh(int argc, char **argv);
int sss_cmd_reference(int argc, char **argv);
int sss_cmd_export(int argc, char **argv);
int sss_cmd_render(int argc, char **argv);
int sss_cmd_techniques(int argc, char **argv);
int sss_cmd_eval(int argc, char **argv);
int sss_cmd_view(int argc, char **argv);
int sss_cmd_sam(int argc, char **argv);
int sss_cmd_import(int argc, char **argv);

/* Prints "sss CMD: message" and "Try 'sss CMD --help'." to stderr; returns CLI_EXIT_USAGE. */
int cli_usage_error(const char *cmd, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
/* Prints "sss CMD: <err->message>" to stderr; returns CLI_EXIT_ERROR. */
int cli_fail(const char *cmd, const sss_error *err);
/* Prints "sss CMD: message" to stderr; returns CLI_EXIT_ERROR. */
int cli_failf(const char *cmd, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* True when any argument is -h or --help. */
int cli_wants_help(int argc, char **argv);

/* Strict number parsing: the whole string must be a finite number (or integer). On failure they print
 * a usage error naming the option and return 0; on success they return 1. */
int cli_parse_double(const char *cmd, const char *option, const char *text, double *out);
int cli_parse_int(const char *cmd, const char *option, const char *text, int *out);

/* For options with a value: returns argv[*i + 1] and advances *i, or prints a usage error and
 * returns NULL when the value is missing. */
const char *cli_option_value(const char *cmd, int argc, char **argv, int *i);

/* The profile of a measured medium, for the commands that take MEDIUM [--scale S] [--eta E]
 * [--model pbd|dipole]. */
typedef struct cli_medium_profile {
    sss_material material;
    sss_pbd_table *table; /* heap-allocated for PBD, NULL for the dipole */
    sss_profile profile;
} cli_medium_profile;

/* model is "pbd" or "dipole" (validated by the caller). On failure prints the error as cmd's and
 * returns CLI_EXIT_ERROR (nothing to free); on success CLI_EXIT_OK. */
int cli_medium_profile_init(const char *cmd, const char *medium, double scale, double eta, const char *model,
                            cli_medium_profile *out);
void cli_medium_profile_free(cli_medium_profile *mp);

#endif
