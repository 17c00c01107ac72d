/* scene/scene_internal.h — the parts of the scene loader shared between its files (internal). */
#ifndef SSS_SCENE_INTERNAL_H
#define SSS_SCENE_INTERNAL_H

#include <cjson/cJSON.h>

#include "scene/json_reader.h"
#include "sss/scene.h"

#define SCENE_COUNT(a) (sizeof(a) / sizeof((a)[0]))

/* What the parsers need besides the JSON: where relative paths start and the load flags. */
typedef struct scene_ctx {
    jr r;
    const char *base_dir;
    unsigned flags;
    sss_mesh *given_meshes; /* objects[i]'s mesh when i < given_count (taken over), else read or built */
    size_t given_count;
    sss_scene_texture *given_textures; /* decoded images standing in for texture files (path relative
                                        * to base_dir as the scene text names it); taken over when used */
    size_t given_texture_count;
    int given_lent; /* the given meshes and textures are checked, then left with their owner */
    /* load phase: per object, the first object with the same texture file; the given textures' resolved
     * paths, sorted (both found once by sorting, not by comparing every pair) */
    size_t *texture_owner;
    struct scene_path_index *given_by_path;
    size_t given_by_path_count;
} scene_ctx;

/* What an imported asset hands the loader in memory instead of files. */
typedef struct scene_given {
    sss_mesh *meshes; /* meshes[i] is objects[i]'s mesh */
    size_t mesh_count;
    sss_scene_texture *textures;
    size_t texture_count;
    int lent; /* nonzero: only lent, to be checked as taken ones are; they stay with the caller and the
               * scene holds none of them (a check before writing an imported scene) */
} scene_given;

char *scene_strdup(const char *s);
/* The folder of a file's path ("." for a bare name, "/" at the root), malloc'd; NULL out of memory. */
char *scene_folder_of(const char *path);
/* sss_scene_parse with meshes and textures already in memory (an imported glTF asset): given->meshes[i]
 * is taken over as objects[i]'s mesh instead of reading its "mesh" file, a given texture is taken over
 * by the materials naming its path instead of decoding a file; both go through the same checks. Whatever
 * is not taken stays with the caller. given may be NULL. */
sss_result scene_parse_given(const char *json_text, size_t size, const char *base_dir, const char *name,
                             const sss_scene_load_desc *desc, scene_given *given, sss_scene *scene, sss_error *err);

/* Reads the string field `key` of obj as a file path: resolved against base_dir (absolute paths are
 * kept) into *out (malloc'd); unless SSS_SCENE_SKIP_FILE_CHECKS, the file must be a readable regular
 * file ("<name>: <path>.<key>: <as written>: cannot open: <reason>"). Absent and not required:
 * *out = NULL. */
sss_result scene_file_field(scene_ctx *c, const cJSON *obj, const char *key, int required, char **out);

/* Parsers of one JSON value at the current path (c->r.path) into an element that the caller zeroed. */
sss_result scene_parse_material(scene_ctx *c, const cJSON *item, sss_scene_material *m);
sss_result scene_parse_light(scene_ctx *c, const cJSON *item, sss_light *l);
sss_result scene_parse_object(scene_ctx *c, const cJSON *item, sss_scene_object *o);

/* Resolves a parsed subsurface/diffuse material's coefficients (table must match its eta and g for
 * subsurface materials; NULL for diffuse). */
sss_result scene_resolve_material(scene_ctx *c, sss_scene_material *m, const sss_pbd_table *table);

/* sss_scene_load of a .gltf or .glb: imported with sss_gltf_load's defaults, meshes kept in memory. */
sss_result scene_load_gltf(const char *path, const sss_scene_load_desc *desc, sss_scene *scene, sss_error *err);

void scene_material_free(sss_scene_material *m);
void scene_object_free(sss_scene_object *o);
void scene_light_free(sss_light *l);

#endif
