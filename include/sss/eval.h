/* sss/eval.h — evaluation of the real-time techniques against the CPU ground truth, as the papers
 * measure them: image quality (DSSIM, FLIP, PSNR, RMSE; Maisch & Ropinski 2020, section 8.1, Figs. 7 and 10; Maisch & Ropinski 2017
 * Figs. 10 and 11), frame time per pass (Maisch & Ropinski 2020, section 8.2, Fig. 11), precomputation and memory.
 *
 * Does: loads scenes, renders every requested technique (the GL registry's, so new techniques appear
 * without changes here) at each requested resolution and the reference (sss/reference.h; a cached
 * EXR next to the scene when asked and present), compares them (sss_image_compare), times every pass
 * (median of N frames), and writes results.json, results.csv, one comparison sheet per scene, plots
 * and a self-contained report.html (cairo for the images).
 * Does not: print (progress and notes go through callbacks), exit, or drop a failing technique: a
 * technique that cannot be created or rendered is an entry with status "failed" and the error.
 *
 * Threading: everything runs on the calling thread (the reference uses its OpenMP workers); the GL
 * context is created and destroyed inside sss_eval_run.
 * Memory: sss_eval_run fills a results struct that sss_eval_results_free releases.
 */
#ifndef SSS_EVAL_H
#define SSS_EVAL_H

#include <stddef.h>

#include "sss/common.h"
#include "sss/gl.h"
#include "sss/image.h"
#include "sss/reference.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sss_eval_size {
    int width, height;
} sss_eval_size;

/* An image of each scene rendered by another program (`sss eval --images NAME=PATTERN`), scored against
 * the same truth as the techniques, in the same tables, sheets, crops and plots, marked as external
 * (no timings, no memory). pattern is a file path in which every "{scene}" stands for the scene's file
 * name without its extension; the format comes from the extension: EXR, PFM or HDR hold linear radiance,
 * PNG sRGB as displayed at the scene's exposure (decoded, then divided by 2^exposure, so that the
 * metrics, which tone-map with the scene's exposure, see the file's own pixels). Each image must have the
 * scene's first quality size and finite values; otherwise sss_eval_run fails before any work, naming the
 * file. Compared at the first quality size only. */
typedef struct sss_eval_image_source {
    const char *name;    /* the entry's label; not a technique spec of the run, nor another image's name */
    const char *pattern; /* "renders/{scene}_cycles.exr" */
} sss_eval_image_source;

/* Zero-initialised means: every registered technique, each scene at its camera's size, 5 timed
 * frames after 2 warm-up frames (SSS_GL_TIMED_FRAMES, SSS_GL_WARMUP_FRAMES),
 * references rendered at final quality, SAM sweep when `sam` is among the techniques.
 *
 * Technique specs are "name" or "name:param=value[:param=value...]" (technique or shared parameters
 * of sss/gl.h); the whole spec is the entry's label. An unknown name or parameter is not an error of
 * the run: the entry is reported as failed with the renderer's message.
 * Scene arguments are "path.json" or "path.json@T": the animation time T in seconds (default 0). */
