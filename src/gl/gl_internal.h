/* gl/gl_internal.h — internals of the OpenGL renderer shared by its files and techniques.
 *
 * Frame structure (every technique): [animation happens in the vertex/compute shaders]
 *   shared passes, run by the renderer when the technique asks for them (gl_technique.needs):
 *     "gbuffer"      positions + projected pixel area, normals + object id, albedo + eta, depth
 *     "shadows"      cube maps (point lights, area-light VPLs), 2D maps (spot, directional, environment)
 *     "illumination" reflected radiance of the visible surface and transmitted irradiance F_t E
 *     "mipmaps"      area-weighted mip chains of positions/areas, irradiance/ids (and normals on request)
 *   then the technique's own passes, ending with a pass that writes the linear target frame.final;
 *   with supersampling (r->supersample = k > 1) all of the above run at k x the output size (r->width,
 *   r->height) and "resolve_ssaa" (ssaa.c) box-filters frame.final into the output image.
 * Binding points are fixed (GL_UBO_*, GL_SSBO_*, GL_UNIT_*) so shaders and C agree; see common.glsl.
 * The camera projection (u_proj) is reversed-Z with an infinite far plane: passes that rasterise with
 * it set glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE), clear depth to 0, test GL_GREATER, and restore
 * GL_NEGATIVE_ONE_TO_ONE afterwards (shadow maps use the standard convention).
 */
#ifndef SSS_GL_INTERNAL_H
#define SSS_GL_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include "sss/gl.h"
#include "sss/gl_pass.h"
#include "sss/kernel.h"
#include "sss/scene.h"

struct GLFWwindow;

struct sss_gl_context {
    const char *platform;
    char renderer[256], version[256];
    int software, debug, max_texture_size;
    int max_viewport[2];     /* GL_MAX_VIEWPORT_DIMS */
    char debug_message[512]; /* first KHR_debug error since the last gl_check */
    EGLDisplay egl_display;
    EGLContext egl_context;
    struct GLFWwindow *window;
    int glfw_initialised;
    /* sss_gl_context_adopt_current: the caller's context, never made current elsewhere nor destroyed
     * here; with EGL its display, context and surfaces are kept to make it current again. */
    int adopted;
    EGLSurface egl_draw, egl_read;
};

/* Reports a pending GL error (or KHR_debug message) as an error naming `what`. */
sss_result gl_check(sss_gl_context *ctx, const char *what, sss_error *err);

/* ---- Shader programs (shader.c) ------------------------------------------------------------- */

typedef struct gl_shader_stage {
    GLenum stage;
    const char *name; /* embedded file name, or the name of `text` */
    const char *text; /* NULL: the embedded file; else this source (tests) */
} gl_shader_stage;

/* Compiles and links; errors name the stage, the shader file and line ("x.glsl:12(5): error ..."). */
sss_result gl_program_build(const gl_shader_stage *stages, int count, const char *defines, GLuint *out,
                            sss_error *err);
sss_result gl_program_vf(const char *vert, const char *frag, const char *defines, GLuint *out, sss_error *err);
sss_result gl_program_compute(const char *comp, const char *defines, GLuint *out, sss_error *err);

/* ---- Timing (timing.c) ---------------------------------------------------------------------- */

typedef struct gl_timer {
    int enabled, use_queries;
    int count;
    const char *names[SSS_GL_MAX_PASSES];
    double ms[SSS_GL_MAX_PASSES];
    GLuint queries[SSS_GL_MAX_PASSES];
    double t0;
    int open; /* index of the pass being timed, -1 when none */
} gl_timer;

void gl_timer_init(gl_timer *t, int enabled, int software);
void gl_timer_free(gl_timer *t);
void gl_timer_frame_begin(gl_timer *t);
void gl_timer_begin(gl_timer *t, const char *name);
void gl_timer_end(gl_timer *t);
void gl_timer_frame_end(gl_timer *t); /* collects query results */

/* ---- GPU memory (gpu_memory.c) --------------------------------------------------------------
 * Every file that includes this header allocates and frees GL storage through these (the names of the
 * GL calls are redirected below), so the bytes of textures and buffers are counted at one place. */

