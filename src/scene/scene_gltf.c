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
        /* the meshes are in memory: they stand in for the "mesh" files the scene text names, and go
         * through the loader's checks (bounds, world reach, texture UVs) like meshes read from files */
        sss_scene_load_desc inner = {(desc ? desc->flags : 0) | SSS_SCENE_SKIP_FILE_CHECKS};
        char *dir = scene_folder_of(path);
        sss_mesh *meshes = calloc(g.object_count ? g.object_count : 1, sizeof *meshes);
        if (!dir || !meshes) res = sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
        for (size_t i = 0; res == SSS_OK && i < g.object_count; i++) {
            meshes[i] = g.objects[i].mesh;
            memset(&g.objects[i].mesh, 0, sizeof g.objects[i].mesh);
        }
        if (res == SSS_OK)
            res = scene_parse_given_meshes(json, strlen(json), dir, path, &inner, meshes, g.object_count, scene, err);
        for (size_t i = 0; meshes && i < g.object_count; i++) sss_mesh_free(&meshes[i]); /* the ones not taken */
        free(meshes);
        free(dir);
    }
    free(json);
    sss_gltf_scene_free(&g);
    return res;
}