typedef struct sss_eval_desc {
    const char *const *techniques;  /* specs; NULL or 0 count: every registered technique */
    int technique_count;
    const sss_eval_size *resolutions; /* quality runs (reference + metrics); 0 count: camera size */
    int resolution_count;
    const sss_eval_size *timing_resolutions; /* extra sizes where only frame times are measured */
    int timing_resolution_count;
    int frames;                     /* timed frames per technique; timings are medians; 0 -> 5 */
    int warmup_frames;              /* frames rendered first and not timed; 0 -> 2, -1 -> none */
    int cached_reference;           /* use <reference_dir>/<scene>_<w>x<h>[_t<T>].exr when present */
    const char *reference_dir;      /* NULL: "references" in each scene file's folder */
    sss_reference_quality reference_quality;
    int reference_threads;          /* 0: all cores */
    int sam_sweep;                  /* 0: auto (sam among the techniques), 1: always, -1: never */
    const int *sam_counts;          /* back-side sample counts; NULL: 3, 10, 20, 50 (Maisch & Ropinski 2017, Fig. 10) */
    int sam_count_count;
    const char *save_references_dir; /* if set, rendered (not cached) references are written here as
                                        half-float EXR with their .json sidecar, ready to commit */
    int supersample;                /* SSAA factor of every technique (sss_gl_renderer_desc.supersample,
                                       1..4; 0 -> 1: off); a spec's "supersample=K" overrides it for that
                                       spec ("maisch2020:supersample=2") */
    int reference_bounces;          /* the truth compared against: sss_reference_desc.bounces (0: the full
                                       transport, the default; 1: the single-event integral); a cached
                                       reference is used only when its sidecar records the same */
    int reference_noise;            /* 1: a second reference at the first quality size, seed 1 (cached as
                                       <scene>_seed1_<w>x<h>[_t<T>].exr): every technique is compared with
                                       both, and the largest change of a metric between them is the scene's
                                       noise (sss_eval_scene.noise_*), which the report's "best" must beat */
    int both_truths;                /* 1: also score every entry at the first quality size against the
                                       single-event truth (sss_reference_desc.bounces 1, the same quality
                                       and time; cached as <scene>_bounces1_<w>x<h>[_t<T>].exr), beside the
                                       main truth (reference_bounces, which must not be 1): for an entry
                                       without the interreflection stage the difference is the light
                                       between surfaces (sss_eval_entry.single_event) */
    const sss_eval_image_source *images; /* images from other programs (above); NULL or 0 count: none */
    int image_count;
    double frame_budget_s;          /* 0: none. Else a technique's timed frames stop once they have taken
                                       this many seconds (at least one is timed), and a technique whose
                                       first warm-up frame alone took longer is timed on that frame, with
                                       its one-off costs (shader compilation, first uploads) in it: its
                                       entry's warmup_frames is 0. For slow techniques in short runs */
} sss_eval_desc;

/* Progress: fraction in [0, 1] of the estimated work and a short description of the current step
 * ("eval_dragon 480x270: reference 35%"). note: one line the user should see (a reference that is
 * rendered because no cached one exists, a stale cache, a skipped SAM count). Either may be NULL. */
typedef struct sss_eval_callbacks {
    void (*progress)(void *user, double fraction, const char *stage);
    void (*note)(void *user, const char *message);
    void *user;
} sss_eval_callbacks;

/* ---- Results --------------------------------------------------------------------------------- */

typedef enum sss_eval_kind {
    SSS_EVAL_QUALITY = 0, /* rendered at a quality resolution and compared with the reference */
    SSS_EVAL_TIMING,      /* frame time only (timing_resolutions) */
    SSS_EVAL_SAM_SWEEP    /* the sam technique at one back-side sample count (Maisch & Ropinski 2017, Fig. 10) */
} sss_eval_kind;

SSS_API const char *sss_eval_kind_name(sss_eval_kind kind); /* "quality", "timing", "sam_sweep" */

typedef struct sss_eval_pass {
    char name[32];
    double ms; /* median over the frames */
} sss_eval_pass;

#define SSS_EVAL_LABEL_SIZE 160

typedef struct sss_eval_entry {
    int scene;                        /* index into sss_eval_results.scenes */
    sss_eval_kind kind;
    char label[SSS_EVAL_LABEL_SIZE];  /* the technique spec as given ("sam:n=10" for sweep points) */
    char technique[64];               /* the technique name of the spec */
    int width, height;
    int sam_n;                        /* SAM_SWEEP: back-side samples; 0 otherwise */
    int ok;                           /* 0: failed, error holds why */
    char error[SSS_ERROR_MESSAGE_SIZE];
    char warning[SSS_ERROR_MESSAGE_SIZE]; /* materials whose kernel the technique cuts (sss_gl_kernel_cut_warnings,
                                         one per line), or empty */
    int has_metrics;                  /* compared with a reference */
    sss_image_metrics metrics;
    int frames;                       /* timed frames (the median's) */
    int warmup_frames;                /* untimed frames rendered before them (fewer than asked only
                                         under sss_eval_desc.frame_budget_s) */
    int supersample;                  /* the SSAA factor it rendered with (1: off) */
    double total_ms;                  /* median of the per-frame totals */
    int pass_count;
    sss_eval_pass passes[SSS_GL_MAX_PASSES];
    double precompute_ms;             /* sss_gl_renderer_create: upload, LUTs, technique set-up */
    int has_stats;
    sss_gl_stats stats;               /* texture_bytes + buffer_bytes is the renderer's GPU memory */
    sss_image image;                  /* QUALITY at the first resolution only (empty otherwise) */
    sss_image dssim_map;              /* per-pixel, per-channel DSSIM of image (same rule) */
    sss_image flip_map;               /* per-pixel FLIP of image, in all three channels (same rule) */
    double mean_ratio[3];             /* has_metrics: the image's mean linear R, G, B over the reference's
                                         (1: as much light; NaN where the reference's mean is 0) */
    int has_single_event;             /* also compared with the single-event truth (sss_eval_desc.both_truths;
                                         QUALITY entries at the first size) */
    sss_image_metrics single_event;   /* its metrics against that truth */
    double single_event_ratio[3];     /* and its mean_ratio against it */
    int external;                     /* an image from another program (sss_eval_desc.images): label its
                                         name, technique "external", no frames, timings or stats */
    char file[1024];                  /* external: the file read */
} sss_eval_entry;

