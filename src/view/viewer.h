/* view/viewer.h — the viewer's state, shared by its loop (viewer.c), input, panel, commands, rebuilds
 * and actions, and the overlay text (status.c); the files' layering is below the struct. */
#ifndef SSS_VIEW_VIEWER_H
#define SSS_VIEW_VIEWER_H

#include "core/file_util.h"
#include "sss/gl.h"
#include "sss/scene.h"
#include "sss/view.h"
#include "view/view_gl.h"
#include "view/view_internal.h"

struct GLFWwindow;

enum { PART_ALL = 0, PART_TRANSLUCENCY, PART_SCREEN };

#define VIEW_MAX_SET_PARAMS 64
enum { VIEW_SPLIT_OFF = 0, VIEW_SPLIT_REFERENCE, VIEW_SPLIT_TECHNIQUE };
struct view_command;

typedef struct view_rebuild_request {
    char *text;       /* the scene file's text with the edit (NULL: no request) */
    int medium;
    double scale;
    char what[128];   /* for the message: "objects[0].material.scale set" */
    int line;         /* the script line, 0 otherwise */
    double started;   /* sss_time_seconds() of the request */
} view_rebuild_request;

/* Buffers of sss_gl_renderer_read_buffer the B key cycles through ("final" is the normal view). */
#define VIEW_BUFFER_COUNT 6
extern const char *const view_buffer_names[VIEW_BUFFER_COUNT];

struct viewer {
    const sss_view_desc *desc;
    /* scene: the file's text (edits are applied to it), the live scene the renderer reads */
    char *text;
    size_t text_size;
    sss_scene *scene;
    sss_camera home;       /* the file's camera (C resets to it) */
    int has_light;         /* the scene has a lights[0] */
    int medium;            /* -1: the file's materials; else a measured medium for all */
    double scale_factor;   /* x2 / /2 on the scattering coefficients */
    double light_angle;    /* degrees lights[0] was turned about the vertical (-180, 180] */
    /* GL */
    sss_gl_context *ctx;
    struct GLFWwindow *window;
    sss_gl_renderer *r;
    view_gl gl;
    int tech;              /* index in the registry */
    int part;              /* PART_* */
    int part_saved_tech;   /* technique before PART_SCREEN switched to "screen", or -1 */
    const char *part_buffer; /* buffer standing for the part when the technique has no switches */
    int buffer;            /* index in view_buffer_names (0 final) */
    int width, height;     /* renderer = framebuffer size */
    /* time */
    double t, wall_last;
    int playing;
    /* input */
    int drag_button;       /* -1 none */
    double mouse_x, mouse_y;
    int shift;
    /* pending actions (set by callbacks, run by the loop) */
    int act_tech, act_part, act_buffer, act_medium, act_light, act_reference, act_screenshot;
    double act_scale;
    /* status */
    int need_render;
    unsigned image_gen;    /* bumps whenever the rendered image changes */
    unsigned shown_gen;    /* image_gen of the buffer uploaded for display */
    const char *shown_name; /* and its name */
    double frame_ms;
    double frame_wall_ms;  /* the last frame from its start to the swap, actions and rebuilds included */
    double overlay_ms;     /* drawing the panel or text overlay in the last frame (scripts: GL finished) */
    sss_gl_timings timings;              /* medians of timing_series */
    sss_gl_timing_series timing_series; /* the renderer's frames after warm-up, the latest few */
    char message[256];
    double message_until;
    int overlay, help;
    double title_at;
    /* reference and DSSIM */
    view_ref_job *job;
    char *job_key;
    view_ref_cache cache;
    char *view_key;        /* key of the current view (NULL: recompute) */
    const sss_image *ref;  /* cached reference of the current view, or NULL */
    double dssim;
    unsigned dssim_gen;    /* image_gen the dssim belongs to (0: none) */
    int ref_draft;
    sss_image frame_img;
    /* panel, parameters, split view, error map (commands.c, panel_imgui.cpp) */
    struct view_panel *panel;     /* NULL: the bitmap-text overlay stands in */
    sss_gl_param_value set_params[VIEW_MAX_SET_PARAMS]; /* set in the panel or script ("tech.name" or "name") */
    char set_names[VIEW_MAX_SET_PARAMS][64];
    int set_count;
    int split;                    /* VIEW_SPLIT_* */
    int split_tech;               /* the right-hand technique of VIEW_SPLIT_TECHNIQUE */
    double split_pos;             /* wipe position, fraction of the width */
    sss_gl_renderer *split_r;     /* its renderer */
    int errormap;                 /* show the per-pixel DSSIM against the reference */
    double error_range;           /* the colour bar's top value */
    unsigned composed_gen;        /* image_gen of the split / error-map image on screen (0: none) */
    const sss_image *composed_ref;
    sss_image other_img, composed_img, map_img;
    /* material edits, built in the background (rebuild.c): the worker loads the edited scene and
     * computes its LUTs, the window thread then only creates the renderer from them */
    view_build_job *build;        /* running, or NULL */
    view_rebuild_request building, pending; /* the running build's edit; the latest edit made meanwhile */
    char *live_text;              /* text, medium and scale of the scene on screen (restored on failure) */
    int live_medium;
    double live_scale;
    int build_frames;             /* frames drawn while the current build ran */
    double build_longest_ms;      /* the longest of them (render to swap, wall clock) */
    int build_dropped;            /* builds dropped for a newer edit since the last applied one */
    int script_line;              /* the script line being run (0: none) */
    int build_failed_line;        /* a script line whose edit failed in the worker (0: none) */
    sss_error build_err;
    double rebuild_ms;            /* the last applied edit: from the request to the new renderer */
    double rebuild_window_ms;     /* of which on the window thread (renderer creation, uploads) */
    int rebuild_in_place;         /* it updated the renderer's materials (else: a new renderer) */
    double rebuild_scene_ms, rebuild_tables_ms; /* the worker's loader and LUT times */
    const char *shot_path;        /* a script's screenshot, taken after the panel is drawn */
    sss_io_set files;             /* the inputs no screenshot may overwrite: the scene, every file it
                                   * reads, the script (material edits change no file name) */
};

