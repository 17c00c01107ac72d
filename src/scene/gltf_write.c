/* sss_gltf_write_scene: an imported glTF scene on disk as a scene file and binary PLY meshes. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/file_util.h"
#include "scene/gltf_internal.h"

#define GLTF_PATH_CAP 4096

/* "<dir>/<stem>_obj<i>.ply" for scene_path "<dir>/<stem>.json"; *name points at the file name. */
static int mesh_file(const char *scene_path, size_t i, char *path, const char **name)
{
    const char *slash = strrchr(scene_path, '/');
    const char *base = slash ? slash + 1 : scene_path;
    const char *dot = strrchr(base, '.');
    size_t stem = dot && dot > base ? (size_t)(dot - scene_path) : strlen(scene_path);
    int n = snprintf(path, GLTF_PATH_CAP, "%.*s_obj%zu.ply", (int)stem, scene_path, i);
    *name = path + (base - scene_path);
    return n > 0 && n < GLTF_PATH_CAP;
}

static sss_result write_json(const char *json, const char *scene_path, sss_error *err)
{
    char tmp[GLTF_PATH_CAP];
    FILE *f = sss_atomic_open(scene_path, tmp, sizeof tmp, err);
    if (!f) return err ? err->code : SSS_ERROR_IO;
    fputs(json, f);
    fputc('\n', f);
    return sss_atomic_close(f, tmp, scene_path, err);
}

sss_result sss_gltf_write_scene(const sss_gltf_scene *scene, const char *scene_path, sss_error *err)
{
    size_t n = scene->object_count;
    char (*paths)[GLTF_PATH_CAP] = calloc(n ? n : 1, GLTF_PATH_CAP);
    const char **names = calloc(n ? n : 1, sizeof *names);
    sss_result res = paths && names ? SSS_OK : sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory", scene_path);
    size_t written = 0;
    for (size_t i = 0; res == SSS_OK && i < n; i++) {
        if (!mesh_file(scene_path, i, paths[i], &names[i]))
            res = sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "%s: path too long", scene_path);
        else if ((res = sss_mesh_write_ply(paths[i], &scene->objects[i].mesh, err)) == SSS_OK)
            written++;
    }
    char *json = NULL;
    if (res == SSS_OK) res = sss_gltf_scene_json(scene, names, &json, err);
    if (res == SSS_OK) res = write_json(json, scene_path, err);
    if (res != SSS_OK)
        for (size_t i = 0; i < written; i++) remove(paths[i]);
    free(json);
    free(names);
    free(paths);
    return res;
}
