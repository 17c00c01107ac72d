/* view/view_internal.h — pieces of the viewer that do not need a window (camera and light motion,
 * scene edits as JSON, the background reference, overlay text geometry), so tests can reach them. */
#ifndef SSS_VIEW_INTERNAL_H
#define SSS_VIEW_INTERNAL_H

#include <pthread.h>
#include <stddef.h>

#include "sss/gl.h"
#include "sss/image.h"
#include "sss/scene.h"
#include "sss/view.h"

/* ---- Camera and light motion (motion.c) ------------------------------------------------------- */

/* Orbit around look_at: azimuth about the camera's up axis (right-handed, degrees), then elevation
 * towards up; the angle between the view offset and up stays within [1, 179] degrees, and the distance
 * to look_at is kept. */
void view_orbit(sss_camera *cam, double azimuth_deg, double elevation_deg);
/* Pan: moves position and look_at together so that points at look_at's depth follow the cursor by
 * (dx, dy) pixels (x right, y down) in a width x height image. */
void view_pan(sss_camera *cam, double dx, double dy, int width, int height);
/* Zoom: the distance to look_at is multiplied by factor (> 0), kept above 1e-6 of its start. */
void view_zoom(sss_camera *cam, double factor);
/* Rotates a light's geometry about the vertical axis (+y, right-handed) through pivot: positions,
 * spot targets, directions, area-light centre and edges, environment rotate_y. */
void view_rotate_light_y(sss_light *light, const double pivot[3], double degrees);

/* ---- Scene edits (scene_edit.c) --------------------------------------------------------------- */

typedef struct view_edits {
    const sss_camera *camera; /* NULL: keep the file's */
    const sss_light *light0;  /* NULL: keep; else the geometry of lights[0] (type must match) */
    int medium;               /* -1: every subsurface material as in the file; else the index of a
                                 measured medium (sss_measured_medium_at) given to all of them */
    double scale_factor;      /* multiplies every subsurface material's coefficients (0 -> 1): `scale`
                                 for media and coefficients, 1 / factor on `mfp` */
} view_edits;

/* The scene file's JSON text with the edits applied (unformatted; free() it). Errors name `name`. */
sss_result view_scene_json(const char *text, size_t size, const char *name, const view_edits *edits, char **out,
                           sss_error *err);

/* One field of objects[object].material in the scene JSON `text` (the panel's and the script's
 * material edits): field is one of view_material_fields (view/script.h); medium names a measured medium
 * (field "medium"), values holds 1 or 3 numbers otherwise. A field of another form switches the
 * material to that form, the missing fields taken from `resolved` (the loaded material: its coefficients
 * with scale 1, or its rho_eff as reflectance and 1 / sigma_t as mfp; medium keeps the scale). The
 * loader checks the result. Errors name `name` and the JSON path. */
struct sss_scene_material;
sss_result view_material_json(const char *text, size_t size, const char *name, int object, const char *field,
                              const char *medium, const double *values, int value_count,
                              const struct sss_scene_material *resolved, char **out, sss_error *err);
/* lights[light].FIELD of the scene JSON: "position" (point and spot position, area center), or the
 * light's power (intensity of point and spot, radiance of directional and area, scale of environment)
 * as `values` (3 numbers, already combined from intensity and colour by the caller). */
sss_result view_light_json(const char *text, size_t size, const char *name, int light, const char *field,
                           const double values[3], char **out, sss_error *err);

/* ---- Background jobs (job.c) ------------------------------------------------------------------ */

/* The first member of a job: its thread and the lock guarding done, abandoned (and the job's own
 * progress fields). run computes on the worker; free releases the whole job. */
typedef struct view_job {
    pthread_t thread;
    pthread_mutex_t lock;
    int lock_ready, done, abandoned;
    void (*run)(struct view_job *job);
    void (*free)(struct view_job *job);
} view_job;

