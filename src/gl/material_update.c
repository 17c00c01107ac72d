/* gl/material_update.c — sss_gl_renderer_update_materials: new materials for the same geometry. The
 * meshes, lights, shadow maps, frame targets and programs stay; the material records and LUT cascades
 * are uploaded again and the technique refreshes what it derived from materials (its materials_changed
 * callback, or a new technique state). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl/gl_internal.h"

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
static int needs_new_scene(const sss_gl_renderer *r, const sss_scene *next)
{
    for (size_t i = 0; i < next->object_count; i++) {
        const sss_scene_object *so = &next->objects[i];
        const gl_object *o = &r->gs.objects[i];
        if ((so->material.type == SSS_SCENE_MATERIAL_SUBSURFACE) != o->subsurface ||
            memcmp(so->transform.matrix, o->uploaded_matrix, sizeof o->uploaded_matrix) != 0 ||
            !same_animation(&so->animation, &o->uploaded_animation))
            return 1;
    }
    return 0;
}

/* The materials part of the upload again; on failure the previous one is kept whole. */
static sss_result reupload_materials(sss_gl_renderer *r, sss_error *err)
{
    gl_scene old = r->gs;
    /* the upload rewrites the objects' material fields in place: their old values, for a failure */
    size_t bytes = sizeof *r->gs.objects * (size_t)r->gs.object_count;
    gl_object *objects = malloc(bytes);
    if (!objects) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (material update)");
    memcpy(objects, r->gs.objects, bytes);
    r->gs.materials = NULL;
    r->gs.ssbo_objects = r->gs.ssbo_materials = r->gs.ssbo_lut_scales = r->gs.lut_array = 0;
    sss_result res = gl_scene_update_materials(r, err);
    if (res == SSS_OK) {
        gl_scene_free_materials(&old);
    } else {
        gl_scene_free_materials(&r->gs); /* what was made of the new materials */
        memcpy(old.objects, objects, bytes);
        r->gs = old;
    }
    free(objects);
    return res;
}

/* The technique's material-dependent state: its callback, or a new state. On failure the technique is
 * dropped and rebuilt with the whole scene at the next render. */
static sss_result refresh_technique(sss_gl_renderer *r, sss_error *err)
{
    sss_result res;
    if (r->tech->materials_changed) {
        GL_MEM_ACCOUNT(r->tech_gpu_bytes, res = r->tech->materials_changed(r, r->tech_state, err));
        if (res != SSS_OK) sss_error_prefix(err, r->tech->info.name);
    } else {
        gl_runtime_technique_destroy(r);
        res = gl_runtime_technique_create(r, err);
    }
    if (res != SSS_OK) {
        gl_runtime_technique_destroy(r);
        r->scene_dirty = 1;
    }
    return res;
}

sss_result sss_gl_renderer_update_materials(sss_gl_renderer *r, const sss_scene *scene, const sss_gl_tables *tables,
                                            sss_error *err)
{
    if (!r) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "update_materials: no renderer");
    const sss_scene *next = scene ? scene : r->scene;
    char what[160] = "";
    if (next != r->scene) geometry_difference(r->scene, next, what, sizeof what);
    if (what[0])
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "update_materials: %s: %s (a new renderer is needed)",
                             next->name ? next->name : "scene", what);
    if (!sss_gl_context_make_current(r->ctx))
        return sss_error_set(err, SSS_ERROR_UNSUPPORTED, "update_materials: cannot make the GL context current");
    const sss_scene *previous = r->scene;
    r->scene = next;
    r->tables = tables;
    sss_result res;
    if (r->scene_dirty || needs_new_scene(r, next)) {
        r->scene_dirty = 1; /* everything again, with the new scene (the image of a new renderer) */
        res = gl_runtime_rebuild_if_dirty(r, err);
    } else {
        res = reupload_materials(r, err);
        if (res == SSS_OK) res = refresh_technique(r, err);
    }
    r->tables = NULL;
    if (res == SSS_OK && next != previous) res = gl_lights_update(r, err);
    if (res != SSS_OK && next != previous) {
        r->scene = previous; /* the caller may free `scene` */
        r->scene_dirty = 1;  /* whatever was made of it is rebuilt from `previous` at the next render */
    }
    r->frame_rendered = 0;
    return res;
}
