/* sss export pbrt SCENE.json -o OUT.pbrt [--time T] [--width W] [--height H] [--spp N] [--maxdepth N]
 * sss export gltf SCENE.json -o OUT.glb [--time T] [--width W] [--height H] [--scatter-extension E] */
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"
#include "sss/export.h"

static const char *const cmd = "export";

enum { OPT_OUTPUT, OPT_TIME, OPT_WIDTH, OPT_HEIGHT, OPT_SPP, OPT_MAXDEPTH, OPT_SCATTER_EXTENSION };
#define EXPORT_OPTIONS(what)                                                                                         \
    {OPT_OUTPUT, "--output", "-o", CLI_ARG_FILE, "FILE", "the " what " file to write", NULL, CLI_REQUIRED},         \
        {OPT_TIME, "--time", NULL, CLI_ARG_NUMBER, "T", "pose of animated objects, seconds", NULL, "0"},             \
        {OPT_WIDTH, "--width", NULL, CLI_ARG_NUMBER, "W", "image width of the exported camera", NULL, "the scene's"}, \
        {OPT_HEIGHT, "--height", NULL, CLI_ARG_NUMBER, "H", "image height", NULL, "the scene's"}
static const cli_option pbrt_options[] = {
    EXPORT_OPTIONS(".pbrt"),
    {OPT_SPP, "--spp", NULL, CLI_ARG_NUMBER, "N", "PBRT's pixel samples", NULL, "256"},
    {OPT_MAXDEPTH, "--maxdepth", NULL, CLI_ARG_NUMBER, "N",
     "the path integrator's maxdepth, 1.." CLI_STR(SSS_EXPORT_PBRT_MAXDEPTH_MAX), NULL, "16"},
};
static const cli_option gltf_options[] = {
    EXPORT_OPTIONS(".glb"),
    {OPT_SCATTER_EXTENSION, "--scatter-extension", NULL, CLI_ARG_TEXT, "E",
     "the extension carrying subsurface scattering: volume_scatter (KHR_materials_volume_scatter +\n"
     "KHR_materials_diffuse_transmission) or scatter (the draft KHR_materials_scatter, which replaces\n"
     "both, + KHR_materials_transmission)",
     "volume_scatter scatter", "volume_scatter"},
};
const cli_command_spec cli_spec_export_pbrt = {
    "export pbrt", pbrt_options, CLI_COUNT(pbrt_options), CLI_ARG_FILE, "pbrt gltf", "SCENE.json",
    "Writes the scene for PBRT-v3: OUT.pbrt plus one binary PLY per object beside it\n"
    "(OUT_objN.ply, world space, posed at --time). Materials map to PBRT's subsurface\n"
    "(measured media and coefficients), kdsubsurface (reflectance + mfp) and matte;\n"
    "lights to point, spot, distant, diffuse area (two triangles) and infinite.\n"
    "The integrator is path with maxdepth 16, the full transport that `sss reference` computes\n"
    "by default. PBRT counts one depth per surface hit (a subsurface hit with its probe, direct\n"
    "light and exit is one): --maxdepth 1 is the single-event integral of `sss reference\n"
    "--bounces 1`, maxdepth N holds the N-event paths of --bounces N, less the mirror reflections\n"
    "off subsurface interfaces that the reference folds into each bounce (PBRT spends a depth on\n"
    "each). Render it with `pbrt OUT.pbrt`.\n",
    NULL, NULL};
const cli_command_spec cli_spec_export_gltf = {
    "export gltf", gltf_options, CLI_COUNT(gltf_options), CLI_ARG_FILE, NULL, "SCENE.json",
    "gltf writes one binary glTF 2.0 file (docs/gltf.md): world-space meshes, subsurface materials\n"
    "as KHR_materials_volume + KHR_materials_volume_scatter (+ ior, diffuse transmission) or, with\n"
    "--scatter-extension scatter, KHR_materials_scatter (+ ior, transmission), the camera and\n"
    "KHR_lights_punctual lights; `sss import` reads it back.\n"
    "--width and --height set the exported camera's image size (pbrt: the film; gltf: the aspect ratio).\n",
    NULL, NULL};

typedef struct export_options {
    int gltf;
    const char *scene_path, *out;
    sss_export_pbrt_desc desc;
    sss_export_gltf_scatter scatter_extension;
    int width, height;
    cli_common common;
} export_options;