typedef struct viewer viewer;

/* The viewer's files call one way, top to bottom (a file calls only those below it):
 *   viewer.c          the window, the frame loop, the fixed-frame and script runners
 *   input.c           GLFW callbacks and scripted input events -> the panel, then commands
 *   panel_imgui.cpp   the panel's widgets -> commands
 *   script.c          script lines parsed into view_command (no viewer state)
 *   status.c          the overlay text, the key help, the title (reads the state)
 *   commands.c        each user action: technique, param, material, light, buffer, split, camera, keys
 *   rebuild.c         material edits built in the background and applied over frames
 *   actions.c         the renderers, parts, buffers, invalidation, reference and DSSIM, screenshots
 *   jobs and pieces   build_job.c, reference_job.c, job.c, scene_edit.c, motion.c, compose.c,
 *                     overlay_text.c, view_gl.c (view_internal.h, view_gl.h: no viewer state) */

/* ---- input.c ---------------------------------------------------------------------------------- */
void view_install_callbacks(viewer *v);
/* One scripted event: a key ("tab", "shift+m", "l", "+", "space", ...), "orbit:DX:DY" / "pan:DX:DY"
 * (a left / right drag by DX, DY framebuffer pixels) or "zoom:STEPS" (wheel). Returns 0 when the
 * event is unknown; apply 0 only checks it. Keys that rebuild are queued: view_cmd_keys runs them. */
int view_input_event(viewer *v, const char *event, int apply);

/* ---- status.c --------------------------------------------------------------------------------- */
void view_overlay_text(viewer *v, char *buf, size_t cap);
void view_update_title(viewer *v);

/* ---- commands.c: the panel's widgets and the script's lines, one function each; failures are
 * returned (the panel turns them into messages, a script stops) and leave the viewer usable. ---- */
sss_result view_cmd_technique(viewer *v, int tech, sss_error *err);
sss_result view_cmd_param(viewer *v, const char *name, double value, sss_error *err);
sss_result view_cmd_material(viewer *v, int object, const char *field, const char *medium, const double *values,
                             int value_count, sss_error *err);
/* field: "position" (3 values), "intensity" (1: the brightest channel, the colour kept) or "colour"
 * (3, scaled to the brightest channel, the intensity kept). */
sss_result view_cmd_light(viewer *v, int light, const char *field, const double *values, int value_count,
                          sss_error *err);
