/* sss/gl_pass.h — a technique as a pass in the caller's own OpenGL frame: the caller renders its
 * G-buffer and lighting into its own textures, the pass reads them and writes the subsurface radiance
 * into a texture the caller owns (docs/integration.md).
 *
 * Does: runs any registered technique (sss/gl.h) but chen2012 on caller-owned GL textures with the
 * caller's camera matrices; registers the caller's surfaces through an sss_scene (material per id; meshes, transforms,
 * animations and lights only for the techniques that splat or rasterise geometry, which then render
 * their own light-space shadow maps of those meshes); allocates nothing per frame; sets the GL state
 * its draws depend on and restores the caller's (the list below); resize, parameter, material and
 * light updates.
 * Does not: render the caller's G-buffer, lighting or shadow maps, read the caller's shadow maps, add
 * the light between surfaces (the renderer's interreflection stage, docs/interreflection.md: the
 * caller's irradiance carries whatever indirect light its engine computes), tone map, print, or create
 * a context (the caller's context must be current, OpenGL 4.5 core:
 * sss_gl_context_adopt_current wraps it).
 *
 * The sss_gl_renderer of sss/gl.h runs techniques the same way: it renders its own G-buffer and
 * illumination and runs the technique on them as this pass runs it on the caller's.
 *
 * Threading and memory as sss/gl.h: the pass belongs to the context's thread; _create allocates,
 * _destroy frees (NULL is accepted).
 */
#ifndef SSS_GL_PASS_H
#define SSS_GL_PASS_H

#include "sss/gl.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Zero-initialised means: the scene's technique, default parameters, no timings. */
typedef struct sss_gl_pass_desc {
    const char *technique;            /* NULL -> scene->render.technique */
    int width, height;                /* the size of every input and of the output (required) */
    const struct sss_scene *scene;    /* objects[i] is the surface whose id is i + 1 in the inputs:
                                         its material (LUTs are built from it); for translucency
                                         techniques also its mesh, splat mesh, transform and
                                         animation; lights[] light the splats. Must outlive the pass. */
    const sss_gl_param_value *params; /* technique or shared parameters by name */
    int param_count;
    int timings;                      /* 1: time every pass (sss_gl_pass_timings) */
    const char *data_file;            /* as sss_gl_renderer_desc.data_file (sam) */
} sss_gl_pass_desc;

/* One frame's inputs: GL texture names (GL_TEXTURE_2D, width x height) and the camera. World space
 * and units are the scene's (metres when the scene's media use their scale in metres).
 *   position    RGBA32F  xyz world position; w: the world area one pixel covers on the surface
 *                        (|dp/dx x dp/dy|), 0 on pixels that must not act as sources (not subsurface,
 *                        background, n.v below the technique's grazing cut-off)
 *   normal      RGBA16F or RGBA32F  xyz world shading normal (unit); w: surface id + 1, 0 background
 *   albedo      RGBA16F, RGBA32F or RGBA8  rgb albedo texture value (1 without texture); a: eta
 *   irradiance  RGBA32F  rgb F_t E sqrt(albedo): irradiance E times the entry Fresnel transmittance
 *                        1 - Fr(n.l, eta) (per light), times sqrt(albedo); w: surface id + 1
 *   reflected   RGBA16F or RGBA32F, or 0  radiance added to the result (the caller's direct lighting);
 *                        0: the output holds the subsurface radiance alone
 *   output      RGBA32F or RGBA16F  written: reflected + subsurface radiance (rgb), a = 1
 * Techniques with mip chains (sss_gl_pass_info.needs_mips) need full mip chains allocated on position
 * and irradiance (and normal when needs_normal_mips); the pass fills levels 1.. itself, level 0 is
 * only read. The matrices are column-major; proj is a perspective projection in the standard OpenGL
 * convention (near plane mapped to -1) or reversed-Z with an infinite far plane (proj[10] = 0).
 *
 * An engine that keeps depth rather than world positions gives `depth` and leaves `position` 0:
 *   depth       GL_DEPTH_COMPONENT32F, 24 or 16, or R32F: the depth buffer of this view and proj, written
 *               with glDepthRange(0, 1) and, for reversed-Z, glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE)
 *               (the standard convention with GL_NEGATIVE_ONE_TO_ONE); the far value (1, or 0 for
 *               reversed-Z) is background
 * The pass then reconstructs the world position (the inverse of proj x view) and the pixel area (the
 * cross product of the position differences to the neighbouring pixels, on the side whose depth
 * agrees better, so edges do not inflate it) into a position texture of its own (with the mip levels
 * it needs), with w = 0 where position's rule above says so (background, not subsurface, n.v below the
 * grazing cut-off). Timed as "position_from_depth". */