sss_result view_job_init(view_job *j, void (*run)(view_job *), void (*free_job)(view_job *), sss_error *err);
sss_result view_job_start(view_job *j, sss_error *err); /* runs j->run on a new thread */
int view_job_done(view_job *j);
void view_job_join(view_job *j);
/* Gives up on the job: freed now when done, else by the worker when run returns. */
void view_job_abandon(view_job *j);
void view_job_destroy(view_job *j); /* the lock (call from the job's free) */

/* ---- The reference in the background (reference_job.c) ---------------------------------------- */

typedef struct view_ref_job view_ref_job; /* one render in a worker thread */

/* Starts sss_reference_render of the scene `json` (base_dir for its paths, name for messages) at time
 * t on a worker thread. */
sss_result view_ref_start(const char *json, const char *base_dir, const char *name, double time, int draft,
                          view_ref_job **out, sss_error *err);
/* 0 while running (progress in [0, 1] and the stage name), 1 when done: then *image receives the
 * result (moved out) or err the failure. */
int view_ref_poll(view_ref_job *job, double *progress, const char **stage);
sss_result view_ref_finish(view_ref_job *job, sss_image *image, sss_error *err); /* joins and frees */
/* Gives up on a running job: the worker frees it when the render returns. */
void view_ref_abandon(view_ref_job *job);

/* A copy of s (NULL -> ""); free() it. NULL when out of memory. */
char *view_dup_str(const char *s);

/* ---- A material edit's CPU part in the background (build_job.c) ------------------------------- */

typedef struct view_build_job view_build_job; /* one build in a worker thread */

typedef struct view_build_result {
    sss_scene *scene;       /* the edited scene (allocated; sss_scene_free + free) */
    sss_gl_tables *tables;  /* its renderer's CPU tables */
    double scene_ms, tables_ms; /* the worker's loader and table times */
} view_build_result;

/* Starts, on a worker thread, sss_scene_parse of json (base_dir for its paths, name for messages) and
 * sss_gl_tables_build of that scene under desc (copied: the caller's may change). delay_s > 0 makes
 * the worker wait that long first (a test hook for a slow build). */
sss_result view_build_start(const char *json, const char *base_dir, const char *name,
                            const sss_gl_renderer_desc *desc, double delay_s, view_build_job **out, sss_error *err);
int view_build_poll(view_build_job *job); /* 1 when done */
/* Joins and frees the job; on success *out owns the scene and tables. */
sss_result view_build_finish(view_build_job *job, view_build_result *out, sss_error *err);
/* Gives up on a running build: the worker frees it when done. */
void view_build_abandon(view_build_job *job);
void view_build_result_free(view_build_result *r);

/* A few references by key (scene JSON + time + quality), most recent first. */
#define VIEW_REF_CACHE 8
typedef struct view_ref_cache {
    char *keys[VIEW_REF_CACHE];
    sss_image images[VIEW_REF_CACHE];
} view_ref_cache;

const sss_image *view_ref_cache_find(view_ref_cache *c, const char *key);
/* Takes ownership of image (and copies key). */
sss_result view_ref_cache_put(view_ref_cache *c, const char *key, sss_image *image, sss_error *err);
void view_ref_cache_free(view_ref_cache *c);

/* ---- Split view and error map (compose.c) ------------------------------------------------------ */

/* A wipe: columns x < cut = round(position * width) from left, the others from right (same size,
 * linear RGB), with a divider (VIEW_DIVIDER_WIDTH columns centred on the cut: white, edged in black so
 * it shows on white and black) and each side's label in a shaded box in its top corner (left label
 * top left, right label top right; shortened to fit its side, left out below 3 characters or on
 * images under 32 rows). Drawn to show white after the viewer's tone map at exposure. out is
 * (re)allocated. */
#define VIEW_DIVIDER_WIDTH 4
sss_result view_compose_split(const sss_image *left, const sss_image *right, double position, const char *left_label,
                              const char *right_label, double exposure, sss_image *out, sss_error *err);
/* The colour of value in [0, 1] on the error map's scale (inferno, sRGB control points, returned
 * linear); values outside are clamped, NaN is black. */
