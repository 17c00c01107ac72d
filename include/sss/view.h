/* sss/view.h — the interactive viewer: a GLFW window showing a scene with a real-time technique, an
 * orbit camera, technique switching, translucency / screen-space parts alone, measured-media presets,
 * the light moved around the object, the animation, screenshots and the DSSIM against a CPU reference
 * rendered in the background at the current view; a Dear ImGui panel (parameters, per-object materials,
 * lights, frame time per pass, buffers, a split view, an error map) that a script can drive
 * (docs/viewer.md).
 *
 * Does: everything in one call (sss_view_run) that returns when the window is closed, or after a fixed
 * number of frames without input or after a script's actions (for tests under Xvfb). Does not: print
 * (messages go through the desc's callback), run without a display (an error that suggests
 * `sss render`).
 * Threading: call from one thread; the reference renders in a worker thread of its own.
 */
#ifndef SSS_VIEW_H
#define SSS_VIEW_H

#include "sss/common.h"
#include "sss/gl.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Zero-initialised means: the scene's technique at the scene camera's size, interactive, overlay on. */
typedef struct sss_view_desc {
    const char *scene_path;           /* required */
    const char *technique;            /* NULL -> the scene's render.technique */
    int width, height;                /* window size; 0 -> the scene camera's */
    const sss_gl_param_value *params; /* technique or shared parameters by name (kept when the technique
                                         changes, for the techniques that know them) */
    int param_count;
    double time;                      /* animation time of the first frame (seconds) */
    int animate;                      /* start with the animation playing */
    int frames;                       /* > 0: render this many frames without input, then return */
    const char *screenshot;           /* with frames: the last frame as PNG (the window's back buffer,
                                         read before the overlay is drawn and before the swap) */
    /* With frames: input events, comma-separated, one per frame from the first (for tests): keys as
     * named in sss_view_help_text ("tab", "shift+tab", "1", "m", "+", "l", "space", ...),
     * "orbit:DX:DY" / "pan:DX:DY" (a left / right drag by DX, DY pixels, y down), "zoom:STEPS". */
    const char *input;
    int no_overlay;                   /* start with the panel (or the text overlay) hidden */
    /* A file of panel actions, one per line (docs/viewer.md): runs them without input, then returns
     * (instead of frames / input / screenshot). */
    const char *script;
    int reference;                    /* render the reference of the first view at once; with frames,
                                         wait for it and report the DSSIM of the last frame (log) */
    int reference_draft;              /* references at draft quality (R; Shift+R is always draft) */
    int supersample;                  /* antialiasing of every technique (sss_gl_renderer_desc.supersample:
                                         1..4, 0 -> 1 = off) */
    /* Messages for the user ("saved sss-view-0000.png", reference finished, ...); may be NULL. */
    void (*log)(void *user, const char *message);
    void *log_user;
} sss_view_desc;

/* Runs the viewer. Errors: the scene (named by its file), no display (the message suggests
 * `sss render`), the GL context or technique, the screenshot file. */
SSS_API sss_result sss_view_run(const sss_view_desc *desc, sss_error *err);

/* The key and mouse bindings as text (one binding per line), for help screens. */
SSS_API const char *sss_view_help_text(void);

#ifdef __cplusplus
}
#endif
#endif
