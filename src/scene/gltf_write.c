/* sss_gltf_write_scene: an imported glTF scene on disk as a scene file and binary PLY meshes. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/file_util.h"
#include "scene/gltf_internal.h"

#define GLTF_PATH_CAP 4096

/* "<dir>/<stem>_<kind><i>.<ext>" for scene_path "<dir>/<stem>.json"; *name points at the file name. */
static int side_file(const char *scene_path, const char *kind, size_t i, const char *ext, char *path,
                     const char **name)
{
    const char *slash = strrchr(scene_path, '/');
    const char *base = slash ? slash + 1 : scene_path;
    const char *dot = strrchr(base, '.');
    size_t stem = dot && dot > base ? (size_t)(dot - scene_path) : strlen(scene_path);
    int n = snprintf(path, GLTF_PATH_CAP, "%.*s_%s%zu.%s", (int)stem, scene_path, kind, i, ext);
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

/* Every file the write reads (the asset's) and writes (paths[i] where names[i] is set, and the scene),
 * checked against each other before anything is written. */
static sss_result check_files(const sss_gltf_scene *scene, const char *scene_path, char (*paths)[GLTF_PATH_CAP],
                              const char **names, size_t files, sss_error *err)
{
    sss_io_set io = {0};
    for (size_t i = 0; i < scene->file_count; i++) sss_io_add_input(&io, scene->files[i]);
    sss_io_add_output(&io, scene_path);
    for (size_t i = 0; i < files; i++)
        if (names[i]) sss_io_add_output(&io, paths[i]);
    sss_result res = sss_io_check(&io, err);
    sss_io_free(&io);
    return res;
}

/* The side files' paths (names[i] NULL for an image that is not written). */
static sss_result side_files(const sss_gltf_scene *scene, const char *scene_path, char (*paths)[GLTF_PATH_CAP],
                             const char **names, sss_error *err)
{
    size_t n = scene->object_count;
    for (size_t i = 0; i < n + scene->image_count; i++) {
        int image = i >= n;
        if (image && !scene->images[i - n].pixels) continue; /* not embedded, or no material uses it */
        if (!side_file(scene_path, image ? "img" : "obj", image ? i - n : i, image ? "png" : "ply", paths[i], &names[i]))
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "%s: path too long", scene_path);
    }
    return SSS_OK;
}

sss_result sss_gltf_write_scene(const sss_gltf_scene *scene, const char *scene_path, sss_error *err)
{
    size_t n = scene->object_count, files = n + scene->image_count;
    char (*paths)[GLTF_PATH_CAP] = calloc(files ? files : 1, GLTF_PATH_CAP);
    const char **names = calloc(files ? files : 1, sizeof *names);
    sss_result res = paths && names ? SSS_OK : sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory", scene_path);
    if (res == SSS_OK) res = side_files(scene, scene_path, paths, names, err);
    if (res == SSS_OK) res = check_files(scene, scene_path, paths, names, files, err);
    sss_outputs t;
    sss_outputs_begin(&t); /* all or none: a failure removes the files written so far */
    t.create_folders = 1;  /* and the folders made for them (`sss import a.glb -o new/scene.json`) */
    for (size_t i = 0; res == SSS_OK && i < files; i++) {
        if (!names[i]) continue;
        if (i >= n) /* 8-bit sources: writing the decoded pixels at exposure 0 gives back their exact codes */
            res = sss_image_write(paths[i], &scene->images[i - n], 0.0, err);
        else
            res = sss_mesh_write_ply(paths[i], &scene->objects[i].mesh, err);
    }
    char *json = NULL;
    if (res == SSS_OK) res = sss_gltf_scene_json(scene, names, names + n, &json, err);
    if (res == SSS_OK) res = write_json(json, scene_path, err);
    sss_result end = sss_outputs_end(&t, res == SSS_OK, err);
    free(json);
    free(names);
    free(paths);
    return res == SSS_OK ? end : res;
}