sss_result view_cmd_buffer(viewer *v, int buffer, sss_error *err);
/* what: "off", "reference" or a technique name; position in (0, 1). */
sss_result view_cmd_split(viewer *v, const char *what, double position, sss_error *err);
void view_cmd_errormap(viewer *v, int on);
/* The reference of the current view in the background (draft, or final unless --draft-reference). */
void view_cmd_reference(viewer *v, int draft);
/* Any script command but frames, wait, screenshot and key (the loop runs those). */
sss_result view_cmd_run(viewer *v, const struct view_command *c, sss_error *err);
/* The camera: orbit (degrees), pan (framebuffer pixels), zoom (distance factor), back to the file's. */
void view_cmd_orbit(viewer *v, double azimuth_deg, double elevation_deg);
void view_cmd_pan(viewer *v, double dx, double dy);
void view_cmd_zoom(viewer *v, double factor);
void view_cmd_camera_home(viewer *v);
/* The key actions input.c queued in v->act_* (technique, part, buffer, medium, scale, light, reference). */
void view_cmd_keys(viewer *v);

/* ---- rebuild.c: material edits off the window thread. view_request_rebuild takes the viewer's
 * current text, medium and scale (what names the edit in messages; line is the script line, 0
 * otherwise) and starts a build, or replaces the one waiting behind the running build (latest wins).
 * view_poll_rebuild (every frame) applies a finished build, or drops it when a newer edit waits and
 * starts that one. A failure restores the scene on screen's text, medium and scale and says why in
 * the message. ---- */
void view_request_rebuild(viewer *v, const char *what, int line);
void view_poll_rebuild(viewer *v);
int view_rebuild_busy(const viewer *v); /* a build runs or waits */
void view_rebuild_free(viewer *v);

/* ---- actions.c: each reports problems through view_message and leaves the viewer usable ---- */
void view_message(viewer *v, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
/* A param the panel or script set for technique `tech` (NaN when none). */
double view_set_param_value(const viewer *v, const char *tech, const char *name);
/* The desc of the viewer's renderers of a technique (--param, then the panel's values); free(*params). */
sss_result view_renderer_desc(viewer *v, const sss_gl_technique_info *info, sss_gl_renderer_desc *d,
                              sss_gl_param_value **params, sss_error *err);
/* A renderer of a technique for `scene` (the viewer's, or an edit's being applied) with the viewer's
 * size, --param and panel parameters, and `tables` (NULL: computed). */
sss_result view_create_renderer(viewer *v, const sss_gl_technique_info *info, const sss_scene *scene,
                                const sss_gl_tables *tables, sss_gl_renderer **out, sss_error *err);
/* The renderer of technique tech for scene and tables (as view_create_renderer) replaces v->r (the part
 * switches applied); on failure v->r stays. */
sss_result view_make_renderer_for(viewer *v, int tech, const sss_scene *scene, const sss_gl_tables *tables,
                                  sss_error *err);
/* view_make_renderer_for of the viewer's own scene. */
sss_result view_make_renderer(viewer *v, int tech, sss_error *err);
/* view_make_renderer with the failure as a message ("technique NAME" too unless quiet). */
void view_switch_technique(viewer *v, int tech, int quiet);
void view_apply_part(viewer *v, int part);
/* Reads the buffer to display (a part's or the B key's) into out; 0 when the final image is shown. */
int view_buffer_to_show(viewer *v, sss_image *out);
/* The view changed (camera, light, materials, size, time): the reference is looked up again. */
void view_invalidate(viewer *v);
void view_camera_changed(viewer *v);
void view_light_changed(viewer *v);
/* The split renderer again after the scene or size changed (no-op when there is none). */
void view_split_refresh(viewer *v);
/* The scene file's text with the viewer's edits (camera, light 0, preset, scale); free() it. */
sss_result view_edited_json(viewer *v, char **json, sss_error *err);
sss_result view_current_key(viewer *v, char **key, char **json, sss_error *err);
void view_request_reference(viewer *v, int draft);
void view_poll_reference(viewer *v);
void view_update_dssim(viewer *v);
/* sss-view-NNNN.png, the first that does not exist in the working folder; 0 when all are taken. */
int view_next_screenshot_name(char *buf, size_t cap);
/* The output rules of every command (sss_io_check) for the viewer's outputs: refuses one that is the
 * same file as an input (v->files) or as another of paths. */
sss_result view_check_outputs(const viewer *v, const char *const *paths, size_t count, sss_error *err);
/* Writes the window's back buffer to path as PNG, after view_check_outputs. */
sss_result view_save_screenshot(const viewer *v, const char *path, sss_error *err);

#endif
