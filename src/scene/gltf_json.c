/* sss_gltf_scene_json: an imported glTF scene as a scene file of our format (docs/scene-format.md). */
#include <stdlib.h>

#include "scene/gltf_internal.h"

static cJSON *vec(const double *v, int n)
{
    return cJSON_CreateDoubleArray(v, n);
}

static int add_vec(cJSON *obj, const char *key, const double *v, int n)
{
    cJSON *a = vec(v, n);
    return a && cJSON_AddItemToObject(obj, key, a);
}

static cJSON *camera_json(const sss_camera *cam)
{
    cJSON *c = cJSON_CreateObject();
    if (!c || !add_vec(c, "position", cam->position, 3) || !add_vec(c, "look_at", cam->look_at, 3) ||
        !add_vec(c, "up", cam->up, 3) || !cJSON_AddNumberToObject(c, "fov", cam->fov) ||
        !cJSON_AddNumberToObject(c, "width", cam->width) || !cJSON_AddNumberToObject(c, "height", cam->height)) {
        cJSON_Delete(c);
        return NULL;
    }
    return c;
}

static cJSON *material_json(const sss_gltf_material *m, const char *const *image_paths)
{
    const char *texture = m->texture ? m->texture : m->image >= 0 && image_paths ? image_paths[m->image] : NULL;
    cJSON *j = cJSON_CreateObject();
    int ok = j != NULL;
    if (ok && m->subsurface) {
        ok = cJSON_AddStringToObject(j, "type", "subsurface") && add_vec(j, "sigma_a", m->sigma_a, 3) &&
             add_vec(j, "sigma_s", m->sigma_s, 3) && cJSON_AddNumberToObject(j, "g", m->g) &&
             cJSON_AddNumberToObject(j, "eta", m->eta) &&
             (!texture || cJSON_AddStringToObject(j, "texture", texture));
    } else if (ok) {
        ok = cJSON_AddStringToObject(j, "type", "diffuse") && add_vec(j, "reflectance", m->albedo, 3);
    }
    if (!ok) {
        cJSON_Delete(j);
        return NULL;
    }
    return j;
}

static cJSON *light_json(const sss_light *l)
{
    cJSON *j = cJSON_CreateObject();
    int ok = j && cJSON_AddStringToObject(j, "type", sss_light_type_name(l->type));
    if (ok && l->type == SSS_LIGHT_DIRECTIONAL) {
        ok = add_vec(j, "direction", l->direction, 3) && add_vec(j, "radiance", l->radiance, 3);
    } else if (ok) {
        ok = add_vec(j, "position", l->position, 3) && add_vec(j, "intensity", l->intensity, 3);
        if (ok && l->type == SSS_LIGHT_SPOT)
            ok = add_vec(j, "look_at", l->look_at, 3) && cJSON_AddNumberToObject(j, "cone_angle", l->cone_angle) &&
                 cJSON_AddNumberToObject(j, "cone_delta", l->cone_delta);
    }
    if (!ok) {
        cJSON_Delete(j);
        return NULL;
    }
    return j;
}

sss_result sss_gltf_scene_json(const sss_gltf_scene *scene, const char *const *mesh_paths,
                               const char *const *image_paths, char **json, sss_error *err)
{
    *json = NULL;
    cJSON *root = cJSON_CreateObject(), *objects = cJSON_CreateArray(), *lights = cJSON_CreateArray();
    int ok = root && objects && lights && cJSON_AddItemToObject(root, "camera", camera_json(&scene->camera));
    ok = ok && cJSON_AddItemToObject(root, "objects", objects);
    if (!ok) cJSON_Delete(objects);
    for (size_t i = 0; ok && i < scene->object_count; i++) {
        cJSON *o = cJSON_CreateObject();
        ok = o && cJSON_AddItemToArray(objects, o) && cJSON_AddStringToObject(o, "mesh", mesh_paths[i]) &&
             cJSON_AddItemToObject(o, "material", material_json(&scene->objects[i].material, image_paths));
    }
    if (ok && scene->light_count) {
        ok = cJSON_AddItemToObject(root, "lights", lights);
        if (!ok) cJSON_Delete(lights);
        lights = NULL;
        cJSON *arr = cJSON_GetObjectItemCaseSensitive(root, "lights");
        for (size_t i = 0; ok && i < scene->light_count; i++)
            ok = cJSON_AddItemToArray(arr, light_json(&scene->lights[i]));
    }
    cJSON_Delete(lights);
    char *text = ok ? cJSON_Print(root) : NULL;
    cJSON_Delete(root);
    if (!text) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory writing the scene JSON");
    *json = text;
    return SSS_OK;
}