void gl_mem_texture_storage_2d(GLuint t, GLsizei levels, GLenum format, GLsizei w, GLsizei h);
void gl_mem_texture_storage_3d(GLuint t, GLsizei levels, GLenum format, GLsizei w, GLsizei h, GLsizei d);
void gl_mem_buffer_storage(GLuint b, GLsizeiptr size, const void *data, GLbitfield flags);
void gl_mem_delete_textures(GLsizei n, const GLuint *t);
void gl_mem_delete_buffers(GLsizei n, const GLuint *b);
#undef glTextureStorage2D
#undef glTextureStorage3D
#undef glNamedBufferStorage
#undef glDeleteTextures
#undef glDeleteBuffers
#define glTextureStorage2D gl_mem_texture_storage_2d
#define glTextureStorage3D gl_mem_texture_storage_3d
#define glNamedBufferStorage gl_mem_buffer_storage
#define glDeleteTextures gl_mem_delete_textures
#define glDeleteBuffers gl_mem_delete_buffers

/* Bytes held now by this thread's textures and buffers (allocated minus freed). */
long long gl_mem_live(void);
/* Runs `call` and adds the bytes it allocated minus those it freed to `account` (a long long): how the
 * renderer keeps the technique's own and the shared frame targets' memory apart. */
#define GL_MEM_ACCOUNT(account, call)                                                                      \
    do {                                                                                                   \
        long long gl_mem_before_ = gl_mem_live();                                                          \
        call;                                                                                              \
        (account) += gl_mem_live() - gl_mem_before_;                                                       \
    } while (0)

/* ---- Binding points ------------------------------------------------------------------------- */

enum {
    GL_UBO_FRAME = 0,
    GL_SSBO_OBJECTS = 1,
    GL_SSBO_MATERIALS = 2,
    GL_SSBO_LIGHTS = 3,
    GL_SSBO_SPLATS = 4,
    GL_SSBO_SPLAT_COUNT = 5,
    GL_SSBO_MESH_POS = 6,
    GL_SSBO_MESH_IDX = 7,
    GL_SSBO_MESH_UV = 8,
    GL_SSBO_LUT_SCALES = 9
};
enum {
    GL_UNIT_LUT = 8,          /* sampler2DArray of the materials' LUTs */
    GL_UNIT_SHADOW_CUBE = 9,  /* samplerCubeArrayShadow */
    GL_UNIT_SHADOW_2D = 10,   /* sampler2DArrayShadow */
    GL_UNIT_ALBEDO = 11,      /* sampler2DArray of albedo textures */
    GL_UNIT_ENV = 12          /* sampler2D environment map */
};

/* ---- GPU scene (scene_gpu.c, lights.c) -------------------------------------------------------- */

enum { GL_LIGHT_POINT = 0, GL_LIGHT_SPOT = 1, GL_LIGHT_DIRECTIONAL = 2, GL_LIGHT_VPL = 3 };
/* direction.w of a directional light made from an environment map (median cut). */
#define GL_LIGHT_FROM_ENVIRONMENT 2.0f
enum { GL_SHADOW_NONE = 0, GL_SHADOW_CUBE = 1, GL_SHADOW_2D = 2 };

/* std430 records; layouts mirror common.glsl. */
typedef struct gl_object_record {
    float model[16];         /* column-major */
    float normal_matrix[16]; /* column-major, upper 3x3 used */
    float bounds_min[4];     /* w: animation type */
    float bounds_max[4];     /* w: amplitude */
    float anim[4];           /* x: period, y: material index, z: subsurface (1/0), w: has uv */
} gl_object_record;

typedef struct gl_material_record {
    float albedo[4]; /* rgb: diffuse reflectance, display albedo or emitted radiance; w: 0 subsurface,
                        1 diffuse, 2 emitter (spec.x: two-sided) */
    float params[4]; /* x: eta, y: c = 1 - 2 FM1(1/eta), z: LUT layer, w: albedo texture layer or -1 */
    float lut[4];    /* x: r_max, y: a_max, z: axes (0 linear, 1 sqrt), w: LUT size */
    float spec[4];   /* x: has specular, y: roughness, z: LUT levels (level l: r_max / 16^l),
                        w: splat reach (radius holding splat_energy of R_d, <= r_max) */
} gl_material_record;

