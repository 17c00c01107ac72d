/* gl/core/gl_core.h — the GL core: one object that owns what every frame is drawn with — the GPU scene
 * (meshes, materials with their kernel LUTs, lights with their shadow maps), the frame targets (its own,
 * or slots for a caller's textures), the frame block, the pass timer and the supersampled output — for
 * its two clients: the renderer (renderer.c, which fills the frame with its own G-buffer and
 * illumination) and the pass (pass.c, which points it at the caller's G-buffer). Both reach the technique
 * through the runtime (runtime.h); techniques never see the core (technique.h gives them a narrow
 * context instead).
 *
 * Frame structure (every technique): [animation happens in the vertex/compute shaders]
 *   passes of the frame, run when the technique reads what they make (gl_technique.reads):
 *     "gbuffer"      positions + projected pixel area, normals + object id, albedo + eta, depth (renderer)
 *     "shadows"      cube maps (point lights, area-light VPLs), 2D maps (spot, directional, environment)
 *     "illumination" reflected radiance of the visible surface and transmitted irradiance F_t E (renderer)
 *     "mipmaps"      area-weighted mip chains of positions/areas, irradiance/ids (and normals on request)
 *   then the technique's own passes, ending with a pass that writes the linear target frame.final;
 *   with supersampling (k > 1) all of the above run at k x the output size and "resolve_ssaa" (ssaa.c)
 *   box-filters frame.final into the output image.
 */
#ifndef SSS_GL_CORE_H
#define SSS_GL_CORE_H

#include "gl/core/gl_base.h"

/* ---- Shared parameters (registry.c's table; values in gl_core.shared) --------------------------- */

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
    GL_P_INTERREFLECTION,
    GL_P_INTERREFLECTION_SOURCES,
    GL_P_INTERREFLECTION_ROWS,
    GL_P_INTERREFLECTION_BOUNCES,
    GL_P_PRESET, /* not stored as a setting: applying it sets the others (runtime.c) */
    GL_P_SHARED_COUNT
};

/* ---- The core ------------------------------------------------------------------------------------ */

/* The interreflection stage's programs and its reduced-resolution target (interreflection.c); the
 * sources it lights live in the GPU scene (gl_scene.bounce_*). */
typedef struct gl_bounce {
    GLuint prog_sources, prog_exitance, prog_relight, prog_gather, prog_apply;
    GLuint tex, tex_plane, fbo; /* RGBA32F, ceil(width / stride) x ceil(height / stride): gathered irradiance,
                                   and the gathered points' tangent planes for the upsampling */
    int width, height, stride;
    size_t bytes;
} gl_bounce;

typedef struct gl_core {
    sss_gl_context *ctx;
    const sss_scene *scene;
    unsigned reads;                    /* GL_READ_* of the technique it serves */
    int external;                      /* the frame's inputs are a caller's textures (a pass) */
    double shared[GL_P_SHARED_COUNT];  /* the shared parameters' values */
    const struct gl_lut_set *luts;     /* LUT cascades computed ahead, while a scene is uploaded; else NULL */
    int width, height;                 /* the size every pass renders at: the output size x supersample */
    int supersample;                   /* SSAA factor k >= 1 */
    int out_width, out_height;         /* the output size (read back, presented) */
    gl_scene gs;
    gl_frame frame;
    gl_timer timer;
    gl_view view;                      /* the frame being drawn */
    double far_plane;                  /* the scene camera's (gl_core_scene_camera) */
    GLuint ubo_frame, vao_empty, prog_shadow, prog_reduce;
    GLuint prog_ssaa, ssaa_tex, ssaa_fbo; /* the k x k box filter into the output image (ssaa.c) */
    size_t ssaa_bytes;
    long long frame_gpu_bytes;         /* GPU bytes of the frame targets and the SSAA output */
    gl_bounce bounce;                  /* the interreflection stage (built on first use) */
} gl_core;

