/* A .gltf or .glb given where a scene is expected: imported (sss/gltf.h) into our scene JSON, parsed
 * by the scene loader without reading meshes, then given the imported world-space meshes. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/scene_internal.h"
#include "sss/gltf.h"

/* The objects' `mesh` in the generated JSON: "<asset file name>#meshes[m].primitives[p]", which
 * resolves against the asset's folder to "<asset path>#..." (a name for messages, never opened). */
static char **mesh_names(const char *asset_name, const sss_gltf_scene *g)
{
    char **names = calloc(g->object_count ? g->object_count : 1, sizeof *names);
    for (size_t i = 0; names && i < g->object_count; i++) {
        const sss_gltf_object *o = &g->objects[i];
        size_t cap = strlen(asset_name) + 64;
        if ((names[i] = malloc(cap)))
            snprintf(names[i], cap, "%s#meshes[%d].primitives[%d]", asset_name, o->mesh_index, o->primitive);
        else {
            for (size_t k = 0; k < i; k++) free(names[k]);
            free(names);
            return NULL;
        }
    }
    return names;
}

static sss_result gltf_scene_text(const char *path, sss_gltf_scene *g, char **json, sss_error *err)
{
    const char *slash = strrchr(path, '/');
    char **names = mesh_names(slash ? slash + 1 : path, g);
    if (!names) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    sss_result res = sss_gltf_scene_json(g, (const char *const *)names, json, err);
    for (size_t i = 0; i < g->object_count; i++) free(names[i]);
    free(names);
    return res;
}

sss_result scene_load_gltf(const char *path, const sss_scene_load_desc *desc, sss_scene *scene, sss_error *err)
{
    sss_gltf_scene g;
    sss_result res = sss_gltf_load(path, NULL, &g, err);
    if (res != SSS_OK) return res;
    char *json = NULL;
    if ((res = gltf_scene_text(path, &g, &json, err)) == SSS_OK) {
        unsigned flags = desc ? desc->flags : 0;
        sss_scene_load_desc inner = {flags | SSS_SCENE_SKIP_MESHES | SSS_SCENE_SKIP_FILE_CHECKS};
        char *dir = scene_folder_of(path);
        if (!dir) res = sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
        if (res == SSS_OK) res = sss_scene_parse(json, strlen(json), dir, path, &inner, scene, err);
        free(dir);
        for (size_t i = 0; res == SSS_OK && i < scene->object_count && !(flags & SSS_SCENE_SKIP_MESHES); i++) {
            sss_scene_object *o = &scene->objects[i];
            o->mesh = g.objects[i].mesh;
            memset(&g.objects[i].mesh, 0, sizeof g.objects[i].mesh);
            sss_mesh_bounds(&o->mesh, o->bounds_min, o->bounds_max);
        }
    }
    free(json);
    sss_gltf_scene_free(&g);
    return res;
}