typedef struct gl_light_record {
    float position[4];  /* xyz; w: type */
    float direction[4]; /* spot axis / direction travelled / VPL normal; w: two-sided (VPL) */
    float color[4];     /* intensity (W/sr) or radiance (directional: irradiance at normal incidence) */
    float spot[4];      /* x: cos total width, y: cos falloff start, z: shadow kind, w: shadow layer */
    float shadow_matrix[16]; /* 2D maps: world -> light clip space, column-major */
    float shadow[4];    /* x: near, y: far (cube: distances), z: world texel size at distance 1 (or
                           absolute for orthographic), w: 1 orthographic */
} gl_light_record;

/* The std430 layouts of common.glsl's Object, Material and Light: vec4 and mat4 members only, so
 * std430 packs them without padding; these tie the C records to that. */
_Static_assert(sizeof(gl_object_record) == 2 * 64 + 3 * 16, "gl_object_record != common.glsl Object (std430)");
_Static_assert(offsetof(gl_object_record, anim) == 160, "Object.anim offset");
_Static_assert(sizeof(gl_material_record) == 4 * 16, "gl_material_record != common.glsl Material (std430)");
_Static_assert(offsetof(gl_material_record, spec) == 48, "Material.spec offset");
_Static_assert(sizeof(gl_light_record) == 4 * 16 + 64 + 16, "gl_light_record != common.glsl Light (std430)");
_Static_assert(offsetof(gl_light_record, shadow_matrix) == 64 && offsetof(gl_light_record, shadow) == 128,
               "Light.shadow_matrix / Light.shadow offsets");

typedef struct gl_object {
    GLuint vao, pos, nrm, uv, idx;
    uint32_t vertex_count, triangle_count;
    int has_uv;
    GLuint splat_pos, splat_idx, splat_uv; /* the low-resolution splat mesh (object space, rest pose) */
    uint32_t splat_vertex_count, splat_triangle_count;
    int subsurface, material, animated;
    int emitter; /* an area light's visible rectangle (no shadows, no scattering) */
    double uploaded_matrix[16];        /* the transform and animation of the upload (material_update.c) */
    sss_animation uploaded_animation;
} gl_object;

typedef struct gl_material {
    int subsurface, lut_layer;
    double r_max, a_max;
    sss_lut_axes axes;
} gl_material;

typedef struct gl_scene {
    int object_count, material_count, light_count, vpl_count;
    gl_object *objects;
    gl_material *materials;
    gl_light_record *lights;      /* light_count records (VPLs included) */
    sss_light_type *light_kinds;  /* the scene's lights' types at the upload, recorded for every
                                     technique (lights built or not): update_lights keeps them */
    size_t light_kind_count;
    int shadow_cube_count, shadow_2d_count;
    GLuint ssbo_objects, ssbo_materials, ssbo_lights, ssbo_lut_scales;
    GLuint lut_array;             /* 2D array, RGBA32F, R'_d / lut_scales[layer]; `levels` layers per
                                     subsurface material (the cascade, scene_gpu.c) */
    int lut_size, lut_layers;
    GLuint albedo_array;          /* RGBA8 2D array with mips, or 0 */
    GLuint shadow_cube, shadow_2d;/* depth cube-map array / 2D array */
    int shadow_cube_size, shadow_2d_size;
    GLuint shadow_fbo;
    float bounds_min[3], bounds_max[3]; /* world bounds of all objects at rest */
    GLuint env_tex;               /* the first environment map (RGB32F), background of camera rays */
    float env_rotate_y, env_scale[3];
    struct gl_env_cache *env_cache; /* each environment map read once, downsampled (lights.c) */
    int env_cache_count;
    size_t texture_bytes, buffer_bytes, lut_bytes; /* lut_bytes: not in texture_bytes */
    int luts_precomputed;         /* materials whose LUT cascade came from sss_gl_renderer_desc.tables */
    size_t record_bytes;          /* the object and material records and LUT scales (not in buffer_bytes) */
    unsigned splat_total;
    int splats_ready;
} gl_scene;

/* ---- Screen-sized shared targets (frame.c) ---------------------------------------------------- */

