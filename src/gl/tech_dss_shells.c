/* gl/tech_dss_shells.c — multi-resolution shell splatting (see tech_dss_shells.h). */
#include <string.h>

#include "gl/tech_dss_shells.h"

sss_result shell_create(shell_targets *s, sss_error *err)
{
    sss_result res = gl_program_vf("fullscreen.vert.glsl", "receivers.frag.glsl", NULL, &s->prog_recv, err);
    if (res == SSS_OK) res = gl_program_vf("dss_splat.vert.glsl", "dss_splat.frag.glsl", NULL, &s->prog_splat, err);
    if (res == SSS_OK)
        res = gl_program_vf("fullscreen.vert.glsl", "dss_resolve.frag.glsl", NULL, &s->prog_resolve, err);
    return res;
}

static void free_targets(shell_targets *s)
{
    for (int l = 0; l < SHELL_MAX_LEVELS; l++) {
        if (s->fbo_recv[l]) glDeleteFramebuffers(1, &s->fbo_recv[l]);
        if (s->fbo_accum[l]) glDeleteFramebuffers(1, &s->fbo_accum[l]);
        if (s->recv[l]) glDeleteTextures(1, &s->recv[l]);
        if (s->accum[l]) glDeleteTextures(1, &s->accum[l]);
        s->fbo_recv[l] = s->fbo_accum[l] = s->recv[l] = s->accum[l] = 0;
    }
    s->levels = 0;
    s->bytes = 0;
    s->frame_w = s->frame_h = 0;
}

void shell_free(shell_targets *s)
{
    free_targets(s);
    GLuint p[3] = {s->prog_recv, s->prog_splat, s->prog_resolve};
    for (int i = 0; i < 3; i++)
        if (p[i]) glDeleteProgram(p[i]);
    s->prog_recv = s->prog_splat = s->prog_resolve = 0;
}

sss_result shell_resize(sss_gl_renderer *r, shell_targets *s, int levels, sss_error *err)
{
    if (levels < 1) levels = 1;
    if (levels > SHELL_MAX_LEVELS) levels = SHELL_MAX_LEVELS;
    if (s->levels == levels && s->frame_w == r->width && s->frame_h == r->height) return SSS_OK;
    free_targets(s);
    s->levels = levels;
    s->frame_w = r->width;
    s->frame_h = r->height;
    for (int l = 0; l < levels; l++) {
        int d = 1 << l;
        s->w[l] = (r->width + d - 1) / d;
        s->h[l] = (r->height + d - 1) / d;
        s->recv[l] = gl_texture_2d(GL_RGBA32F, s->w[l], s->h[l], 1, &s->bytes);
        s->accum[l] = gl_texture_2d(GL_RGBA32F, s->w[l], s->h[l], 1, &s->bytes);
        glTextureParameteri(s->accum[l], GL_TEXTURE_MIN_FILTER, GL_LINEAR); /* bilinear upsampling */
        glTextureParameteri(s->accum[l], GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        GLenum bufs[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
        glCreateFramebuffers(1, &s->fbo_recv[l]);
        glNamedFramebufferTexture(s->fbo_recv[l], GL_COLOR_ATTACHMENT0, s->recv[l], 0);
        glNamedFramebufferTexture(s->fbo_recv[l], GL_COLOR_ATTACHMENT1, s->accum[l], 0);
        glNamedFramebufferDrawBuffers(s->fbo_recv[l], 2, bufs);
        glCreateFramebuffers(1, &s->fbo_accum[l]);
        glNamedFramebufferTexture(s->fbo_accum[l], GL_COLOR_ATTACHMENT0, s->accum[l], 0);
        glNamedFramebufferDrawBuffers(s->fbo_accum[l], 1, bufs);
        if (glCheckNamedFramebufferStatus(s->fbo_recv[l], GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE ||
            glCheckNamedFramebufferStatus(s->fbo_accum[l], GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            return sss_error_set(err, SSS_ERROR_UNSUPPORTED, "incomplete %dx%d splatting target (level %d)", s->w[l],
                                 s->h[l], l);
    }
    return gl_check(r->ctx, "splatting targets", err);
}

void shell_receivers(sss_gl_renderer *r, shell_targets *s)
{
    glDisable(GL_BLEND);
    glUseProgram(s->prog_recv);
    glBindTextureUnit(0, r->frame.pos);
    glBindTextureUnit(1, r->frame.nrm);
    GLint u_div = glGetUniformLocation(s->prog_recv, "u_divisor");
    for (int l = 0; l < s->levels; l++) {
        glBindFramebuffer(GL_FRAMEBUFFER, s->fbo_recv[l]);
        glViewport(0, 0, s->w[l], s->h[l]);
        glUniform1i(u_div, 1 << l);
        gl_draw_fullscreen(r);
    }
}

void shell_splat(sss_gl_renderer *r, shell_targets *s, GLuint splats, GLuint cmd, unsigned capacity,
                 double epsilon, int preintegrated)
{
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    glUseProgram(s->prog_splat);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GL_SSBO_SPLATS, splats);
    glUniform1i(glGetUniformLocation(s->prog_splat, "u_levels"), s->levels);
    glUniform1f(glGetUniformLocation(s->prog_splat, "u_epsilon"), (float)epsilon);
    glUniform1ui(glGetUniformLocation(s->prog_splat, "u_capacity"), capacity);
    glUniform1i(glGetUniformLocation(s->prog_splat, "u_preintegrated"), preintegrated);
    GLint u_level = glGetUniformLocation(s->prog_splat, "u_level");
    glBindVertexArray(r->vao_empty);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, cmd);
    for (int l = 0; l < s->levels; l++) {
        glBindFramebuffer(GL_FRAMEBUFFER, s->fbo_accum[l]);
        glViewport(0, 0, s->w[l], s->h[l]);
        glBindTextureUnit(0, s->recv[l]);
        glUniform1i(u_level, l);
        glDrawArraysIndirect(GL_TRIANGLE_STRIP, NULL);
    }
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    glBindVertexArray(0);
    glDisable(GL_BLEND);
}

void shell_resolve(sss_gl_renderer *r, shell_targets *s)
{
    glBindFramebuffer(GL_FRAMEBUFFER, r->frame.fbo_final);
    glViewport(0, 0, r->width, r->height);
    glDisable(GL_BLEND);
    glUseProgram(s->prog_resolve);
    glBindTextureUnit(0, r->frame.pos);
    glBindTextureUnit(1, r->frame.nrm);
    glBindTextureUnit(2, r->frame.albedo);
    glBindTextureUnit(3, r->frame.refl);
    for (int l = 0; l < SHELL_MAX_LEVELS; l++) glBindTextureUnit(4 + (GLuint)l, s->accum[l < s->levels ? l : 0]);
    glUniform1i(glGetUniformLocation(s->prog_resolve, "u_levels"), s->levels);
    gl_draw_fullscreen(r);
}

unsigned shell_splat_count(GLuint cmd, unsigned capacity)
{
    GLuint c[4] = {0, 0, 0, 0};
    if (cmd) glGetNamedBufferSubData(cmd, 0, sizeof c, c);
    return c[1] < capacity ? c[1] : capacity;
}
