/* cli/cli.h — shared helpers of the `sss` command-line tool: option parsing and error reporting.
 * Exit codes: 0 success, 1 an error in the inputs or the work, 2 a usage error. */
#ifndef SSS_CLI_H
#define SSS_CLI_H

#include <stdio.h>

#include "sss/common.h"
#include "sss/gl.h"
#include "sss/profile.h"

enum { CLI_EXIT_OK = 0, CLI_EXIT_ERROR = 1, CLI_EXIT_USAGE = 2 };

/* ---- Option tables -------------------------------------------------------------------------------
 * Every command declares its options in a table (cli_option) inside a cli_command_spec: the parser
 * (cli_parse), --help (cli_print_help: the synopsis and one line per option), the "did you mean" of
 * unknown options and `sss completion bash` all read the same tables. -q/--quiet, --progress and
 * -h/--help are common to every command and handled by the parser.
 * A command is three steps: parse (argv -> its options struct, values and their combinations
 * checked; usage errors exit 2), run (options -> the work, an exit code), and the entry point
 * sss_cmd_NAME that chains them. A new command: a file cmd_NAME.c here with its option table, its spec
 * (operands, about, notes), an options struct, a setter for cli_parse, NAME_parse, NAME_run and
 * sss_cmd_NAME; an entry in main.c's commands[]. --help, `sss help NAME`, the option suggestions and
 * the completion follow from the table. */

/* What an option's value is: the parser only takes it; the command parses numbers and checks ranges
 * (its messages name its limits). The kind picks what completion offers. */
typedef enum cli_arg {
    CLI_ARG_NONE,      /* a flag without a value */
    CLI_ARG_TEXT,      /* text; with choices, one of them */
    CLI_ARG_NUMBER,    /* an integer or a number */
    CLI_ARG_FILE,      /* a path */
    CLI_ARG_DIR,       /* a folder */
    CLI_ARG_TECHNIQUE, /* a real-time technique's name (`sss techniques`) */
    CLI_ARG_MEDIUM     /* a measured medium's name */
} cli_arg;

/* The def of an option without which the command does not run: the synopsis shows it without
 * brackets, --help says "(required)". */
extern const char CLI_REQUIRED[];

typedef struct cli_option {
    int id;                 /* what the parser hands on; aliases share the id of the option they stand for */
    const char *name;       /* "--width" */
    const char *short_name; /* "-o", or NULL */
    cli_arg arg;
    const char *meta;       /* the value's name in --help ("W"); NULL for flags */
    const char *help;       /* one or more lines ('\n'); NULL hides the option from --help */
    const char *choices;    /* values offered by completion, space-separated ("draft final"), or NULL */
    const char *def;        /* the default as --help shows it ("1.33", "the scene camera's"), CLI_REQUIRED,
                             * or NULL; the command's parse starts from the same value */
} cli_option;

typedef struct cli_command_spec {
    const char *name;       /* "render", or "mesh simplify" for a subcommand */
    const cli_option *options;
    int option_count;
    cli_arg positional;     /* what the operands are, for completion (CLI_ARG_NONE: none) */
    const char *subcommands; /* space-separated words after the command ("info simplify convert"), or NULL */
    const char *operands;   /* the operands in the synopsis ("SCENE.json", "A B"), or NULL */
    const char *about;      /* --help's text between the synopsis and the options, or NULL */
    const char *notes;      /* --help's text after the options (exit status, ...), or NULL */
    void (*print_more)(FILE *f); /* text computed at run time after the notes (view's keys), or NULL */
} cli_command_spec;

/* A macro's value as a string literal, for limits in help texts: CLI_STR(SSS_ETA_MAX) is "2.5". */
#define CLI_STR_(x) #x
#define CLI_STR(x) CLI_STR_(x)
#define CLI_COUNT(array) ((int)(sizeof(array) / sizeof((array)[0])))

/* The common options' state: -q/--quiet, --progress. */
typedef struct cli_common {
    int quiet, progress;
} cli_common;

