/* Meshes of scene objects in world space at a time t: animation (object space), then the transform. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sss/scene.h"

static void *dup_array(const void *src, size_t count, size_t elem, int *failed)
{
    if (!src || count == 0) return NULL;
    void *d = malloc(count * elem);
    if (!d) *failed = 1;
    else memcpy(d, src, count * elem);
    return d;
}

void sss_scene_object_animated_bounds(const sss_scene_object *obj, float lo[3], float hi[3])
{
    double diag = 0.0;
    for (int k = 0; k < 3; k++) {
        lo[k] = obj->bounds_min[k];
        hi[k] = obj->bounds_max[k];
        diag += (double)(hi[k] - lo[k]) * (hi[k] - lo[k]);
    }
    diag = sqrt(diag);
    double pad = 0.0;
    if (obj->animation.type == SSS_ANIMATION_TWIST || obj->animation.type == SSS_ANIMATION_BEND) pad = diag;
    if (obj->animation.type == SSS_ANIMATION_WAVE) pad = fabs(obj->animation.amplitude);
    for (int k = 0; k < 3; k++) {
        lo[k] -= (float)pad;
        hi[k] += (float)pad;
    }
}

double sss_scene_object_world_reach(const sss_scene_object *obj)
{
    float lo[3], hi[3];
    sss_scene_object_animated_bounds(obj, lo, hi);
    double reach = 0.0;
    for (int c = 0; c < 8; c++) {
        double p[3] = {(c & 1) ? hi[0] : lo[0], (c & 2) ? hi[1] : lo[1], (c & 4) ? hi[2] : lo[2]}, w[3];
        sss_transform_point(obj->transform.matrix, p, w);
        for (int k = 0; k < 3; k++) {
            if (!isfinite(w[k])) return INFINITY;
            if (fabs(w[k]) > reach) reach = fabs(w[k]);
        }
    }
    return reach;
}

sss_result sss_scene_mesh_copy(const sss_mesh *mesh, sss_mesh *out, sss_error *err)
{
    memset(out, 0, sizeof *out);
    int failed = 0;
    size_t nv = mesh->vertex_count, nt = mesh->triangle_count;
    out->positions = dup_array(mesh->positions, 3 * nv, sizeof(float), &failed);
    out->normals = dup_array(mesh->normals, 3 * nv, sizeof(float), &failed);
    out->uvs = dup_array(mesh->uvs, 2 * nv, sizeof(float), &failed);
    out->indices = dup_array(mesh->indices, 3 * nt, sizeof(uint32_t), &failed);
    if (failed) {
        sss_mesh_free(out);
        memset(out, 0, sizeof *out);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory copying a mesh of %zu vertices", nv);
    }
    out->vertex_count = mesh->vertex_count;
    out->triangle_count = mesh->triangle_count;
    out->source_flags = mesh->source_flags;
    return SSS_OK;
}

static void deform_in_place(const sss_animation *anim, const float lo[3], const float hi[3], double t, sss_mesh *m)
{
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        float p[3] = {m->positions[3 * v], m->positions[3 * v + 1], m->positions[3 * v + 2]};
        if (m->normals) sss_animation_deform_normal(anim, lo, hi, t, p, &m->normals[3 * v], &m->normals[3 * v]);
        sss_animation_deform_point(anim, lo, hi, t, p, &m->positions[3 * v]);
    }
}

static sss_result check_finite(sss_mesh *m, sss_error *err)
{
    for (size_t i = 0; i < 3 * (size_t)m->vertex_count; i++)
        if (!isfinite(m->positions[i]))
            return sss_error_set(err, SSS_ERROR_NUMERIC, "posed mesh: vertex %zu is not finite (scale too large?)",
                                 i / 3);
    return SSS_OK;
}

sss_result sss_animation_deform_mesh(const sss_animation *anim, const float bounds_min[3], const float bounds_max[3],
                                     double t, const sss_mesh *mesh, sss_mesh *out, sss_error *err)
{
    if (!isfinite(t)) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "animation: time must be finite");
    sss_result res = sss_animation_validate(anim, err);
    if (res != SSS_OK) return res;
    if ((res = sss_scene_mesh_copy(mesh, out, err)) != SSS_OK) return res;
    deform_in_place(anim, bounds_min, bounds_max, t, out);
    if ((res = check_finite(out, err)) != SSS_OK) sss_mesh_free(out);
    return res;
}

sss_result sss_scene_object_pose_mesh(const sss_scene_object *obj, const sss_mesh *mesh, double t, sss_mesh *out,
                                      sss_error *err)
{
    if (!isfinite(t)) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "pose: time must be finite");
    sss_result res = sss_scene_mesh_copy(mesh, out, err);
    if (res != SSS_OK) return res;
    if (obj->animation.type != SSS_ANIMATION_NONE) {
        if ((res = sss_animation_validate(&obj->animation, err)) != SSS_OK) {
            sss_mesh_free(out);
            return res;
        }
        deform_in_place(&obj->animation, obj->bounds_min, obj->bounds_max, t, out);
    }
    const sss_transform *tr = &obj->transform;
    for (uint32_t v = 0; v < out->vertex_count; v++) {
        double p[3] = {out->positions[3 * v], out->positions[3 * v + 1], out->positions[3 * v + 2]};
        sss_transform_point(tr->matrix, p, p);
        for (int i = 0; i < 3; i++) out->positions[3 * v + i] = (float)p[i];
        if (out->normals) {
            double n[3] = {out->normals[3 * v], out->normals[3 * v + 1], out->normals[3 * v + 2]};
            sss_transform_normal(tr->normal_matrix, n, n);
            for (int i = 0; i < 3; i++) out->normals[3 * v + i] = (float)n[i];
        }
    }
    /* A mirroring transform turns counter-clockwise triangles clockwise: swap two corners. */
    const double *m = tr->matrix;
    double det = m[0] * (m[5] * m[10] - m[6] * m[9]) - m[1] * (m[4] * m[10] - m[6] * m[8]) +
                 m[2] * (m[4] * m[9] - m[5] * m[8]);
    if (det < 0)
        for (uint32_t f = 0; f < out->triangle_count; f++) {
            uint32_t tmp = out->indices[3 * f + 1];
            out->indices[3 * f + 1] = out->indices[3 * f + 2];
            out->indices[3 * f + 2] = tmp;
        }
    if ((res = check_finite(out, err)) != SSS_OK) sss_mesh_free(out);
    return res;
}

sss_result sss_scene_object_world_mesh(const sss_scene_object *obj, double t, sss_mesh *out, sss_error *err)
{
    return sss_scene_object_pose_mesh(obj, &obj->mesh, t, out, err);
}
