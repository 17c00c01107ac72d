/* A .gltf or .glb given where a scene is expected: imported (sss/gltf.h) into our scene JSON, parsed
 * by the scene loader without reading meshes, then given the imported world-space meshes and the
 * decoded embedded images. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/scene_internal.h"
#include "sss/gltf.h"

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

/* The asset's meshes and decoded images handed to the loader (taken over; the rest freed by the caller). */
static sss_result load_given(const char *path, sss_gltf_scene *g, const char *json, char **images,
                             const sss_scene_load_desc *desc, sss_scene *scene, sss_error *err)
{
    /* the meshes stand in for the "mesh" files the scene text names, and go through the loader's
     * checks (bounds, world reach, texture UVs) like meshes read from files */
    sss_scene_load_desc inner = {(desc ? desc->flags : 0) | SSS_SCENE_SKIP_FILE_CHECKS};
    char *dir = scene_folder_of(path);
    scene_given given = {calloc(g->object_count ? g->object_count : 1, sizeof(sss_mesh)), g->object_count,
                         calloc(g->image_count ? g->image_count : 1, sizeof(sss_scene_texture)), g->image_count};
    sss_result res = SSS_OK;
    if (!dir || !given.meshes || !given.textures)
        res = sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    for (size_t i = 0; res == SSS_OK && i < g->object_count; i++) {
        given.meshes[i] = g->objects[i].mesh;
        memset(&g->objects[i].mesh, 0, sizeof g->objects[i].mesh);
    }
    for (size_t k = 0; res == SSS_OK && k < g->image_count; k++) {
        given.textures[k].path = images[k] ? images[k] : "";
        given.textures[k].image = g->images[k];
        memset(&g->images[k], 0, sizeof g->images[k]);
    }
    if (res == SSS_OK) res = scene_parse_given(json, strlen(json), dir, path, &inner, &given, scene, err);
    for (size_t i = 0; given.meshes && i < g->object_count; i++) sss_mesh_free(&given.meshes[i]); /* not taken */
    for (size_t k = 0; given.textures && k < g->image_count; k++) sss_image_free(&given.textures[k].image);
    free(given.meshes);
    free(given.textures);
    free(dir);
    return res;
}

sss_result scene_load_gltf(const char *path, const sss_scene_load_desc *desc, sss_scene *scene, sss_error *err)
{
    sss_gltf_scene g;
    sss_result res = sss_gltf_load(path, NULL, &g, err);
    if (res != SSS_OK) return res;
    const char *slash = strrchr(path, '/');
    const char *asset_name = slash ? slash + 1 : path;
    char **meshes = mesh_names(asset_name, &g), **images = image_names(asset_name, &g), *json = NULL;
    if (!meshes || !images) res = sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    if (res == SSS_OK)
        res = sss_gltf_scene_json(&g, (const char *const *)meshes, (const char *const *)images, &json, err);
    if (res == SSS_OK) res = load_given(path, &g, json, images, desc, scene, err);
    if (res == SSS_OK) { /* the asset's files are the scene's inputs (an output must not replace them) */
        scene->files = g.files;
        scene->file_count = g.file_count;
        g.files = NULL;
        g.file_count = 0;
    }
    free(json);
    free_names(meshes, g.object_count);
    free_names(images, g.image_count);
    sss_gltf_scene_free(&g);
    return res;
}
