/* reference/ref_scene.c — sss_reference_render: a loaded scene (sss/scene.h) posed at a time and
 * handed to the scene-independent renderer. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "reference/ref_internal.h"

sss_result ref_render_scene(const sss_scene *scene, const sss_reference_desc *desc, const ref_source_mask *mask,
                            sss_image *out, sss_reference_progress_fn progress, void *user,
                            sss_reference_stats *stats, sss_error *err)
{
    if (out) memset(out, 0, sizeof *out);
    if (!scene) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "reference: scene is NULL");
    double t = desc ? desc->time : 0.0;
    if (!isfinite(t)) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "reference: time is not finite");
    size_t n = scene->object_count;
    sss_mesh *meshes = calloc(n + 1, sizeof *meshes);
    sss_reference_object *objects = calloc(n + 1, sizeof *objects);
    if (!meshes || !objects) {
        free(meshes);
        free(objects);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "reference: out of memory");
    }
    sss_result r = SSS_OK;
    for (size_t i = 0; i < n && r == SSS_OK; i++) {
        const sss_scene_object *so = &scene->objects[i];
        r = sss_scene_object_world_mesh(so, t, &meshes[i], err);
        if (r != SSS_OK) {
            char prefix[512]; /* the scene file and the object, like the loader's messages */
            snprintf(prefix, sizeof prefix, "%s: objects[%zu]", scene->name ? scene->name : "scene", i);
            sss_error_prefix(err, prefix);
            break;
        }
        sss_reference_object *o = &objects[i];
        o->mesh = &meshes[i];
        const sss_scene_material *m = &so->material;
        if (m->type == SSS_SCENE_MATERIAL_DIFFUSE) {
            o->type = SSS_REFERENCE_DIFFUSE;
            memcpy(o->reflectance, m->albedo, sizeof o->reflectance);
        } else {
            o->type = SSS_REFERENCE_SUBSURFACE;
            o->optical = m->optical;
            o->profile = m->profile;
            o->table = m->table;
            o->artist = m->artist;
            memcpy(o->albedo, m->albedo, sizeof o->albedo);
        }
    }
    if (r == SSS_OK) {
        sss_reference_world world;
        memset(&world, 0, sizeof world);
        world.camera = scene->camera;
        world.objects = objects;
        world.object_count = n;
        world.lights = scene->lights;
        world.light_count = scene->light_count;
        world.exposure = scene->render.exposure;
        r = ref_render_world(&world, desc, mask, out, progress, user, stats, err);
        /* messages about the scene's parts ("lights[0].file: ...") name the scene file, as the loader's do */
        if (r != SSS_OK && err && (!strncmp(err->message, "lights[", 7) || !strncmp(err->message, "objects[", 8)))
            sss_error_prefix(err, scene->name ? scene->name : "scene");
    }
    for (size_t i = 0; i < n; i++) sss_mesh_free(&meshes[i]);
    free(meshes);
    free(objects);
    return r;
}

sss_result sss_reference_render(const sss_scene *scene, const sss_reference_desc *desc, sss_image *out,
                                sss_reference_progress_fn progress, void *user,
                                sss_reference_stats *stats, sss_error *err)
{
    return ref_render_scene(scene, desc, NULL, out, progress, user, stats, err);
}