typedef struct gl_frame {
    int width, height, levels;
    GLuint pos;      /* RGBA32F, mips: xyz world position (area-weighted mean), w: projected area (sum) */
    GLuint nrm;      /* RGBA16F: xyz normal, w: object id + 1 (0: background); mips when needed */
    GLuint albedo;   /* RGBA16F: rgb albedo (texture), a: eta */
    GLuint depth;    /* DEPTH_COMPONENT32F */
    GLuint irr;      /* RGBA32F, mips: level 0 rgb F_t E (sqrt albedo applied), w: object id + 1 */
    GLuint refl;     /* RGBA16F: directly reflected radiance */
    GLuint final;    /* RGBA32F: linear result */
    GLuint fbo_gbuffer, fbo_light, fbo_final;
    size_t bytes;    /* all of the above */
    int normal_mips;
    /* A pass in the caller's frame (gl_pass.h): pos, nrm, albedo, irr, refl and final are the caller's
     * textures of the current frame (never freed here); depth, fbo_gbuffer and fbo_light are 0;
     * fbo_final is ours, with the caller's output attached; black stands in for a missing refl. */
    int external;
    GLuint black;
} gl_frame;

/* ---- Techniques -------------------------------------------------------------------------------
 *
 * Adding a technique (the six planned ones: ssss, sam, mertens2003, dss, chen2012, screen):
 *  1. src/gl/<name>/tech_<name>.c defines `const gl_technique gl_technique_<name>` with its parameter table
 *     (name, type, default = the paper's, range, one-line doc citing the paper), the shared passes it
 *     needs (GL_NEED_*) and its callbacks; registry.c gets one line. Parameters are read with
 *     gl_param(r, index) at render time (set_param only stores them; resize() is called after a
 *     technique parameter changes and after the frame size changes).
 *  2. Shaders are src/gl/<name>/<name>_*.glsl with `#include "common.glsl"` (frame block, objects,
 *     materials, lights with shadows, Fresnel, animation, lut_eval of the kernel LUT, exit_factor).
 *  3. render() runs the technique's passes on the shared results of this frame and must end by
 *     writing the linear radiance of every pixel into frame.final (fbo_final), reflected light and
 *     background included (frame.refl holds them). Bracket each pass with gl_timer_begin/end and
 *     finish it with gl_check(r->ctx, "<technique>: <pass>", err).
 * Shared resources available in render():
 *  - frame.pos/nrm/albedo/depth (G-buffer; reversed-Z depth), frame.irr (F_t E with sqrt(albedo) and
 *    the object id), frame.refl (diffuse, emitters, specular, environment background); with
 *    GL_NEED_MIPS area-weighted premultiplied mip chains of pos and irr (and nrm with
 *    GL_NEED_NORMAL_MIPS), see gl_frame;
 *  - gs.shadow_cube / gs.shadow_2d through light_irradiance() in any shader stage (compute too), so a
 *    technique can light its own sample points (splats, texture-space atlases, shadow-map texels);
 *  - gs.objects[i].splat_pos/splat_idx (GL_NEED_SPLAT_MESHES): the low-resolution splat mesh in
 *    object space at rest; deform with anim_deform() in the shader like maisch2020_splat_generate.comp.glsl;
 *  - the kernel LUT of every subsurface material (lut_info/lut_eval) and the materials' records;
 *  - gl_draw_objects() to rasterise the scene with the caller's program (u_object uniform), and
 *    gl_draw_fullscreen() for screen passes. */

#define GL_NEED_GBUFFER 1u
#define GL_NEED_SHADOWS 2u
#define GL_NEED_ILLUMINATION 4u
#define GL_NEED_MIPS 8u
#define GL_NEED_NORMAL_MIPS 16u
#define GL_NEED_SPLAT_MESHES 32u
/* The technique's own shaders read lights and shadow maps (not only the illumination pass): as a pass
 * in a caller's frame (gl_pass.h) it then renders its own shadow maps of the registered meshes. */
#define GL_NEED_LIGHTS 64u

#define GL_MAX_PARAMS 48

