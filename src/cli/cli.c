#include "cli/cli.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/file_util.h"
#include "core/text.h"
#include "scene/scene_files.h"
#include "sss/gl.h"
#include "sss/scene.h"

/* Every diagnostic of the tool goes through here: "sss CMD: message" (or "sss: message") with the
 * message's control characters escaped, since it names files and scene strings from data. */
static void vmessage(const char *cmd, const char *fmt, va_list ap)
{
    va_list again;
    va_copy(again, ap);
    int n = vsnprintf(NULL, 0, fmt, ap);
    char *text = n >= 0 ? malloc((size_t)n + 1) : NULL;
    char *escaped = text ? malloc(SSS_TEXT_ESCAPE_MAX * (size_t)n + 1) : NULL;
    if (cmd) fprintf(stderr, "sss %s: ", cmd);
    else fputs("sss: ", stderr);
    if (escaped) {
        vsnprintf(text, (size_t)n + 1, fmt, again);
        sss_text_escape(text, (size_t)n, escaped);
        fputs(escaped, stderr);
    } else {
        fputs("(out of memory formatting the message)", stderr);
    }
    fputc('\n', stderr);
    free(escaped);
    free(text);
    va_end(again);
}

void cli_message(const char *cmd, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vmessage(cmd, fmt, ap);
    va_end(ap);
}

int cli_usage_error(const char *cmd, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vmessage(cmd, fmt, ap);
    va_end(ap);
    fprintf(stderr, "Try 'sss %s --help'.\n", cmd);
    return CLI_EXIT_USAGE;
}

int cli_fail(const char *cmd, const sss_error *err)
{
    cli_message(cmd, "%s", err && err->message[0] ? err->message : "unknown error");
    return CLI_EXIT_ERROR;
}

int cli_failf(const char *cmd, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vmessage(cmd, fmt, ap);
    va_end(ap);
    return CLI_EXIT_ERROR;
}

int cli_check_outputs(const char *cmd, const char *const *outputs, size_t output_count, const char *const *inputs,
                      size_t input_count, const sss_scene *scene)
{
    sss_io_set io = {0};
    for (size_t i = 0; i < input_count; i++) sss_io_add_input(&io, inputs[i]);
    if (scene) scene_add_inputs(&io, scene);
    for (size_t i = 0; i < output_count; i++) sss_io_add_output(&io, outputs[i]);
    sss_error err = {0};
    sss_result r = sss_io_check(&io, &err);
    sss_io_free(&io);
    return r == SSS_OK ? CLI_EXIT_OK : cli_fail(cmd, &err);
}

int cli_wants_help(int argc, char **argv)
{
    for (int i = 1; i < argc && strcmp(argv[i], "--") != 0; i++)
        if (strcmp(argv[i], "-h") == 0 || strcmp(argv[i], "--help") == 0) return 1;
    return 0;
}

int cli_parse_double(const char *cmd, const char *option, const char *text, double *out)
{
    char *end = NULL;
    errno = 0;
    double v = strtod(text, &end);
    if (end == text || *end != '\0' || errno == ERANGE || !isfinite(v)) {
        cli_usage_error(cmd, "%s expects a number, got '%s'", option, text);
        return 0;
    }
    *out = v;
    return 1;
}

int cli_parse_int(const char *cmd, const char *option, const char *text, int *out)
{
    char *end = NULL;
    errno = 0;
    long v = strtol(text, &end, 10);
    if (end == text || *end != '\0' || errno == ERANGE || v < INT_MIN || v > INT_MAX) {
        cli_usage_error(cmd, "%s expects an integer, got '%s'", option, text);
        return 0;
    }
    *out = (int)v;
    return 1;
}

int cli_parse_int_in(const char *cmd, const char *option, const char *text, int min, int max, int *out)
{
    int v;
    if (!cli_parse_int(cmd, option, text, &v)) return 0;
    if (v < min || v > max) {
        cli_usage_error(cmd, "%s must be in %d..%d, got %d", option, min, max, v);
        return 0;
    }
    *out = v;
    return 1;
}