/* core.c: sets the sizes, parameters and timer of a core (no GL; k >= 1 checked by the caller). */
void gl_core_init(gl_core *core, sss_gl_context *ctx, const sss_scene *scene, unsigned reads, int external,
                  int width, int height, int k, int timings);
/* Programs, frame block, scene upload (with LUT cascades from `luts` where it has them; may be NULL),
 * frame targets, SSAA output. */
sss_result gl_core_create_gl(gl_core *core, const struct gl_lut_set *luts, sss_error *err);
void gl_core_free(gl_core *core);
/* The GPU scene of `scene` (the core's own after a scene-level parameter changed, or a new one) built
 * beside the current one, then put in its place with core->scene = scene; on failure the core keeps
 * what it had. */
sss_result gl_core_rebuild_scene(gl_core *core, const sss_scene *scene, sss_error *err);
/* New output size and SSAA factor (already checked): the frame targets and the output image. */
sss_result gl_core_resize(gl_core *core, int width, int height, int k, sss_error *err);
/* The scene camera's at the render size (far plane beyond the scene bounds). */
void gl_core_scene_camera(gl_core *core, gl_camera *c);
/* Starts a frame: the frame block for camera c at time (grazing_cutoff: Eq. 8's cut-off of the
 * technique, Maisch & Ropinski 2020), the scene bound to its units, the timer's frame begun. */
void gl_core_frame_begin(gl_core *core, const gl_camera *c, double time, double grazing_cutoff);
/* The frame's shared passes: shadow maps, mip chains (timed as "shadows", "mipmaps"). */
sss_result gl_core_shadows(gl_core *core, sss_error *err);
sss_result gl_core_mipmaps(gl_core *core, sss_error *err);
/* The output-size linear image: the resolved one, or frame.final when k = 1. */
GLuint gl_core_output(const gl_core *core);

/* ---- Light between surfaces (interreflection.c) --------------------------------------------------- */

/* 1 when the renderer's frame adds the interreflection stage (the parameter is on and the technique
 * reads the illumination pass, which the stage adds to). */
int gl_bounce_enabled(const gl_core *core);
/* After the illumination pass: lights the scene's bounce sources (shadow maps included), scatters the
 * subsurface ones' light to their exitance, gathers the one-bounce irradiance at every `stride`-th
 * pixel and adds it, upsampled, to frame.irr (subsurface receivers) and frame.refl (diffuse ones).
 * Timed as "bounce_sources", "bounce_gather" and "bounce_apply". Builds what it needs on first use. */
sss_result gl_bounce_frame(gl_core *core, sss_error *err);
void gl_bounce_free(gl_bounce *b);
/* The sources of the GPU scene (gl_scene.bounce_*) for the budget `count`: triangles of each object's
 * surface (CPU; scene_gpu.c frees them with the scene). */
sss_result gl_scene_prepare_bounce(gl_core *core, sss_error *err);

/* ---- Frame targets and passes (frame.c) ---------------------------------------------------------- */

sss_result gl_frame_create(gl_frame *f, int width, int height, int normal_mips, sss_error *err);
/* The slots of a caller's frame (gl_pass.h): fbo_final with nothing attached, a black `refl`. */
sss_result gl_frame_create_external(gl_frame *f, int width, int height, int normal_mips, sss_error *err);
void gl_frame_free(gl_frame *f);
/* The caller's matrices (gl_pass.h conventions); 0 when proj is not a perspective projection. */
int gl_camera_from_matrices(const float view[16], const float proj[16], int height, gl_camera *c);
size_t gl_frame_ubo_size(void); /* bytes of the frame block (the UBO is created with it) */
/* Writes the frame block (common.glsl FrameBlock) for camera c at time and keeps them in core->view. */
void gl_frame_ubo_write(gl_core *core, const gl_camera *c, double time, double grazing_cutoff);

/* ---- GPU scene (scene_gpu.c, lut_cascade.c, lights.c, textures.c) -------------------------------------- */

