/* gl/technique.h — the plug-in interface of the real-time techniques.
 *
 * A technique is one `const gl_technique` in src/gl/techniques/<name>/ (docs/integration.md, "Adding a
 * technique"; techniques/local is the smallest). It declares:
 *  - its parameters: one list X(name, type, default, min, max, doc) that gives both the table users set
 *    by name (sss_gl_param_info) and the struct its code reads (one double per entry: p->name);
 *  - what it reads (GL_READ_*, gl_base.h): the frame's inputs (G-buffer, irradiance, reflected light,
 *    mip chains) and the scene's resources beyond the materials and LUTs (lights and shadow maps, splat
 *    meshes); the frame runs only the shared passes that make what is read, and the context shows only
 *    the frame targets declared;
 *  - what it writes: frame.final (every technique: reflected light plus its subsurface light, in linear
 *    radiance) and its intermediate targets, named in `targets` (sss_gl_renderer_read_buffer reads them
 *    by these names through `target`);
 *  - its state: state_size zeroed bytes it owns, given to every callback.
 * Callbacks get a gl_tech_ctx: the GL context, the scene and its GPU upload, the frame's targets, the
 * camera, the timer, the sizes and the technique's parameters. They see nothing else of the frame, and
 * own nothing but their state. A technique that reuses another runs it through this same interface
 * (gl_sub_technique). Pieces shared by several techniques live in src/gl/common/.
 *
 * Every pass is bracketed with gl_timer_begin/end on ctx->timer and ends with
 * gl_check(ctx->gl, "<technique>: <pass>", err). Shaders are src/gl/techniques/<name>/<name>_*.glsl with
 * `#include "common.glsl"` (frame block, objects, materials, lights with shadows, Fresnel, animation,
 * lut_eval of the kernel LUT, subsurface_exit).
 */
#ifndef SSS_GL_TECHNIQUE_H
#define SSS_GL_TECHNIQUE_H

#include "gl/core/gl_base.h"

#define GL_MAX_PARAMS 48

/* ---- Parameters -------------------------------------------------------------------------------- */

/* X(name, type, default, min, max, doc) entries of a technique's parameter list, as table rows and as
 * struct fields (the struct is the table's values in table order). */
