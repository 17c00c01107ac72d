/* sam/sam_scene.c — maps of scene objects: the rest mesh in scene units (transform, no animation),
 * the material's profile, building and reading with the checks that tie a file to its object. */
#include <stdlib.h>
#include <string.h>

#include "sam/sam_internal.h"
#include "sss/scene.h"

sss_result sss_sam_object_mesh(const sss_scene_object *obj, sss_mesh *out, sss_error *err)
{
    sss_scene_object rest = *obj;
    rest.animation.type = SSS_ANIMATION_NONE; /* the map is built at rest; the GPU update follows the animation */
    return sss_scene_object_world_mesh(&rest, 0.0, out, err);
}

sss_result sss_sam_object_profile(const sss_scene_object *obj, sss_profile *out, sss_error *err)
{
    if (obj->material.type != SSS_SCENE_MATERIAL_SUBSURFACE)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "the object's material is not subsurface");
    *out = obj->material.rd;
    return SSS_OK;
}

static sss_result object_at(const sss_scene *scene, size_t index, const sss_scene_object **obj, sss_error *err)
{
    const char *name = scene->name ? scene->name : "scene";
    if (index >= scene->object_count)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "%s: no objects[%zu] (the scene has %zu objects)", name,
                             index, scene->object_count);
    *obj = &scene->objects[index];
    if ((*obj)->material.type != SSS_SCENE_MATERIAL_SUBSURFACE)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "%s: objects[%zu].material is not subsurface", name, index);
    if ((*obj)->mesh.vertex_count == 0)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "%s: objects[%zu] has no mesh loaded", name, index);
    return SSS_OK;
}

sss_result sss_sam_build_object(const sss_scene *scene, size_t index, const sss_sam_desc *desc, sss_sam *out,
                                sss_sam_stats *stats, sss_error *err)
{
    if (out) memset(out, 0, sizeof *out);
    const sss_scene_object *obj = NULL;
    sss_result res = object_at(scene, index, &obj, err);
    if (res != SSS_OK) return res;
    sss_profile prof;
    res = sss_sam_object_profile(obj, &prof, err);
    if (res != SSS_OK) return res;
    sss_mesh mesh;
    res = sss_sam_object_mesh(obj, &mesh, err);
    if (res != SSS_OK) return res;
    sss_sam_desc d;
    memset(&d, 0, sizeof d);
    if (desc) d = *desc;
    d.transform = obj->transform.matrix;
    /* a back-side mesh is given in object space: it is posed at rest as the object's mesh */
    sss_mesh back;
    memset(&back, 0, sizeof back);
    if (d.backside) {
        sss_scene_object rest = *obj;
        rest.animation.type = SSS_ANIMATION_NONE;
        res = sss_scene_object_pose_mesh(&rest, d.backside, 0.0, &back, err);
        if (res != SSS_OK) {
            sss_error_prefix(err, "back-side mesh");
            sss_mesh_free(&mesh);
            return res;
        }
        d.backside = &back;
    }
    res = sss_sam_build(&mesh, &prof, &d, out, stats, err);
    sss_mesh_free(&mesh);
    sss_mesh_free(&back);
    return res;
}

sss_result sss_sam_read_object(const char *path, const sss_scene *scene, size_t index, sss_sam *out, sss_error *err)
{
    if (out) memset(out, 0, sizeof *out);
    const sss_scene_object *obj = NULL;
    sss_result res = object_at(scene, index, &obj, err);
    if (res != SSS_OK) return res;
    res = sss_sam_read(path, out, err);
    if (res != SSS_OK) return res;
    sss_mesh mesh;
    res = sss_sam_object_mesh(obj, &mesh, err);
    if (res == SSS_OK) {
        res = sss_sam_check(out, &mesh, &obj->material.optical, sss_scene_material_profile_model(&obj->material),
                            obj->transform.matrix, path, err);
        sss_mesh_free(&mesh);
    }
    if (res != SSS_OK) sss_sam_free(out);
    return res;
}
