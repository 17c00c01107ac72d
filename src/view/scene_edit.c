/* view/scene_edit.c — the viewer's changes to a scene (camera, first light, measured-media preset,
 * scattering scale) written into the scene file's JSON, so that the edited scene goes through the
 * scene loader's validation and resolution exactly like a file (materials resolved per scene unit,
 * PBD tables built, mesh paths relative to the original folder). The same text feeds the CPU reference
 * of the current view. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <cjson/cJSON.h>

#include "scene/json_reader.h"
#include "sss/material.h"
#include "sss/scene.h"
#include "view/view_internal.h"

static int set_number(cJSON *obj, const char *key, double v)
{
    cJSON_DeleteItemFromObjectCaseSensitive(obj, key);
    return cJSON_AddNumberToObject(obj, key, v) != NULL;
}

static int set_vec3(cJSON *obj, const char *key, const double v[3])
{
    cJSON_DeleteItemFromObjectCaseSensitive(obj, key);
    cJSON *a = cJSON_CreateDoubleArray(v, 3);
    if (!a) return 0;
    cJSON_AddItemToObject(obj, key, a);
    return 1;
}

static int edit_camera(cJSON *root, const sss_camera *c)
{
    cJSON *cam = cJSON_GetObjectItemCaseSensitive(root, "camera");
    if (!cJSON_IsObject(cam)) return 0;
    return set_vec3(cam, "position", c->position) && set_vec3(cam, "look_at", c->look_at) &&
           set_vec3(cam, "up", c->up) && set_number(cam, "fov", c->fov) && set_number(cam, "width", c->width) &&
           set_number(cam, "height", c->height);
}

static int edit_light(cJSON *root, const sss_light *L)
{
    cJSON *lights = cJSON_GetObjectItemCaseSensitive(root, "lights");
    cJSON *l = cJSON_IsArray(lights) ? cJSON_GetArrayItem(lights, 0) : NULL;
    if (!cJSON_IsObject(l)) return 0;
    switch (L->type) {
    case SSS_LIGHT_POINT: return set_vec3(l, "position", L->position);
    case SSS_LIGHT_SPOT: return set_vec3(l, "position", L->position) && set_vec3(l, "look_at", L->look_at);
    case SSS_LIGHT_DIRECTIONAL: return set_vec3(l, "direction", L->direction);
    case SSS_LIGHT_AREA:
        return set_vec3(l, "center", L->center) && set_vec3(l, "u", L->u) && set_vec3(l, "v", L->v);
    case SSS_LIGHT_ENVIRONMENT: return set_number(l, "rotate_y", L->rotate_y);
    }
    return 0;
}

static double number_or(const cJSON *obj, const char *key, double fallback)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    return cJSON_IsNumber(v) ? v->valuedouble : fallback;
}

/* One subsurface material. Measured media are coefficients in mm^-1 times `scale` (mm per scene unit,
 * docs/physics.md §2.2): a preset keeps the file's `scale` when it had one (the scene's unit), and the scale
 * factor multiplies the coefficients, i.e. `scale`, or divides the mean free path of kdsubsurface. */
