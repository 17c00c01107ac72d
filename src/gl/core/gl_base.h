/* gl/core/gl_base.h — the GL vocabulary every part of the real-time renderer shares: the context, shader
 * programs, pass timing, GPU memory accounting, the fixed binding points, the GPU scene's records and the
 * screen-sized frame targets, texture helpers. The core (gl_core.h) owns these objects; techniques
 * (technique.h) see them read-only through their context.
 *
 * Binding points are fixed (GL_UBO_*, GL_SSBO_*, GL_UNIT_*) so shaders and C agree; see common.glsl.
 * The camera projection (u_proj) is reversed-Z with an infinite far plane: passes that rasterise with
 * it set glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE), clear depth to 0, test GL_GREATER, and restore
 * GL_NEGATIVE_ONE_TO_ONE afterwards (shadow maps use the standard convention).
 */
#ifndef SSS_GL_BASE_H
#define SSS_GL_BASE_H

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
    GL_SSBO_LUT_SCALES = 9,
    GL_SSBO_BOUNCE_TRIANGLES = 10, /* interreflection.c */
    GL_SSBO_BOUNCE_SOURCES = 11,
    GL_SSBO_BOUNCE_VPLS = 12,
    GL_SSBO_BOUNCE_TRANSMIT = 13
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

/* The material part of a GPU scene: built whole for a scene (scene_gpu.c) and put in place of the old
 * one, so that a material update that fails leaves the scene as it was. */
typedef struct gl_scene_materials {
    int count;
    gl_material *items;
    int *of_object;               /* per object (emitters included): its material */
    GLuint ssbo_objects, ssbo_materials, ssbo_lut_scales;
    GLuint ssbo_transmit;         /* per material: 1 - 2 FM1(eta), the transmittance of a subsurface
                                     surface for a diffuse incident field (interreflection.c); 0 on others */
    GLuint lut_array;             /* 2D array, RGBA32F, R'_d / lut_scales[layer]; `levels` layers per
                                     subsurface material (the cascade, scene_gpu.c) */
    int lut_size, lut_layers;
    size_t lut_bytes;             /* not in gl_scene.texture_bytes */
    size_t record_bytes;          /* the object and material records and LUT scales (not in buffer_bytes) */
    int luts_precomputed;         /* materials whose LUT cascade came from sss_gl_renderer_desc.tables */
} gl_scene_materials;

typedef struct gl_scene {
    int object_count, light_count, vpl_count;
    gl_object *objects;
    gl_scene_materials mat;
    gl_light_record *lights;      /* light_count records (VPLs included) */
    sss_light_type *light_kinds;  /* the scene's lights' types at the upload, recorded for every
                                     technique (lights built or not): update_lights keeps them */
    size_t light_kind_count;
    int shadow_cube_count, shadow_2d_count;
    GLuint ssbo_lights;
    GLuint albedo_array;          /* RGBA8 2D array with mips, or 0 */
    GLuint shadow_cube, shadow_2d;/* depth cube-map array / 2D array */
    int shadow_cube_size, shadow_2d_size;
    GLuint shadow_fbo;
    float bounds_min[3], bounds_max[3]; /* world bounds of all objects (animation included) */
    GLuint env_tex;               /* the first environment map (RGB32F), background of camera rays */
    float env_rotate_y, env_scale[3];
    struct gl_env_cache *env_cache; /* each environment map read once, downsampled (lights.c) */
    int env_cache_count;
    size_t texture_bytes, buffer_bytes;
    unsigned splat_total;
    int splats_ready;
    GLuint bounce_tris, bounce_sources, bounce_vpls; /* interreflection.c: triangles, lit, emitting */
    int bounce_count, bounce_ready;
} gl_scene;

/* ---- Screen-sized shared targets (frame.c) ---------------------------------------------------- */

typedef struct gl_frame {
    int width, height, levels;
    GLuint pos;      /* RGBA32F, mips: xyz world position (area-weighted mean), w: projected area (sum) */
    GLuint nrm;      /* RGBA32F: xyz normal, w: object id + 1 (0: background); mips when needed */
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

/* ---- What a frame provides ---------------------------------------------------------------------- */

/* What a frame reads (gl_technique.reads): the core and its clients make only what is read. */
#define GL_READ_POSITION 1u       /* frame.pos: world position, projected pixel area in w */
#define GL_READ_NORMAL 2u         /* frame.nrm: normal, object id + 1 in w */
#define GL_READ_ALBEDO 4u         /* frame.albedo: albedo (texture), eta in a */
#define GL_READ_DEPTH 8u          /* frame.depth (the renderer's own frame only) */
#define GL_READ_IRRADIANCE 16u    /* frame.irr: F_t E with sqrt(albedo), object id + 1 in w */
#define GL_READ_REFLECTED 32u     /* frame.refl: reflected light, emitters, background */
#define GL_READ_MIPS 64u          /* area-weighted mip chains of frame.pos and frame.irr */
#define GL_READ_NORMAL_MIPS 128u  /* and of frame.nrm */
#define GL_READ_LIGHTS 256u       /* light records and shadow maps in the technique's own shaders: as a pass
                                     in a caller's frame it renders its own shadow maps of the scene's meshes */
#define GL_READ_SPLAT_MESHES 512u /* the low-resolution splat meshes (gl_object.splat_*) */
#define GL_READ_GBUFFER (GL_READ_POSITION | GL_READ_NORMAL | GL_READ_ALBEDO)
#define GL_READ_ILLUMINATION (GL_READ_IRRADIANCE | GL_READ_REFLECTED)

/* ---- The camera of a frame (frame.c) ----------------------------------------------------------- */

/* Matrices (column-major; proj reversed-Z with an infinite far plane, as every pass rasterises with it)
 * and what the frame block derives from them. */
typedef struct gl_camera {
    float view[16], proj[16];
    double position[3], forward[3];
    double near_plane;
    double pixel_size; /* image-plane size of one pixel at distance 1 */
} gl_camera;

/* What one frame is drawn with: its camera, the matrices the frame block holds, and its time. */
typedef struct gl_view {
    gl_camera camera;
    float view_proj[16];
    double time;
} gl_view;

/* ---- Texture and draw helpers (frame.c) -------------------------------------------------------- */

/* Allocates immutable storage with nearest/clamp sampling; adds its bytes to *bytes (may be NULL). */
GLuint gl_texture_2d(GLenum format, int width, int height, int levels, size_t *bytes);
size_t gl_format_bytes(GLenum format);
int gl_mip_levels(int width, int height);
/* A framebuffer with `count` colour attachments (drawn in that order) and an optional depth texture. */
GLuint gl_framebuffer(const GLuint *color, int count, GLuint depth);
/* A full-screen triangle with an empty vertex array (the bound program's fragment stage covers every
 * pixel of the viewport). */
void gl_fullscreen_triangle(GLuint vao_empty);
/* Draws every object of gs with the bound program (a G-buffer-style vertex stage; the object index in
 * the uniform `object_uniform`); subsurface_only: skip the others. */
void gl_scene_draw_objects(const gl_scene *gs, GLint object_uniform, int subsurface_only);
/* Area-weighted mip chains of frame.pos and frame.irr (and frame.nrm when it has mips) with the
 * mip_reduce program `prog` (also a technique's after it changed level 0: maisch2020's grazing areas). */
sss_result gl_frame_mipmaps(sss_gl_context *ctx, const gl_frame *f, GLuint prog, sss_error *err);
/* Reads an RGBA float texture level into an RGB image (created here). */
sss_result gl_read_texture_rgb(GLuint tex, int level, int width, int height, sss_image *out, sss_error *err);

#endif
