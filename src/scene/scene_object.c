/* Objects of docs/scene-format.md: mesh | procedural, transform, material, splat mesh, animation. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scene/scene_internal.h"

static sss_result parse_transform(scene_ctx *c, const cJSON *item, sss_transform *t)
{
    jr *r = &c->r;
    static const char *const fields[] = {"translate", "rotate", "scale"};
    static const double zero[3] = {0, 0, 0};
    static const double rot_default[4] = {0, 1, 0, 0};
    sss_result res;
    if ((res = jr_expect_object(r, item)) != SSS_OK) return res;
    if ((res = jr_check_fields(r, item, fields, SCENE_COUNT(fields))) != SSS_OK) return res;
    if ((res = jr_vec(r, item, "translate", 0, zero, 3, t->translate, NULL)) != SSS_OK) return res;
    if ((res = jr_vec(r, item, "rotate", 0, rot_default, 4, t->rotate, NULL)) != SSS_OK) return res;
    if (!(t->rotate[0] != 0 || t->rotate[1] != 0 || t->rotate[2] != 0))
        return jr_fail_key(r, "rotate", SSS_ERROR_INVALID_ARGUMENT,
                           "the axis (the first three numbers) must be non-zero");
    if ((res = jr_number_or_vec(r, item, "scale", 0, 1, 3, t->scale, NULL)) != SSS_OK) return res;
    for (int i = 0; i < 3; i++) {
        if (t->scale[i] == 0)
            return jr_fail_key(r, "scale", SSS_ERROR_INVALID_ARGUMENT, "must be non-zero");
        /* Normals transform with 1/scale and positions are floats: keep both far from overflow. */
        if (!(fabs(t->scale[i]) >= SSS_SCENE_SCALE_MIN && fabs(t->scale[i]) <= SSS_SCENE_SCALE_MAX))
            return jr_fail_key(r, "scale", SSS_ERROR_INVALID_ARGUMENT, "%.3g is out of range: |scale| in [%g, %g]",
                               t->scale[i], SSS_SCENE_SCALE_MIN, SSS_SCENE_SCALE_MAX);
    }
    sss_error err = {0};
    res = sss_transform_update(t, &err);
    if (res != SSS_OK) {
        const char *msg = strncmp(err.message, "transform: ", 11) == 0 ? err.message + 11 : err.message;
        res = jr_fail(r, res, "%s", msg);
    }
    return res;
}

static sss_result positive(jr *r, const cJSON *obj, const char *key, double *out)
{
    sss_result res = jr_number(r, obj, key, 1, 0, out);
    if (res != SSS_OK) return res;
    return jr_range(r, key, *out, 0, 1, INFINITY, 0);
}

static sss_result count(jr *r, const cJSON *obj, const char *key, long def, long min, long max, int *out)
{
    long v = 0;
    sss_result res = jr_int(r, obj, key, 0, def, min, max, &v);
    *out = (int)v;
    return res;
}

/* Shape parameters and their ranges follow sss/mesh.h so that errors name the JSON path. */
static sss_result parse_procedural(scene_ctx *c, const cJSON *item, sss_procedural *p)
{
    jr *r = &c->r;
    sss_result res;
    if ((res = jr_expect_object(r, item)) != SSS_OK) return res;
    const char *shape = NULL;
    if ((res = jr_string(r, item, "shape", 1, &shape)) != SSS_OK) return res;
    if (strcmp(shape, "sphere") == 0) {
        static const char *const fields[] = {"shape", "radius", "subdivisions"};
        p->shape = SSS_SHAPE_SPHERE;
        if ((res = jr_check_fields(r, item, fields, SCENE_COUNT(fields))) != SSS_OK) return res;
        if ((res = positive(r, item, "radius", &p->radius)) != SSS_OK) return res;
        return count(r, item, "subdivisions", 4, 0, 8, &p->subdivisions);
    }
    if (strcmp(shape, "torus") == 0) {
        static const char *const fields[] = {"shape", "major", "minor", "segments"};
        p->shape = SSS_SHAPE_TORUS;
        if ((res = jr_check_fields(r, item, fields, SCENE_COUNT(fields))) != SSS_OK) return res;
        if ((res = positive(r, item, "major", &p->major)) != SSS_OK) return res;
        if ((res = positive(r, item, "minor", &p->minor)) != SSS_OK) return res;
        if (!(p->minor < p->major))
            return jr_fail_key(r, "minor", SSS_ERROR_INVALID_ARGUMENT, "must be smaller than major (%g)", p->major);
        return count(r, item, "segments", 64, 3, 2048, &p->segments);
    }
    if (strcmp(shape, "trefoil") == 0) {
        static const char *const fields[] = {"shape", "radius", "tube", "segments"};
        p->shape = SSS_SHAPE_TREFOIL;
        if ((res = jr_check_fields(r, item, fields, SCENE_COUNT(fields))) != SSS_OK) return res;
        if ((res = positive(r, item, "radius", &p->radius)) != SSS_OK) return res;
        if ((res = positive(r, item, "tube", &p->tube)) != SSS_OK) return res;
        if (!(p->tube <= p->radius / 6))
            return jr_fail_key(r, "tube", SSS_ERROR_INVALID_ARGUMENT,
                               "must be at most radius / 6 (%g) or the tube intersects itself", p->radius / 6);
        return count(r, item, "segments", 256, 3, 4096, &p->segments);
    }
    if (strcmp(shape, "plane") == 0) {
        static const char *const fields[] = {"shape", "size"};
        p->shape = SSS_SHAPE_PLANE;
        if ((res = jr_check_fields(r, item, fields, SCENE_COUNT(fields))) != SSS_OK) return res;
        return positive(r, item, "size", &p->size);
    }
    if (strcmp(shape, "box") == 0) {
        static const char *const fields[] = {"shape", "size"};
        p->shape = SSS_SHAPE_BOX;
        if ((res = jr_check_fields(r, item, fields, SCENE_COUNT(fields))) != SSS_OK) return res;
        if ((res = jr_number_or_vec(r, item, "size", 1, 0, 3, p->box_size, NULL)) != SSS_OK) return res;
        return jr_range_vec(r, "size", p->box_size, 3, 0, 1, INFINITY, 0);
    }
    return jr_fail_key(r, "shape", SSS_ERROR_INVALID_ARGUMENT,
                       "unknown shape \"%s\" (expected sphere, torus, trefoil, plane or box)", shape);
}