#define GL_PARAM_INFO(name, type, def, lo, hi, doc) {#name, type, def, lo, hi, doc},
#define GL_PARAM_FIELD(name, type, def, lo, hi, doc) double name;
#define GL_PARAM_ONE(name, type, def, lo, hi, doc) +1
/* Declares `typedef struct type {...} type;` from list and checks that it has no padding. */
#define GL_PARAM_STRUCT(type, list)                                                                         \
    typedef struct type {                                                                                  \
        list(GL_PARAM_FIELD)                                                                               \
    } type;                                                                                                \
    _Static_assert(sizeof(type) == (0 list(GL_PARAM_ONE)) * sizeof(double), #type " is its table's values")

/* The defaults of a table, in table order. */
void gl_params_defaults(const sss_gl_technique_info *info, double *values);
/* Sets parameter `name` of info's table in values (no change when the table has no such parameter). */
void gl_params_set(const sss_gl_technique_info *info, double *values, const char *name, double value);

/* ---- The context a technique works in ----------------------------------------------------------- */

typedef struct gl_tech_ctx {
    sss_gl_context *gl;        /* for gl_check; NULL in tables_build (no GL there) */
    const sss_scene *scene;    /* the scene: objects' materials and meshes, lights */
    const gl_scene *gs;        /* its GPU upload: objects, material records, LUTs, lights, shadow maps */
    gl_frame frame;            /* the frame's targets: those of `reads` (the others 0), final and fbo_final */
    const gl_view *view;       /* the frame's camera and time (the frame block is bound) */
    gl_timer *timer;
    int width, height;         /* the render size: the output size x supersample */
    int supersample;           /* k: lengths counted in output pixels are k render pixels (pattern sizes,
                                  resolution divisors: supersampling changes the sampling density, not the
                                  image; docs/supersampling.md) */
    const void *params;        /* the technique's parameter struct (GL_PARAM_STRUCT) */
    const char *data_file;     /* sss_gl_renderer_desc.data_file (may be NULL) */
    const void *tables_data;   /* what tables_build made for these parameters, or NULL (create and
                                  materials_changed only) */
    int frame_rendered;        /* a frame was drawn since the last change (stats read its counters) */
    GLuint vao_empty;          /* gl_draw_fullscreen */
    GLuint prog_mips;          /* mip_reduce, for gl_frame_mipmaps after a change of level 0 */
} gl_tech_ctx;

/* A full-screen triangle (the bound program's fragment stage covers every pixel). */
void gl_draw_fullscreen(const gl_tech_ctx *c);
/* The start of the resolve every technique ends with (common/resolve.glsl's bindings): frame.final as
 * the target at the render size, prog in use, the G-buffer's position, normal and albedo on units 0-2
 * and the reflected light on 3. The caller binds its own light from unit 4 on and draws; blending is
 * left as it is. */
void gl_resolve_begin(const gl_tech_ctx *c, GLuint prog);
/* glUniform1i / glUniform1f of prog's uniform `name` (prog in use; an unknown name is ignored, as GL does). */
void gl_uniform_i(GLuint prog, const char *name, int v);
void gl_uniform_f(GLuint prog, const char *name, double v);
/* Deletes the n programs / samplers that exist (0 entries are skipped). */
void gl_delete_programs(const GLuint *progs, int n);
void gl_delete_samplers(const GLuint *samplers, int n);
/* Draws every object with the bound program (a G-buffer-style vertex stage; object index in the
 * uniform `object_uniform`); subsurface_only: skip the others. */
void gl_draw_objects(const gl_tech_ctx *c, GLint object_uniform, int subsurface_only);
/* Runs the bound compute program prog (local size 64) once per triangle of every subsurface object's
 * splat mesh: binds the mesh SSBOs, sets u_has_uv, u_object, u_triangles; ends with a barrier for
 * storage and indirect-command reads (maisch2020's splats, dss's surfels). */
void gl_dispatch_splat_triangles(const gl_tech_ctx *c, GLuint prog);

/* ---- The interface ------------------------------------------------------------------------------ */

typedef struct gl_technique {
    sss_gl_technique_info info;
    unsigned reads;              /* GL_READ_* */
    const char *const *targets;  /* its intermediate targets by name, NULL-terminated (may be NULL) */
    size_t state_size;           /* zeroed state passed to every callback */
    sss_result (*create)(const gl_tech_ctx *c, void *state, sss_error *err);
    /* after the frame size or a technique parameter changed */
    sss_result (*resize)(const gl_tech_ctx *c, void *state, sss_error *err);
    sss_result (*render)(const gl_tech_ctx *c, void *state, sss_error *err); /* writes frame.final */
    void (*destroy)(void *state);
    /* after the material records and LUTs were uploaded again (same meshes and subsurface objects):
     * refresh what create() derived from materials; NULL: destroy + create. */
    sss_result (*materials_changed)(const gl_tech_ctx *c, void *state, sss_error *err);
    /* optional: CPU-only data for the context's scene, data file and parameters, made by
     * sss_gl_tables_build without GL (any thread); create() and materials_changed() find it in
     * ctx->tables_data */
    sss_result (*tables_build)(const gl_tech_ctx *c, void **out, sss_error *err);
    void (*tables_free)(void *data);
    GLuint (*target)(void *state, const char *name); /* one of `targets`, 0 when it has none now */
    void (*stats)(const gl_tech_ctx *c, void *state, sss_gl_stats *out);
    /* Eq. 8's cut-off n.v of Maisch & Ropinski 2020 in the frame block (the illumination pass reads
     * it): the technique's parameter, or NULL for the paper's 0.2 */
    double (*grazing_cutoff)(const void *params);
    /* preset=paper: the published values of the parameters (technique or shared, by name) whose
     * defaults depart from them; the others are the paper's already */
    const sss_gl_param_value *paper;
    int paper_count;
    /* 1: the paper's configuration is Unity HDRP's shipped defaults, so preset=hdrp takes it too */
    int paper_is_hdrp;
    /* optional: how far (scene units) from where light enters object `object`'s surface the technique
     * carries it, with these parameters, at an output of width x height; NULL: across the whole object.
     * sss_gl_kernel_cut (support.c) warns when a material spreads half of its light farther. */
    double (*support)(const double *params, const sss_scene *scene, int object, int width, int height);
    /* NULL, or why the technique cannot run as a pass over a caller's frame (sss_gl_pass_create refuses
     * it with this reason): a technique that does not read the frame's inputs would ignore them */
    const char *not_a_pass;
} gl_technique;

/* Supports (support.c): Cauchy's mean chord 4 V / A of the object's world mesh (INFINITY when it has no
 * volume), the distance across the object light travels on average; the side of one pixel at the
 * object's centre, at width x height. */
double gl_object_mean_chord(const sss_scene *scene, int object);
double gl_object_pixel_size(const sss_scene *scene, int object, int width, int height);

/* materials_changed of a technique that derives nothing from materials at creation (its shaders read
 * the material records and LUTs at render time). */
sss_result gl_materials_read_at_render(const gl_tech_ctx *c, void *state, sss_error *err);

/* The registry (registry.c): a technique by name, NULL when there is none. */
const gl_technique *gl_technique_lookup(const char *name);

/* ---- One technique run by another (screen runs maisch2020; sam runs ssss or screen) -------------- */

typedef struct gl_sub_technique {
    const gl_technique *tech;
    void *state;
    double params[GL_MAX_PARAMS]; /* in tech's table order: set them before each call that reads them */
} gl_sub_technique;

/* sub->tech = tech with its defaults (no state yet). */
void gl_sub_init(gl_sub_technique *sub, const gl_technique *tech);
/* The callbacks of sub->tech in c, with sub's parameters (the caller's own stay in c). */
sss_result gl_sub_create(gl_sub_technique *sub, const gl_tech_ctx *c, sss_error *err);
sss_result gl_sub_resize(gl_sub_technique *sub, const gl_tech_ctx *c, sss_error *err);
sss_result gl_sub_render(gl_sub_technique *sub, const gl_tech_ctx *c, sss_error *err);
sss_result gl_sub_materials_changed(gl_sub_technique *sub, const gl_tech_ctx *c, sss_error *err);
void gl_sub_stats(gl_sub_technique *sub, const gl_tech_ctx *c, sss_gl_stats *out);
GLuint gl_sub_target(gl_sub_technique *sub, const char *name);
void gl_sub_destroy(gl_sub_technique *sub);

#endif