/* The common options' table (cli.c), listed last in every --help. */
#define CLI_COMMON_OPTION_COUNT 3
extern const cli_option cli_common_options[CLI_COMMON_OPTION_COUNT];

/* What cli_parse hands to a command's setter besides an option's id (ids are >= 0). */
enum { CLI_OPERAND = -2 };

/* A command's setter: stores one option (id, its name as written "-o"/"--width", its value; NULL for
 * a flag) or operand (id CLI_OPERAND, the operand as value) in the options struct opts, checking the
 * value. Returns CLI_EXIT_OK, or the exit code after printing the error (a usage error: 2). */
typedef int (*cli_setter)(void *opts, int id, const char *given, const char *value);

/* Parses argv[first..argc-1] against spec, in order, through set; the common options go to *common
 * (NULL: dropped). "--name=value" is accepted; after "--" everything is an operand. Unknown options
 * (with a suggestion when one is close), missing values and values given to flags are usage errors.
 * Returns CLI_EXIT_OK or the first failure's exit code (its message printed). */
int cli_parse(const cli_command_spec *spec, int argc, char **argv, int first, cli_setter set, void *opts,
              cli_common *common);
/* Whether to draw progress on stderr: never with --quiet; with --progress, or when stderr is a terminal. */
int cli_show_progress(const cli_common *common);

/* ---- Help ------------------------------------------------------------------------------------------
 * Generated from the tables (cli_help.c): "usage:" with one synopsis line per spec of the command (its
 * operands, then every option of its table: required ones bare, the others in brackets), each spec's
 * about, the "options:" (one entry per option: names, value name, doc, default; the common options
 * last), the media when the operand is one, each spec's notes and print_more. */
struct cli_command_entry;
void cli_print_help(FILE *f, const struct cli_command_entry *command);
/* The command named name ("render"), or NULL. */
const struct cli_command_entry *cli_find_command(const char *name);

/* The candidate closest to word (edit distance, or word is the start of exactly one candidate),
 * NULL when none is close enough to be a likely typo. */
const char *cli_suggest(const char *word, const char *const *candidates, int count);
/* Prints the usage error "unknown WHAT 'word'" with "; did you mean 'x'?" when a candidate is close;
 * returns CLI_EXIT_USAGE. */
int cli_unknown(const char *cmd, const char *what, const char *word, const char *const *candidates, int count);
/* The real-time techniques' names (at most max); returns their count. */
int cli_technique_names(const char **names, int max);
/* For a --technique value: CLI_EXIT_OK when it names a technique, else prints "unknown technique"
 * with a suggestion and the known names and returns CLI_EXIT_ERROR (as the renderer's own check). */
int cli_check_technique(const char *cmd, const char *name);

/* Progress on stderr for the long commands: a bar with the time left on a terminal, else a line
 * 'NN%' every 10% (with --progress). Inactive (every call a no-op) unless cli_show_progress. */
typedef struct cli_progress {
    int active, tty, last_percent, drawn;
    double start;
} cli_progress;
void cli_progress_init(cli_progress *pr, const cli_common *common);
void cli_progress_update(cli_progress *pr, double fraction, const char *stage);
/* Ends the bar's line (a terminal), so that what follows starts on a new line. */
void cli_progress_end(cli_progress *pr);

/* The specs of every command, for `sss completion` and the command names' suggestions (main.c). */
typedef struct cli_command_entry {
    const char *name;
    int (*run)(int argc, char **argv);
    const char *summary;
    int staged; /* its outputs are written by one transaction (core/file_util.h): all or none */
    const cli_command_spec *specs[3]; /* the command's spec, or one per subcommand (NULL-padded) */
} cli_command_entry;
const cli_command_entry *cli_commands(int *count);

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
int sss_cmd_completion(int argc, char **argv);

