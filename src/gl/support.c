/* gl/support.c — where a technique's kernel is cut (sss/gl.h, sss_gl_kernel_cut). Techniques that carry
 * light only over a bounded distance (screen-space kernels on the visible surface, a per-pixel model)
 * lose what a material spreads farther: with a long mean free path the colour of the long distances
 * (a magenta medium turns white-green under ssss, local and sam; issue 30). A technique declares its
 * support (technique.h, gl_technique.support); this file compares it with the profile's reach. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "gl/core/gl_core.h"
#include "gl/runtime.h"
#include "gl/technique.h"
#include "sss/profile.h"

/* Cauchy's mean chord 4 V / A of a closed surface: the mean length of the straight lines through the
 * object (Cauchy 1832; a sphere of radius r gives 4r/3, a slab of thickness t about 2t). */
double gl_object_mean_chord(const sss_scene *scene, int object)
{
    const sss_scene_object *o = &scene->objects[object];
    sss_mesh m;
    if (o->mesh.triangle_count == 0 || sss_scene_object_world_mesh(o, 0.0, &m, NULL) != SSS_OK) return INFINITY;
    double volume = 0.0, area = 0.0;
    for (uint32_t t = 0; t < m.triangle_count; t++) {
        const float *a = m.positions + 3 * m.indices[3 * t], *b = m.positions + 3 * m.indices[3 * t + 1],
                    *c = m.positions + 3 * m.indices[3 * t + 2];
        double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
        area += 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        volume += (a[0] * n[0] + a[1] * n[1] + a[2] * n[2]) / 6.0; /* divergence theorem, signed */
    }
    sss_mesh_free(&m);
    /* an open surface (no volume) has no chord: unknown, no warning */
    return area > 0.0 && fabs(volume) > 0.0 ? 4.0 * fabs(volume) / area : INFINITY;
}

/* The side of one pixel on a plane facing the camera through the object's centre, at width x height. */
double gl_object_pixel_size(const sss_scene *scene, int object, int width, int height)
{
    const sss_scene_object *o = &scene->objects[object];
    const sss_camera *cam = &scene->camera;
    double lo[3] = {o->bounds_min[0], o->bounds_min[1], o->bounds_min[2]};
    double hi[3] = {o->bounds_max[0], o->bounds_max[1], o->bounds_max[2]};
    double c[3], w[3];
    for (int i = 0; i < 3; i++) c[i] = 0.5 * (lo[i] + hi[i]);
    sss_transform_point(o->transform.matrix, c, w);
    double d = 0.0;
    for (int i = 0; i < 3; i++) d += (w[i] - cam->position[i]) * scene->basis.forward[i];
    int shorter = width < height ? width : height;
    return d > 0.0 && shorter > 0 ? 2.0 * d * tan(cam->fov * M_PI / 360.0) / shorter : 0.0;
}

int sss_gl_kernel_cut(const sss_scene *scene, const sss_gl_renderer_desc *desc, int object, double *reach,
                      double *support)
{
    const gl_technique *tech = NULL;
    double params[GL_MAX_PARAMS], shared[GL_P_SHARED_COUNT];
    if (!scene || !desc || object < 0 || (size_t)object >= scene->object_count ||
        scene->objects[object].material.type != SSS_SCENE_MATERIAL_SUBSURFACE ||
        gl_params_technique(scene, desc, &tech, NULL) != SSS_OK ||
        gl_params_from_desc(tech, desc, params, shared, NULL) != SSS_OK)
        return -1;
    double r = sss_profile_reach(&scene->objects[object].material.rd, SSS_GL_KERNEL_CUT_FRACTION);
    int w = desc->width > 0 ? desc->width : scene->camera.width, h = desc->height > 0 ? desc->height : scene->camera.height;
    double s = tech->support ? tech->support(params, scene, object, w, h) : INFINITY;
    if (reach) *reach = r;
    if (support) *support = s;
    return r > s;
}

/* The material as the scene file gives it. */
static void describe_material(const sss_scene_material *m, char *out, size_t cap)
{
    if (m->source == SSS_SUBSURFACE_MEDIUM && m->medium)
        snprintf(out, cap, "medium %s, scale %g", m->medium->name, m->scale);
    else if (m->source == SSS_SUBSURFACE_REFLECTANCE)
        snprintf(out, cap, "reflectance %g %g %g, mfp %g %g %g", m->reflectance[0], m->reflectance[1],
                 m->reflectance[2], m->mfp[0], m->mfp[1], m->mfp[2]);
    else
        snprintf(out, cap, "sigma_a %g %g %g, sigma_s %g %g %g", m->input_sigma_a[0], m->input_sigma_a[1],
                 m->input_sigma_a[2], m->input_sigma_s[0], m->input_sigma_s[1], m->input_sigma_s[2]);
}

int sss_gl_kernel_cut_warnings(const sss_scene *scene, const sss_gl_renderer_desc *desc, char *out, size_t cap)
{
    int count = 0;
    size_t at = 0;
    if (out && cap) out[0] = '\0';
    for (size_t i = 0; scene && i < scene->object_count; i++) {
        double reach, support;
        if (sss_gl_kernel_cut(scene, desc, (int)i, &reach, &support) != 1) continue;
        count++;
        char what[200];
        describe_material(&scene->objects[i].material, what, sizeof what);
        const gl_technique *tech = NULL;
        gl_params_technique(scene, desc, &tech, NULL);
        if (out && at < cap)
            at += (size_t)snprintf(out + at, cap - at,
                                   "%sobject %zu (%s): half of its light spreads beyond %.3g scene units, but %s carries "
                                   "light only %.3g (truncated kernel: the long distances' colour is lost)",
                                   count > 1 ? "\n" : "", i, what, reach, tech->info.name, support);
    }
    return count;
}
