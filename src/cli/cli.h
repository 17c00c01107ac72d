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

/* Prints "sss CMD: message" (cmd NULL: "sss: message") to stderr with the message's control characters
 * escaped (core/text.h): every diagnostic goes through it, since messages name files and scene
 * strings from data. The functions below print through it. */
void cli_message(const char *cmd, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
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

/* Refuses an output that is the same file as an input (device and inode: other spellings and hard
 * links too) before any work: the inputs given (NULL entries skipped) and, when scene is not NULL,
 * every file the scene reads (itself, meshes, textures, environment maps). Outputs that are NULL are
 * skipped. Prints the error as cmd's and returns CLI_EXIT_ERROR, else CLI_EXIT_OK. */
struct sss_scene;
int cli_check_outputs(const char *cmd, const char *const *outputs, size_t output_count, const char *const *inputs,
                      size_t input_count, const struct sss_scene *scene);

/* True when any argument is -h or --help. */
int cli_wants_help(int argc, char **argv);

/* Strict number parsing: the whole string must be a finite number (or integer). On failure they print
 * a usage error naming the option and return 0; on success they return 1. */
int cli_parse_double(const char *cmd, const char *option, const char *text, double *out);
int cli_parse_int(const char *cmd, const char *option, const char *text, int *out);
/* The same with a range: options whose default is a sentinel (0, -1) must not take it silently from
 * the command line ("--range 0" is refused, not "the default range"). */
int cli_parse_int_in(const char *cmd, const char *option, const char *text, int min, int max, int *out);
int cli_parse_positive(const char *cmd, const char *option, const char *text, double *out); /* finite, > 0 */

/* For an output written in one format: 1 when path ends in .ext (any case), otherwise prints a usage
 * error and returns 0 (a .obj name must not receive PLY bytes). */
int cli_require_extension(const char *cmd, const char *option, const char *path, const char *ext);

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
