/* eval/eval_internal.h — internals of the evaluation module shared by its files. */
#ifndef SSS_EVAL_INTERNAL_H
#define SSS_EVAL_INTERNAL_H

#include <cairo.h>
#include <stdint.h>

#include "sss/eval.h"
#include "sss/scene.h"

#define EVAL_MAX_QUALITY_SIZES 8
#define EVAL_MAX_SPEC_PARAMS 32

/* A parsed technique spec "name:param=value:...". */
typedef struct eval_spec {
    char name[64];
    char names[EVAL_MAX_SPEC_PARAMS][64];
    sss_gl_param_value params[EVAL_MAX_SPEC_PARAMS + 1]; /* +1: room for the SAM sweep's count */
    int param_count;
} eval_spec;

sss_result eval_parse_spec(const char *text, eval_spec *out, sss_error *err);

/* Names from data (scene file names, technique specs) as the outputs show them: control characters
 * and bytes that are not UTF-8 as visible escapes (core/text.h), into out (cap bytes, cut to fit),
 * or as a malloc'd copy (NULL when out of memory). */
void eval_escape(const char *text, char *out, size_t cap);
char *eval_escaped(const char *text);

/* Appends a zeroed entry (growing the array); NULL when out of memory. */
sss_eval_entry *eval_add_entry(sss_eval_results *res);
/* " (N frame[s][, no warm-up])" into out when --frame-budget cut e's frames (fewer timed or warm-up frames
 * than the run asked), "" otherwise; returns whether it did. */
int eval_frames_note(const sss_eval_results *res, const sss_eval_entry *e, char *out, size_t cap);

/* Where --cached-reference looks for the scene's reference at w x h: "<scene folder>/references/
 * <file_stem>_<w>x<h>[_t<T>].exr" (committed next to the scene), or with desc->reference_dir,
 * "<reference_dir>/<stem>_..." (the run's name of the scene: what a run saves to its references/).
 * Returns 0 when the path does not fit. */
int eval_cached_reference_path(const sss_eval_desc *desc, const sss_eval_scene *es, int w, int h, char *out,
                               size_t cap);
/* 64-bit FNV-1a of a file's bytes; 0 on read failure. */
uint64_t eval_file_hash(const char *path);

/* The reference of one scene at one size: cached when desc asks and a fresh one exists, else
 * rendered (and saved when desc->save_references_dir is set). Fills ref; img is created on success.
 * Returns SSS_OK also when the reference is unavailable (ref->source NONE, ref->error set); errors
 * are for failures the run must stop on (saving, memory). */
typedef struct eval_progress eval_progress;
sss_result eval_reference(const sss_scene *view, const sss_eval_scene *es, const sss_eval_desc *desc,
                          eval_progress *prog, sss_eval_reference *ref, sss_image *img, sss_error *err);
/* The same at another seed of the reference renderer and/or another truth: seed > 0 is cached and saved
 * as <stem>_seed<S>_... (sss_eval_desc.reference_noise); bounces other than desc->reference_bounces as
 * <stem>_bounces<B>_... (sss_eval_desc.both_truths). */
sss_result eval_reference_variant(const sss_scene *view, const sss_eval_scene *es, const sss_eval_desc *desc,
                                  uint64_t seed, int bounces, eval_progress *prog, sss_eval_reference *ref,
                                  sss_image *img, sss_error *err);
/* The scene as such a variant's files are named (stem, file_stem and name with the suffixes above). */
sss_eval_scene eval_variant_scene(const sss_eval_scene *es, const sss_eval_desc *desc, uint64_t seed, int bounces);
/* The image's mean linear R, G, B over the reference's (NaN for a channel whose reference mean is 0). */
void eval_mean_ratio(const sss_image *img, const sss_image *ref, double out[3]);

