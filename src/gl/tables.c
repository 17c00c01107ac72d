/* gl/tables.c — sss_gl_tables: the CPU-only tables of a renderer (the kernel LUT cascades of the
 * subsurface materials, and what its technique precomputes), computed without GL so that a caller can
 * build them on another thread and hand them to sss_gl_renderer_create (desc.tables), which then only
 * uploads them: the texels are kept normalised as the LUT texture holds them. */
#include <stdlib.h>
#include <string.h>

#include "gl/runtime.h"

struct sss_gl_tables {
    gl_lut_set luts;
    /* the technique's own (gl_technique.tables_build), valid for what it was built with */
    const gl_technique *tech;
    const sss_scene *scene;
    const char *data_file;
    double params[GL_MAX_PARAMS];
    void *tech_data;
};

/* The technique's own CPU data (tables_build), made with a context that has no GL. */
static sss_result build_technique_data(sss_gl_tables *t, const gl_technique *tech, const sss_scene *scene,
                                       const char *data_file, const double *params, sss_error *err)
{
    t->tech = tech;
    t->scene = scene;
    t->data_file = data_file;
    memcpy(t->params, params, sizeof t->params);
    gl_tech_ctx c;
    memset(&c, 0, sizeof c);
    c.scene = scene;
    c.params = t->params;
    c.data_file = data_file;
    sss_result res = tech->tables_build(&c, &t->tech_data, err);
    if (res != SSS_OK) sss_error_prefix(err, tech->info.name);
    return res;
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
    sss_gl_tables *t = calloc(1, sizeof *t);
    if (!t) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (tables)");
    const gl_technique *tech = NULL;
    double params[GL_MAX_PARAMS], shared[GL_P_SHARED_COUNT];
    sss_result res = gl_params_technique(scene, &d, &tech, err);
    if (res == SSS_OK) res = gl_params_from_desc(tech, &d, params, shared, err);
    if (res == SSS_OK) res = gl_lut_set_build(&t->luts, scene, shared, err);
    if (res == SSS_OK && tech->tables_build) res = build_technique_data(t, tech, scene, d.data_file, params, err);
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
    gl_lut_set_free(&t->luts);
    if (t->tech_data && t->tech->tables_free) t->tech->tables_free(t->tech_data);
    free(t);
}

const gl_lut_set *gl_tables_luts(const sss_gl_tables *t) { return t ? &t->luts : NULL; }

const void *gl_tables_technique_data(const sss_gl_tables *t, const gl_technique *tech, const sss_scene *scene,
                                     const char *data_file, const double *params)
{
    if (!t || !t->tech_data || t->tech != tech || t->scene != scene || t->data_file != data_file) return NULL;
    for (int i = 0; i < tech->info.param_count; i++)
        if (t->params[i] != params[i]) return NULL;
    return t->tech_data;
}