int cli_parse_positive(const char *cmd, const char *option, const char *text, double *out)
{
    double v;
    if (!cli_parse_double(cmd, option, text, &v)) return 0;
    if (!(v > 0.0)) {
        cli_usage_error(cmd, "%s must be a number > 0, got '%s'", option, text);
        return 0;
    }
    *out = v;
    return 1;
}

int cli_parse_size(const char *cmd, const char *option, const char *text, int *out)
{
    int v;
    if (!cli_parse_int(cmd, option, text, &v)) return 0;
    if (v < 1 || v > SSS_SCENE_MAX_IMAGE_SIZE) {
        cli_usage_error(cmd, "%s must be in 1..%d, got %d", option, SSS_SCENE_MAX_IMAGE_SIZE, v);
        return 0;
    }
    *out = v;
    return 1;
}

int cli_parse_supersample(const char *cmd, const char *option, const char *text, int *out)
{
    int v;
    if (!cli_parse_int(cmd, option, text, &v)) return 0;
    if (v < 1 || v > SSS_GL_MAX_SUPERSAMPLE) {
        cli_usage_error(cmd, "%s must be in 1..%d (the antialiasing factor per axis; 1: off), got %d", option,
                        SSS_GL_MAX_SUPERSAMPLE, v);
        return 0;
    }
    *out = v;
    return 1;
}

int cli_params_add(const char *cmd, cli_params *params, const char *text)
{
    const char *eq = strchr(text, '=');
    if (!eq || eq == text || (size_t)(eq - text) >= sizeof params->names[0]) {
        cli_usage_error(cmd, "--param expects NAME=VALUE, got '%s'", text);
        return 0;
    }
    if (params->count >= CLI_MAX_PARAMS) {
        cli_usage_error(cmd, "at most %d --param options", CLI_MAX_PARAMS);
        return 0;
    }
    int k = params->count;
    memcpy(params->names[k], text, (size_t)(eq - text));
    params->names[k][eq - text] = '\0';
    params->values[k].name = params->names[k];
    sss_error err = {0};
    if (sss_gl_param_parse(params->names[k], eq + 1, &params->values[k].value, &err) != SSS_OK) {
        cli_usage_error(cmd, "--param: %s", err.message); /* preset=paper|measured, or a number */
        return 0;
    }
    params->count++;
    return 1;
}

int cli_scene_resize(const char *cmd, sss_scene *scene, int width, int height)
{
    if (width) scene->camera.width = width;
    if (height) scene->camera.height = height;
    sss_error err = {0};
    if (sss_camera_basis_init(&scene->camera, &scene->basis, &err) != SSS_OK) return cli_fail(cmd, &err);
    return CLI_EXIT_OK;
}

int cli_require_extension(const char *cmd, const char *option, const char *path, const char *ext)
{
    char have[16];
    sss_path_extension(path, have, sizeof have);
    if (strcmp(have, ext) == 0) return 1;
    cli_usage_error(cmd, "%s '%s': the file is written as .%s, so its name must end in .%s", option, path, ext, ext);
    return 0;
}

int cli_medium_profile_init(const char *cmd, const char *medium, double scale, double eta, const char *model,
                            cli_medium_profile *out)
{
    sss_error err = {0};
    sss_profile_model m = strcmp(model, "dipole") == 0 ? SSS_PROFILE_DIPOLE : SSS_PROFILE_PBD;
    if (sss_medium_profile_init(out, medium, scale, eta, m, &err) != SSS_OK) return cli_fail(cmd, &err);
    return CLI_EXIT_OK;
}

void cli_medium_profile_free(cli_medium_profile *mp) { sss_medium_profile_free(mp); }

/* ---- Option tables ------------------------------------------------------------------------------- */

const char CLI_REQUIRED[] = "required";

