/* gl/runtime.h — a technique at work on a GL core: the core (core/gl_core.h), the technique
 * (technique.h) with its parameters and state, and what ties them: the technique's context, parameter
 * changes, scene rebuilds, material updates. The renderer (renderer.c) and the pass (pass.c) each own
 * one runtime and fill its frame their way; neither calls the other.
 */
#ifndef SSS_GL_RUNTIME_H
#define SSS_GL_RUNTIME_H

#include "gl/core/gl_core.h"
#include "gl/technique.h"

typedef struct gl_runtime {
    gl_core core;
    const gl_technique *tech;
    void *state;                   /* the technique's (NULL until created, and after a failed rebuild) */
    double params[GL_MAX_PARAMS];  /* the technique's parameters, in its table's order */
    const char *data_file;         /* sss_gl_renderer_desc.data_file (may be NULL) */
    const sss_gl_tables *tables;   /* precomputed tables while a scene is uploaded, else NULL */
    int scene_dirty;               /* a parameter changed that rebuilds the scene resources */
    int frame_rendered;            /* a frame was drawn since the last change */
    long long tech_gpu_bytes;      /* GPU bytes of the technique's own textures and buffers */
} gl_runtime;

/* ---- Parameters (params.c): a technique's values and the shared ones, without GL ----------------- */

/* The technique a desc names, else the scene's render.technique, else the default. */
sss_result gl_params_technique(const sss_scene *scene, const sss_gl_renderer_desc *desc, const gl_technique **out,
                               sss_error *err);
/* params and shared from the defaults, then desc's preset, then desc's other values. */
sss_result gl_params_from_desc(const gl_technique *tech, const sss_gl_renderer_desc *desc, double *params,
                               double *shared, sss_error *err);
/* Sets one value by name (technique or shared table; "preset" resets and applies the paper's values).
 * *scene_level (may be NULL): 1 when the scene resources depend on it. Unknown names are refused with
 * the closest known name. */
sss_result gl_params_set_value(const gl_technique *tech, double *params, double *shared, const char *name, double value,
                               int *scene_level, sss_error *err);
/* A value by name; NAN when neither table has it. */
double gl_params_get(const gl_technique *tech, const double *params, const double *shared, const char *name);

/* ---- Tables computed ahead (tables.c) ------------------------------------------------------------ */

const gl_lut_set *gl_tables_luts(const sss_gl_tables *t); /* NULL when t is NULL */
/* The technique's data in t (tables_build) when t was built for this technique, scene object, data file
 * and parameter values; NULL otherwise. */
const void *gl_tables_technique_data(const sss_gl_tables *t, const gl_technique *tech, const sss_scene *scene,
                                     const char *data_file, const double *params);

/* ---- The runtime (runtime.c) ---------------------------------------------------------------------- */

/* Everything without GL: the technique, its parameters, the sizes (checked against the context). */
sss_result gl_runtime_init(gl_runtime *rt, sss_gl_context *ctx, const sss_scene *scene,
                           const sss_gl_renderer_desc *desc, int external, sss_error *err);
/* The core's GL objects (scene upload with `tables`, which may be NULL) and the technique's state. */
sss_result gl_runtime_create_gl(gl_runtime *rt, const sss_gl_tables *tables, sss_error *err);
void gl_runtime_free(gl_runtime *rt);
/* The technique's state made (with the scene uploaded), and freed. */
sss_result gl_runtime_technique_create(gl_runtime *rt, sss_error *err);
void gl_runtime_technique_destroy(gl_runtime *rt);
/* The technique's context for the current frame and parameters. */
void gl_runtime_ctx(const gl_runtime *rt, gl_tech_ctx *c);
sss_result gl_runtime_set_param(gl_runtime *rt, const char *name, double value, sss_error *err);
double gl_runtime_get_param(const gl_runtime *rt, const char *name);
/* New output size and SSAA factor (checked here): the core's targets, then the technique's. */
sss_result gl_runtime_resize(gl_runtime *rt, int width, int height, int k, sss_error *err);
/* Rebuilds the scene resources and the technique after a scene-level parameter changed. */
sss_result gl_runtime_rebuild_if_dirty(gl_runtime *rt, sss_error *err);
/* New materials for the same geometry (material_update.c): scene (NULL: the runtime's own, changed in
 * place) is checked against the one drawn, then the material records and LUTs are built and put in
 * place, and the technique refreshes what it derived from them; on failure nothing changes. */
sss_result gl_runtime_update_materials(gl_runtime *rt, const sss_scene *scene, const sss_gl_tables *tables,
                                       sss_error *err);
/* The lights' records again from the scene's lights (same number and kinds). */
sss_result gl_runtime_update_lights(gl_runtime *rt, sss_error *err);
/* One frame's start: rebuild if dirty, the frame block for cam at time, the scene bound, timing begun. */
sss_result gl_runtime_frame_begin(gl_runtime *rt, const gl_camera *cam, double time, sss_error *err);
/* The frame's end: when the frame's passes so far succeeded (so_far), the technique's passes into
 * frame.final and the SSAA resolve; the timing in any case. */
sss_result gl_runtime_frame_finish(gl_runtime *rt, sss_result so_far, sss_error *err);
/* The technique's intermediate target `name` (one of its declared targets), 0 when none. */
GLuint gl_runtime_target(const gl_runtime *rt, const char *name);
void gl_runtime_stats(const gl_runtime *rt, sss_gl_stats *out);
void gl_runtime_timings(const gl_runtime *rt, sss_gl_timings *out);

#endif
