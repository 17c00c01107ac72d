/* sss export pbrt SCENE.json -o OUT.pbrt [--time T] [--spp N] [--maxdepth N]
 * sss export gltf SCENE.json -o OUT.glb [--time T] */
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"
#include "sss/export.h"

static const char usage[] =
    "usage: sss export pbrt SCENE.json -o OUT.pbrt [--time T] [--spp N] [--maxdepth N]\n"
    "       sss export gltf SCENE.json -o OUT.glb [--time T]\n"
    "\n"
    "Writes the scene for PBRT-v3: OUT.pbrt plus one binary PLY per object beside it\n"
    "(OUT_objN.ply, world space, posed at --time). Materials map to PBRT's subsurface\n"
    "(measured media and coefficients), kdsubsurface (reflectance + mfp) and matte;\n"
    "lights to point, spot, distant, diffuse area (two triangles) and infinite.\n"
    "The integrator is path with maxdepth 16, the full transport that `sss reference` computes\n"
    "by default. PBRT counts one depth per surface hit (a subsurface hit with its probe, direct\n"
    "light and exit is one): --maxdepth 1 is the single-event integral of `sss reference\n"
    "--bounces 1`, maxdepth N holds the N-event paths of --bounces N, less the mirror reflections\n"
    "off subsurface interfaces that the reference folds into each bounce (PBRT spends a depth on\n"
    "each). Render it with `pbrt OUT.pbrt`.\n"
    "\n"
    "gltf writes one binary glTF 2.0 file (docs/gltf.md): world-space meshes, subsurface materials\n"
    "as KHR_materials_volume + KHR_materials_volume_scatter (+ ior, diffuse transmission), the\n"
    "camera and KHR_lights_punctual lights; `sss import` reads it back.\n"
    "\n"
    "  -o FILE      the .pbrt file to write (required)\n"
    "  --time T     pose of animated objects, seconds (default 0)\n"
    "  --spp N      PBRT's pixel samples (default 256)\n"
    "  --maxdepth N the path integrator's maxdepth, 1..1024 (default 16)\n";

int sss_cmd_export(int argc, char **argv)
{
    const char *cmd = "export";
    if (cli_wants_help(argc, argv)) {
        fputs(usage, stdout);
        return CLI_EXIT_OK;
    }
    if (argc < 2) return cli_usage_error(cmd, "missing the format (pbrt or gltf)");
    int gltf = strcmp(argv[1], "gltf") == 0;
    if (!gltf && strcmp(argv[1], "pbrt") != 0)
        return cli_usage_error(cmd, "unknown format '%s' (known: pbrt, gltf)", argv[1]);

    const char *scene_path = NULL, *out = NULL;
    sss_export_pbrt_desc desc = {0};
    for (int i = 2; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "-o") == 0) {
            if (!(out = cli_option_value(cmd, argc, argv, &i))) return CLI_EXIT_USAGE;
        } else if (strcmp(a, "--time") == 0) {
            const char *v = cli_option_value(cmd, argc, argv, &i);
            if (!v || !cli_parse_double(cmd, "--time", v, &desc.time)) return CLI_EXIT_USAGE;
        } else if (strcmp(a, "--spp") == 0 && !gltf) {
            const char *v = cli_option_value(cmd, argc, argv, &i);
            if (!v || !cli_parse_int(cmd, "--spp", v, &desc.pixel_samples)) return CLI_EXIT_USAGE;
            if (desc.pixel_samples < 1) return cli_usage_error(cmd, "--spp must be at least 1");
        } else if (strcmp(a, "--maxdepth") == 0 && !gltf) {
            const char *v = cli_option_value(cmd, argc, argv, &i);
            if (!v || !cli_parse_int(cmd, "--maxdepth", v, &desc.maxdepth)) return CLI_EXIT_USAGE;
            if (desc.maxdepth < 1 || desc.maxdepth > SSS_EXPORT_PBRT_MAXDEPTH_MAX)
                return cli_usage_error(cmd, "--maxdepth must be in 1..%d, got %d", SSS_EXPORT_PBRT_MAXDEPTH_MAX,
                                       desc.maxdepth);
        } else if (a[0] == '-' && a[1] != '\0') {
            return cli_usage_error(cmd, "unknown option '%s'", a);
        } else if (!scene_path) {
            scene_path = a;
        } else {
            return cli_usage_error(cmd, "unexpected argument '%s'", a);
        }
    }
    if (!scene_path) return cli_usage_error(cmd, "missing the scene file");
    if (!out) return cli_usage_error(cmd, gltf ? "missing -o OUT.glb" : "missing -o OUT.pbrt");

    sss_scene scene = {0};
    sss_error err = {0};
    if (sss_scene_load(scene_path, NULL, &scene, &err) != SSS_OK) return cli_fail(cmd, &err);
    if (cli_check_outputs(cmd, &out, 1, NULL, 0, &scene) != CLI_EXIT_OK) {
        sss_scene_free(&scene);
        return CLI_EXIT_ERROR;
    }
    sss_export_gltf_desc gltf_desc = {.time = desc.time};
    sss_result res = gltf ? sss_export_gltf(&scene, &gltf_desc, out, &err) : sss_export_pbrt(&scene, &desc, out, &err);
    sss_scene_free(&scene);
    if (res != SSS_OK) return cli_fail(cmd, &err);
    if (gltf_desc.skipped_lights)
        fprintf(stderr, "sss export: warning: %d area/environment light(s) left out (glTF has no such lights)\n",
                gltf_desc.skipped_lights);
    printf("wrote %s\n", out);
    return CLI_EXIT_OK;
}
