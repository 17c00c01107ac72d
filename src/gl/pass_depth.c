/* gl/pass_depth.c — positions and pixel areas from a caller's depth buffer (pass_depth.h). */
#include <string.h>

#include "core/vecmath.h"
#include "gl/pass_depth.h"

sss_result gl_pass_depth_prepare(gl_pass_depth *d, int width, int height, int levels, sss_error *err)
{
    if (!d->prog) {
        sss_result res = gl_program_vf("fullscreen.vert.glsl", "pass_depth.frag.glsl", NULL, &d->prog, err);
        if (res != SSS_OK) return res;
    }
    if (d->position && d->width == width && d->height == height && d->levels == levels) return SSS_OK;
    if (d->fbo) glDeleteFramebuffers(1, &d->fbo);
    if (d->position) glDeleteTextures(1, &d->position);
    d->position = gl_texture_2d(GL_RGBA32F, width, height, levels, NULL);
    /* bilinear within one level, as the renderer's own position target (frame.c) */
    glTextureParameteri(d->position, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_NEAREST);
    glTextureParameteri(d->position, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    d->fbo = gl_framebuffer(&d->position, 1, 0);
    d->width = width, d->height = height, d->levels = levels;
    if (glCheckNamedFramebufferStatus(d->fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return sss_error_set(err, SSS_ERROR_UNSUPPORTED, "the %dx%d position target is incomplete", width, height);
    return SSS_OK;
}

sss_result gl_pass_depth_resolve(gl_pass_depth *d, gl_core *core, GLuint depth, GLuint normal, const float view[16],
                                 const float proj[16], sss_error *err)
{
    float vp[16], inv[16];
    m4_mul(proj, view, vp);
    if (!m4_inverse(vp, inv))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sss_gl_pass_execute: frame.proj x frame.view is singular");
    int reversed = proj[10] == 0.0f; /* reversed-Z with an infinite far plane (sss/gl_pass.h) */
    gl_timer_begin(&core->timer, "position_from_depth");
    glBindFramebuffer(GL_FRAMEBUFFER, d->fbo);
    glViewport(0, 0, d->width, d->height);
    glUseProgram(d->prog);
    glBindTextureUnit(0, depth);
    glBindTextureUnit(1, normal);
    glUniformMatrix4fv(glGetUniformLocation(d->prog, "u_caller_inv_view_proj"), 1, GL_FALSE, inv);
    glUniform1i(glGetUniformLocation(d->prog, "u_zero_to_one"), reversed);
    glUniform1f(glGetUniformLocation(d->prog, "u_background"), reversed ? 0.0f : 1.0f);
    glUniform2f(glGetUniformLocation(d->prog, "u_pixel"), 2.0f / (proj[0] * (float)d->width),
                2.0f / (proj[5] * (float)d->height));
    gl_fullscreen_triangle(core->vao_empty);
    return gl_check(core->ctx, "the position from depth", err);
}

void gl_pass_depth_free(gl_pass_depth *d)
{
    if (d->fbo) glDeleteFramebuffers(1, &d->fbo);
    if (d->position) glDeleteTextures(1, &d->position);
    if (d->prog) glDeleteProgram(d->prog);
    memset(d, 0, sizeof *d);
}