static int edit_material(cJSON *m, int medium, double factor)
{
    const cJSON *type = cJSON_GetObjectItemCaseSensitive(m, "type");
    if (!cJSON_IsString(type) || strcmp(type->valuestring, "subsurface") != 0) return 1;
    int kd = cJSON_GetObjectItemCaseSensitive(m, "reflectance") != NULL;
    if (medium >= 0) {
        const sss_measured_medium *med = sss_measured_medium_at((size_t)medium);
        if (!med) return 0;
        double base = kd ? 1.0 : number_or(m, "scale", 1.0);
        static const char *const drop[] = {"sigma_a", "sigma_s", "g", "reflectance", "mfp", "medium", "scale"};
        for (size_t i = 0; i < sizeof drop / sizeof drop[0]; i++) cJSON_DeleteItemFromObjectCaseSensitive(m, drop[i]);
        return cJSON_AddStringToObject(m, "medium", med->name) && set_number(m, "scale", base * factor);
    }
    if (factor == 1.0) return 1;
    if (!kd) return set_number(m, "scale", number_or(m, "scale", 1.0) * factor);
    cJSON *mfp = cJSON_GetObjectItemCaseSensitive(m, "mfp");
    if (cJSON_IsNumber(mfp)) return set_number(m, "mfp", mfp->valuedouble / factor);
    if (cJSON_IsArray(mfp)) {
        cJSON *e;
        cJSON_ArrayForEach(e, mfp)
        {
            if (cJSON_IsNumber(e)) cJSON_SetNumberValue(e, e->valuedouble / factor);
        }
        return 1;
    }
    return 0;
}

static sss_result parse_root(const char *text, size_t size, const char *name, cJSON **root, sss_error *err)
{
    jr r;
    jr_init(&r, name, err);
    sss_result res = jr_parse(&r, text, size, root);
    if (res != SSS_OK) return res;
    if (!cJSON_IsObject(*root)) {
        cJSON_Delete(*root);
        *root = NULL;
        return sss_error_set(err, SSS_ERROR_PARSE, "%s: not a JSON object", name);
    }
    return SSS_OK;
}

/* Prints and deletes root; *out is malloc'ed. */
static sss_result print_root(cJSON *root, char **out, sss_error *err)
{
    char *printed = cJSON_PrintUnformatted(root);
    cJSON_Delete(root);
    if (!printed) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (scene JSON)");
    *out = malloc(strlen(printed) + 1);
    if (*out) strcpy(*out, printed);
    cJSON_free(printed);
    if (!*out) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (scene JSON)");
    return SSS_OK;
}

sss_result view_scene_json(const char *text, size_t size, const char *name, const view_edits *edits, char **out,
                           sss_error *err)
{
    *out = NULL;
    if (!name) name = "scene";
    cJSON *root = NULL;
    sss_result res = parse_root(text, size, name, &root, err);
    if (res != SSS_OK) return res;
    const char *what = NULL;
    if (edits->camera && !edit_camera(root, edits->camera)) what = "camera";
    if (!what && edits->light0 && !edit_light(root, edits->light0)) what = "lights[0]";
    double factor = edits->scale_factor > 0.0 ? edits->scale_factor : 1.0;
    if (!what && (edits->medium >= 0 || factor != 1.0)) {
        cJSON *objects = cJSON_GetObjectItemCaseSensitive(root, "objects"), *o;
        cJSON_ArrayForEach(o, objects)
        {
            cJSON *m = cJSON_GetObjectItemCaseSensitive(o, "material");
            if (cJSON_IsObject(m) && !edit_material(m, edits->medium, factor)) {
                what = "objects[].material";
                break;
            }
        }
    }
    if (what) {
        cJSON_Delete(root);
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "%s: cannot apply the viewer's change to %s", name,
                             what);
    }
    return print_root(root, out, err);
}

/* ---- Panel and script edits of one material or light ------------------------------------------ */

static void drop_fields(cJSON *m, const char *const *keys, size_t n)
{
    for (size_t i = 0; i < n; i++) cJSON_DeleteItemFromObjectCaseSensitive(m, keys[i]);
}

static int set_values(cJSON *obj, const char *key, const double *v, int n)
{
    if (n == 1) return set_number(obj, key, v[0]);
    return set_vec3(obj, key, v);
}

