/* view/view_gl.h — the viewer's own GL drawing on the window's default framebuffer: the text overlay,
 * intermediate buffers of a technique, and reading the back buffer for screenshots. Needs the window's
 * context current. */
#ifndef SSS_VIEW_GL_H
#define SSS_VIEW_GL_H

#include "view/view_internal.h"

typedef struct view_gl {
    unsigned prog_text, prog_image;
    unsigned vao_text, vbo_text, ebo_text, vao_empty;
    int ebo_quads;   /* quads the index buffer covers */
    unsigned tex_image;
    int tex_w, tex_h;
} view_gl;

sss_result view_gl_init(view_gl *g, sss_error *err);
void view_gl_free(view_gl *g);
/* Alpha-blends the text quads over the framebuffer (fb_w x fb_h pixels). */
sss_result view_gl_draw_text(view_gl *g, const view_text *t, int fb_w, int fb_h, sss_error *err);
/* Uploads img (linear RGB) and draws it stretched over the framebuffer, tone mapped with exposure. */
sss_result view_gl_draw_image(view_gl *g, const sss_image *img, double exposure, int fb_w, int fb_h, sss_error *err);
/* Draws the last uploaded image again (after view_gl_draw_image). */
sss_result view_gl_redraw_image(view_gl *g, double exposure, int fb_w, int fb_h, sss_error *err);
/* Reads the back buffer (8-bit RGB, before any swap) and writes it as a PNG, top row first. */
sss_result view_gl_screenshot(int fb_w, int fb_h, const char *path, sss_error *err);

#endif
