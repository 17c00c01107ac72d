/* The project's scenes (the json files under scenes/) load with their meshes and have the properties they exist for:
 * default = translucent object lit partly from behind over a diffuse ground; backlit = light behind a
 * detailed object; shadow_edge = front light with an occluder casting a shadow across the object. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "sss/scene.h"

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static double norm3(const double a[3])
{
    return sqrt(dot3(a, a));
}

static int load(const char *name, sss_scene *s)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/scenes/%s", SSS_SOURCE_DIR, name);
    sss_error err = {0};
    sss_result res = sss_scene_load(path, NULL, s, &err);
    CHECK_MSG(res == SSS_OK, "%s", err.message);
    if (res != SSS_OK) return 0;
    CHECK(s->object_count >= 1 && s->light_count >= 1);
    for (size_t i = 0; i < s->object_count; i++) CHECK(s->objects[i].mesh.triangle_count > 0);
    CHECK(s->camera.width == s->camera.height && (s->camera.width == 256 || s->camera.width == 512));
    return 1;
}

/* World-space bounding box centre and diagonal of an object. */
static void world_box(const sss_scene_object *o, double centre[3], double *diag)
{
    sss_mesh w;
    CHECK(sss_scene_object_world_mesh(o, 0, &w, NULL) == SSS_OK);
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (uint32_t v = 0; v < w.vertex_count; v++)
        for (int i = 0; i < 3; i++) {
            lo[i] = fmin(lo[i], w.positions[3 * v + i]);
            hi[i] = fmax(hi[i], w.positions[3 * v + i]);
        }
    double d[3];
    for (int i = 0; i < 3; i++) {
        centre[i] = 0.5 * (lo[i] + hi[i]);
        d[i] = hi[i] - lo[i];
    }
    *diag = norm3(d);
    sss_mesh_free(&w);
}

/* Cosine of the angle at the object's centre between the camera and the light: < 0 when the light
 * is behind the object as seen from the camera. */
static double light_camera_cosine(const sss_scene *s, const sss_scene_object *o, const sss_light *l)
{
    double c[3], diag, tl[3], tc[3];
    world_box(o, c, &diag);
    for (int i = 0; i < 3; i++) {
        tl[i] = l->position[i] - c[i];
        tc[i] = s->camera.position[i] - c[i];
    }
    return dot3(tl, tc) / (norm3(tl) * norm3(tc));
}

/* Radius holding 90% of the red channel's diffuse reflectance, as a fraction of the object's size. */
static double scattering_fraction(const sss_scene_object *o)
{
    sss_profile p;
    const sss_scene_material *m = &o->material;
    CHECK(sss_profile_init(&p, sss_scene_material_profile_model(m), &m->optical, m->table, NULL) == SSS_OK);
    double c[3], diag;
    world_box(o, c, &diag);
    return sss_profile_radius_for_fraction(&p, 0, 0.9) / diag;
}

static void test_default(void)
{
    sss_scene s;
    if (!load("default.json", &s)) return;
    const sss_scene_object *obj = NULL, *ground = NULL;
    for (size_t i = 0; i < s.object_count; i++) {
        if (s.objects[i].material.type == SSS_SCENE_MATERIAL_SUBSURFACE) obj = &s.objects[i];
        if (s.objects[i].material.type == SSS_SCENE_MATERIAL_DIFFUSE &&
            s.objects[i].procedural.shape == SSS_SHAPE_PLANE)
            ground = &s.objects[i];
    }
    CHECK(obj && ground && s.light_count == 1 && s.lights[0].type == SSS_LIGHT_POINT);
    if (!obj || !ground) return;
    CHECK(obj->material.source == SSS_SUBSURFACE_MEDIUM);
    /* Partly from behind: more than 90 degrees from the camera direction, but not straight behind. */
    double cosine = light_camera_cosine(&s, obj, &s.lights[0]);
    CHECK_MSG(cosine < 0 && cosine > -0.9, "cosine %g", cosine);
    /* Translucent at this scale: 90% of the light re-emerges within 5..100% of the object's size. */
    double f = scattering_fraction(obj);
    CHECK_MSG(f > 0.05 && f < 1, "r90 / size = %g", f);
    /* The object rests on the ground (its lowest point within 1% of its size of the plane). */
    double c[3], diag;
    world_box(obj, c, &diag);
    sss_mesh w;
    CHECK(sss_scene_object_world_mesh(obj, 0, &w, NULL) == SSS_OK);
    double ymin = INFINITY, plane_y = ground->transform.translate[1];
    for (uint32_t v = 0; v < w.vertex_count; v++) ymin = fmin(ymin, w.positions[3 * v + 1]);
    CHECK_MSG(fabs(ymin - plane_y) < 0.01 * diag, "lowest point %g, ground %g", ymin, plane_y);
    sss_mesh_free(&w);
    sss_scene_free(&s);
}

static void test_backlit(void)
{
    sss_scene s;
    if (!load("backlit.json", &s)) return;
    const sss_scene_object *obj = &s.objects[0];
    CHECK(obj->material.type == SSS_SCENE_MATERIAL_SUBSURFACE);
    CHECK(obj->mesh.triangle_count > 50000); /* detailed */
    CHECK(obj->splat_mesh.triangle_count > 0 && obj->splat_mesh.triangle_count < obj->mesh.triangle_count);
    /* Every light is behind the object. */
    for (size_t i = 0; i < s.light_count; i++) {
        double cosine = light_camera_cosine(&s, obj, &s.lights[i]);
        CHECK_MSG(cosine < -0.5, "light %zu: cosine %g", i, cosine);
    }
    /* Light crosses the thin parts (horns, claws, a few % of the size): r90 exceeds 4% of the size. */
    double f = scattering_fraction(obj);
    CHECK_MSG(f > 0.04 && f < 1, "r90 / size = %g", f);
    sss_scene_free(&s);
}

