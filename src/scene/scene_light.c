/* Lights of docs/scene-format.md: point, spot, directional, area, environment. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scene/scene_internal.h"

static double len3(const double v[3])
{
    return hypot(hypot(v[0], v[1]), v[2]); /* no overflow for components near DBL_MAX */
}

/* An intensity, radiance or scale: 0..SSS_SCENE_MAX_LIGHT_VALUE per channel (sss/scene.h says why). */
static sss_result nonneg_colour(jr *r, const cJSON *obj, const char *key, int required, const double *def,
                                double out[3])
{
    sss_result res = jr_vec(r, obj, key, required, def, 3, out, NULL);
    if (res != SSS_OK) return res;
    return jr_range_vec(r, key, out, 3, 0, 0, SSS_SCENE_MAX_LIGHT_VALUE, 0);
}

/* A position or extent: the renderers take it as floats, where a larger value is Inf. */
static sss_result float_vec(jr *r, const cJSON *obj, const char *key, double out[3])
{
    sss_result res = jr_vec(r, obj, key, 1, NULL, 3, out, NULL);
    if (res != SSS_OK) return res;
    return jr_range_vec(r, key, out, 3, -FLT_MAX, 0, FLT_MAX, 0);
}

static sss_result nonzero_vec(jr *r, const char *key, const double v[3])
{
    if (len3(v) > 0) return SSS_OK;
    return jr_fail_key(r, key, SSS_ERROR_INVALID_ARGUMENT, "must be a non-zero vector");
}

