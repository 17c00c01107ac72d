/* view/view_gl.c — the viewer's drawing: overlay quads (src/view/shaders/view_overlay.*.glsl),
 * technique buffers shown alone (src/view/shaders/view_image.*.glsl) and screenshots from the back
 * buffer. The shaders are embedded like the renderer's and built by the GL module's program builder
 * (gl_program_vf: errors name the shader file and line). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <epoxy/gl.h>

#include "gl/core/gl_base.h"
#include "view/view_gl.h"

static sss_result gl_error(const char *what, sss_error *err)
{
    GLenum e = glGetError();
    if (e == GL_NO_ERROR) return SSS_OK;
    while (glGetError() != GL_NO_ERROR) {}
    return sss_error_set(err, e == GL_OUT_OF_MEMORY ? SSS_ERROR_OUT_OF_MEMORY : SSS_ERROR_NUMERIC,
                         "OpenGL error 0x%x in the viewer's %s", (unsigned)e, what);
}

sss_result view_gl_init(view_gl *g, sss_error *err)
{
    memset(g, 0, sizeof *g);
    sss_result res = gl_program_vf("view_overlay.vert.glsl", "view_overlay.frag.glsl", NULL, &g->prog_text, err);
    if (res == SSS_OK) res = gl_program_vf("view_image.vert.glsl", "view_image.frag.glsl", NULL, &g->prog_image, err);
    if (res != SSS_OK) return res;
    glCreateVertexArrays(1, &g->vao_text);
    glCreateBuffers(1, &g->vbo_text);
    glCreateBuffers(1, &g->ebo_text);
    glVertexArrayVertexBuffer(g->vao_text, 0, g->vbo_text, 0, sizeof(view_text_vertex));
    glVertexArrayElementBuffer(g->vao_text, g->ebo_text);
    glEnableVertexArrayAttrib(g->vao_text, 0);
    glVertexArrayAttribFormat(g->vao_text, 0, 2, GL_FLOAT, GL_FALSE, offsetof(view_text_vertex, x));
    glVertexArrayAttribBinding(g->vao_text, 0, 0);
    glEnableVertexArrayAttrib(g->vao_text, 1);
    glVertexArrayAttribFormat(g->vao_text, 1, 4, GL_UNSIGNED_BYTE, GL_TRUE, offsetof(view_text_vertex, rgba));
    glVertexArrayAttribBinding(g->vao_text, 1, 0);
    glCreateVertexArrays(1, &g->vao_empty);
    return gl_error("setup", err);
}

void view_gl_free(view_gl *g)
{
    if (g->prog_text) glDeleteProgram(g->prog_text);
    if (g->prog_image) glDeleteProgram(g->prog_image);
    GLuint bufs[2] = {g->vbo_text, g->ebo_text};
    for (int i = 0; i < 2; i++)
        if (bufs[i]) glDeleteBuffers(1, &bufs[i]);
    GLuint vaos[2] = {g->vao_text, g->vao_empty};
    for (int i = 0; i < 2; i++)
        if (vaos[i]) glDeleteVertexArrays(1, &vaos[i]);
    if (g->tex_image) glDeleteTextures(1, &g->tex_image);
    memset(g, 0, sizeof *g);
}

sss_result view_gl_draw_text(view_gl *g, const view_text *t, int fb_w, int fb_h, sss_error *err)
{
    if (t->quads == 0 || fb_w < 1 || fb_h < 1) return SSS_OK;
    if (t->quads > g->ebo_quads) {
        /* Quads as two triangles each: 0 1 2, 0 2 3. */
        int n = t->quads > 1024 ? t->quads : 1024;
        unsigned *idx = malloc(sizeof *idx * 6 * (size_t)n);
        if (!idx) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (overlay indices)");
        for (int q = 0; q < n; q++) {
            unsigned b = 4u * (unsigned)q, *o = idx + 6 * q;
            o[0] = b, o[1] = b + 1, o[2] = b + 2, o[3] = b, o[4] = b + 2, o[5] = b + 3;
        }
        glNamedBufferData(g->ebo_text, (GLsizeiptr)(sizeof *idx * 6 * (size_t)n), idx, GL_STATIC_DRAW);
        free(idx);
        g->ebo_quads = n;
    }
    glNamedBufferData(g->vbo_text, (GLsizeiptr)(sizeof(view_text_vertex) * 4 * (size_t)t->quads), t->vertices,
                      GL_STREAM_DRAW);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, fb_w, fb_h);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glUseProgram(g->prog_text);
    glUniform2f(glGetUniformLocation(g->prog_text, "u_viewport"), (float)fb_w, (float)fb_h);
    glBindVertexArray(g->vao_text);
    glDrawElements(GL_TRIANGLES, 6 * t->quads, GL_UNSIGNED_INT, NULL);
    glBindVertexArray(0);
    glUseProgram(0);
    glDisable(GL_BLEND);
    return gl_error("overlay", err);
}

sss_result view_gl_redraw_image(view_gl *g, double exposure, int fb_w, int fb_h, sss_error *err)
{
    if (!g->tex_image || fb_w < 1 || fb_h < 1) return SSS_OK;
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, fb_w, fb_h);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glUseProgram(g->prog_image);
    glUniform1f(glGetUniformLocation(g->prog_image, "u_exposure"), (float)exposure);
    glBindTextureUnit(0, g->tex_image);
    glBindVertexArray(g->vao_empty);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glUseProgram(0);
    return gl_error("buffer display", err);
}

sss_result view_gl_draw_image(view_gl *g, const sss_image *img, double exposure, int fb_w, int fb_h, sss_error *err)
{
    if (!img->pixels || img->width < 1 || img->height < 1) return SSS_OK;
    if (!g->tex_image || g->tex_w != img->width || g->tex_h != img->height) {
        if (g->tex_image) glDeleteTextures(1, &g->tex_image);
        glCreateTextures(GL_TEXTURE_2D, 1, &g->tex_image);
        glTextureStorage2D(g->tex_image, 1, GL_RGB32F, img->width, img->height);
        glTextureParameteri(g->tex_image, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(g->tex_image, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTextureParameteri(g->tex_image, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(g->tex_image, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        g->tex_w = img->width;
        g->tex_h = img->height;
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTextureSubImage2D(g->tex_image, 0, 0, 0, img->width, img->height, GL_RGB, GL_FLOAT, img->pixels);
    return view_gl_redraw_image(g, exposure, fb_w, fb_h, err);
}

sss_result view_gl_screenshot(int fb_w, int fb_h, const char *path, sss_error *err)
{
    if (fb_w < 1 || fb_h < 1) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "%s: the window is empty", path);
    size_t row = 3 * (size_t)fb_w;
    unsigned char *px = malloc(row * (size_t)fb_h), *flip = malloc(row * (size_t)fb_h);
    if (!px || !flip) {
        free(px);
        free(flip);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (screenshot)");
    }
    /* The back buffer: after a swap its contents are undefined and the front buffer of a window under
     * Xvfb reads back empty (GL-NOTES.md). */
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, fb_w, fb_h, GL_RGB, GL_UNSIGNED_BYTE, px);
    sss_result res = gl_error("screenshot read-back", err);
    if (res == SSS_OK) {
        for (int y = 0; y < fb_h; y++) memcpy(flip + row * (size_t)y, px + row * (size_t)(fb_h - 1 - y), row);
        res = sss_image_write_png8(path, fb_w, fb_h, flip, err);
    }
    free(px);
    free(flip);
    return res;
}
