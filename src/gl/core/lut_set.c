/* gl/core/lut_set.c — a set of kernel LUT cascades computed ahead (sss_gl_tables holds one), found by
 * what a cascade depends on: the material's optics, profile model and PBD table, and the shared LUT
 * parameters. */
#include <stdlib.h>
#include <string.h>

#include "gl/core/gl_core.h"

struct gl_lut_key {
    sss_material optical;
    sss_profile_model model;
    const sss_pbd_table *table;
    double size, axes, cutoff, energy, levels;
};

static void key_of(const double *shared, const sss_scene_material *m, gl_lut_key *k)
{
    memset(k, 0, sizeof *k);
    k->optical = m->optical;
    k->model = sss_scene_material_profile_model(m);
    k->table = m->table;
    k->size = shared[GL_P_LUT_SIZE];
    k->axes = shared[GL_P_LUT_AXES];
    k->cutoff = shared[GL_P_LUT_CUTOFF];
    k->energy = shared[GL_P_LUT_ENERGY];
    k->levels = shared[GL_P_LUT_LEVELS];
}

static int same_key(const gl_lut_key *a, const gl_lut_key *b)
{
    return memcmp(&a->optical, &b->optical, sizeof a->optical) == 0 && a->model == b->model &&
           a->table == b->table && a->size == b->size && a->axes == b->axes && a->cutoff == b->cutoff &&
           a->energy == b->energy && a->levels == b->levels;
}

static int find_key(const gl_lut_set *set, const gl_lut_key *k)
{
    for (int i = 0; i < set->count; i++)
        if (same_key(&set->keys[i], k)) return i;
    return -1;
}

static sss_result add_material(gl_lut_set *set, const double *shared, const sss_scene_material *m, sss_error *err)
{
    gl_lut_key k;
    key_of(shared, m, &k);
    if (find_key(set, &k) >= 0) return SSS_OK;
    sss_result res = gl_lut_cascade_build(shared, m, &set->cascades[set->count], err);
    if (res != SSS_OK) return res;
    set->keys[set->count++] = k;
    return SSS_OK;
}

sss_result gl_lut_set_build(gl_lut_set *set, const sss_scene *scene, const double *shared, sss_error *err)
{
    memset(set, 0, sizeof *set);
    size_t n = scene->object_count ? scene->object_count : 1;
    set->keys = calloc(n, sizeof *set->keys);
    set->cascades = calloc(n, sizeof *set->cascades);
    if (!set->keys || !set->cascades) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (tables)");
    sss_result res = SSS_OK;
    for (size_t i = 0; i < scene->object_count && res == SSS_OK; i++)
        if (scene->objects[i].material.type == SSS_SCENE_MATERIAL_SUBSURFACE) {
            res = add_material(set, shared, &scene->objects[i].material, err);
            if (res != SSS_OK) sss_error_prefix(err, "kernel LUT");
        }
    return res;
}

void gl_lut_set_free(gl_lut_set *set)
{
    for (int i = 0; set->cascades && i < set->count; i++) gl_lut_cascade_free(&set->cascades[i]);
    free(set->keys);
    free(set->cascades);
    memset(set, 0, sizeof *set);
}

const gl_lut_cascade *gl_lut_set_find(const gl_lut_set *set, const double *shared, const sss_scene_material *m)
{
    if (!set) return NULL;
    gl_lut_key k;
    key_of(shared, m, &k);
    int i = find_key(set, &k);
    return i >= 0 ? &set->cascades[i] : NULL;
}
