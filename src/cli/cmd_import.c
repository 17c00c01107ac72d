/* sss import ASSET.gltf|ASSET.glb -o SCENE.json [--width W] [--height H] [--camera N] [--light-scale S] */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "sss/gltf.h"

static const char *const cmd = "import";

enum { OPT_OUTPUT, OPT_WIDTH, OPT_HEIGHT, OPT_CAMERA, OPT_LIGHT_SCALE };
static const cli_option options[] = {
    {OPT_OUTPUT, "--output", "-o", CLI_ARG_FILE, "FILE", "the scene file to write", NULL, CLI_REQUIRED},
    {OPT_WIDTH, "--width", NULL, CLI_ARG_NUMBER, "W", "image width", NULL, "from the camera's aspect ratio, else 960"},
    {OPT_HEIGHT, "--height", NULL, CLI_ARG_NUMBER, "H", "image height", NULL, "540"},
    {OPT_CAMERA, "--camera", NULL, CLI_ARG_NUMBER, "N", "use cameras[N] (the first node that uses it)", NULL, NULL},
    {OPT_LIGHT_SCALE, "--light-scale", NULL, CLI_ARG_NUMBER, "S", "multiply every light's intensity by S > 0", NULL, "1"},
};
const cli_command_spec cli_spec_import = {
    "import", options, CLI_COUNT(options), CLI_ARG_FILE, NULL, "ASSET.gltf|ASSET.glb",
    "Imports a glTF 2.0 asset as a scene (docs/gltf.md): SCENE.json plus one binary PLY per mesh\n"
    "primitive beside it (SCENE_objN.ply, world space: the node hierarchy is flattened).\n"
    "KHR_materials_volume + KHR_materials_scatter, KHR_materials_volume_scatter or\n"
    "KHR_materials_diffuse_transmission (+ KHR_materials_ior) become subsurface materials (sigma_a,\n"
    "sigma_s, g, eta per world unit), other materials diffuse (baseColor); a warning names what was\n"
    "approximated or left out. Draco, meshopt and quantized meshes are decoded.\n"
    "KHR_lights_punctual point, spot and directional lights keep their intensity (candela as W/sr,\n"
    "lux as irradiance). The camera is the first camera node (or --camera N), else one that frames\n"
    "the scene. render, reference, view and eval also read .gltf/.glb directly.\n",
    NULL, NULL};

typedef struct import_options {
    const char *asset, *out;
    sss_gltf_desc desc;
    cli_common common;
} import_options;

static int set_option(void *opts, int id, const char *a, const char *v)
{
    import_options *o = opts;
    sss_gltf_desc *desc = &o->desc;
    switch (id) {
    case OPT_OUTPUT: o->out = v; break;
    case OPT_WIDTH:
    case OPT_HEIGHT:
        if (!cli_parse_size(cmd, a, v, id == OPT_WIDTH ? &desc->width : &desc->height)) return CLI_EXIT_USAGE;
        break;
    case OPT_CAMERA:
        if (!cli_parse_int(cmd, a, v, &desc->camera)) return CLI_EXIT_USAGE;
        if (desc->camera < 0) return cli_usage_error(cmd, "--camera must be >= 0");
        desc->use_camera = 1;
        break;
    case OPT_LIGHT_SCALE:
        if (!cli_parse_double(cmd, a, v, &desc->light_scale)) return CLI_EXIT_USAGE;
        if (!(desc->light_scale > 0 && desc->light_scale <= SSS_SCENE_MAX_LIGHT_VALUE))
            return cli_usage_error(cmd, "--light-scale must be in (0, %g] (docs/limits.md)", SSS_SCENE_MAX_LIGHT_VALUE);
        break;
    default: /* CLI_OPERAND */
        if (o->asset) return cli_usage_error(cmd, "unexpected argument '%s'", v);
        o->asset = v;
    }
    return CLI_EXIT_OK;
}

static int import_parse(int argc, char **argv, import_options *o)
{
    memset(o, 0, sizeof *o);
    int status = cli_parse(&cli_spec_import, argc, argv, 1, set_option, o, &o->common);
    if (status != CLI_EXIT_OK) return status;
    if (!o->asset) return cli_usage_error(cmd, "missing the glTF asset");
    if (!o->out) return cli_usage_error(cmd, "missing -o SCENE.json");
    return CLI_EXIT_OK;
}

/* What the material mapping approximated or left out, once per material of the asset. */
static void print_notes(const char *asset, const sss_gltf_scene *s)
{
    int top = 0;
    for (size_t i = 0; i < s->object_count; i++)
        if (s->objects[i].material_index > top) top = s->objects[i].material_index;
    unsigned char *said = calloc((size_t)top + 2, 1); /* by material index + 1 (-1: the default material) */
    for (size_t i = 0; i < s->object_count; i++) {
        const sss_gltf_object *o = &s->objects[i];
        if (!o->material.note || (said && said[o->material_index + 1])) continue;
        if (said) said[o->material_index + 1] = 1;
        fprintf(stderr, "sss import: warning: %s: materials[%d]: %s\n", asset, o->material_index, o->material.note);
    }
    free(said);
}

static int import_run(const import_options *o)
{
    sss_gltf_scene scene;
    sss_error err = {0};
    if (sss_gltf_load(o->asset, &o->desc, &scene, &err) != SSS_OK) return cli_fail(cmd, &err);
    if (!o->common.quiet) print_notes(o->asset, &scene);
    /* it refuses an output that is one of the asset's files (or another output) before writing */
    sss_result res = sss_gltf_write_scene(&scene, o->out, &err);
    size_t objects = scene.object_count, lights = scene.light_count;
    int own_camera = scene.camera_from_asset;
    sss_gltf_scene_free(&scene);
    if (res != SSS_OK) return cli_fail(cmd, &err);
    printf("wrote %s: %zu objects, %zu lights, %s camera\n", o->out, objects, lights,
           own_camera ? "the asset's" : "a framing");
    return CLI_EXIT_OK;
}

int sss_cmd_import(int argc, char **argv)
{
    import_options o;
    int status = import_parse(argc, argv, &o);
    return status == CLI_EXIT_OK ? import_run(&o) : status;
}