sss_result gl_scene_upload(gl_core *core, sss_error *err);
/* The material part again (records, LUT cascades) for `scene`, whose objects have the meshes, subsurface
 * flags and textures of the upload (material_update.c checks): built whole, then put in place of the
 * old one, which stays as it was when the build fails. core->scene is not changed. */
sss_result gl_scene_update_materials(gl_core *core, const sss_scene *scene, sss_error *err);
sss_result gl_scene_prepare_splats(gl_core *core, sss_error *err); /* splat meshes on demand */
void gl_scene_free(gl_scene *gs);
void gl_scene_bind(const gl_core *core); /* frame block, SSBOs, LUT, shadow and albedo samplers */
/* textures.c: albedo textures as one RGBA16F array (common size, bilinear resampling, mipmapped);
 * count 0 makes a 1x1 white layer so the sampler is always complete. */
sss_result gl_albedo_upload(gl_scene *gs, const sss_scene_texture *textures, size_t count, sss_error *err);

/* A subsurface material's kernel LUT cascade ready for upload: `levels` layers of size^2 RGBA32F texels
 * holding R'_d / scales[layer] (alpha 0); r_max, a_max and axes of the first, widest level. */
typedef struct gl_lut_cascade {
    int size, levels;
    double r_max, a_max;
    sss_lut_axes axes;
    float *rgba;   /* levels x size x size x 4 */
    float *scales; /* levels */
} gl_lut_cascade;
/* The cascade of m under the shared LUT parameters `shared` (Maisch & Ropinski 2020, section 7.1); CPU
 * only. */
sss_result gl_lut_cascade_build(const double *shared, const sss_scene_material *m, gl_lut_cascade *out,
                                sss_error *err);
void gl_lut_cascade_free(gl_lut_cascade *c);
/* lut_cascade.c: cascades computed ahead (sss_gl_tables holds one set), found by what they depend on. */
typedef struct gl_lut_key gl_lut_key;
typedef struct gl_lut_set {
    int count;
    gl_lut_key *keys;
    gl_lut_cascade *cascades;
} gl_lut_set;
/* The cascades of the scene's subsurface materials under `shared`. */
sss_result gl_lut_set_build(gl_lut_set *set, const sss_scene *scene, const double *shared, sss_error *err);
void gl_lut_set_free(gl_lut_set *set);
/* The cascade of m under `shared` (owned by set), or NULL when set is NULL or has none. */
const gl_lut_cascade *gl_lut_set_find(const gl_lut_set *set, const double *shared, const sss_scene_material *m);

/* lights.c */
sss_result gl_lights_build(gl_core *core, sss_error *err);
/* Rewrites the light records from the scene's lights (same count, kinds and shadow slots). */
sss_result gl_lights_update(gl_core *core, sss_error *err);
/* Records the scene's light types at an upload, for every technique (lights built or not). */
sss_result gl_lights_record_kinds(gl_core *core, sss_error *err);
/* The scene's lights against those recorded: the same number and types, else INVALID_ARGUMENT naming
 * what changed. */
sss_result gl_lights_check_kinds(const gl_core *core, sss_error *err);
void gl_env_cache_free(gl_scene *gs); /* the environment maps read by gl_lights_build */
sss_result gl_shadows_render(gl_core *core, sss_error *err);

/* ssaa.c: supersampling antialiasing. */
/* Checks a factor (1..SSS_GL_MAX_SUPERSAMPLE) and the render size it gives for an output size. */
sss_result gl_ssaa_check(const sss_gl_context *ctx, int width, int height, int k, sss_error *err);
/* (Re)creates the output image and its framebuffer for the output size when k > 1 (the program is built
 * on first use); frees them when k = 1. */
sss_result gl_ssaa_resize(gl_core *core, sss_error *err);
void gl_ssaa_free(gl_core *core);
/* The box filter frame.final -> the output image (no-op when k = 1), timed as "resolve_ssaa". */
sss_result gl_ssaa_resolve(gl_core *core, sss_error *err);

#endif
