/* cli/cmd_techniques.c — `sss techniques [--params]`: one line per real-time technique; with --params
 * also every parameter (type, default, range, description) and the parameters all techniques share. */
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"
#include "sss/gl.h"

#define CMD "techniques"

static const char *type_name(sss_gl_param_type t)
{
    return t == SSS_GL_PARAM_BOOL ? "bool" : t == SSS_GL_PARAM_INT ? "int" : "float";
}

/* technique: the one whose preset=paper values are shown where they differ from the default (NULL: none) */
static void print_params(const char *technique, const sss_gl_param_info *p, int count)
{
    for (int i = 0; i < count; i++) {
        printf("    %-22s %-5s default %-8g range [%g, %g]  %s", p[i].name, type_name(p[i].type), p[i].default_value,
               p[i].min_value, p[i].max_value, p[i].doc);
        double paper = technique ? sss_gl_paper_value(technique, p[i].name) : p[i].default_value;
        if (paper == paper && paper != p[i].default_value) printf(" [preset=paper: %g]", paper);
        printf("\n");
    }
}

enum { OPT_PARAMS };
static const cli_option options[] = {
    {OPT_PARAMS, "--params", NULL, CLI_ARG_NONE, NULL, "also each technique's parameters and the shared ones", NULL, NULL},
};
const cli_command_spec cli_spec_techniques = {
    CMD, options, CLI_COUNT(options), CLI_ARG_NONE, NULL, NULL,
    "Lists the real-time techniques of `sss render --technique NAME`, one per line (name, then a\n"
    "summary). --params also lists each technique's parameters (set them with\n"
    "`sss render --param NAME=VALUE`) and the parameters shared by all techniques. Defaults are the\n"
    "values that measure best on the evaluation scenes; `--param preset=paper` sets the published\n"
    "configuration, shown as [preset=paper: VALUE] where it differs.\n",
    NULL, NULL};

typedef struct techniques_options {
    int with_params;
} techniques_options;

static int set_option(void *opts, int id, const char *given, const char *value)
{
    (void)given;
    techniques_options *o = opts;
    if (id == OPT_PARAMS) o->with_params = 1;
    else return cli_usage_error(CMD, "unexpected argument '%s'", value);
    return CLI_EXIT_OK;
}

static int techniques_parse(int argc, char **argv, techniques_options *o)
{
    memset(o, 0, sizeof *o);
    return cli_parse(&cli_spec_techniques, argc, argv, 1, set_option, o, NULL);
}

static int techniques_run(const techniques_options *o)
{
    for (int i = 0; i < sss_gl_technique_count(); i++) {
        const sss_gl_technique_info *t = sss_gl_technique_at(i);
        printf("%-12s %s\n", t->name, t->summary);
        if (!o->with_params) continue;
        print_params(t->name, t->params, t->param_count);
        int n = 0;
        const sss_gl_param_info *sp = sss_gl_shared_params(&n);
        for (int k = 0; k < n; k++) {
            double paper = sss_gl_paper_value(t->name, sp[k].name);
            if (strcmp(sp[k].name, "preset") != 0 && paper != sp[k].default_value)
                printf("    %-22s (shared)        [preset=paper: %g]\n", sp[k].name, paper);
        }
    }
    if (o->with_params) {
        int n = 0;
        const sss_gl_param_info *sp = sss_gl_shared_params(&n);
        printf("shared parameters (every technique):\n");
        print_params(NULL, sp, n);
    }
    return CLI_EXIT_OK;
}

int sss_cmd_techniques(int argc, char **argv)
{
    techniques_options o;
    int status = techniques_parse(argc, argv, &o);
    return status == CLI_EXIT_OK ? techniques_run(&o) : status;
}
