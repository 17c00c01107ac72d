/* sss — command-line front end of the sss library (git-style subcommands). */
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"

typedef struct command {
    const char *name;
    int (*run)(int argc, char **argv);
    const char *summary;
} command;

static const command commands[] = {
    {"profile", sss_cmd_profile, "print the diffusion profile S_r(r) of a medium as TSV"},
    {"lut", sss_cmd_lut, "build the disc-integrated kernel LUT of seed 000 and write it as EXR"},
    {"kernel", sss_cmd_kernel, "print the taps of a separable kernel (seed 002)"},
    {"compare", sss_cmd_compare, "compare two images: DSSIM, PSNR, RMSE, and a DSSIM map"},
    {"mesh", sss_cmd_mesh, "inspect or simplify a mesh (mesh info, mesh simplify)"},
    {"reference", sss_cmd_reference, "render a scene's CPU ground truth (the subsurface integral)"},
    {"render", sss_cmd_render, "render a scene in real time with OpenGL (headless) to an image"},
    {"techniques", sss_cmd_techniques, "list the real-time techniques"},
    {"eval", sss_cmd_eval, "evaluate techniques against the reference: metrics, timings, sheets, plots, report"},
    {"view", sss_cmd_view, "show a scene in a window: orbit camera, techniques, DSSIM vs reference"},
    {"export", sss_cmd_export, "write a scene for another renderer or format (export pbrt, export gltf)"},
    {"import", sss_cmd_import, "import a glTF 2.0 asset (.gltf, .glb) as a scene"},
    {"sam", sss_cmd_sam, "build or inspect a Spatial Adjacency Map (seed 001) of a mesh"},
};
#define COMMAND_COUNT (sizeof commands / sizeof commands[0])

static void print_help(FILE *f)
{
    fprintf(f, "usage: sss COMMAND [OPTIONS]\n\n"
               "Subsurface scattering: physics, kernels, images and meshes.\n\ncommands:\n");
    for (size_t i = 0; i < COMMAND_COUNT; i++)
        fprintf(f, "  %-10s %s\n", commands[i].name, commands[i].summary);
    fprintf(f, "  %-10s %s\n", "help", "this text, or 'sss help COMMAND' for one command");
    fprintf(f, "\nRun 'sss COMMAND --help' for a command's options.\n");
}

static const command *find_command(const char *name)
{
    for (size_t i = 0; i < COMMAND_COUNT; i++)
        if (strcmp(commands[i].name, name) == 0) return &commands[i];
    return NULL;
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
            const command *c = find_command(argv[2]);
            if (!c) {
                fprintf(stderr, "sss: unknown command '%s'\n", argv[2]);
                return CLI_EXIT_USAGE;
            }
            char help[] = "--help";
            char *sub[] = {argv[2], help, NULL};
            return c->run(2, sub);
        }
        print_help(stdout);
        return CLI_EXIT_OK;
    }
    if (strcmp(name, "--version") == 0) {
        printf("sss 0.1.0\n");
        return CLI_EXIT_OK;
    }
    const command *c = find_command(name);
    if (!c) {
        fprintf(stderr, "sss: unknown command '%s'\n", name);
        print_help(stderr);
        return CLI_EXIT_USAGE;
    }
    return c->run(argc - 1, argv + 1);
}