typedef struct gl_technique {
    sss_gl_technique_info info;
    unsigned needs;
    size_t state_size; /* zeroed state passed to every callback */
    sss_result (*create)(sss_gl_renderer *r, void *state, sss_error *err);
    sss_result (*resize)(sss_gl_renderer *r, void *state, sss_error *err); /* after frame targets change */
    sss_result (*render)(sss_gl_renderer *r, void *state, sss_error *err); /* writes frame.final */
    void (*destroy)(sss_gl_renderer *r, void *state);
    /* after sss_gl_renderer_update_materials re-uploaded the material records and LUTs (same meshes and
     * subsurface objects): refresh what create() derived from materials. NULL: destroy + create. */
    sss_result (*materials_changed)(sss_gl_renderer *r, void *state, sss_error *err);
    /* optional: CPU-only data of the technique for r->scene under r's parameters, made by
     * sss_gl_tables_build without GL (any thread; r holds the scene, data_file and parameters only).
     * create() and materials_changed() find it with gl_tables_technique_data. */
    sss_result (*tables_build)(const sss_gl_renderer *r, void **out, sss_error *err);
    void (*tables_free)(void *data);
    /* optional: intermediate buffers by name (sss_gl_renderer_read_buffer), statistics */
    GLuint (*buffer)(sss_gl_renderer *r, void *state, const char *name);
    void (*stats)(sss_gl_renderer *r, void *state, sss_gl_stats *out);
    /* preset=paper: the published values of the parameters (technique or shared, by name) whose
     * defaults depart from them; the others are the paper's already */
    const sss_gl_param_value *paper;
    int paper_count;
    /* NULL, or why the technique cannot run as a pass over a caller's frame (sss_gl_pass_create refuses
     * it with this reason): a technique that does not read the frame's inputs would ignore them */
    const char *not_a_pass;
} gl_technique;

/* A technique that another one runs in place (screen runs maisch2020; sam runs ssss or screen for the
 * front side): its callbacks with the parameter values passed explicitly, one per entry of
 * tech->info.params in that order, so the caller keeps values of its own and the renderer's params stay
 * those of the technique it was created with. The state is tech->state_size zeroed bytes. */
typedef struct gl_inner_technique {
    const gl_technique *tech;
    sss_result (*create)(sss_gl_renderer *r, void *state, const double *params, sss_error *err);
    sss_result (*resize)(sss_gl_renderer *r, void *state, const double *params, sss_error *err);
    sss_result (*render)(sss_gl_renderer *r, void *state, const double *params, sss_error *err);
    void (*stats)(sss_gl_renderer *r, void *state, const double *params, sss_gl_stats *out);
    void (*destroy)(sss_gl_renderer *r, void *state);
    GLuint (*buffer)(sss_gl_renderer *r, void *state, const char *name);
    /* as gl_technique's; NULL: it derives nothing from materials at creation */
    sss_result (*materials_changed)(sss_gl_renderer *r, void *state, const double *params, sss_error *err);
} gl_inner_technique;

extern const gl_inner_technique gl_inner_maisch2020, gl_inner_ssss, gl_inner_screen;

/* The registry (registry.c). */
const gl_technique *gl_technique_lookup(const char *name);
/* Values for `to`'s parameter table: its defaults, then the value of every parameter of `from` with the
 * same name (from_values in from's table order; from may be NULL). */
void gl_params_by_name(const sss_gl_technique_info *to, double *to_values, const sss_gl_technique_info *from,
                       const double *from_values);
/* Sets parameter `name` of `info`'s table in values (no change when the table has no such parameter). */
void gl_params_set(const sss_gl_technique_info *info, double *values, const char *name, double value);

/* Shared parameter indices (params.c); values in r->shared[]. */
enum {
    GL_P_SHADOW_2D_SIZE = 0,
    GL_P_SHADOW_CUBE_SIZE,
    GL_P_SHADOW_VPL_SIZE,
    GL_P_SHADOW_BIAS,
    GL_P_AREA_SAMPLES,
    GL_P_ENV_LIGHTS,
    GL_P_LUT_SIZE,
    GL_P_LUT_AXES,
    GL_P_LUT_CUTOFF,
    GL_P_LUT_ENERGY,
    GL_P_SPLAT_TRIANGLES,
    GL_P_LUT_LEVELS,
    GL_P_SPLAT_ENERGY,
    GL_P_PRESET, /* not stored as a setting: applying it sets the others (renderer.c) */
    GL_P_SHARED_COUNT
};