typedef enum sss_eval_ref_source {
    SSS_EVAL_REF_NONE = 0, /* not available (failed) */
    SSS_EVAL_REF_CACHED,
    SSS_EVAL_REF_RENDERED
} sss_eval_ref_source;

typedef struct sss_eval_reference {
    int width, height;
    sss_eval_ref_source source;
    char path[1024];                  /* the cached file read, or the file saved (may be empty) */
    double seconds;                   /* render (or read) time */
    char quality[8];                  /* "final" / "draft" (cached: from its sidecar, else "unknown") */
    int bounces;                      /* its sss_reference_desc.bounces (0: full transport) */
    char error[SSS_ERROR_MESSAGE_SIZE]; /* SSS_EVAL_REF_NONE: why */
} sss_eval_reference;

typedef struct sss_eval_scene {
    char *path;                       /* as given, without the @T suffix */
    char name[128];                   /* stem, plus "@T" when a time was given */
    char stem[128];                   /* the scene's name in the outputs (sheet_<stem>.png, ...): its
                                         file stem, or, when another scene of the run has the same
                                         file stem and time, the file stem with its folders' names
                                         ("s-d1" for d1/s.json, "s-a-x" for a/x/s.json) */
    char file_stem[128];              /* the scene file's name without its extension */
    double time;
    int has_time;
    int width, height;                /* camera size */
    double exposure;
    unsigned long long triangles;     /* of all objects' render meshes */
    int reference_count;
    sss_eval_reference references[8]; /* one per quality resolution, in order */
    sss_image reference;              /* at the first quality resolution (empty when unavailable) */
    sss_image object_ids;             /* G-buffer object index + 1 of the subsurface objects (0: other
                                         objects and background) from the first technique that rendered
                                         at that size, at its supersampled size (a whole multiple of it);
                                         empty when none did. For the silhouette crops */
    sss_eval_reference single_event_reference; /* sss_eval_results.both_truths: the single-event truth at the
                                         first quality size (bounces 1) */
    int has_noise;                    /* desc.reference_noise and both references were available */
    double noise_dssim, noise_flip;   /* the largest |metric against seed 0 - metric against seed 1| of any
                                         technique at the first quality size */
} sss_eval_scene;

typedef struct sss_eval_results {
    sss_eval_scene *scenes;
    int scene_count;
    sss_eval_entry *entries;
    int entry_count, entry_capacity;
    char **labels;                    /* the technique specs evaluated, in order, then the names of the
                                         external images (sss_eval_desc.images) */
    int label_count;
    int external_count;               /* the last external_count labels are external images */
    char **external_patterns;         /* their patterns, as given (external_count entries) */
    int frames;                       /* timed frames per technique */
    int warmup_frames;                /* untimed frames before them */
    double frame_budget_s;            /* sss_eval_desc.frame_budget_s (0: none) */
    int supersample;                  /* sss_eval_desc.supersample (1: off) */
    sss_reference_quality reference_quality;
    int cached_reference;
    int reference_bounces;            /* sss_eval_desc.reference_bounces */
    int both_truths;                  /* sss_eval_desc.both_truths */
    int gl_ok;                        /* a GL context could be created */
    char gl_error[SSS_ERROR_MESSAGE_SIZE];
    char gl_platform[64], gl_renderer[160], gl_version[160], timing_method[64];
    int gl_software;
    int sam_available;                /* the registry has sam with a sample-count parameter */
    int sam_swept;                    /* the sweep ran */
    char sam_param[32];               /* that parameter's name */
    char sam_note[256];               /* why not, when unavailable */
    double seconds;                   /* wall time of sss_eval_run */
    char created[32];                 /* UTC, ISO 8601 */
} sss_eval_results;