/* Puts m into the form of `field` (coefficients or reflectance) when it is in another one. */
static int switch_form(cJSON *m, const char *field, const sss_scene_material *resolved)
{
    int coeff = strcmp(field, "sigma_a") == 0 || strcmp(field, "sigma_s") == 0;
    int refl = strcmp(field, "reflectance") == 0 || strcmp(field, "mfp") == 0;
    if (!coeff && !refl) return 1;
    if (coeff && cJSON_HasObjectItem(m, "sigma_a")) return 1;
    if (refl && cJSON_HasObjectItem(m, "reflectance")) return 1;
    if (!resolved) return 0;
    static const char *const forms[] = {"medium", "sigma_a", "sigma_s", "reflectance", "mfp", "scale", "g"};
    drop_fields(m, forms, sizeof forms / sizeof forms[0]);
    const sss_material *o = &resolved->optical;
    if (coeff)
        return set_vec3(m, "sigma_a", o->sigma_a) && set_vec3(m, "sigma_s", o->sigma_s) && set_number(m, "g", o->g);
    double mfp[3];
    for (int c = 0; c < 3; c++) mfp[c] = 1.0 / (o->sigma_a[c] + o->sigma_s[c]);
    return set_vec3(m, "reflectance", resolved->albedo) && set_vec3(m, "mfp", mfp);
}

sss_result view_material_json(const char *text, size_t size, const char *name, int object, const char *field,
                              const char *medium, const double *values, int value_count,
                              const sss_scene_material *resolved, char **out, sss_error *err)
{
    *out = NULL;
    if (!name) name = "scene";
    cJSON *root = NULL;
    sss_result res = parse_root(text, size, name, &root, err);
    if (res != SSS_OK) return res;
    cJSON *objects = cJSON_GetObjectItemCaseSensitive(root, "objects");
    cJSON *m = cJSON_GetObjectItemCaseSensitive(cJSON_GetArrayItem(objects, object), "material");
    const cJSON *type = cJSON_GetObjectItemCaseSensitive(m, "type");
    if (!cJSON_IsString(type) || strcmp(type->valuestring, "subsurface") != 0) {
        cJSON_Delete(root);
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "%s: objects[%d].material: %s", name, object,
                             cJSON_IsObject(m) ? "not a subsurface material" : "no such object");
    }
    int ok = 1;
    if (strcmp(field, "medium") == 0) {
        static const char *const forms[] = {"medium", "sigma_a", "sigma_s", "reflectance", "mfp", "g"};
        drop_fields(m, forms, sizeof forms / sizeof forms[0]);
        ok = medium && cJSON_AddStringToObject(m, "medium", medium) != NULL;
    } else {
        ok = switch_form(m, field, resolved) && value_count >= 1 && set_values(m, field, values, value_count);
    }
    if (!ok) {
        cJSON_Delete(root);
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "%s: objects[%d].material.%s: cannot set it", name,
                             object, field);
    }
    return print_root(root, out, err);
}

sss_result view_light_json(const char *text, size_t size, const char *name, int light, const char *field,
                           const double values[3], char **out, sss_error *err)
{
    *out = NULL;
    if (!name) name = "scene";
    cJSON *root = NULL;
    sss_result res = parse_root(text, size, name, &root, err);
    if (res != SSS_OK) return res;
    cJSON *l = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(root, "lights"), light);
    const cJSON *type = cJSON_GetObjectItemCaseSensitive(l, "type");
    const char *t = cJSON_IsString(type) ? type->valuestring : "";
    const char *key = NULL;
    if (strcmp(field, "position") == 0)
        key = strcmp(t, "point") == 0 || strcmp(t, "spot") == 0 ? "position" : strcmp(t, "area") == 0 ? "center" : NULL;
    else
        key = strcmp(t, "point") == 0 || strcmp(t, "spot") == 0         ? "intensity"
              : strcmp(t, "directional") == 0 || strcmp(t, "area") == 0 ? "radiance"
              : strcmp(t, "environment") == 0                           ? "scale"
                                                                        : NULL;
    if (!key || !set_vec3(l, key, values)) {
        cJSON_Delete(root);
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "%s: lights[%d]: %s", name, light,
                             !cJSON_IsObject(l) ? "no such light" : "a light of this type has no position");
    }
    return print_root(root, out, err);
}