struct sss_gl_renderer {
    sss_gl_context *ctx;
    const sss_scene *scene;
    const gl_technique *tech;
    void *tech_state;
    const sss_gl_tables *tables;   /* sss_gl_renderer_desc.tables while sss_gl_renderer_create runs, else NULL */
    const char *data_file;         /* sss_gl_renderer_desc.data_file (may be NULL) */
    double params[GL_MAX_PARAMS];  /* technique parameters, in info.params order */
    double shared[GL_P_SHARED_COUNT];
    int width, height;             /* the size every pass renders at: the output size x supersample */
    int supersample;               /* SSAA factor k >= 1 (sss_gl_renderer_desc.supersample) */
    int out_width, out_height;     /* the output size (read back, presented) */
    GLuint prog_ssaa, ssaa_tex, ssaa_fbo; /* the k x k box filter into the output image (ssaa.c) */
    size_t ssaa_bytes;
    /* GPU bytes held by the technique's own textures and buffers, and by the shared frame targets and
     * the SSAA output, counted at the GL calls (gpu_memory.c) around every call that makes or frees them */
    long long tech_gpu_bytes, frame_gpu_bytes;
    double time;
    gl_scene gs;
    gl_frame frame;
    gl_timer timer;
    GLuint ubo_frame;
    GLuint prog_gbuffer, prog_shadow, prog_illum, prog_reduce, prog_present, vao_empty;
    int frame_rendered;
    int scene_dirty;    /* parameters changed that rebuild scene resources */
    float view[16], proj[16], view_proj[16];
    double near_plane, far_plane;
    unsigned splat_drawn;
};

/* Technique parameter by index (as declared in the technique's table). */
static inline double gl_param(const sss_gl_renderer *r, int i) { return r->params[i]; }

/* The SSAA factor k: r->width x r->height are k x the output size, so a length of p output pixels is
 * k p render pixels. Techniques scale parameters counted in pixels (pattern sizes, resolution divisors)
 * by it, so that supersampling changes the sampling density, not the image (docs/supersampling.md). */
static inline int gl_supersample(const sss_gl_renderer *r) { return r->supersample > 1 ? r->supersample : 1; }

/* ssaa.c: supersampling antialiasing. */
/* Checks a factor (1..SSS_GL_MAX_SUPERSAMPLE) and the render size it gives for an output size. */
sss_result gl_ssaa_check(const sss_gl_context *ctx, int width, int height, int k, sss_error *err);
/* (Re)creates the output image and its framebuffer for r->out_width x r->out_height when k > 1 (the
 * program is built on first use); frees them when k = 1. */
sss_result gl_ssaa_resize(sss_gl_renderer *r, sss_error *err);
void gl_ssaa_free(sss_gl_renderer *r);
/* The box filter frame.final -> the output image (no-op when k = 1), timed as "resolve_ssaa". */
sss_result gl_ssaa_resolve(sss_gl_renderer *r, sss_error *err);
/* The output-size linear image: the resolved one, or frame.final when k = 1. */
GLuint gl_output_texture(const sss_gl_renderer *r);

/* scene_gpu.c */
sss_result gl_scene_upload(sss_gl_renderer *r, sss_error *err);
/* The materials part again (records, LUT cascades) over the meshes already uploaded, into a gl_scene
 * whose material part is empty (0 handles, NULL materials): the scene's objects must have the meshes,
 * subsurface flags and textures of the upload (material_update.c checks). */
sss_result gl_scene_update_materials(sss_gl_renderer *r, sss_error *err);
void gl_scene_free_materials(gl_scene *gs); /* records, LUT array and scales */
/* A subsurface material's kernel LUT cascade ready for upload: `levels` layers of size^2 RGBA32F texels
 * holding R'_d / scales[layer] (alpha 0); r_max, a_max and axes of the first, widest level. */
typedef struct gl_lut_cascade {
    int size, levels;
    double r_max, a_max;
    sss_lut_axes axes;
    float *rgba;   /* levels x size x size x 4 */
    float *scales; /* levels */
} gl_lut_cascade;
/* The cascade of m under r's LUT parameters (Maisch & Ropinski 2020, section 7.1); CPU only. */
sss_result gl_lut_cascade_build(const sss_gl_renderer *r, const sss_scene_material *m, gl_lut_cascade *out,
                                sss_error *err);
void gl_lut_cascade_free(gl_lut_cascade *c);
/* tables.c: the cascade of m precomputed in t under r's LUT parameters (owned by t), or NULL when t is
 * NULL or has none (the caller computes it). */
const gl_lut_cascade *gl_tables_find(const sss_gl_tables *t, const sss_gl_renderer *r, const sss_scene_material *m);
/* The technique's data in t (tables_build) when t was built for r's technique, scene object, data file
 * and parameter values; NULL otherwise. */
