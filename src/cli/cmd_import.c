/* sss import ASSET.gltf|ASSET.glb -o SCENE.json [--width W] [--height H] [--camera N] [--light-scale S] */
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"
#include "sss/gltf.h"

static const char usage[] =
    "usage: sss import ASSET.gltf|ASSET.glb -o SCENE.json [--width W] [--height H] [--camera N]\n"
    "                  [--light-scale S]\n"
    "\n"
    "Imports a glTF 2.0 asset as a scene (docs/gltf.md): SCENE.json plus one binary PLY per mesh\n"
    "primitive beside it (SCENE_objN.ply, world space: the node hierarchy is flattened).\n"
    "KHR_materials_volume + KHR_materials_volume_scatter (+ KHR_materials_ior) become subsurface\n"
    "materials (sigma_a, sigma_s, g, eta per world unit), other materials diffuse (baseColor);\n"
    "KHR_lights_punctual point, spot and directional lights keep their intensity (candela as W/sr,\n"
    "lux as irradiance). The camera is the first camera node (or --camera N), else one that frames\n"
    "the scene. render, reference, view and eval also read .gltf/.glb directly.\n"
    "\n"
    "  -o FILE          the scene file to write (required)\n"
    "  --width W        image width (default: from the camera's aspect ratio, else 960)\n"
    "  --height H       image height (default: 540)\n"
    "  --camera N       use cameras[N] (the first node that uses it)\n"
    "  --light-scale S  multiply every light's intensity by S > 0 (default 1)\n";

static int parse_size(const char *cmd, const char *option, const char *v, int *out)
{
    if (!cli_parse_int(cmd, option, v, out)) return 0;
    if (*out < 1 || *out > SSS_SCENE_MAX_IMAGE_SIZE) {
        cli_usage_error(cmd, "%s must be in 1..%d", option, SSS_SCENE_MAX_IMAGE_SIZE);
        return 0;
    }
    return 1;
}

int sss_cmd_import(int argc, char **argv)
{
    const char *cmd = "import";
    if (cli_wants_help(argc, argv)) {
        fputs(usage, stdout);
        return CLI_EXIT_OK;
    }
    const char *asset = NULL, *out = NULL;
    sss_gltf_desc desc = {0};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = NULL;
        if (strcmp(a, "-o") == 0) {
            if (!(out = cli_option_value(cmd, argc, argv, &i))) return CLI_EXIT_USAGE;
        } else if (strcmp(a, "--width") == 0 || strcmp(a, "--height") == 0) {
            if (!(v = cli_option_value(cmd, argc, argv, &i)) ||
                !parse_size(cmd, a, v, a[2] == 'w' ? &desc.width : &desc.height))
                return CLI_EXIT_USAGE;
        } else if (strcmp(a, "--camera") == 0) {
            if (!(v = cli_option_value(cmd, argc, argv, &i)) || !cli_parse_int(cmd, a, v, &desc.camera))
                return CLI_EXIT_USAGE;
            if (desc.camera < 0) return cli_usage_error(cmd, "--camera must be >= 0");
            desc.use_camera = 1;
        } else if (strcmp(a, "--light-scale") == 0) {
            if (!(v = cli_option_value(cmd, argc, argv, &i)) || !cli_parse_double(cmd, a, v, &desc.light_scale))
                return CLI_EXIT_USAGE;
            if (!(desc.light_scale > 0)) return cli_usage_error(cmd, "--light-scale must be > 0");
        } else if (a[0] == '-' && a[1] != '\0') {
            return cli_usage_error(cmd, "unknown option '%s'", a);
        } else if (!asset) {
            asset = a;
        } else {
            return cli_usage_error(cmd, "unexpected argument '%s'", a);
        }
    }
    if (!asset) return cli_usage_error(cmd, "missing the glTF asset");
    if (!out) return cli_usage_error(cmd, "missing -o SCENE.json");

    if (cli_check_outputs(cmd, &out, 1, &asset, 1, NULL) != CLI_EXIT_OK) return CLI_EXIT_ERROR;
    sss_gltf_scene scene;
    sss_error err = {0};
    if (sss_gltf_load(asset, &desc, &scene, &err) != SSS_OK) return cli_fail(cmd, &err);
    sss_result res = sss_gltf_write_scene(&scene, out, &err);
    size_t objects = scene.object_count, lights = scene.light_count;
    int own_camera = scene.camera_from_asset;
    sss_gltf_scene_free(&scene);
    if (res != SSS_OK) return cli_fail(cmd, &err);
    printf("wrote %s: %zu objects, %zu lights, %s camera\n", out, objects, lights, own_camera ? "the asset's" : "a framing");
    return CLI_EXIT_OK;
}
