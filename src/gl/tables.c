/* gl/tables.c — sss_gl_tables: the CPU-only tables of a renderer (the kernel LUT cascades of the
 * subsurface materials), computed without GL so that a caller can build them on another thread and
 * hand them to sss_gl_renderer_create (desc.tables), which then only uploads them: the texels are kept
 * normalised as the LUT texture holds them. */
#include <stdlib.h>
#include <string.h>

#include "gl/gl_internal.h"

/* What a LUT cascade depends on (gl_lut_cascade_build): the material's optics, profile model and PBD table,
 * and the shared LUT parameters. */
typedef struct lut_key {
    sss_material optical;
    sss_profile_model model;
    const sss_pbd_table *table;
    double size, axes, cutoff, energy, levels;
} lut_key;

struct sss_gl_tables {
    int count;
    lut_key *keys;
    gl_lut_cascade *cascades; /* count, ready for upload (normalised RGBA texels) */
    /* the technique's own (gl_technique.tables_build), valid for what it was built with */
    const gl_technique *tech;
    const sss_scene *scene;
    const char *data_file;
    double params[GL_MAX_PARAMS];
    void *tech_data;
};

static void key_of(const sss_gl_renderer *r, const sss_scene_material *m, lut_key *k)
{
    memset(k, 0, sizeof *k);
    k->optical = m->optical;
    k->model = sss_scene_material_profile_model(m);
    k->table = m->table;
    k->size = r->shared[GL_P_LUT_SIZE];
    k->axes = r->shared[GL_P_LUT_AXES];
    k->cutoff = r->shared[GL_P_LUT_CUTOFF];
    k->energy = r->shared[GL_P_LUT_ENERGY];
    k->levels = r->shared[GL_P_LUT_LEVELS];
}

static int same_key(const lut_key *a, const lut_key *b)
{
    return memcmp(&a->optical, &b->optical, sizeof a->optical) == 0 && a->model == b->model &&
           a->table == b->table && a->size == b->size && a->axes == b->axes && a->cutoff == b->cutoff &&
           a->energy == b->energy && a->levels == b->levels;
}

static int find_key(const sss_gl_tables *t, const lut_key *k)
{
    for (int i = 0; i < t->count; i++)
        if (same_key(&t->keys[i], k)) return i;
    return -1;
}

static sss_result add_material(sss_gl_tables *t, const sss_gl_renderer *r, const sss_scene_material *m,
                               sss_error *err)
{
    lut_key k;
    key_of(r, m, &k);
    if (find_key(t, &k) >= 0) return SSS_OK;
    sss_result res = gl_lut_cascade_build(r, m, &t->cascades[t->count], err);
    if (res != SSS_OK) return res;
    t->keys[t->count++] = k;
    return SSS_OK;
}

sss_result sss_gl_tables_build(const sss_scene *scene, const sss_gl_renderer_desc *desc, sss_gl_tables **out,
                               sss_error *err)
{
    if (!out) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sss_gl_tables_build: out is NULL");
    *out = NULL;
    if (!scene) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sss_gl_tables_build: no scene");
    sss_gl_renderer_desc d;
    memset(&d, 0, sizeof d);
    if (desc) d = *desc;
    sss_gl_renderer *r = calloc(1, sizeof *r); /* parameters only: no context, nothing of GL */
    sss_gl_tables *t = calloc(1, sizeof *t);
    if (!r || !t) {
        free(r);
        free(t);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (tables)");
    }
    r->scene = scene;
    sss_result res = gl_technique_for(scene, &d, &r->tech, err);
    r->data_file = d.data_file;
    if (res == SSS_OK) res = gl_params_from_desc(r, &d, err);
    size_t n = scene->object_count ? scene->object_count : 1;
    t->keys = calloc(n, sizeof *t->keys);
    t->cascades = calloc(n, sizeof *t->cascades);
    if (res == SSS_OK && (!t->keys || !t->cascades)) res = sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (tables)");
    for (size_t i = 0; i < scene->object_count && res == SSS_OK; i++)
        if (scene->objects[i].material.type == SSS_SCENE_MATERIAL_SUBSURFACE) {
            res = add_material(t, r, &scene->objects[i].material, err);
            if (res != SSS_OK) sss_error_prefix(err, "kernel LUT");
        }
    if (res == SSS_OK && r->tech->tables_build) {
        t->tech = r->tech;
        t->scene = scene;
        t->data_file = r->data_file;
        memcpy(t->params, r->params, sizeof t->params);
        res = r->tech->tables_build(r, &t->tech_data, err);
        if (res != SSS_OK) sss_error_prefix(err, r->tech->info.name);
    }
    free(r);
    if (res != SSS_OK) {
        sss_gl_tables_free(t);
        return res;
    }
    *out = t;
    return SSS_OK;
}

void sss_gl_tables_free(sss_gl_tables *t)
{
    if (!t) return;
    for (int i = 0; t->cascades && i < t->count; i++) gl_lut_cascade_free(&t->cascades[i]);
    if (t->tech_data && t->tech->tables_free) t->tech->tables_free(t->tech_data);
    free(t->keys);
    free(t->cascades);
    free(t);
}

const gl_lut_cascade *gl_tables_find(const sss_gl_tables *t, const sss_gl_renderer *r, const sss_scene_material *m)
{
    if (!t) return NULL;
    lut_key k;
    key_of(r, m, &k);
    int i = find_key(t, &k);
    return i >= 0 ? &t->cascades[i] : NULL;
}

const void *gl_tables_technique_data(const sss_gl_tables *t, const sss_gl_renderer *r)
{
    if (!t || !t->tech_data || t->tech != r->tech || t->scene != r->scene || t->data_file != r->data_file) return NULL;
    for (int i = 0; i < r->tech->info.param_count; i++)
        if (t->params[i] != r->params[i]) return NULL;
    return t->tech_data;
}