typedef struct sss_gl_pass_frame {
    unsigned position, normal, albedo, irradiance, reflected, output;
    float view[16], proj[16];
    double time;                      /* seconds: animations of the registered meshes */
    unsigned depth;                   /* instead of position (which is then 0): the camera's depth */
} sss_gl_pass_frame;

typedef struct sss_gl_pass sss_gl_pass;

/* Creates the technique's resources (LUTs, splat meshes, shadow maps, its own targets) on the current
 * context. Errors as sss_gl_renderer_create, plus a missing scene or size, and SSS_ERROR_UNSUPPORTED
 * for chen2012, which never reads the frame's irradiance (it lights its sources in light space, one
 * buffer per light; docs/integration.md). */
SSS_API sss_result sss_gl_pass_create(sss_gl_context *ctx, const sss_gl_pass_desc *desc, sss_gl_pass **out,
                                      sss_error *err);
SSS_API void sss_gl_pass_destroy(sss_gl_pass *pass);

/* Runs the technique on one frame. Checks every texture (exists, size, format, mip levels) and names
 * the field that is wrong; on error nothing is written. Restores the GL state listed below; GL errors
 * pending before the call are cleared (glGetError), so check yours before it. */
SSS_API sss_result sss_gl_pass_execute(sss_gl_pass *pass, const sss_gl_pass_frame *frame, sss_error *err);

/* New input/output size (the pass's own targets follow); the next frame's textures must have it. */
SSS_API sss_result sss_gl_pass_resize(sss_gl_pass *pass, int width, int height, sss_error *err);
/* Changes a technique or shared parameter (as sss_gl_renderer_set_param). */
SSS_API sss_result sss_gl_pass_set_param(sss_gl_pass *pass, const char *name, double value, sss_error *err);
/* Re-reads the materials of the registered scene (edit objects[i].material in place; the number of
 * objects must not change): LUTs and records are rebuilt now, meshes and programs stay (as
 * sss_gl_renderer_update_materials with scene NULL). */
SSS_API sss_result sss_gl_pass_update_materials(sss_gl_pass *pass, sss_error *err);
/* Re-reads the lights (same rules as sss_gl_renderer_update_lights, for every technique, also those
 * that light nothing themselves): a light added, removed or of another type is
 * SSS_ERROR_INVALID_ARGUMENT naming it, and a new pass is needed. */
SSS_API sss_result sss_gl_pass_update_lights(sss_gl_pass *pass, sss_error *err);

typedef struct sss_gl_pass_info {
    int needs_mips, needs_normal_mips; /* mip chains the inputs must have (see sss_gl_pass_frame) */
    int uses_geometry;                 /* splats or rasterises the registered meshes */
    int uses_lights;                   /* lights the registered meshes itself (its own shadow maps) */
} sss_gl_pass_info;
SSS_API void sss_gl_pass_get_info(const sss_gl_pass *pass, sss_gl_pass_info *out);
SSS_API void sss_gl_pass_timings(const sss_gl_pass *pass, sss_gl_timings *out);
/* Memory the pass owns (per_pixel_bytes: its own screen-sized targets only, the inputs excluded). */
SSS_API void sss_gl_pass_stats(sss_gl_pass *pass, sss_gl_stats *out);