static int set_option(void *opts, int id, const char *a, const char *v)
{
    export_options *o = opts;
    switch (id) {
    case OPT_OUTPUT: o->out = v; break;
    case OPT_TIME:
        if (!cli_parse_double(cmd, "--time", v, &o->desc.time)) return CLI_EXIT_USAGE;
        break;
    case OPT_WIDTH:
    case OPT_HEIGHT:
        if (!cli_parse_size(cmd, a, v, id == OPT_WIDTH ? &o->width : &o->height)) return CLI_EXIT_USAGE;
        break;
    case OPT_SPP:
        if (!cli_parse_int(cmd, "--spp", v, &o->desc.pixel_samples)) return CLI_EXIT_USAGE;
        if (o->desc.pixel_samples < 1) return cli_usage_error(cmd, "--spp must be at least 1");
        break;
    case OPT_MAXDEPTH:
        if (!cli_parse_int(cmd, "--maxdepth", v, &o->desc.maxdepth)) return CLI_EXIT_USAGE;
        if (o->desc.maxdepth < 1 || o->desc.maxdepth > SSS_EXPORT_PBRT_MAXDEPTH_MAX)
            return cli_usage_error(cmd, "--maxdepth must be in 1..%d, got %d", SSS_EXPORT_PBRT_MAXDEPTH_MAX,
                                   o->desc.maxdepth);
        break;
    case OPT_SCATTER_EXTENSION: {
        const char *names[] = {"volume_scatter", "scatter"};
        if (strcmp(v, names[0]) != 0 && strcmp(v, names[1]) != 0)
            return cli_unknown(cmd, "scatter extension", v, names, 2);
        o->scatter_extension = strcmp(v, names[1]) == 0 ? SSS_EXPORT_GLTF_SCATTER : SSS_EXPORT_GLTF_VOLUME_SCATTER;
        break;
    }
    default: /* CLI_OPERAND */
        if (o->scene_path) return cli_usage_error(cmd, "unexpected argument '%s'", v);
        o->scene_path = v;
    }
    return CLI_EXIT_OK;
}

/* argv[1] is the format (pbrt, gltf), its options follow. */
static int export_parse(int argc, char **argv, export_options *o)
{
    memset(o, 0, sizeof *o);
    if (argc < 2) return cli_usage_error(cmd, "missing the format (pbrt or gltf)");
    o->gltf = strcmp(argv[1], "gltf") == 0;
    if (!o->gltf && strcmp(argv[1], "pbrt") != 0) {
        const char *formats[] = {"pbrt", "gltf"};
        return cli_unknown(cmd, "format", argv[1], formats, 2);
    }
    const cli_command_spec *spec = o->gltf ? &cli_spec_export_gltf : &cli_spec_export_pbrt;
    int status = cli_parse(spec, argc, argv, 2, set_option, o, &o->common);
    if (status != CLI_EXIT_OK) return status;
    if (!o->scene_path) return cli_usage_error(cmd, "missing the scene file");
    if (!o->out) return cli_usage_error(cmd, o->gltf ? "missing -o OUT.glb" : "missing -o OUT.pbrt");
    return CLI_EXIT_OK;
}

static int export_run(const export_options *o)
{
    sss_scene scene = {0};
    sss_error err = {0};
    if (sss_scene_load(o->scene_path, NULL, &scene, &err) != SSS_OK) return cli_fail(cmd, &err);
    if (cli_scene_resize(cmd, &scene, o->width, o->height) != CLI_EXIT_OK ||
        cli_check_outputs(cmd, &o->out, 1, NULL, 0, &scene) != CLI_EXIT_OK) {
        sss_scene_free(&scene);
        return CLI_EXIT_ERROR;
    }
    sss_export_gltf_desc gltf_desc = {.time = o->desc.time, .scatter_extension = o->scatter_extension};
    sss_result res = o->gltf ? sss_export_gltf(&scene, &gltf_desc, o->out, &err)
                             : sss_export_pbrt(&scene, &o->desc, o->out, &err);
    sss_scene_free(&scene);
    if (res != SSS_OK) return cli_fail(cmd, &err);
    if (gltf_desc.skipped_lights && !o->common.quiet)
        fprintf(stderr, "sss export: warning: %d area/environment light(s) left out (glTF has no such lights)\n",
                gltf_desc.skipped_lights);
    printf("wrote %s\n", o->out);
    return CLI_EXIT_OK;
}

int sss_cmd_export(int argc, char **argv)
{
    export_options o;
    int status = export_parse(argc, argv, &o);
    return status == CLI_EXIT_OK ? export_run(&o) : status;
}