/* The options every command takes (ids below every command's own). */
enum { COMMON_QUIET = -100, COMMON_PROGRESS, COMMON_HELP };
const cli_option cli_common_options[CLI_COMMON_OPTION_COUNT] = {
    {COMMON_QUIET, "--quiet", "-q", CLI_ARG_NONE, NULL, "no progress, notes or warnings on stderr (errors still)", NULL,
     NULL},
    {COMMON_PROGRESS, "--progress", NULL, CLI_ARG_NONE, NULL,
     "progress on stderr also when it is not a terminal (long commands)", NULL, NULL},
    {COMMON_HELP, "--help", "-h", CLI_ARG_NONE, NULL, "this help", NULL, NULL},
};

/* The option named by arg (its first name_len bytes), from the command's table or the common one. */
static const cli_option *find_option(const cli_command_spec *spec, const char *arg, size_t name_len)
{
    for (int t = 0; t < 2; t++) {
        const cli_option *table = t == 0 ? spec->options : cli_common_options;
        int n = t == 0 ? spec->option_count : CLI_COMMON_OPTION_COUNT;
        for (int k = 0; k < n; k++) {
            const char *names[2] = {table[k].name, table[k].short_name};
            for (int j = 0; j < 2; j++)
                if (names[j] && strlen(names[j]) == name_len && strncmp(names[j], arg, name_len) == 0)
                    return &table[k];
        }
    }
    return NULL;
}

static int unknown_option(const cli_command_spec *spec, const char *arg)
{
    const char *names[256];
    int n = 0;
    for (int k = 0; k < spec->option_count && n < 250; k++) names[n++] = spec->options[k].name;
    for (int k = 0; k < CLI_COMMON_OPTION_COUNT; k++) names[n++] = cli_common_options[k].name;
    char word[128];
    snprintf(word, sizeof word, "%.*s", (int)strcspn(arg, "="), arg);
    return cli_unknown(spec->name, "option", word, names, n);
}

/* One option argv[*next - 1] = a (its value, when it takes one, "--name=value" or the next argument)
 * handed to set; the common ones kept in *common. */
static int parse_option(const cli_command_spec *spec, int argc, char **argv, int *next, const char *a,
                        cli_setter set, void *opts, cli_common *common)
{
    const char *eq = strncmp(a, "--", 2) == 0 ? strchr(a, '=') : NULL;
    const cli_option *o = find_option(spec, a, eq ? (size_t)(eq - a) : strlen(a));
    if (!o) return unknown_option(spec, a);
    const char *given = a[1] == '-' ? o->name : o->short_name; /* as written, without "=value" */
    const char *value = NULL;
    if (o->arg == CLI_ARG_NONE) {
        if (eq) return cli_usage_error(spec->name, "%s takes no value", o->name);
    } else if (eq) {
        value = eq + 1;
    } else if (*next < argc) {
        value = argv[(*next)++];
    } else {
        return cli_usage_error(spec->name, "%s needs a value%s%s", a, o->meta ? " " : "", o->meta ? o->meta : "");
    }
    if (o->id == COMMON_QUIET) common->quiet = 1;
    else if (o->id == COMMON_PROGRESS) common->progress = 1;
    else if (o->id != COMMON_HELP) return set(opts, o->id, given, value);
    return CLI_EXIT_OK;
}

int cli_parse(const cli_command_spec *spec, int argc, char **argv, int first, cli_setter set, void *opts,
              cli_common *common)
{
    cli_common dropped = {0};
    if (!common) common = &dropped;
    memset(common, 0, sizeof *common);
    int operands_only = 0, status = CLI_EXIT_OK;
    for (int next = first; next < argc && status == CLI_EXIT_OK;) {
        const char *a = argv[next++];
        if (!operands_only && strcmp(a, "--") == 0) operands_only = 1;
        else if (operands_only || a[0] != '-' || a[1] == '\0') status = set(opts, CLI_OPERAND, a, a);
        else status = parse_option(spec, argc, argv, &next, a, set, opts, common);
    }
    return status;
}

int cli_show_progress(const cli_common *common)
{
    return !common->quiet && (common->progress || isatty(fileno(stderr)));
}