/* The option tables of the commands (in their cmd_*.c). */
extern const cli_command_spec cli_spec_profile, cli_spec_lut, cli_spec_kernel, cli_spec_compare, cli_spec_mesh_info,
    cli_spec_mesh_simplify, cli_spec_mesh_convert, cli_spec_reference, cli_spec_render, cli_spec_techniques,
    cli_spec_eval, cli_spec_view, cli_spec_export_pbrt, cli_spec_export_gltf, cli_spec_import, cli_spec_sam_build,
    cli_spec_sam_info, cli_spec_version, cli_spec_completion;

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

/* A command's file set checked before any work (core/file_util.h sss_io_check): refuses an output
 * that is the same file as an input (device and inode: other spellings and hard links too) or as
 * another output. Inputs: those given (NULL entries skipped) and, when scene is not NULL, every file
 * the scene reads (scene/scene_files.h: itself, meshes, textures, environment maps, a glTF asset's
 * buffers and images). Outputs that are NULL are skipped. Prints the error as cmd's and returns
 * CLI_EXIT_ERROR, else CLI_EXIT_OK. */
struct sss_scene;
int cli_check_outputs(const char *cmd, const char *const *outputs, size_t output_count, const char *const *inputs,
                      size_t input_count, const struct sss_scene *scene);

/* True when any argument after argv[0] is -h or --help (before "--"). */
int cli_wants_help(int argc, char **argv);

/* Strict number parsing: the whole string must be a finite number (or integer). On failure they print
 * a usage error naming the option and return 0; on success they return 1. */
int cli_parse_double(const char *cmd, const char *option, const char *text, double *out);
int cli_parse_int(const char *cmd, const char *option, const char *text, int *out);
/* The same with a range: options whose default is a sentinel (0, -1) must not take it silently from
 * the command line ("--range 0" is refused, not "the default range"). */
int cli_parse_int_in(const char *cmd, const char *option, const char *text, int min, int max, int *out);
int cli_parse_positive(const char *cmd, const char *option, const char *text, double *out); /* finite, > 0 */

/* An image width or height, 1..SSS_SCENE_MAX_IMAGE_SIZE, and a supersampling factor,
 * 1..SSS_GL_MAX_SUPERSAMPLE (--width, --height, --supersample of every command that renders). */
int cli_parse_size(const char *cmd, const char *option, const char *text, int *out);
int cli_parse_supersample(const char *cmd, const char *option, const char *text, int *out);

/* The technique parameters of --param NAME=VALUE (render, view), at most CLI_MAX_PARAMS. */
#define CLI_MAX_PARAMS 64
typedef struct cli_params {
    sss_gl_param_value values[CLI_MAX_PARAMS];
    char names[CLI_MAX_PARAMS][64];
    int count;
} cli_params;
/* Adds one NAME=VALUE; prints a usage error and returns 0 when it is malformed or one too many. */
int cli_params_add(const char *cmd, cli_params *params, const char *text);

/* Gives the scene's camera the size --width/--height asked for (0: keep the camera's) and rebuilds its
 * basis, as eval's sized views do. Prints the error as cmd's and returns CLI_EXIT_ERROR on failure. */
struct sss_scene;
int cli_scene_resize(const char *cmd, struct sss_scene *scene, int width, int height);

/* For an output written in one format: 1 when path ends in .ext (any case), otherwise prints a usage
 * error and returns 0 (a .obj name must not receive PLY bytes). */
int cli_require_extension(const char *cmd, const char *option, const char *path, const char *ext);

/* The profile of a measured medium, for the commands that take MEDIUM [--scale S] [--eta E]
 * [--model pbd|dipole]; --eta's default, as PBRT-v3's subsurface material's (eta 1.33). */
#define CLI_DEFAULT_ETA 1.33
typedef sss_medium_profile cli_medium_profile; /* the library's (sss/profile.h) */

/* model is "pbd" or "dipole" (validated by the caller). On failure prints the error as cmd's and
 * returns CLI_EXIT_ERROR (nothing to free); on success CLI_EXIT_OK. */
int cli_medium_profile_init(const char *cmd, const char *medium, double scale, double eta, const char *model,
                            cli_medium_profile *out);
void cli_medium_profile_free(cli_medium_profile *mp);

#endif