const void *gl_tables_technique_data(const sss_gl_tables *t, const sss_gl_renderer *r);
/* renderer.c: the technique a desc names (else the scene's), and r->params / r->shared from its
 * defaults, the preset and desc.params (r->tech set); no GL. */
sss_result gl_technique_for(const sss_scene *scene, const sss_gl_renderer_desc *desc, const gl_technique **out,
                            sss_error *err);
sss_result gl_params_from_desc(sss_gl_renderer *r, const sss_gl_renderer_desc *desc, sss_error *err);
/* renderer.c: the technique's state, created with the scene already uploaded, and destroyed. */
sss_result gl_runtime_technique_create(sss_gl_renderer *r, sss_error *err);
void gl_runtime_technique_destroy(sss_gl_renderer *r);
/* materials_changed of a technique that derives nothing from materials at creation (its shaders read
 * the material records and LUTs at render time). */
sss_result gl_materials_read_at_render(sss_gl_renderer *r, void *state, sss_error *err);
sss_result gl_scene_prepare_splats(sss_gl_renderer *r, sss_error *err); /* splat meshes on demand */
void gl_scene_free(gl_scene *gs);
/* textures.c: albedo textures as one RGBA16F array (common size, bilinear resampling, mipmapped);
 * count 0 makes a 1x1 white layer so the sampler is always complete. */
sss_result gl_albedo_upload(gl_scene *gs, const sss_scene_texture *textures, size_t count, sss_error *err);
void gl_bind_scene(const sss_gl_renderer *r); /* SSBOs, LUT, shadow and albedo samplers */
/* lights.c */
sss_result gl_lights_build(sss_gl_renderer *r, sss_error *err);
/* Rewrites the light records from the scene's lights (same count, kinds and shadow slots). */
sss_result gl_lights_update(sss_gl_renderer *r, sss_error *err);
sss_result gl_lights_record_kinds(sss_gl_renderer *r, sss_error *err);
/* The scene's lights against gs.light_kinds: the same number and types, else INVALID_ARGUMENT naming
 * what changed (every technique: a pass that lights nothing itself builds no light records). */
sss_result gl_lights_check_kinds(const sss_gl_renderer *r, sss_error *err);
void gl_env_cache_free(gl_scene *gs); /* the environment maps read by gl_lights_build */
sss_result gl_shadows_render(sss_gl_renderer *r, sss_error *err);
/* frame.c */
/* The camera of one frame: matrices (column-major; proj reversed-Z with an infinite far plane, as
 * every pass rasterises with it) and what the frame block derives from them. */
typedef struct gl_camera {
    float view[16], proj[16];
    double position[3], forward[3];
    double near_plane;
    double pixel_size; /* image-plane size of one pixel at distance 1 */
} gl_camera;
/* The scene camera's at the render size (far plane beyond the scene bounds). */
void gl_camera_from_scene(sss_gl_renderer *r, gl_camera *c);
/* The caller's matrices (gl_pass.h conventions); 0 when proj is not a perspective projection. */
int gl_camera_from_matrices(const float view[16], const float proj[16], int height, gl_camera *c);
/* Writes the frame block (common.glsl FrameBlock) for camera c and binds it. */
void gl_frame_ubo_write(sss_gl_renderer *r, const gl_camera *c);
size_t gl_frame_ubo_size(void); /* bytes of the frame block (the UBO is created with it) */
sss_result gl_frame_create_external(gl_frame *f, int width, int height, int normal_mips, sss_error *err);
sss_result gl_frame_create(gl_frame *f, int width, int height, int normal_mips, sss_error *err);
void gl_frame_free(gl_frame *f);
sss_result gl_pass_gbuffer(sss_gl_renderer *r, sss_error *err);
sss_result gl_pass_illumination(sss_gl_renderer *r, sss_error *err);
sss_result gl_pass_mipmaps(sss_gl_renderer *r, sss_error *err);
/* Draws every object (G-buffer style vertex stage must be bound); mask: 1 subsurface only, 2 all. */
void gl_draw_objects(sss_gl_renderer *r, GLint object_uniform, int subsurface_only);
void gl_draw_fullscreen(sss_gl_renderer *r);
/* Runs the bound compute program prog (local size 64) once per triangle of every subsurface object's
 * splat mesh: binds the mesh SSBOs, sets u_has_uv, u_object, u_triangles; ends with a barrier for
 * storage and indirect-command reads (maisch2020's splats, dss's surfels). */