sss_result scene_parse_light(scene_ctx *c, const cJSON *item, sss_light *l)
{
    jr *r = &c->r;
    sss_result res;
    if ((res = jr_expect_object(r, item)) != SSS_OK) return res;
    const char *type = NULL;
    if ((res = jr_string(r, item, "type", 1, &type)) != SSS_OK) return res;

    if (strcmp(type, "point") == 0) {
        static const char *const fields[] = {"type", "position", "intensity"};
        l->type = SSS_LIGHT_POINT;
        if ((res = jr_check_fields(r, item, fields, SCENE_COUNT(fields))) != SSS_OK) return res;
        if ((res = float_vec(r, item, "position", l->position)) != SSS_OK) return res;
        return nonneg_colour(r, item, "intensity", 1, NULL, l->intensity);
    }
    if (strcmp(type, "spot") == 0) {
        static const char *const fields[] = {"type", "position", "look_at", "cone_angle", "cone_delta",
                                             "intensity"};
        l->type = SSS_LIGHT_SPOT;
        if ((res = jr_check_fields(r, item, fields, SCENE_COUNT(fields))) != SSS_OK) return res;
        if ((res = float_vec(r, item, "position", l->position)) != SSS_OK) return res;
        if ((res = float_vec(r, item, "look_at", l->look_at)) != SSS_OK) return res;
        double d[3] = {l->look_at[0] - l->position[0], l->look_at[1] - l->position[1],
                       l->look_at[2] - l->position[2]};
        if (!(len3(d) > 0))
            return jr_fail_key(r, "look_at", SSS_ERROR_INVALID_ARGUMENT, "equals the light's position");
        /* PBRT-v3 spot: coneangle is the half-angle of the cone, conedelta the falloff width. */
        if ((res = jr_number(r, item, "cone_angle", 1, 0, &l->cone_angle)) != SSS_OK) return res;
        if ((res = jr_range(r, "cone_angle", l->cone_angle, 0, 1, 90, 0)) != SSS_OK) return res;
        if ((res = jr_number(r, item, "cone_delta", 1, 0, &l->cone_delta)) != SSS_OK) return res;
        if ((res = jr_range(r, "cone_delta", l->cone_delta, 0, 0, l->cone_angle, 0)) != SSS_OK) return res;
        return nonneg_colour(r, item, "intensity", 1, NULL, l->intensity);
    }
    if (strcmp(type, "directional") == 0) {
        static const char *const fields[] = {"type", "direction", "radiance"};
        l->type = SSS_LIGHT_DIRECTIONAL;
        if ((res = jr_check_fields(r, item, fields, SCENE_COUNT(fields))) != SSS_OK) return res;
        if ((res = jr_vec(r, item, "direction", 1, NULL, 3, l->direction, NULL)) != SSS_OK) return res;
        if ((res = nonzero_vec(r, "direction", l->direction)) != SSS_OK) return res;
        double n = len3(l->direction);
        for (int i = 0; i < 3; i++) l->direction[i] /= n;
        return nonneg_colour(r, item, "radiance", 1, NULL, l->radiance);
    }
    if (strcmp(type, "area") == 0) {
        static const char *const fields[] = {"type", "center", "u", "v", "radiance", "two_sided"};
        l->type = SSS_LIGHT_AREA;
        if ((res = jr_check_fields(r, item, fields, SCENE_COUNT(fields))) != SSS_OK) return res;
        if ((res = float_vec(r, item, "center", l->center)) != SSS_OK) return res;
        if ((res = float_vec(r, item, "u", l->u)) != SSS_OK) return res;
        if ((res = nonzero_vec(r, "u", l->u)) != SSS_OK) return res;
        if ((res = float_vec(r, item, "v", l->v)) != SSS_OK) return res;
        if ((res = nonzero_vec(r, "v", l->v)) != SSS_OK) return res;
        const double *u = l->u, *v = l->v;
        double cr[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
        if (!(len3(cr) > 1e-9 * len3(u) * len3(v)))
            return jr_fail_key(r, "v", SSS_ERROR_INVALID_ARGUMENT, "parallel to u (the rectangle has no area)");
        if ((res = nonneg_colour(r, item, "radiance", 1, NULL, l->radiance)) != SSS_OK) return res;
        return jr_bool(r, item, "two_sided", 0, &l->two_sided);
    }
    if (strcmp(type, "environment") == 0) {
        static const char *const fields[] = {"type", "file", "scale", "rotate_y"};
        static const double one[3] = {1, 1, 1};
        l->type = SSS_LIGHT_ENVIRONMENT;
        if ((res = jr_check_fields(r, item, fields, SCENE_COUNT(fields))) != SSS_OK) return res;
        if ((res = scene_file_field(c, item, "file", 1, &l->file)) != SSS_OK) return res;
        if ((res = nonneg_colour(r, item, "scale", 0, one, l->scale)) != SSS_OK) return res;
        if ((res = jr_number(r, item, "rotate_y", 0, 0, &l->rotate_y)) != SSS_OK) return res;
        /* The same rotation in [-360, 360]: 1e308 degrees would overflow to inf radians downstream. */
        l->rotate_y = fmod(l->rotate_y, 360.0);
        return SSS_OK;
    }
    return jr_fail_key(r, "type", SSS_ERROR_INVALID_ARGUMENT,
                       "unknown light type \"%s\" (expected point, spot, directional, area or environment)",
                       type);
}

void scene_light_free(sss_light *l)
{
    free(l->file);
    l->file = NULL;
}

/* The light is parsed into a copy by the loader's own parser, so a bad field leaves the scene as it was.
 * An environment light keeps its file pointer, so that copies of the lights array stay valid. */
sss_result sss_scene_set_light(sss_scene *scene, size_t index, const char *json_text, size_t size, sss_error *err)
{
    scene_ctx ctx;
    memset(&ctx, 0, sizeof ctx);
    jr_init(&ctx.r, scene && scene->name ? scene->name : "scene", err);
    if (!scene || index >= scene->light_count)
        return jr_fail(&ctx.r, SSS_ERROR_INVALID_ARGUMENT, "lights[%zu]: no such light (the scene has %zu)", index,
                       scene ? scene->light_count : (size_t)0);
    ctx.base_dir = scene->base_dir ? scene->base_dir : ".";
    jr_enter_key(&ctx.r, "lights");
    jr_enter_index(&ctx.r, index);
    if (!json_text || size > SSS_SCENE_MAX_FILE_SIZE)
        return jr_fail(&ctx.r, SSS_ERROR_INVALID_ARGUMENT, "no light text, or more than %u bytes",
                       (unsigned)SSS_SCENE_MAX_FILE_SIZE);
    cJSON *item = NULL;
    sss_result parsed = jr_parse(&ctx.r, json_text, size, &item);
    if (parsed != SSS_OK) return parsed;
    sss_light *old = &scene->lights[index];
    if (old->type == SSS_LIGHT_ENVIRONMENT && cJSON_IsObject(item) && !jr_get(item, "file")) {
        ctx.base_dir = ""; /* the resolved path, as it is */
        cJSON_AddStringToObject(item, "file", old->file);
    }
    sss_light light;
    memset(&light, 0, sizeof light);
    sss_result res = scene_parse_light(&ctx, item, &light);
    cJSON_Delete(item);
    if (res == SSS_OK && light.type != old->type)
        res = jr_fail_key(&ctx.r, "type", SSS_ERROR_INVALID_ARGUMENT, "is %s, but the light is %s (a light keeps its type)",
                          sss_light_type_name(light.type), sss_light_type_name(old->type));
    if (res == SSS_OK && light.type == SSS_LIGHT_ENVIRONMENT && strcmp(light.file, old->file) != 0)
        res = jr_fail_key(&ctx.r, "file", SSS_ERROR_INVALID_ARGUMENT, "differs from the light's %s (a map is loaded once)",
                          old->file);
    if (res == SSS_OK && light.type == SSS_LIGHT_ENVIRONMENT) {
        free(light.file);
        light.file = old->file;
    } else if (res == SSS_OK) {
        scene_light_free(old);
    }
    if (res != SSS_OK) {
        scene_light_free(&light);
        return res;
    }
    *old = light;
    return SSS_OK;
}
