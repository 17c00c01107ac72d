/* sss — command-line front end of the sss library (git-style subcommands). */
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"
#include "core/file_util.h"
#include "sss/version.h"

const cli_command_spec cli_spec_version = {
    "version", NULL, 0, CLI_ARG_NONE, NULL, NULL,
    "Prints 'sss MAJOR.MINOR.PATCH', the version of the sss library (also 'sss --version').\n", NULL, NULL};

static int version_set(void *opts, int id, const char *given, const char *value)
{
    (void)opts, (void)id, (void)value;
    return cli_usage_error("version", "takes no arguments, got '%s'", given);
}

/* `sss version` and `sss --version`: the version of the library the tool runs with. */
static int cmd_version(int argc, char **argv)
{
    int status = cli_parse(&cli_spec_version, argc, argv, 1, version_set, NULL, NULL);
    if (status == CLI_EXIT_OK) printf("sss %s\n", sss_version());
    return status;
}

static const cli_command_entry commands[] = {
    {"profile", sss_cmd_profile, "print the diffusion profile S_r(r) of a medium as TSV", 1, {&cli_spec_profile}},
    {"lut", sss_cmd_lut, "build the disc-integrated kernel LUT of Maisch & Ropinski 2020 and write it as EXR", 1,
     {&cli_spec_lut}},
    {"kernel", sss_cmd_kernel, "print the taps of a separable kernel (Jimenez et al. 2019)", 1, {&cli_spec_kernel}},
    {"compare", sss_cmd_compare, "compare two images: DSSIM, PSNR, RMSE, and a DSSIM map", 1, {&cli_spec_compare}},
    {"mesh", sss_cmd_mesh, "inspect or simplify a mesh (mesh info, mesh simplify)", 1,
     {&cli_spec_mesh_info, &cli_spec_mesh_simplify, &cli_spec_mesh_convert}},
    {"reference", sss_cmd_reference, "render a scene's CPU ground truth (the subsurface integral)", 1,
     {&cli_spec_reference}},
    {"render", sss_cmd_render, "render a scene in real time with OpenGL (headless) to an image", 1, {&cli_spec_render}},
    {"techniques", sss_cmd_techniques, "list the real-time techniques", 1, {&cli_spec_techniques}},
    {"version", cmd_version, "print the library's version (also 'sss --version')", 1, {&cli_spec_version}},
    {"eval", sss_cmd_eval, "evaluate techniques against the reference: metrics, timings, sheets, plots, report", 1,
     {&cli_spec_eval}},
    {"view", sss_cmd_view, "show a scene in a window: orbit camera, techniques, DSSIM vs reference", 0, {&cli_spec_view}},
    {"export", sss_cmd_export, "write a scene for another renderer or format (export pbrt, export gltf)", 1,
     {&cli_spec_export_pbrt, &cli_spec_export_gltf}},
    {"import", sss_cmd_import, "import a glTF 2.0 asset (.gltf, .glb) as a scene", 1, {&cli_spec_import}},
    {"sam", sss_cmd_sam, "build or inspect a Spatial Adjacency Map (Maisch & Ropinski 2017) of a mesh", 1,
     {&cli_spec_sam_build, &cli_spec_sam_info}},
    {"completion", sss_cmd_completion, "print a shell completion script (completion bash)", 0, {&cli_spec_completion}},
};
#define COMMAND_COUNT (sizeof commands / sizeof commands[0])

const cli_command_entry *cli_commands(int *count)
{
    *count = (int)COMMAND_COUNT;
    return commands;
}

/* "unknown command" with the closest command's name when one is close; returns whether there was one. */
static int unknown_command(const char *name)
{
    const char *names[COMMAND_COUNT + 1];
    for (size_t i = 0; i < COMMAND_COUNT; i++) names[i] = commands[i].name;
    names[COMMAND_COUNT] = "help";
    const char *s = cli_suggest(name, names, (int)COMMAND_COUNT + 1);
    if (s) cli_message(NULL, "unknown command '%s'; did you mean '%s'?", name, s);
    else cli_message(NULL, "unknown command '%s'", name);
    return s != NULL;
}

static void print_help(FILE *f)
{
    fprintf(f, "usage: sss COMMAND [OPTIONS]\n\n"
               "Subsurface scattering: physics, kernels, images and meshes.\n\ncommands:\n");
    for (size_t i = 0; i < COMMAND_COUNT; i++)
        fprintf(f, "  %-10s %s\n", commands[i].name, commands[i].summary);
    fprintf(f, "  %-10s %s\n", "help", "this text, or 'sss help COMMAND' for one command");
    fprintf(f, "\nRun 'sss COMMAND --help' for a command's options.\n");
}

const cli_command_entry *cli_find_command(const char *name)
{
    for (size_t i = 0; i < COMMAND_COUNT; i++)
        if (strcmp(commands[i].name, name) == 0) return &commands[i];
    return NULL;
}

/* A command's --help (anywhere before "--"), else the command: its outputs staged when it is (all or
 * none are written). */
static int run_command(const cli_command_entry *c, int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) {
        cli_print_help(stdout, c);
        return CLI_EXIT_OK;
    }
    if (!c->staged) return c->run(argc, argv); /* view writes screenshots while it runs: each on its own */
    sss_outputs outputs;
    sss_outputs_begin(&outputs);
    int status = c->run(argc, argv);
    sss_error err = {0};
    if (sss_outputs_end(&outputs, status == CLI_EXIT_OK, &err) != SSS_OK) status = cli_fail(c->name, &err);
    return status;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        print_help(stderr);
        return CLI_EXIT_USAGE;
    }
    const char *name = argv[1];
    if (strcmp(name, "help") == 0 || strcmp(name, "--help") == 0 || strcmp(name, "-h") == 0) {
        if (argc >= 3 && strcmp(name, "help") == 0) {
            const cli_command_entry *c = cli_find_command(argv[2]);
            if (!c) {
                unknown_command(argv[2]);
                return CLI_EXIT_USAGE;
            }
            cli_print_help(stdout, c);
            return CLI_EXIT_OK;
        }
        print_help(stdout);
        return CLI_EXIT_OK;
    }
    const cli_command_entry *c = cli_find_command(strcmp(name, "--version") == 0 ? "version" : name);
    if (!c) {
        if (!unknown_command(name)) print_help(stderr);
        return CLI_EXIT_USAGE;
    }
    return run_command(c, argc - 1, argv + 1);
}
