#include "cli/cli.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/file_util.h"
#include "core/text.h"
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

/* The files a scene reads, after the given inputs: a new array (free it), NULL when out of memory. */
static const char **input_list(const char *const *inputs, size_t input_count, const sss_scene *scene, size_t *count)
{
    size_t n = input_count;
    if (scene) n += 1 + 3 * scene->object_count + scene->light_count;
    const char **list = malloc((n ? n : 1) * sizeof *list);
    if (!list) return NULL;
    size_t k = 0;
    for (size_t i = 0; i < input_count; i++) list[k++] = inputs[i];
    if (scene) {
        list[k++] = scene->name;
        for (size_t i = 0; i < scene->object_count; i++) {
            list[k++] = scene->objects[i].mesh_path;
            list[k++] = scene->objects[i].splat_mesh_path;
            list[k++] = scene->objects[i].material.texture;
        }
        for (size_t i = 0; i < scene->light_count; i++) list[k++] = scene->lights[i].file;
    }
    *count = k;
    return list;
}

int cli_check_outputs(const char *cmd, const char *const *outputs, size_t output_count, const char *const *inputs,
                      size_t input_count, const sss_scene *scene)
{
    size_t n = 0;
    const char **list = input_list(inputs, input_count, scene, &n);
    if (!list) return cli_failf(cmd, "out of memory");
    sss_error err = {0};
    sss_result r = SSS_OK;
    for (size_t i = 0; i < output_count && r == SSS_OK; i++)
        r = sss_check_output_not_input(outputs[i], list, n, &err);
    free(list);
    return r == SSS_OK ? CLI_EXIT_OK : cli_fail(cmd, &err);
}

int cli_wants_help(int argc, char **argv)
{
    for (int i = 1; i < argc; i++)
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

int cli_require_extension(const char *cmd, const char *option, const char *path, const char *ext)
{
    char have[16];
    sss_path_extension(path, have, sizeof have);
    if (strcmp(have, ext) == 0) return 1;
    cli_usage_error(cmd, "%s '%s': the file is written as .%s, so its name must end in .%s", option, path, ext, ext);
    return 0;
}

const char *cli_option_value(const char *cmd, int argc, char **argv, int *i)
{
    if (*i + 1 >= argc) {
        cli_usage_error(cmd, "%s needs a value", argv[*i]);
        return NULL;
    }
    *i += 1;
    return argv[*i];
}

int cli_medium_profile_init(const char *cmd, const char *medium, double scale, double eta, const char *model,
                            cli_medium_profile *out)
{
    sss_error err = {0};
    memset(out, 0, sizeof *out);
    if (sss_material_from_medium(medium, scale, eta, &out->material, &err) != SSS_OK) return cli_fail(cmd, &err);
    sss_profile_model m = strcmp(model, "dipole") == 0 ? SSS_PROFILE_DIPOLE : SSS_PROFILE_PBD;
    if (m == SSS_PROFILE_PBD) {
        out->table = malloc(sizeof *out->table);
        if (!out->table) return cli_failf(cmd, "out of memory for the PBD table");
        if (sss_pbd_table_build(out->material.eta, out->material.g, out->table, &err) != SSS_OK) {
            cli_medium_profile_free(out);
            return cli_fail(cmd, &err);
        }
    }
    if (sss_profile_init(&out->profile, m, &out->material, out->table, &err) != SSS_OK) {
        cli_medium_profile_free(out);
        return cli_fail(cmd, &err);
    }
    return CLI_EXIT_OK;
}

void cli_medium_profile_free(cli_medium_profile *mp)
{
    free(mp->table);
    mp->table = NULL;
}