/* Progress bookkeeping (eval_run.c): units done and planned, the callbacks. */
struct eval_progress {
    const sss_eval_callbacks *cb;
    double done, total;  /* work units */
    double step;         /* units of the current step */
    char stage[256];
};
void eval_progress_update(eval_progress *p, double step_fraction, const char *stage);
void eval_progress_finish_step(eval_progress *p);
void eval_note(eval_progress *p, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* ---- Running techniques (eval_tech.c) ---- */

typedef struct eval_gl {
    sss_gl_context *gl;   /* NULL: every technique fails with gl_error */
    const char *gl_error;
    const char *method;   /* timing method the renderer reported */
    int frames, warmup_frames;
    double frame_budget_s; /* sss_eval_desc.frame_budget_s */
    int supersample;      /* SSAA factor of specs that do not set "supersample" */
    eval_progress *prog;
    sss_image *object_ids; /* when not NULL and still empty: receives the G-buffer object ids of the next
                              technique that renders ("object_id" buffer; stays empty if unreadable) */
} eval_gl;

void eval_fail_entry(sss_eval_entry *e, const char *msg);
/* Renders spec (its first nparams parameters) on view (already sized) at time t, frames times; fills
 * e's results (the caller sets label, kind, size) and keeps the image in e->image. Technique failures
 * are recorded in e; only bookkeeping allocation failures are returned. */
sss_result eval_run_technique(eval_gl *rc, const sss_scene *view, double t, const eval_spec *spec, int nparams,
                              int frames, sss_eval_entry *e, const char *stage);

#define EVAL_DEFAULT_SAM_COUNTS 4
extern const int eval_default_sam_counts[EVAL_DEFAULT_SAM_COUNTS]; /* 3, 10, 20, 50 (Maisch & Ropinski 2017, Fig. 10) */
/* sam's back-side sample count parameter, or NULL. */
const sss_gl_param_info *eval_find_sam_param(const sss_gl_technique_info *t);

/* ---- Images from other programs (eval_external.c) ---- */

/* Checks sss_eval_desc.images before any work: names (non-empty, distinct, not a technique spec of the
 * run) and patterns ("{scene}" required when there are several scenes). */
sss_result eval_external_validate(const sss_eval_desc *d, int scene_count, sss_error *err);
/* Reads every source's image of scene es, which must be w x h and finite, into imgs[0..image_count)
 * (created; all freed on failure) and their files into paths. Errors name the source and the file. */
sss_result eval_external_load(const sss_eval_desc *d, const sss_eval_scene *es, int w, int h, sss_image *imgs,
                              char (*paths)[1024], sss_error *err);
/* The QUALITY entry of an external image (label, technique "external", ok, no timings); img moves into it. */
void eval_external_entry(int scene, const char *label, const char *path, sss_image *img, sss_eval_entry *e);

/* ---- Drawing (eval_draw.c) ---- */

typedef struct eval_rgb {
    double r, g, b;
} eval_rgb;

eval_rgb eval_palette(int i); /* distinct colours (Tableau 10, then darker variants) */
/* A cairo image surface holding img tone-mapped with exposure (8-bit sRGB); NULL on failure. */
cairo_surface_t *eval_surface_from_image(const sss_image *img, double exposure);
/* The DSSIM map as colours: channel value * gain, clamped to [0, 1] (black = no difference). */
cairo_surface_t *eval_surface_from_map(const sss_image *map, double gain);
/* matplotlib's magma colour map at t in [0, 1] (clamped), as the FLIP paper shows its maps. */
eval_rgb eval_magma(double t);
/* A FLIP map (first channel, in [0, 1]) through eval_magma. */
cairo_surface_t *eval_surface_from_flip(const sss_image *map);
/* A horizontal colour bar in the box (x, y, w, h) with ticks and values under it from 0 to vmax:
 * grey (black to white, the DSSIM maps' per-channel scale) or magma; label (may be NULL) is written
 * right of the bar, inside the box. */
void eval_draw_colour_bar(cairo_t *cr, double x, double y, double w, double h, int magma, double vmax,
                          const char *label);
/* Draws the crop (x, y, size) of surface s scaled into the square box (bx, by, box), nearest-neighbour. */
void eval_draw_crop(cairo_t *cr, cairo_surface_t *s, int x, int y, int size, double bx, double by, double box);

/* ---- Zoomed crops (eval_crops.c) ---- */

typedef struct eval_window {
    int x, y, size; /* top-left pixel and side, in the image's pixels */
    int valid;
} eval_window;
/* Side of the crop windows of a w x h image: an eighth of the shorter side, at least 12 pixels (and
 * at most the image). */
int eval_crop_size(int w, int h);
/* The window of the entry's FLIP map with the largest mean FLIP (the worst-error window). */
eval_window eval_worst_window(const sss_image *flip_map, int size);
/* The window holding the most coverage edges of a scene: pixels where the G-buffer object id
 * (sss_eval_scene.object_ids, at `scale` x the w x h output) changes to a neighbour, i.e. silhouettes
 * against the background and between objects. Invalid when there are no ids or no edges. */
eval_window eval_silhouette_window(const sss_image *object_ids, int w, int h, int size);
/* "crops_<stem>[_t<T>]_<k>.png": the crops of technique k (label index) in scene s. */
void eval_crops_file(const sss_eval_scene *s, int k, char *out, size_t cap);
/* Writes that file: reference | technique for the worst-FLIP window and the silhouette window, 192-pixel
 * boxes. Only for techniques compared at the scene's first quality size (SSS_ERROR_INVALID_ARGUMENT
 * otherwise). */
sss_result eval_write_crops(const sss_eval_results *res, int scene, int k, const char *path, sss_error *err);
/* Draws surface scaled into the box (x, y, w, h) keeping its aspect ratio; returns the drawn height. */
double eval_draw_surface(cairo_t *cr, cairo_surface_t *s, double x, double y, double w, double h);
/* Text helpers: size in pixels; align 0 left, 0.5 centre, 1 right (x is the anchor); y the baseline. */
void eval_text(cairo_t *cr, double x, double y, double size, int bold, double align, const char *text);
double eval_text_width(cairo_t *cr, double size, int bold, const char *text);
/* Writes an ARGB32/RGB24 surface as PNG atomically (sss_image_write_png8). */
sss_result eval_write_surface(cairo_surface_t *s, const char *path, sss_error *err);
/* Writes the canvas (unless cairo failed: the error names path) and destroys cr and s. */
sss_result eval_finish_canvas(cairo_surface_t *s, cairo_t *cr, const char *path, sss_error *err);
/* Surface + context of a white canvas; 0 on failure (both set to NULL). */
int eval_canvas(int width, int height, cairo_surface_t **s, cairo_t **cr);

/* Some technique was timed at two sizes or more in some scene: plot_resolution.png has a line to draw
 * (with one size per scene it would show one dot per technique and is not written). */
int eval_resolutions_plotted(const sss_eval_results *res);

/* Nice axis ticks from lo to hi (about `target` of them): step and first tick. */
void eval_ticks(double lo, double hi, int target, double *first, double *step, int *count);
/* Number formatting for labels: short, no exponent for usual ranges. */
void eval_format_number(double v, double step, char *out, size_t cap);

/* Entry lookup: QUALITY/TIMING entry of (scene, label index, size); NULL when absent. */
const sss_eval_entry *eval_find(const sss_eval_results *res, int scene, sss_eval_kind kind, const char *label,
                                int width, int height);
/* "sheet_<stem>.png", "sheet_<stem>_t<T>.png" for a scene with a time. */
void eval_sheet_file(const sss_eval_scene *s, char *out, size_t cap);
/* The scene's first quality size (its camera size when no references were planned). */
void eval_primary_size(const sss_eval_results *res, int scene, int *width, int *height);
/* Creates the folder dir and its missing parents (mkdir -p); errors name the folder. */
sss_result eval_make_dirs(const char *dir, sss_error *err);

#endif
