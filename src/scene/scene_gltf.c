/* A .gltf or .glb given where a scene is expected: imported (sss/gltf.h) into our scene JSON, parsed
 * by the scene loader without reading meshes, then given the imported world-space meshes and the
 * decoded embedded images. The import itself ends with the same load, the meshes and images only lent
 * (scene_check_gltf), so that a scene `sss import` writes is one every command loads. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/gltf_internal.h"
#include "scene/scene_internal.h"

/* The names standing in for files in the generated JSON: "<asset file name>#meshes[m].primitives[p]"
 * per object, "<asset file name>#images[k]" per decoded embedded image (NULL for the others). They
 * resolve against the asset's folder to "<asset path>#..." (names for messages, never opened). */
static void free_names(char **names, size_t n)
{
    for (size_t i = 0; names && i < n; i++) free(names[i]);
    free(names);
}

static char **mesh_names(const char *asset_name, const sss_gltf_scene *g)
{
    char **names = calloc(g->object_count ? g->object_count : 1, sizeof *names);
    for (size_t i = 0; names && i < g->object_count; i++) {
        const sss_gltf_object *o = &g->objects[i];
        size_t cap = strlen(asset_name) + 64;
        if (!(names[i] = malloc(cap))) {
            free_names(names, i);
            return NULL;
        }
        snprintf(names[i], cap, "%s#meshes[%d].primitives[%d]", asset_name, o->mesh_index, o->primitive);
    }
    return names;
}

static char **image_names(const char *asset_name, const sss_gltf_scene *g)
{
    char **names = calloc(g->image_count ? g->image_count : 1, sizeof *names);
    for (size_t k = 0; names && k < g->image_count; k++) {
        if (!g->images[k].pixels) continue;
        size_t cap = strlen(asset_name) + 32;
        if (!(names[k] = malloc(cap))) {
            free_names(names, k);
            return NULL;
        }
        snprintf(names[k], cap, "%s#images[%zu]", asset_name, k);
    }
    return names;
}

/* The asset's meshes and decoded images handed to the loader with the scene text: taken over (the rest
 * freed by the caller), or only lent (given.lent: checked, then left in g). */
static sss_result load_given(const char *name, const char *dir, sss_gltf_scene *g, const char *json, char **images,
                             unsigned flags, int lend, sss_scene *scene, sss_error *err)
{
    /* the meshes stand in for the "mesh" files the scene text names, and go through the loader's
     * checks (bounds, world reach, texture UVs) like meshes read from files */
    sss_scene_load_desc inner = {flags | SSS_SCENE_SKIP_FILE_CHECKS};
    scene_given given = {calloc(g->object_count ? g->object_count : 1, sizeof(sss_mesh)), g->object_count,
                         calloc(g->image_count ? g->image_count : 1, sizeof(sss_scene_texture)), g->image_count, lend};
    sss_result res = SSS_OK;
    if (!given.meshes || !given.textures) res = sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory", name);
    for (size_t i = 0; res == SSS_OK && i < g->object_count; i++) {
        given.meshes[i] = g->objects[i].mesh;
        if (!lend) memset(&g->objects[i].mesh, 0, sizeof g->objects[i].mesh);
    }
    for (size_t k = 0; res == SSS_OK && k < g->image_count; k++) {
        given.textures[k].path = images[k] ? images[k] : "";
        given.textures[k].image = g->images[k];
        if (!lend) memset(&g->images[k], 0, sizeof g->images[k]);
    }
    if (res == SSS_OK) res = scene_parse_given(json, strlen(json), dir, name, &inner, &given, scene, err);
    for (size_t i = 0; !lend && given.meshes && i < g->object_count; i++)
        sss_mesh_free(&given.meshes[i]); /* not taken */
    for (size_t k = 0; !lend && given.textures && k < g->image_count; k++)
        sss_image_free(&given.textures[k].image);
    free(given.meshes);
    free(given.textures);
    return res;
}

/* The imported asset g (from the file name, in the folder dir) through the scene loader. */
static sss_result gltf_to_scene(const char *name, const char *dir, sss_gltf_scene *g, unsigned flags, int lend,
                                sss_scene *scene, sss_error *err)
{
    const char *slash = strrchr(name, '/');
    const char *asset_name = slash ? slash + 1 : name;
    char **meshes = mesh_names(asset_name, g), **images = image_names(asset_name, g), *json = NULL;
    sss_result res = SSS_OK;
    if (!meshes || !images) res = sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory", name);
    if (res == SSS_OK)
        res = sss_gltf_scene_json(g, (const char *const *)meshes, (const char *const *)images, &json, err);
    if (res == SSS_OK) res = load_given(name, dir, g, json, images, flags, lend, scene, err);
    free(json);
    free_names(meshes, g->object_count);
    free_names(images, g->image_count);
    return res;
}

sss_result scene_check_gltf(const char *name, const char *dir, sss_gltf_scene *g, sss_error *err)
{
    sss_scene scene;
    sss_result res = gltf_to_scene(name, dir, g, 0, 1, &scene, err);
    if (res == SSS_OK) sss_scene_free(&scene);
    return res;
}

sss_result scene_load_gltf(const char *path, const sss_scene_load_desc *desc, sss_scene *scene, sss_error *err)
{
    sss_gltf_scene g;
    /* unchecked: the load below makes the same checks */
    sss_result res = gltf_load(path, NULL, 0, &g, err);
    if (res != SSS_OK) return res;
    char *dir = scene_folder_of(path);
    if (!dir) res = sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    if (res == SSS_OK) res = gltf_to_scene(path, dir, &g, desc ? desc->flags : 0, 0, scene, err);
    if (res == SSS_OK) { /* the asset's files are the scene's inputs (an output must not replace them) */
        scene->files = g.files;
        scene->file_count = g.file_count;
        g.files = NULL;
        g.file_count = 0;
    }
    free(dir);
    sss_gltf_scene_free(&g);
    return res;
}