const char *cli_suggest(const char *word, const char *const *candidates, int count)
{
    const char *best = NULL, *prefix_of = NULL;
    int best_d = 1 << 30, prefixes = 0;
    size_t len = strlen(word);
    for (int k = 0; k < count; k++) {
        if (!candidates[k]) continue;
        int d = sss_text_edit_distance(word, candidates[k]);
        if (d < best_d) {
            best_d = d;
            best = candidates[k];
        }
        if (len >= 3 && strncmp(word, candidates[k], len) == 0) {
            prefixes++;
            prefix_of = candidates[k];
        }
    }
    /* a typo changes a few characters: up to a third of the name, at least 1, at most 3 */
    int allowed = (int)(len / 3);
    if (allowed < 1) allowed = 1;
    if (allowed > 3) allowed = 3;
    if (best && best_d <= allowed) return best;
    return prefixes == 1 ? prefix_of : NULL;
}

int cli_unknown(const char *cmd, const char *what, const char *word, const char *const *candidates, int count)
{
    const char *s = cli_suggest(word, candidates, count);
    if (s) return cli_usage_error(cmd, "unknown %s '%s'; did you mean '%s'?", what, word, s);
    return cli_usage_error(cmd, "unknown %s '%s'", what, word);
}

int cli_technique_names(const char **names, int max)
{
    int n = 0;
    for (int k = 0; k < sss_gl_technique_count() && n < max; k++) names[n++] = sss_gl_technique_at(k)->name;
    return n;
}

int cli_check_technique(const char *cmd, const char *name)
{
    if (sss_gl_technique_find(name)) return CLI_EXIT_OK;
    const char *names[64];
    int n = cli_technique_names(names, 64);
    char known[1024] = "";
    for (int k = 0; k < n; k++) {
        size_t used = strlen(known);
        snprintf(known + used, sizeof known - used, "%s%s", k ? ", " : "", names[k]);
    }
    const char *s = cli_suggest(name, names, n);
    if (s) return cli_failf(cmd, "unknown technique '%s'; did you mean '%s'? (known: %s)", name, s, known);
    return cli_failf(cmd, "unknown technique '%s' (known: %s)", name, known);
}

void cli_progress_init(cli_progress *pr, const cli_common *common)
{
    memset(pr, 0, sizeof *pr);
    pr->active = cli_show_progress(common);
    pr->tty = isatty(fileno(stderr));
    pr->last_percent = -1;
    pr->start = sss_time_seconds();
}

void cli_progress_update(cli_progress *pr, double fraction, const char *stage)
{
    if (!pr->active) return;
    int percent = (int)floor(100.0 * fraction);
    if (pr->tty) {
        double elapsed = sss_time_seconds() - pr->start;
        char eta[32] = "--:--";
        if (fraction > 0.02) {
            int s = (int)(elapsed * (1.0 - fraction) / fraction + 0.5);
            snprintf(eta, sizeof eta, "%d:%02d", s / 60, s % 60);
        }
        char bar[31];
        int filled = (int)(30.0 * fraction);
        for (int i = 0; i < 30; i++) bar[i] = i < filled ? '#' : '.';
        bar[30] = '\0';
        char shown[SSS_TEXT_ESCAPE_MAX * 32 + 1]; /* stages may name files: escaped like every message */
        sss_text_escape(stage ? stage : "", stage ? strnlen(stage, 32) : 0, shown);
        fprintf(stderr, "\r[%s] %3d%%  ETA %s  %-16s", bar, percent, eta, shown);
        fflush(stderr);
        pr->drawn = 1;
    } else if (percent / 10 > pr->last_percent / 10 || (percent == 100 && pr->last_percent < 100)) {
        fprintf(stderr, "%d%%\n", percent - percent % 10);
    }
    if (percent > pr->last_percent) pr->last_percent = percent;
}

void cli_progress_end(cli_progress *pr)
{
    if (pr->active && pr->tty && pr->drawn) fputc('\n', stderr);
    pr->drawn = 0;
}