void gl_dispatch_splat_triangles(sss_gl_renderer *r, GLuint prog);

/* Texture helpers: allocate immutable storage, set nearest/clamp sampling, count bytes. */
GLuint gl_texture_2d(GLenum format, int width, int height, int levels, size_t *bytes);
size_t gl_format_bytes(GLenum format);
int gl_mip_levels(int width, int height);

/* Reads an RGBA float texture level into an RGB image (created here). */
sss_result gl_read_texture_rgb(GLuint tex, int level, int width, int height, sss_image *out, sss_error *err);

/* ---- The pass over a G-buffer (pass.c, pass_state.c) ------------------------------------------ */

/* Creates the runtime of a technique (scene resources, programs, technique state); external: the frame
 * inputs are the caller's (gl_pass.h), else the renderer's own targets. */
sss_result gl_runtime_create(sss_gl_context *ctx, const sss_scene *scene, const sss_gl_renderer_desc *desc,
                             int external, sss_gl_renderer **out, sss_error *err);
/* One frame through the technique: rebuilds scene resources after parameter changes, writes the frame
 * block for cam, then the shared passes the frame needs (G-buffer and illumination only for the
 * renderer's own targets), the mip chains, the technique, the SSAA resolve. Shared by
 * sss_gl_renderer_render and sss_gl_pass_execute. */
/* Rebuilds the scene resources and the technique after a scene-level change (r->scene_dirty). */
sss_result gl_runtime_rebuild_if_dirty(sss_gl_renderer *r, sss_error *err);
sss_result gl_frame_run(sss_gl_renderer *r, const gl_camera *cam, double time, sss_error *err);

#define GL_PASS_TEXTURE_TARGETS 5
#define GL_PASS_GENERIC_BUFFERS 8
#define GL_PASS_CAPABILITIES 23
#define GL_PASS_PIXEL_STORE 24
#define GL_PASS_INDEXED 16 /* draw buffers, viewports and clip distances saved (at most) */
typedef struct gl_pass_state {
    GLint draw_fbo, read_fbo, program, vertex_array;
    GLboolean enabled[GL_PASS_CAPABILITIES], depth_mask;
    GLint depth_func, clip_control[2], polygon_mode[2], cull_face, front_face, provoking_vertex, derivative_hint;
    GLint pixel_store[GL_PASS_PIXEL_STORE];
    GLfloat polygon_offset[2];
    /* indexed state: per draw buffer, per viewport, per clip distance (counts: this GL's, capped) */
    int draw_buffers, viewports, clip_distances;
    GLboolean blend[GL_PASS_INDEXED], color_mask[GL_PASS_INDEXED][4];
    GLint blend_func[GL_PASS_INDEXED][6]; /* src rgb, dst rgb, src alpha, dst alpha, equation rgb, alpha */
    GLboolean scissor[GL_PASS_INDEXED], clip_distance[GL_PASS_INDEXED];
    GLfloat viewport[GL_PASS_INDEXED][4];
    GLdouble depth_range[GL_PASS_INDEXED][2];
    GLint active_texture;
    GLint texture[SSS_GL_PASS_TEXTURE_UNITS][GL_PASS_TEXTURE_TARGETS], sampler[SSS_GL_PASS_TEXTURE_UNITS];
    GLint image[SSS_GL_PASS_IMAGE_UNITS][6]; /* name, level, layered, layer, access, format */
    GLint indexed_buffer[2][SSS_GL_PASS_BUFFER_BINDINGS]; /* uniform, shader storage */
    GLint64 indexed_start[2][SSS_GL_PASS_BUFFER_BINDINGS], indexed_size[2][SSS_GL_PASS_BUFFER_BINDINGS];
    GLint generic_buffer[GL_PASS_GENERIC_BUFFERS];
} gl_pass_state;
void gl_pass_state_save(gl_pass_state *s);
void gl_pass_state_restore(const gl_pass_state *s);
/* The GL state the passes assume (the list in sss/gl_pass.h and docs/integration.md: the GL defaults,
 * no sampler objects, pixel or query buffers), set after saving the caller's. */
void gl_pass_state_defaults(void);

#endif
