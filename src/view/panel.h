/* view/panel.h — the viewer's Dear ImGui panel (panel_imgui.cpp, the only C++ of the viewer) behind a
 * C interface: technique list, the technique's parameters from its table, per-object materials, lights,
 * a frame-time graph per pass, buffer, split view, error map. Its widgets call view/commands.c, the
 * same functions as `--script` lines. Needs the window's context current. Does not: own any viewer
 * state besides ImGui's and the frame-time history. */
#ifndef SSS_VIEW_PANEL_H
#define SSS_VIEW_PANEL_H

#include "sss/common.h"

#ifdef __cplusplus
extern "C" {
#endif

struct viewer;

/* Sets v->panel; on failure it stays NULL (the viewer falls back to the bitmap overlay). */
sss_result view_panel_create(struct viewer *v, sss_error *err);
void view_panel_destroy(struct viewer *v);
/* Builds this frame's widgets (running the actions they trigger) and draws them over the framebuffer. */
sss_result view_panel_draw(struct viewer *v, sss_error *err);
/* 1 when the panel uses the mouse (mouse 1) or the keyboard (mouse 0): the viewer then ignores it. */
int view_panel_wants(const struct viewer *v, int mouse);
/* GLFW events forwarded by view/input.c. */
void view_panel_key(struct viewer *v, int key, int scancode, int action, int mods);
void view_panel_char(struct viewer *v, unsigned codepoint);
void view_panel_button(struct viewer *v, int button, int action, int mods);
void view_panel_scroll(struct viewer *v, double dx, double dy);

#ifdef __cplusplus
}
#endif
#endif