/* Moller-Trumbore: does the segment from o to o + d (t in (eps, 1 - eps)) hit the triangle? */
static int segment_hits(const double o[3], const double d[3], const float *a, const float *b, const float *c)
{
    double e1[3], e2[3], p[3], q[3], tv[3];
    for (int i = 0; i < 3; i++) {
        e1[i] = b[i] - a[i];
        e2[i] = c[i] - a[i];
        tv[i] = o[i] - a[i];
    }
    p[0] = d[1] * e2[2] - d[2] * e2[1];
    p[1] = d[2] * e2[0] - d[0] * e2[2];
    p[2] = d[0] * e2[1] - d[1] * e2[0];
    double det = dot3(e1, p);
    if (fabs(det) < 1e-12) return 0;
    double u = dot3(tv, p) / det;
    if (u < 0 || u > 1) return 0;
    q[0] = tv[1] * e1[2] - tv[2] * e1[1];
    q[1] = tv[2] * e1[0] - tv[0] * e1[2];
    q[2] = tv[0] * e1[1] - tv[1] * e1[0];
    double v = dot3(d, q) / det;
    if (v < 0 || u + v > 1) return 0;
    double t = dot3(e2, q) / det;
    return t > 1e-6 && t < 1 - 1e-6;
}

static void test_shadow_edge(void)
{
    sss_scene s;
    if (!load("shadow_edge.json", &s)) return;
    const sss_scene_object *obj = NULL;
    for (size_t i = 0; i < s.object_count; i++)
        if (s.objects[i].material.type == SSS_SCENE_MATERIAL_SUBSURFACE) obj = &s.objects[i];
    CHECK(obj && s.object_count >= 2 && s.light_count == 1 && s.lights[0].type == SSS_LIGHT_POINT);
    if (!obj) return;
    const sss_light *l = &s.lights[0];
    /* Front-lit: the light is on the camera's side. */
    CHECK(light_camera_cosine(&s, obj, l) > 0.5);
    /* The occluders shadow part of the object's light-facing, camera-facing vertices, not all. */
    sss_mesh w;
    CHECK(sss_scene_object_world_mesh(obj, 0, &w, NULL) == SSS_OK);
    size_t n_occ = 0;
    sss_mesh occ[8];
    for (size_t i = 0; i < s.object_count && n_occ < 8; i++)
        if (&s.objects[i] != obj) CHECK(sss_scene_object_world_mesh(&s.objects[i], 0, &occ[n_occ++], NULL) == SSS_OK);
    size_t lit = 0, shadowed = 0;
    for (uint32_t v = 0; v < w.vertex_count; v += 7) {
        double p[3] = {w.positions[3 * v], w.positions[3 * v + 1], w.positions[3 * v + 2]};
        double n[3] = {w.normals[3 * v], w.normals[3 * v + 1], w.normals[3 * v + 2]}, d[3], tc[3];
        for (int i = 0; i < 3; i++) {
            d[i] = l->position[i] - p[i];
            tc[i] = s.camera.position[i] - p[i];
        }
        if (dot3(n, d) <= 0 || dot3(n, tc) <= 0) continue;
        int hit = 0;
        for (size_t k = 0; k < n_occ && !hit; k++)
            for (uint32_t f = 0; f < occ[k].triangle_count && !hit; f++)
                hit = segment_hits(p, d, &occ[k].positions[3 * occ[k].indices[3 * f]],
                                   &occ[k].positions[3 * occ[k].indices[3 * f + 1]],
                                   &occ[k].positions[3 * occ[k].indices[3 * f + 2]]);
        if (hit) shadowed++;
        else lit++;
    }
    double frac = (double)shadowed / (double)(lit + shadowed);
    CHECK_MSG(frac > 0.2 && frac < 0.8, "shadowed fraction %g (%zu lit, %zu shadowed)", frac, lit, shadowed);
    /* The occluders are outside the camera's view: only their shadow is seen. The view frustum lies
     * in the four half-spaces x + t0 z >= 0, -x + t0 z >= 0, y + t1 z >= 0, -y + t1 z >= 0 (camera
     * coordinates along right, up, forward); a convex occluder whose vertices all violate one of them
     * is outside. */
    for (size_t k = 0; k < n_occ; k++) {
        int outside[4] = {1, 1, 1, 1};
        for (uint32_t v = 0; v < occ[k].vertex_count; v++) {
            double q[3];
            for (int i = 0; i < 3; i++) q[i] = occ[k].positions[3 * v + i] - s.basis.origin[i];
            double x = dot3(q, s.basis.right), y = dot3(q, s.basis.up), z = dot3(q, s.basis.forward);
            outside[0] &= x + s.basis.tan_half[0] * z < 0;
            outside[1] &= -x + s.basis.tan_half[0] * z < 0;
            outside[2] &= y + s.basis.tan_half[1] * z < 0;
            outside[3] &= -y + s.basis.tan_half[1] * z < 0;
        }
        CHECK_MSG(outside[0] || outside[1] || outside[2] || outside[3], "occluder %zu is in view", k);
        sss_mesh_free(&occ[k]);
    }
    sss_mesh_free(&w);
    sss_scene_free(&s);
}

int main(void)
{
    test_default();
    test_backlit();
    test_shadow_edge();
    return CHECK_DONE();
}