static sss_result parse_animation(scene_ctx *c, const cJSON *item, sss_animation *a)
{
    jr *r = &c->r;
    static const char *const fields[] = {"type", "amplitude", "period"};
    sss_result res;
    if ((res = jr_expect_object(r, item)) != SSS_OK) return res;
    if ((res = jr_check_fields(r, item, fields, SCENE_COUNT(fields))) != SSS_OK) return res;
    const char *type = NULL;
    if ((res = jr_string(r, item, "type", 1, &type)) != SSS_OK) return res;
    if (strcmp(type, "twist") == 0) a->type = SSS_ANIMATION_TWIST;
    else if (strcmp(type, "bend") == 0) a->type = SSS_ANIMATION_BEND;
    else if (strcmp(type, "wave") == 0) a->type = SSS_ANIMATION_WAVE;
    else
        return jr_fail_key(r, "type", SSS_ERROR_INVALID_ARGUMENT,
                           "unknown animation \"%s\" (expected twist, bend or wave)", type);
    if ((res = jr_number(r, item, "amplitude", 1, 0, &a->amplitude)) != SSS_OK) return res;
    if ((res = jr_number(r, item, "period", 1, 0, &a->period)) != SSS_OK) return res;
    return jr_range(r, "period", a->period, 0, 1, INFINITY, 0);
}

sss_result scene_parse_object(scene_ctx *c, const cJSON *item, sss_scene_object *o)
{
    jr *r = &c->r;
    static const char *const fields[] = {"mesh", "procedural", "transform", "material", "splat_mesh",
                                         "splat_triangles", "animation"};
    sss_result res;
    if ((res = jr_expect_object(r, item)) != SSS_OK) return res;
    if ((res = jr_check_fields(r, item, fields, SCENE_COUNT(fields))) != SSS_OK) return res;

    const cJSON *mesh = jr_get(item, "mesh"), *proc = jr_get(item, "procedural");
    if (mesh && proc) return jr_fail(r, SSS_ERROR_PARSE, "has both mesh and procedural (exactly one is allowed)");
    if (!mesh && !proc) return jr_fail(r, SSS_ERROR_PARSE, "needs either mesh or procedural");
    if (mesh) {
        o->procedural.shape = SSS_SHAPE_MESH;
        if ((res = scene_file_field(c, item, "mesh", 1, &o->mesh_path)) != SSS_OK) return res;
    } else {
        size_t mark = jr_enter_key(r, "procedural");
        res = parse_procedural(c, proc, &o->procedural);
        jr_leave(r, mark);
        if (res != SSS_OK) return res;
    }

    const cJSON *tr = jr_get(item, "transform");
    if (tr) {
        size_t mark = jr_enter_key(r, "transform");
        res = parse_transform(c, tr, &o->transform);
        jr_leave(r, mark);
        if (res != SSS_OK) return res;
    } else {
        sss_transform_identity(&o->transform);
    }

    if ((res = jr_require(r, item, "material")) != SSS_OK) return res;
    size_t mark = jr_enter_key(r, "material");
    res = scene_parse_material(c, jr_get(item, "material"), &o->material);
    jr_leave(r, mark);
    if (res != SSS_OK) return res;

    if (jr_get(item, "splat_mesh") && jr_get(item, "splat_triangles"))
        return jr_fail(r, SSS_ERROR_PARSE, "splat_mesh and splat_triangles are mutually exclusive");
    if ((res = scene_file_field(c, item, "splat_mesh", 0, &o->splat_mesh_path)) != SSS_OK) return res;
    long tris = 0;
    if ((res = jr_int(r, item, "splat_triangles", 0, 0, 1, (long)SSS_MESH_MAX_TRIANGLES, &tris)) != SSS_OK)
        return res;
    o->splat_triangles = (uint32_t)tris;

    const cJSON *anim = jr_get(item, "animation");
    o->animation.type = SSS_ANIMATION_NONE;
    if (anim) {
        mark = jr_enter_key(r, "animation");
        res = parse_animation(c, anim, &o->animation);
        jr_leave(r, mark);
        if (res != SSS_OK) return res;
    }
    return SSS_OK;
}

void scene_object_free(sss_scene_object *o)
{
    free(o->mesh_path);
    free(o->splat_mesh_path);
    sss_mesh_free(&o->mesh);
    sss_mesh_free(&o->splat_mesh);
    scene_material_free(&o->material);
    memset(o, 0, sizeof *o);
}