/* Runs the evaluation. Fails (nothing to free) on invalid arguments, a scene that cannot be loaded
 * (the message names the file), an EXR that cannot be saved, or out of memory; technique failures
 * and reference failures are results, not errors. */
SSS_API sss_result sss_eval_run(const char *const *scenes, int scene_count, const sss_eval_desc *desc,
                                const sss_eval_callbacks *cb, sss_eval_results *out, sss_error *err);
SSS_API void sss_eval_results_free(sss_eval_results *res);

/* Checks a technique spec's syntax ("name[:param=value...]", value a finite number); the name and
 * parameters are not looked up. */
SSS_API sss_result sss_eval_check_spec(const char *spec, sss_error *err);
/* Parses "WxH[,WxH...]" (each 11..16384, the SSIM window needs 11). *out is malloc'ed. */
SSS_API sss_result sss_eval_parse_sizes(const char *text, sss_eval_size **out, int *count, sss_error *err);
/* The cached reference's file name: "<dir>/<stem>_<w>x<h>.exr", with "_t<T>" before ".exr" when a
 * time was given (T printed with %g). */
SSS_API int sss_eval_reference_path(const char *dir, const char *stem, int width, int height, int has_time,
                                    double time, char *out, size_t cap);

/* ---- Output ---------------------------------------------------------------------------------- */

/* Everything below into out_dir (created if missing): results.json, results.csv, sheet_<scene>.png per
 * scene, crops_<scene>_<k>.png per compared technique k (its zoomed crops), plot_dssim.png,
 * plot_flip.png, plot_passes.png, plot_sam_rmse.png (only when the SAM sweep ran: without points it
 * would be an empty plot; the report says why it is missing), plot_resolution.png and report.html.
 * Files are written atomically. */
SSS_API sss_result sss_eval_write_all(const sss_eval_results *res, const char *out_dir, sss_error *err);

SSS_API sss_result sss_eval_write_json(const sss_eval_results *res, const char *path, sss_error *err);
SSS_API sss_result sss_eval_write_csv(const sss_eval_results *res, const char *path, sss_error *err);
/* The comparison sheet of one scene (Maisch & Ropinski 2020, Fig. 7): the reference large, each technique with its
 * label, DSSIM, FLIP and milliseconds, its per-pixel DSSIM map (R, G, B = the channels' DSSIM) and FLIP map
 * with colour bars, and zoomed crops of its worst-FLIP window and of the scene's silhouette window. */
SSS_API sss_result sss_eval_write_sheet(const sss_eval_results *res, int scene, const char *path, sss_error *err);
/* Plots (PNG): DSSIM (and FLIP) per technique per scene (grouped bars, Maisch & Ropinski 2020, Fig. 10); stacked milliseconds
 * per pass (Maisch & Ropinski 2020, Fig. 11); SAM RMSE against back-side samples (Maisch & Ropinski 2017, Fig. 10; says "sam not
 * available" when it is not); total frame time against resolution (one panel per scene, a line per
 * technique). */
SSS_API sss_result sss_eval_plot_dssim(const sss_eval_results *res, const char *path, sss_error *err);
SSS_API sss_result sss_eval_plot_flip(const sss_eval_results *res, const char *path, sss_error *err);
SSS_API sss_result sss_eval_plot_passes(const sss_eval_results *res, const char *path, sss_error *err);
SSS_API sss_result sss_eval_plot_sam(const sss_eval_results *res, const char *path, sss_error *err);
SSS_API sss_result sss_eval_plot_resolution(const sss_eval_results *res, const char *path, sss_error *err);
/* report.html: one page, images embedded as base64 data URIs, CSS inline, no scripts. Reads the PNGs
 * named above from out_dir (missing ones are left out with a note). */
SSS_API sss_result sss_eval_write_report(const sss_eval_results *res, const char *out_dir, sss_error *err);

#ifdef __cplusplus
}
#endif
#endif
