/* sss/gl.h — the real-time OpenGL 4.5 renderer: contexts, techniques and their parameters, rendering a
 * scene to a linear float image with per-pass timings.
 *
 * Does: headless contexts through EGL (Mesa's surfaceless platform, then the EGL device platform;
 * rendering goes to framebuffer objects), a GLFW window, or the caller's own current context (adopted,
 * not owned); a registry of techniques selected by name, each with a parameter table (name, type,
 * default, range, doc); shared passes every technique can use (G-buffer, shadow maps, illumination
 * with mip chains, low-resolution splat meshes); rendering at a time t (animated objects deform on
 * the GPU every frame, nothing is precomputed from the geometry).
 * Does not: load scenes (sss/scene.h does), write files (sss/image.h does), print.
 *
 * Threading: a context and everything created with it belong to the thread that created it.
 * Memory: _create allocates, the matching _destroy frees (NULL is accepted).
 */
#ifndef SSS_GL_H
#define SSS_GL_H

#include <stddef.h>

#include "sss/common.h"
#include "sss/image.h"

#ifdef __cplusplus
extern "C" {
#endif

struct sss_scene;

/* ---- Contexts -------------------------------------------------------------------------------- */

typedef enum sss_gl_platform {
    SSS_GL_PLATFORM_HEADLESS = 0, /* EGL surfaceless (Mesa), falling back to the EGL device platform */
    SSS_GL_PLATFORM_SURFACELESS,  /* EGL_PLATFORM_SURFACELESS_MESA only */
    SSS_GL_PLATFORM_DEVICE,       /* EGL_PLATFORM_DEVICE_EXT only (device_index) */
    SSS_GL_PLATFORM_WINDOW        /* a GLFW window (needs a display: DISPLAY or WAYLAND_DISPLAY) */
} sss_gl_platform;

/* Zero-initialised means: headless, OpenGL 4.5 core, no debug output (debug builds always enable it). */
typedef struct sss_gl_context_desc {
    sss_gl_platform platform;
    int device_index;              /* DEVICE: which EGL device (default 0) */
    int gl_major, gl_minor;        /* requested core version, at least 4.5 (0 -> 4.5) */
    int window_width, window_height; /* WINDOW: 0 -> 960 x 540 */
    const char *window_title;      /* WINDOW: NULL -> "sss" */
    int debug;                     /* KHR_debug output: errors are reported by the pass that caused them */
} sss_gl_context_desc;

typedef struct sss_gl_context sss_gl_context;

/* Creates a context and makes it current. Errors name what is missing: an EGL client extension or
 * platform, EGL_KHR_no_config_context / EGL_KHR_surfaceless_context, the GL version, the display of a
 * window (with a hint to use `sss render`). Never aborts. */
SSS_API sss_result sss_gl_context_create(const sss_gl_context_desc *desc, sss_gl_context **out, sss_error *err);
SSS_API void sss_gl_context_destroy(sss_gl_context *ctx);

/* Wraps the context the caller made current on this thread (an engine's own, from EGL, GLFW, SDL,
 * Qt, ...) without owning it: the renderer and sss/gl_pass.h then use it. Checks that a context is
 * current (SSS_ERROR_INVALID_ARGUMENT otherwise) and that it is OpenGL 4.5 core or later
 * (SSS_ERROR_UNSUPPORTED otherwise). sss_gl_context_destroy frees only the wrapper: the caller's
 * context stays current and alive. sss_gl_context_make_current makes an adopted EGL context current
 * again; for other window systems it only reports whether some context is current (keep yours
 * current while sss works). No debug callback is installed (the caller's stays), window helpers are
 * no-ops. */
SSS_API sss_result sss_gl_context_adopt_current(sss_gl_context **out, sss_error *err);

typedef struct sss_gl_context_info {
    const char *platform; /* "EGL surfaceless (Mesa)", "EGL device", "GLFW window" */
    const char *renderer; /* GL_RENDERER */
    const char *version;  /* GL_VERSION */
    int software;         /* 1 on llvmpipe/softpipe/SwiftShader: timings use glFinish + a clock */
} sss_gl_context_info;

/* Strings stay valid while the context lives. */
SSS_API void sss_gl_context_get_info(const sss_gl_context *ctx, sss_gl_context_info *out);
SSS_API int sss_gl_context_make_current(sss_gl_context *ctx); /* 1 on success */
/* The driver's view of video memory (GL_NVX_gpu_memory_info: NVIDIA): total dedicated and currently
 * available bytes, 1 on success (the context is made current). Returns 0 and sets both to 0 where the
 * extension is not offered (Mesa, llvmpipe). */
SSS_API int sss_gl_context_video_memory(sss_gl_context *ctx, size_t *total_bytes, size_t *available_bytes);

/* Window helpers (no-ops / 1 on headless contexts). */
SSS_API int sss_gl_window_should_close(sss_gl_context *ctx); /* also polls events */
SSS_API void sss_gl_window_swap(sss_gl_context *ctx);
SSS_API void sss_gl_window_size(sss_gl_context *ctx, int *width, int *height);

/* ---- Techniques and parameters --------------------------------------------------------------- */

typedef enum sss_gl_param_type {
    SSS_GL_PARAM_BOOL = 0, /* 0 or 1 */
    SSS_GL_PARAM_INT,
    SSS_GL_PARAM_FLOAT
} sss_gl_param_type;

typedef struct sss_gl_param_info {
    const char *name;      /* e.g. "layers" */
    sss_gl_param_type type;
    double default_value;  /* the best-measured value (docs/maisch2020.md); preset=paper gives the paper's */
    double min_value, max_value; /* inclusive range */
    const char *doc;       /* one line, citing the paper's section or equation */
} sss_gl_param_info;

typedef struct sss_gl_technique_info {
    const char *name;      /* "maisch2020" */
    const char *summary;   /* one line */
    const sss_gl_param_info *params;
    int param_count;
} sss_gl_technique_info;

/* Registered techniques, in a fixed order. */
SSS_API int sss_gl_technique_count(void);
SSS_API const sss_gl_technique_info *sss_gl_technique_at(int index);     /* NULL out of range */
SSS_API const sss_gl_technique_info *sss_gl_technique_find(const char *name); /* NULL when unknown */

/* Parameters shared by every technique (shadow map sizes, light sampling of area and environment
 * lights, LUT construction, splat meshes, timing). Accepted by sss_gl_renderer_set_param too. */
SSS_API const sss_gl_param_info *sss_gl_shared_params(int *count);

/* Presets: the shared parameter "preset" sets every parameter of the technique, its own and the shared
 * ones, to the preset's values: SSS_GL_PRESET_MEASURED (0, the defaults: what measures best on the
 * evaluation scenes) or SSS_GL_PRESET_PAPER (1, the published configuration of the technique's paper).
 * In a renderer desc the preset is applied first, wherever it stands, so the other parameters given
 * with it override it; sss_gl_renderer_set_param("preset", ...) resets every parameter. */
#define SSS_GL_PRESET_MEASURED 0
#define SSS_GL_PRESET_PAPER 1
/* The value a parameter (technique or shared) takes under preset=paper for a technique: the paper's
 * where it departs from the default, else the default. NaN for an unknown technique or parameter. */
SSS_API double sss_gl_paper_value(const char *technique, const char *param);
/* Parses the text of a parameter value (--param NAME=TEXT): a finite number, or for "preset" also the
 * names "paper" and "measured". SSS_ERROR_INVALID_ARGUMENT naming the parameter otherwise. */
SSS_API sss_result sss_gl_param_parse(const char *name, const char *text, double *out, sss_error *err);

/* ---- Renderer -------------------------------------------------------------------------------- */

typedef struct sss_gl_param_value {
    const char *name;
    double value;
} sss_gl_param_value;

/* CPU tables precomputed for a scene (sss_gl_tables_build below). */
typedef struct sss_gl_tables sss_gl_tables;

/* Zero-initialised means: the scene's technique at the scene camera's size, default parameters. */
typedef struct sss_gl_renderer_desc {
    const char *technique;            /* NULL -> scene->render.technique */
    int width, height;                /* 0 -> the scene camera's */
    const sss_gl_param_value *params; /* technique or shared parameters by name */
    int param_count;
    int timings;                      /* 1: time every pass (on software GL this adds a glFinish per pass) */
    const char *data_file;            /* a technique's precomputed data (sam: a .sam file of `sss sam build`),
                                         NULL: none; must outlive the renderer, like the scene */
    int supersample;                  /* supersampling antialiasing (SSAA) factor k in 1..SSS_GL_MAX_SUPERSAMPLE
                                         (0 -> 1 = off): every pass renders at k x the width and height, and
                                         the linear result is box-filtered (k x k mean, before any tone
                                         mapping) to width x height in the timed pass "resolve_ssaa".
                                         Technique parameters counted in pixels follow k, so the image is the
                                         one at k = 1, antialiased (docs/supersampling.md). */
    const sss_gl_tables *tables;      /* CPU tables of sss_gl_tables_build for this same scene object, read
                                         during sss_gl_renderer_create only (free them after it); NULL: the
                                         renderer computes every table itself. Either way the image is the same. */
} sss_gl_renderer_desc;

#define SSS_GL_MAX_SUPERSAMPLE 4

/* The CPU-only tables sss_gl_renderer_create would compute for `scene` under `desc` (its technique and
 * parameters; sizes are ignored): the kernel LUT cascade of every distinct subsurface material
 * (Maisch & Ropinski 2020, section 7.1), most of the cost of a renderer on software GL, and for sam the
 * adjacency maps of the subsurface objects (not with desc.data_file: the file is read instead). Needs no GL
 * context and touches nothing shared, so it may run on any thread (the viewer builds the tables of an
 * edited scene on a worker while its window keeps drawing), while another thread reads the same scene.
 * A renderer created with desc.tables takes a material's LUTs from them when the material, its PBD table
 * and the LUT parameters match exactly, and sam's maps when they were built for the same scene object,
 * parameter values and data file; it computes them otherwise. Errors as sss_gl_renderer_create's for the
 * technique and parameters, the LUT builder's, prefixed "kernel LUT", and the map builder's, prefixed
 * "sam". */
SSS_API sss_result sss_gl_tables_build(const struct sss_scene *scene, const sss_gl_renderer_desc *desc,
                                       sss_gl_tables **out, sss_error *err);
SSS_API void sss_gl_tables_free(sss_gl_tables *tables); /* NULL is accepted */

typedef struct sss_gl_renderer sss_gl_renderer;

/* Uploads the scene (meshes, materials with their LUTs, lights, textures) and creates the technique.
 * The scene must outlive the renderer. Errors: unknown technique or parameter (the message lists the
 * known ones), parameter out of range, supersample outside 0..4 or a supersampled size beyond the GL's
 * GL_MAX_TEXTURE_SIZE / GL_MAX_VIEWPORT_DIMS, a resource the GL cannot provide. */
SSS_API sss_result sss_gl_renderer_create(sss_gl_context *ctx, const struct sss_scene *scene,
                                          const sss_gl_renderer_desc *desc, sss_gl_renderer **out, sss_error *err);
SSS_API void sss_gl_renderer_destroy(sss_gl_renderer *r);

/* Changes one parameter (takes effect at the next render; may rebuild resources). */
SSS_API sss_result sss_gl_renderer_set_param(sss_gl_renderer *r, const char *name, double value, sss_error *err);
/* Re-reads the lights of the scene the renderer was created with (it keeps using that sss_scene: edit
 * its lights[] in place, e.g. move, turn, recolour, rotate the environment) without rebuilding shadow
 * maps, LUTs or programs; takes effect at the next render, which equals a new renderer's. The lights
 * must keep their number and kinds (the same virtual lights and shadow-map slots): otherwise
 * SSS_ERROR_INVALID_ARGUMENT, nothing changes, and a new renderer is needed. */
SSS_API sss_result sss_gl_renderer_update_lights(sss_gl_renderer *r, sss_error *err);
/* New materials for the same geometry, without uploading meshes, lights, shadow maps or programs again:
 * the material records and kernel LUTs are rebuilt (from `tables` when given, as desc.tables; else
 * computed here) and the technique refreshes what it derived from materials (ssss its kernels,
 * mertens2003 its sampling tables). `scene` NULL re-reads the renderer's own scene (edit
 * objects[i].material in place); otherwise the renderer draws `scene` from now on (it must outlive the
 * renderer, the previous one may then be freed), and `scene` must hold the same geometry: the same
 * objects with equal meshes, splat meshes, transforms and animations, lights of the same kinds (their
 * values are re-read as by sss_gl_renderer_update_lights) and equal textures. The next render equals a
 * new renderer's for the scene. When an object starts or stops scattering, or (scene NULL) its
 * transform or animation was edited, everything is rebuilt (the same result, the cost of a new
 * renderer). Errors: SSS_ERROR_INVALID_ARGUMENT naming the first
 * difference when the geometry differs (nothing changes: create a new renderer); the LUT builder's
 * (prefixed "kernel LUT"). On any error the renderer keeps drawing its previous scene (no pointer to
 * `scene` remains). */
SSS_API sss_result sss_gl_renderer_update_materials(sss_gl_renderer *r, const struct sss_scene *scene,
                                                    const sss_gl_tables *tables, sss_error *err);
SSS_API double sss_gl_renderer_get_param(const sss_gl_renderer *r, const char *name); /* NaN when unknown */
/* Sizes are the output's (what sss_gl_renderer_read returns); passes render at supersample x them. */
SSS_API sss_result sss_gl_renderer_resize(sss_gl_renderer *r, int width, int height, sss_error *err);
SSS_API void sss_gl_renderer_size(const sss_gl_renderer *r, int *width, int *height);
/* Changes the SSAA factor (1..SSS_GL_MAX_SUPERSAMPLE; 0 -> 1) at the same output size: the frame
 * targets are rebuilt, the next render uses it. Errors as for sss_gl_renderer_create; on error the
 * renderer keeps its previous factor. */
SSS_API sss_result sss_gl_renderer_set_supersample(sss_gl_renderer *r, int supersample, sss_error *err);
SSS_API int sss_gl_renderer_get_supersample(const sss_gl_renderer *r); /* 1 when off (0 for NULL) */

/* Renders one frame at time t (seconds; animations use it) into the renderer's linear target. */
SSS_API sss_result sss_gl_renderer_render(sss_gl_renderer *r, double time, sss_error *err);
/* Reads the last frame as linear RGB (top row first). out must have been created with the renderer's
 * (output) size; with supersampling it is the box-filtered image. Non-finite values are reported as
 * SSS_ERROR_NUMERIC (they never reach a file). */
SSS_API sss_result sss_gl_renderer_read(sss_gl_renderer *r, sss_image *out, sss_error *err);
/* Reads a named intermediate buffer for tests and debugging, as linear RGB at its own size (out is
 * created by the call; free with sss_image_free): "reflected", "irradiance", "translucency",
 * "translucency_full", "screen", "final" (the output image, as sss_gl_renderer_read), "supersampled"
 * (the linear result before the SSAA box filter, supersample x the output size; with supersample 1
 * the same as "final"), "object_id" (the G-buffer's object index + 1 in every channel, 0 where no
 * object covers the pixel). Intermediate buffers are at the supersampled size. Unknown or unavailable
 * names are errors. */
SSS_API sss_result sss_gl_renderer_read_buffer(sss_gl_renderer *r, const char *name, sss_image *out, sss_error *err);
/* Draws the last frame, tone mapped with the scene's exposure, to the window's back buffer. */
SSS_API sss_result sss_gl_renderer_present(sss_gl_renderer *r, sss_error *err);

#define SSS_GL_MAX_PASSES 24

typedef struct sss_gl_pass_timing {
    const char *name; /* "gbuffer", "shadows", "illumination", ... (static strings) */
    double ms;
} sss_gl_pass_timing;

typedef struct sss_gl_timings {
    int pass_count;
    sss_gl_pass_timing passes[SSS_GL_MAX_PASSES];
    double total_ms;    /* sum of the passes */
    const char *method; /* "glFinish + monotonic clock" or "GL_TIME_ELAPSED queries"; "off" when disabled */
} sss_gl_timings;

/* Timings of the last frame (pass_count 0 when timing is off). */
SSS_API void sss_gl_renderer_timings(const sss_gl_renderer *r, sss_gl_timings *out);

/* ---- Frame-time statistics ------------------------------------------------------------------
 * The first frames of a renderer are slower than the rest (shader compilation and JIT, first touches of
 * buffers; on llvmpipe the first frame of a process can cost 30x a later one), so reported timings drop
 * warm-up frames and give the median of the timed ones. A series matches passes by name across frames:
 * a name repeated within a frame adds up, a pass missing from a frame counts 0 ms there. */
#define SSS_GL_WARMUP_FRAMES 2 /* default frames dropped before timing */
#define SSS_GL_TIMED_FRAMES 5  /* default frames timed */

typedef struct sss_gl_timing_series {
    int warmup;       /* frames dropped before timing */
    int capacity;     /* timed frames it holds; when full, a new frame replaces the oldest */
    int added;        /* frames added so far, warm-up included */
    int timed;        /* timed frames held */
    int pass_count;
    const char *pass_names[SSS_GL_MAX_PASSES];
    double *ms;       /* (SSS_GL_MAX_PASSES + 1) x capacity: per pass, then the frame totals */
    const char *method;
} sss_gl_timing_series;

/* warmup >= 0 frames to drop, then room for timed_frames >= 1 (about 200 bytes per frame). */
SSS_API sss_result sss_gl_timing_series_init(sss_gl_timing_series *s, int warmup, int timed_frames, sss_error *err);
/* Adds one frame's timings (from sss_gl_renderer_timings); the first `warmup` frames are dropped. */
SSS_API void sss_gl_timing_series_add(sss_gl_timing_series *s, const sss_gl_timings *frame);
/* Median per pass and of the totals over the timed frames (pass_count 0 before the first). */
SSS_API void sss_gl_timing_series_median(const sss_gl_timing_series *s, sss_gl_timings *out);
SSS_API void sss_gl_timing_series_free(sss_gl_timing_series *s);

typedef struct sss_gl_stats {
    size_t texture_bytes;       /* all textures the renderer owns (shared passes + technique) */
    size_t buffer_bytes;        /* all buffer objects (meshes, splats, uniforms) */
    size_t per_pixel_bytes;     /* bytes of screen-sized targets per output pixel (mips included) */
    size_t per_splat_bytes;     /* bytes per splat record (0 when the technique does not splat) */
    size_t lut_bytes;           /* the kernel LUTs */
    int luts_precomputed;       /* materials whose LUTs were taken from desc.tables (not computed) */
    unsigned splat_total;       /* triangles of the splat meshes */
    unsigned splat_drawn;       /* splats that survived culling in the last frame */
    int material_count, light_count, virtual_light_count, object_count;
    /* fragment shader invocations of the last frame's shell splatting (chen2012, dss: a pipeline-statistics
     * query, which waits for the frame); -1 when not counted (other techniques, no such query, no frame) */
    long long splat_fragments;
} sss_gl_stats;

SSS_API void sss_gl_renderer_stats(sss_gl_renderer *r, sss_gl_stats *out);

/* GPU memory a renderer holds now, counted where the GL allocates and frees storage (logical sizes:
 * texels x the bits of the format, buffer sizes; drivers add padding): the technique's own textures and
 * buffers (its passes' targets, splat buffers, tables) and the shared frame targets (G-buffer,
 * illumination and their mip chains, the linear result, the SSAA output). Scene data (meshes, LUTs,
 * shadow maps) is in neither. Either pointer may be NULL; a NULL renderer gives 0. */
SSS_API void sss_gl_renderer_gpu_memory(const sss_gl_renderer *r, size_t *technique_bytes, size_t *frame_bytes);

/* GPU bytes held now by the textures and buffers sss created on this thread's contexts (everything a
 * renderer, pass or viewer made, scene data included), counted as for sss_gl_stats: the difference
 * across sss_gl_renderer_create is what one renderer holds; after every _destroy it is back where it was. */
SSS_API size_t sss_gl_allocated_bytes(void);

#ifdef __cplusplus
}
#endif
#endif