/* GL state (docs/integration.md, "What the pass sets and restores"). Every call above but get_info,
 * timings and stats queries this state first, sets the values shown (the GL defaults, which the
 * passes' draws, clears, uploads and readbacks assume) and restores the caller's before it returns:
 * rasterisation: glPolygonMode GL_FILL; GL_RASTERIZER_DISCARD, GL_CULL_FACE, GL_POLYGON_OFFSET_FILL/
 *   LINE/POINT, GL_POLYGON_SMOOTH, GL_LINE_SMOOTH, GL_PROGRAM_POINT_SIZE, GL_DEPTH_CLAMP and every
 *   GL_CLIP_DISTANCEi off; glCullFace GL_BACK, glFrontFace GL_CCW, glPolygonOffset(0, 0),
 *   glProvokingVertex GL_LAST_VERTEX_CONVENTION, glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE),
 *   GL_FRAGMENT_SHADER_DERIVATIVE_HINT GL_DONT_CARE; every viewport and its depth range (0, 1);
 *   GL_MULTISAMPLE on, GL_SAMPLE_ALPHA_TO_COVERAGE, GL_SAMPLE_ALPHA_TO_ONE, GL_SAMPLE_COVERAGE,
 *   GL_SAMPLE_MASK, GL_SAMPLE_SHADING off;
 * vertex fetch: GL_PRIMITIVE_RESTART and GL_PRIMITIVE_RESTART_FIXED_INDEX off; the vertex array,
 *   GL_ARRAY_BUFFER, GL_DRAW_INDIRECT_BUFFER, GL_DISPATCH_INDIRECT_BUFFER;
 * fragment operations: GL_SCISSOR_TEST (per viewport), GL_STENCIL_TEST, GL_DEPTH_TEST,
 *   GL_COLOR_LOGIC_OP, GL_FRAMEBUFFER_SRGB off, GL_DITHER on; glDepthFunc GL_LESS, glDepthMask GL_TRUE;
 *   per draw buffer GL_BLEND off, glBlendFunc(GL_ONE, GL_ZERO), glBlendEquation GL_FUNC_ADD and
 *   glColorMask all true;
 * textures: GL_TEXTURE_CUBE_MAP_SEAMLESS off; the active unit, the textures of units 0..15 (2D,
 *   2D array, cube map, cube map array, 3D), their sampler objects (none), image units 0..7;
 * pixel transfer: every GL_PACK_* and GL_UNPACK_* pixel-store value (alignment 4, the others 0);
 *   no GL_PIXEL_PACK_BUFFER, GL_PIXEL_UNPACK_BUFFER or GL_QUERY_BUFFER;
 * bindings: GL_DRAW_FRAMEBUFFER, GL_READ_FRAMEBUFFER, the current program, the indexed uniform and
 *   shader storage buffers 0..23 (name, offset, size) and the generic GL_UNIFORM_BUFFER and
 *   GL_SHADER_STORAGE_BUFFER.
 * Per draw buffer, viewport and clip distance: the first 16 (GL_MAX_DRAW_BUFFERS, GL_MAX_VIEWPORTS,
 * GL_MAX_CLIP_DISTANCES are 8, 16 and 8 on current GLs). The caller must not be inside
 * glBeginTransformFeedback or glBeginConditionalRender, nor have a GL_TIME_ELAPSED query (desc.timings)
 * or GL_FRAGMENT_SHADER_INVOCATIONS query (dss's statistics) active. */
#define SSS_GL_PASS_TEXTURE_UNITS 16
#define SSS_GL_PASS_IMAGE_UNITS 8
#define SSS_GL_PASS_BUFFER_BINDINGS 24

#ifdef __cplusplus
}
#endif
#endif
