/* gl/material_update.c — new materials for the same geometry (sss_gl_renderer_update_materials,
 * sss_gl_pass_update_materials). The meshes, lights, shadow maps, frame targets and programs stay; the
 * material records and LUT cascades are built again and put in place, and the technique refreshes what
 * it derived from materials (its materials_changed callback, or a new technique state). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl/runtime.h"

static int same_floats(const float *a, const float *b, size_t n)
{
    if (!a || !b) return a == b;
    return memcmp(a, b, sizeof *a * n) == 0;
}

static int same_mesh(const sss_mesh *a, const sss_mesh *b)
{
    if (a->vertex_count != b->vertex_count || a->triangle_count != b->triangle_count) return 0;
    size_t v = a->vertex_count;
    int indices = (!a->indices && !b->indices) ||
                  (a->indices && b->indices &&
                   memcmp(a->indices, b->indices, sizeof *a->indices * 3 * a->triangle_count) == 0);
    return indices && same_floats(a->positions, b->positions, 3 * v) && same_floats(a->normals, b->normals, 3 * v) &&
           same_floats(a->uvs, b->uvs, 2 * v);
}

static int same_animation(const sss_animation *a, const sss_animation *b)
{
    return a->type == b->type && a->amplitude == b->amplitude && a->period == b->period;
}

static int same_object(const sss_scene_object *a, const sss_scene_object *b)
{
    return same_mesh(&a->mesh, &b->mesh) && same_mesh(&a->splat_mesh, &b->splat_mesh) &&
           a->splat_triangles == b->splat_triangles &&
           memcmp(a->transform.matrix, b->transform.matrix, sizeof a->transform.matrix) == 0 &&
           same_animation(&a->animation, &b->animation);
}

static int same_texture(const sss_scene_texture *a, const sss_scene_texture *b)
{
    const sss_image *x = &a->image, *y = &b->image;
    return x->width == y->width && x->height == y->height &&
           same_floats(x->pixels, y->pixels, (size_t)x->width * (size_t)x->height * 3);
}

/* What differs between the scene the renderer draws and `next`, other than materials; "" when nothing. */
static void geometry_difference(const sss_scene *now, const sss_scene *next, char *what, size_t size)
{
    what[0] = '\0';
    if (now->object_count != next->object_count)
        snprintf(what, size, "%zu objects instead of %zu", next->object_count, now->object_count);
    else if (now->light_count != next->light_count)
        snprintf(what, size, "%zu lights instead of %zu", next->light_count, now->light_count);
    else if (now->texture_count != next->texture_count)
        snprintf(what, size, "%zu textures instead of %zu", next->texture_count, now->texture_count);
    for (size_t i = 0; !what[0] && i < now->object_count; i++)
        if (!same_object(&now->objects[i], &next->objects[i]))
            snprintf(what, size, "objects[%zu] has another mesh, transform or animation", i);
    for (size_t i = 0; !what[0] && i < now->light_count; i++)
        if (now->lights[i].type != next->lights[i].type) snprintf(what, size, "lights[%zu] is of another kind", i);
    for (size_t i = 0; !what[0] && i < now->texture_count; i++)
        if (!same_texture(&now->textures[i], &next->textures[i]))
            snprintf(what, size, "textures[%zu] has other pixels", i);
}

/* 1 when an object starts or stops scattering (splat meshes and technique state follow that set) or
 * moved since the upload (shadow and translucency bounds follow it): then everything is rebuilt. */
static int needs_new_scene(const gl_scene *gs, const sss_scene *next)
{
    for (size_t i = 0; i < next->object_count; i++) {
        const sss_scene_object *so = &next->objects[i];
        const gl_object *o = &gs->objects[i];
        if ((so->material.type == SSS_SCENE_MATERIAL_SUBSURFACE) != o->subsurface ||
            memcmp(so->transform.matrix, o->uploaded_matrix, sizeof o->uploaded_matrix) != 0 ||
            !same_animation(&so->animation, &o->uploaded_animation))
            return 1;
    }
    return 0;
}

/* The technique's material-dependent state: its callback, or a new state. */
static sss_result refresh_technique(gl_runtime *rt, sss_error *err)
{
    if (!rt->tech->materials_changed) {
        gl_runtime_technique_destroy(rt);
        return gl_runtime_technique_create(rt, err);
    }
    gl_tech_ctx c;
    gl_runtime_ctx(rt, &c);
    sss_result res;
    GL_MEM_ACCOUNT(rt->tech_gpu_bytes, res = rt->tech->materials_changed(&c, rt->state, err));
    if (res != SSS_OK) sss_error_prefix(err, rt->tech->info.name);
    return res;
}

/* The GPU scene for `next`: everything again (a new subsurface set or a moved object), or its material
 * part only. Either is built beside what the core has and put in its place only when complete. */
static sss_result rebuild_for(gl_runtime *rt, const sss_scene *next, sss_error *err)
{
    gl_core *core = &rt->core;
    core->luts = gl_tables_luts(rt->tables);
    sss_result res;
    if (rt->scene_dirty || needs_new_scene(&core->gs, next)) {
        gl_runtime_technique_destroy(rt);
        res = gl_core_rebuild_scene(core, next, err);
        if (res == SSS_OK) res = gl_runtime_technique_create(rt, err);
        rt->scene_dirty = res != SSS_OK;
    } else {
        res = gl_scene_update_materials(core, next, err);
        if (res == SSS_OK) {
            core->scene = next;
            res = refresh_technique(rt, err);
        }
    }
    core->luts = NULL;
    return res;
}

sss_result gl_runtime_update_materials(gl_runtime *rt, const sss_scene *scene, const sss_gl_tables *tables,
                                       sss_error *err)
{
    const sss_scene *now = rt->core.scene, *next = scene ? scene : now;
    char what[160] = "";
    if (next != now) geometry_difference(now, next, what, sizeof what);
    if (what[0])
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "update_materials: %s: %s (a new renderer is needed)",
                             next->name ? next->name : "scene", what);
    if (!sss_gl_context_make_current(rt->core.ctx))
        return sss_error_set(err, SSS_ERROR_UNSUPPORTED, "update_materials: cannot make the GL context current");
    rt->tables = tables;
    sss_result res = rebuild_for(rt, next, err);
    rt->tables = NULL;
    if (res == SSS_OK && next != now) res = gl_lights_update(&rt->core, err);
    if (res != SSS_OK) {
        /* whatever was made of `next` goes (the caller may free it): the next frame rebuilds everything
         * from the scene the runtime had */
        gl_runtime_technique_destroy(rt);
        rt->core.scene = now;
        rt->scene_dirty = 1;
    }
    rt->frame_rendered = 0;
    return res;
}