void view_error_colour(double value, float rgb[3]);
/* A per-pixel error map (the mean of dssim_map's channels) in colours over the fixed range [0, range]
 * (values above show the top colour), and a colour bar along the bottom: VIEW_COLOUR_BAR_HEIGHT rows
 * (low values left) under a 1-row black rule, with ticks (white marks VIEW_TICK_HEIGHT rows up from
 * the rule) at 5, 3 or 2 evenly spaced values, the most whose labels fit side by side, and, on images
 * of VIEW_TICK_LABEL_MIN_HEIGHT rows or more, the values as text above them (the last one followed
 * by " DSSIM" when it fits). out is (re)allocated. */
#define VIEW_COLOUR_BAR_HEIGHT 8
#define VIEW_TICK_HEIGHT 4
#define VIEW_TICK_LABEL_MIN_HEIGHT 96
#define VIEW_ERROR_RANGE_DEFAULT 0.2
sss_result view_error_map(const sss_image *dssim_map, double range, sss_image *out, sss_error *err);
/* The ticks of a colour bar `width` pixels wide over [0, range]: their count (5, 3 or 2), each one's
 * column (x[k] = round(k / (count - 1) * (width - 1))) and label ("%g" of its value; the last one
 * with " DSSIM" when unit is set and it fits). Labels of text width (view_text_block_width) must not
 * overlap: the first is left-aligned at 0, the last right-aligned at width, the others centred. */
#define VIEW_MAX_TICKS 5
typedef struct view_ticks {
    int count;
    int x[VIEW_MAX_TICKS];
    char label[VIEW_MAX_TICKS][24];
    float label_x[VIEW_MAX_TICKS]; /* left edge of each label's box */
} view_ticks;
void view_colour_bar_ticks(int width, double range, int unit, view_ticks *out);

/* ---- The window's layout (layout.c) ----------------------------------------------------------- */

/* The panel is docked at the right of the window, beside the image (never over it): the image is
 * the window minus the panel, and the renderer renders at the image's size. */
#define VIEW_PANEL_MIN_WIDTH 160 /* framebuffer pixels */
#define VIEW_IMAGE_MIN_WIDTH 64
/* The panel's width in a window win_width pixels wide: 0 when it is not shown, else want clamped to
 * [VIEW_PANEL_MIN_WIDTH, win_width - image_min] (the image keeps its minimum first: VIEW_IMAGE_MIN_WIDTH,
 * or the width asked for when that is smaller, viewer.image_min). */
int view_dock_width(int win_width, double want, int shown, int image_min);

/* ---- Overlay text geometry (overlay_text.c) --------------------------------------------------- */

typedef struct view_text_vertex {
    float x, y;            /* pixels, origin top left, y down */
    unsigned char rgba[4];
} view_text_vertex;

typedef struct view_text {
    view_text_vertex *vertices; /* 4 per quad */
    int quads, capacity;
    float width, height;        /* extent of the text block (pixels, before scale) */
} view_text;

/* Appends the quads of a multi-line text at (x, y) pixels, with a darkened background rectangle behind
 * the block; scale multiplies the 6 x 12 pixel font of stb_easy_font. */
sss_result view_text_build(view_text *t, const char *text, float x, float y, float scale, sss_error *err);
/* The width of view_text_build's block of a one-line text at scale 1 (the text and its padding). */
float view_text_block_width(const char *text);
#define VIEW_TEXT_BLOCK_HEIGHT 20.0f /* of one line at scale 1: 12 rows of text and the padding */
/* Appends one filled rectangle [x0, x1) x [y0, y1) in pixels of colour rgba (sRGB 8-bit, alpha). */
sss_result view_text_rect(view_text *t, float x0, float y0, float x1, float y1, const unsigned char rgba[4],
                          sss_error *err);
/* Paints the quads, in order, into a linear-RGB image (the pixels whose centres they cover; alpha
 * blended in linear light), their colours divided by 2^exposure so that the viewer's tone map at that
 * exposure shows them as given. */
void view_text_paint(const view_text *t, sss_image *img, double exposure);
void view_text_free(view_text *t);

#endif
