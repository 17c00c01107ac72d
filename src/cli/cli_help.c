/* cli/cli_help.c — `sss COMMAND --help`, generated from the command's option tables (cli.h): the
 * synopsis of every spec (subcommand), each spec's about text, one entry per option (names, value
 * name, doc, default) and the common options, the measured media when the operand is one, the notes. */
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"
#include "sss/profile.h"

#define HELP_WIDTH 100 /* columns the synopsis wraps at */
#define HELP_COLUMN 24 /* where an option's doc starts */

/* The synopsis word of option k: "-o FILE", "--width W", "--timings", "--model pbd|dipole" (its
 * choices); NULL for a hidden option or an alias of one listed before it (the same id). */
static const char *synopsis_word(const cli_command_spec *spec, int k, char *buf, size_t cap)
{
    const cli_option *o = &spec->options[k];
    if (!o->help) return NULL;
    for (int j = 0; j < k; j++)
        if (spec->options[j].id == o->id) return NULL;
    char value[96];
    snprintf(value, sizeof value, "%s", o->choices ? o->choices : o->meta ? o->meta : "");
    for (char *c = value; o->choices && *c; c++) /* the choices as alternatives: "draft|final" */
        if (*c == ' ') *c = '|';
    int required = o->def == CLI_REQUIRED;
    snprintf(buf, cap, "%s%s%s%s%s", required ? "" : "[", o->short_name ? o->short_name : o->name, value[0] ? " " : "",
             value, required ? "" : "]");
    return buf;
}

/* "usage: sss NAME OPERANDS REQUIRED [OPTIONAL]...", wrapped at HELP_WIDTH under its first word. */
static void print_synopsis(FILE *f, const cli_command_spec *spec, int first)
{
    char head[128];
    int indent = snprintf(head, sizeof head, "%s sss %s", first ? "usage:" : "      ", spec->name);
    fputs(head, f);
    int col = indent;
    if (spec->operands) col += fprintf(f, " %s", spec->operands);
    for (int pass = 0; pass < 2; pass++) /* the required options first */
        for (int k = 0; k < spec->option_count; k++) {
            char word[128];
            if ((spec->options[k].def == CLI_REQUIRED) != (pass == 0) || !synopsis_word(spec, k, word, sizeof word))
                continue;
            int len = (int)strlen(word);
            if (col + 1 + len > HELP_WIDTH) col = fprintf(f, "\n%*s", indent, "") - 1;
            col += fprintf(f, " %s", word);
        }
    fputc('\n', f);
}

/* "  -o, --output FILE     doc", the doc's further lines under its first, the default after the
 * last line (or on a line of its own when it does not fit). */
static void print_option(FILE *f, const cli_option *o)
{
    int n = fprintf(f, "  %s%s%s%s%s", o->short_name ? o->short_name : "", o->short_name ? ", " : "", o->name,
                    o->meta ? " " : "", o->meta ? o->meta : "");
    if (n + 1 > HELP_COLUMN) {
        fputc('\n', f);
        n = 0;
    }
    char tail[256] = "";
    if (o->def == CLI_REQUIRED) snprintf(tail, sizeof tail, "(required)");
    else if (o->def) snprintf(tail, sizeof tail, "(default: %s)", o->def);
    for (const char *line = o->help; *line;) {
        size_t len = strcspn(line, "\n");
        int last = line[len] == '\0' || line[len + 1] == '\0';
        fprintf(f, "%*s%.*s", HELP_COLUMN - n, "", (int)len, line);
        n = 0;
        if (last && tail[0]) {
            if (HELP_COLUMN + (int)len + 1 + (int)strlen(tail) <= HELP_WIDTH) fprintf(f, " %s", tail);
            else fprintf(f, "\n%*s%s", HELP_COLUMN, "", tail);
        }
        fputc('\n', f);
        line += len;
        if (*line == '\n') line++;
    }
}

/* Whether option k of specs[s] was listed already (the same name in an earlier spec: subcommands
 * share options). */
static int listed_before(const cli_command_spec *const *specs, int s, int k)
{
    const char *name = specs[s]->options[k].name;
    for (int i = 0; i <= s; i++)
        for (int j = 0; j < (i == s ? k : specs[i]->option_count); j++)
            if (strcmp(specs[i]->options[j].name, name) == 0) return 1;
    return 0;
}

static void print_options(FILE *f, const cli_command_spec *const *specs, int count)
{
    fprintf(f, "options:\n");
    for (int s = 0; s < count; s++)
        for (int k = 0; k < specs[s]->option_count; k++)
            if (specs[s]->options[k].help && !listed_before(specs, s, k)) print_option(f, &specs[s]->options[k]);
    for (int k = 0; k < CLI_COMMON_OPTION_COUNT; k++) print_option(f, &cli_common_options[k]);
}

static void print_media(FILE *f)
{
    fprintf(f, "\nmedia:");
    for (size_t i = 0; i < sss_measured_medium_count(); i++) fprintf(f, " %s", sss_measured_medium_at(i)->name);
    fprintf(f, " (case-insensitive)\n");
}

void cli_print_help(FILE *f, const cli_command_entry *command)
{
    const cli_command_spec *const *specs = command->specs;
    int count = 0;
    while (count < CLI_COUNT(command->specs) && specs[count]) count++;
    for (int s = 0; s < count; s++) print_synopsis(f, specs[s], s == 0);
    for (int s = 0; s < count; s++)
        if (specs[s]->about) fprintf(f, "\n%s", specs[s]->about);
    fputc('\n', f);
    print_options(f, specs, count);
    if (specs[0]->positional == CLI_ARG_MEDIUM) print_media(f);
    for (int s = 0; s < count; s++) {
        if (specs[s]->notes) fprintf(f, "\n%s", specs[s]->notes);
        if (specs[s]->print_more) specs[s]->print_more(f);
    }
}
