/* gl/common/shells.c — multi-resolution shell splatting (see shells.h). */
#include <math.h>
#include <string.h>

#include "gl/common/shells.h"

sss_result shell_create(shell_targets *s, sss_error *err)
{
    sss_result res = gl_program_vf("fullscreen.vert.glsl", "shell_receivers.frag.glsl", NULL, &s->prog_recv, err);
    if (res == SSS_OK)
        res = gl_program_vf("fullscreen.vert.glsl", "shell_receivers.frag.glsl", "#define FINE 1\n", &s->prog_recv_fine,
                            err);
    if (res == SSS_OK) res = gl_program_vf("shell_splat.vert.glsl", "shell_splat.frag.glsl", NULL, &s->prog_splat, err);
    if (res == SSS_OK)
        res = gl_program_vf("shell_splat.vert.glsl", "shell_splat.frag.glsl", "#define FINE 1\n", &s->prog_splat_fine, err);
    if (res == SSS_OK)
        res = gl_program_vf("fullscreen.vert.glsl", "shell_resolve.frag.glsl", NULL, &s->prog_resolve, err);
    /* the splatting work, for tests (shell_splat_fragments): core in GL 4.6, an extension before */
    if (res == SSS_OK && (epoxy_gl_version() >= 46 || epoxy_has_gl_extension("GL_ARB_pipeline_statistics_query")))
        glGenQueries(1, &s->query); /* Mesa's glCreateQueries refuses pipeline-statistics targets */
    return res;
}

static void free_targets(shell_targets *s)
{
    for (int l = 0; l <= SHELL_MAX_LEVELS; l++) {
        if (s->fbo_recv[l]) glDeleteFramebuffers(1, &s->fbo_recv[l]);
        if (s->fbo_accum[l]) glDeleteFramebuffers(1, &s->fbo_accum[l]);
        if (s->recv[l]) glDeleteTextures(1, &s->recv[l]);
        if (s->accum[l]) glDeleteTextures(1, &s->accum[l]);
        s->fbo_recv[l] = s->fbo_accum[l] = s->recv[l] = s->accum[l] = 0;
    }
    if (s->link) glDeleteTextures(1, &s->link);
    s->link = 0;
    s->levels = 0;
    s->bytes = 0;
    s->frame_w = s->frame_h = s->base = s->fine = 0;
}

void shell_free(shell_targets *s)
{
    free_targets(s);
    GLuint p[5] = {s->prog_recv, s->prog_recv_fine, s->prog_splat, s->prog_splat_fine, s->prog_resolve};
    gl_delete_programs(p, 5);
    s->prog_recv = s->prog_recv_fine = s->prog_splat = s->prog_splat_fine = s->prog_resolve = 0;
    if (s->query) glDeleteQueries(1, &s->query);
    s->query = 0;
    s->query_pending = 0;
}

/* Target i (a pyramid level or SHELL_FINE) with texels d render pixels wide. */
static sss_result make_target(const gl_tech_ctx *c, shell_targets *s, int i, int d, sss_error *err)
{
    s->w[i] = (c->width + d - 1) / d;
    s->h[i] = (c->height + d - 1) / d;
    s->recv[i] = gl_texture_2d(GL_RGBA32F, s->w[i], s->h[i], 1, &s->bytes);
    s->accum[i] = gl_texture_2d(GL_RGBA32F, s->w[i], s->h[i], 1, &s->bytes);
    glTextureParameteri(s->accum[i], GL_TEXTURE_MIN_FILTER, GL_LINEAR); /* bilinear upsampling */
    glTextureParameteri(s->accum[i], GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    GLenum bufs[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
    glCreateFramebuffers(1, &s->fbo_recv[i]);
    glNamedFramebufferTexture(s->fbo_recv[i], GL_COLOR_ATTACHMENT0, s->recv[i], 0);
    glNamedFramebufferTexture(s->fbo_recv[i], GL_COLOR_ATTACHMENT1, s->accum[i], 0);
    if (i == SHELL_FINE) {
        s->link = gl_texture_2d(GL_RGBA32F, s->w[i], s->h[i], 1, &s->bytes);
        glNamedFramebufferTexture(s->fbo_recv[i], GL_COLOR_ATTACHMENT2, s->link, 0);
    }
    glNamedFramebufferDrawBuffers(s->fbo_recv[i], i == SHELL_FINE ? 3 : 2, bufs);
    glCreateFramebuffers(1, &s->fbo_accum[i]);
    glNamedFramebufferTexture(s->fbo_accum[i], GL_COLOR_ATTACHMENT0, s->accum[i], 0);
    glNamedFramebufferDrawBuffers(s->fbo_accum[i], 1, bufs);
    if (glCheckNamedFramebufferStatus(s->fbo_recv[i], GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE ||
        glCheckNamedFramebufferStatus(s->fbo_accum[i], GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return sss_error_set(err, SSS_ERROR_UNSUPPORTED, "incomplete %dx%d splatting target (level %d)", s->w[i],
                             s->h[i], i == SHELL_FINE ? -1 : i);
    return SSS_OK;
}

sss_result shell_resize(const gl_tech_ctx *c, shell_targets *s, int levels, double fine_radius, sss_error *err)
{
    if (levels < 1) levels = 1;
    if (levels > SHELL_MAX_LEVELS) levels = SHELL_MAX_LEVELS;
    int k = c->supersample;
    int fine = k > 1 && fine_radius > 0.0;
    s->fine_radius = fine_radius;
    if (s->levels == levels && s->frame_w == c->width && s->frame_h == c->height && s->base == k && s->fine == fine)
        return SSS_OK;
    free_targets(s);
    s->levels = levels;
    s->frame_w = c->width;
    s->frame_h = c->height;
    s->base = k;
    s->fine = fine;
    sss_result res = fine ? make_target(c, s, SHELL_FINE, 1, err) : SSS_OK;
    for (int l = 0; l < levels && res == SSS_OK; l++) res = make_target(c, s, l, k << l, err); /* 2^l output px */
    return res == SSS_OK ? gl_check(c->gl, "splatting targets", err) : res;
}

void shell_receivers(const gl_tech_ctx *c, shell_targets *s)
{
    glDisable(GL_BLEND);
    glUseProgram(s->prog_recv);
    glBindTextureUnit(0, c->frame.pos);
    glBindTextureUnit(1, c->frame.nrm);
    GLint u_div = glGetUniformLocation(s->prog_recv, "u_divisor");
    glUniform1i(glGetUniformLocation(s->prog_recv, "u_base"), s->base);
    for (int l = 0; l < s->levels; l++) {
        glBindFramebuffer(GL_FRAMEBUFFER, s->fbo_recv[l]);
        glViewport(0, 0, s->w[l], s->h[l]);
        glUniform1i(u_div, s->base << l);
        gl_draw_fullscreen(c);
    }
    if (!s->fine) return;
    /* the render-resolution level, after level 0 (it records which level-0 receiver each pixel reads) */
    glUseProgram(s->prog_recv_fine);
    glBindTextureUnit(2, s->recv[0]);
    glUniform1i(glGetUniformLocation(s->prog_recv_fine, "u_base"), s->base);
    glBindFramebuffer(GL_FRAMEBUFFER, s->fbo_recv[SHELL_FINE]);
    glViewport(0, 0, s->w[SHELL_FINE], s->h[SHELL_FINE]);
    gl_draw_fullscreen(c);
}

/* One level's draw: its shell [inner, outer) in output pixels (x the world size of one at the splat's
 * depth); the last shell reaches the kernel's reach. */
static void splat_level(shell_targets *s, GLuint prog, int i, double inner, double outer, int last)
{
    glUseProgram(prog);
    glBindFramebuffer(GL_FRAMEBUFFER, s->fbo_accum[i]);
    glViewport(0, 0, s->w[i], s->h[i]);
    glBindTextureUnit(0, s->recv[i]);
    glUniform2f(glGetUniformLocation(prog, "u_shell"), (float)inner, (float)outer);
    glUniform1i(glGetUniformLocation(prog, "u_last"), last);
    glDrawArraysIndirect(GL_TRIANGLE_STRIP, NULL);
}

void shell_splat(const gl_tech_ctx *c, shell_targets *s, GLuint splats, GLuint cmd, unsigned capacity,
                 double epsilon, int preintegrated)
{
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GL_SSBO_SPLATS, splats);
    /* the fine level has a program of its own (shell_splat.frag.glsl, FINE) */
    GLuint progs[2] = {s->prog_splat, s->prog_splat_fine};
    for (int j = 0; j < 2; j++) {
        glUseProgram(progs[j]);
        glUniform1ui(glGetUniformLocation(progs[j], "u_capacity"), capacity);
        glUniform1i(glGetUniformLocation(progs[j], "u_preintegrated"), preintegrated);
        glUniform1f(glGetUniformLocation(progs[j], "u_base"), (float)s->base);
        glUniform1f(glGetUniformLocation(progs[j], "u_footprint"), preintegrated ? s->footprint : 0.0f);
        /* the fine level takes back what level 0 counted, up to its outer radius (-1: the reach), and its
         * quads reach 0.75 (k - 1) / k >= 0.71 (k - 1) / k output pixels further */
        glUniform1f(glGetUniformLocation(progs[j], "u_outer0"), s->levels > 1 ? (float)(2.0 / epsilon) : -1.0f);
        glUniform1f(glGetUniformLocation(progs[j], "u_margin"), j ? (float)(0.75 * (s->base - 1) / s->base) : 0.0f);
    }
    glBindVertexArray(c->vao_empty);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, cmd);
    if (s->query) glBeginQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB, s->query);
    /* D_0 = 0, D_l = 2^l / epsilon output pixels; the fine level [0, D), D at most level 0's outer radius */
    if (s->fine) {
        glBindTextureUnit(1, s->link);
        glBindTextureUnit(2, s->recv[0]);
        splat_level(s, s->prog_splat_fine, SHELL_FINE, 0.0, fmin(s->fine_radius, 2.0 / epsilon), 0);
    }
    for (int l = 0; l < s->levels; l++)
        splat_level(s, s->prog_splat, l, l ? ldexp(1.0, l) / epsilon : 0.0, ldexp(1.0, l + 1) / epsilon,
                    l == s->levels - 1);
    if (s->query) {
        glEndQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB);
        s->query_pending = 1;
    }
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    glBindVertexArray(0);
    glDisable(GL_BLEND);
}

void shell_resolve(const gl_tech_ctx *c, shell_targets *s)
{
    glDisable(GL_BLEND);
    gl_resolve_begin(c, s->prog_resolve);
    for (int l = 0; l < SHELL_MAX_LEVELS; l++) glBindTextureUnit(4 + (GLuint)l, s->accum[l < s->levels ? l : 0]);
    glBindTextureUnit(8, s->recv[0]);
    glBindTextureUnit(9, s->fine ? s->accum[SHELL_FINE] : s->accum[0]);
    glBindTextureUnit(10, s->fine ? s->link : s->accum[0]);
    glUniform1i(glGetUniformLocation(s->prog_resolve, "u_levels"), s->levels);
    glUniform1i(glGetUniformLocation(s->prog_resolve, "u_base"), s->base);
    glUniform1i(glGetUniformLocation(s->prog_resolve, "u_fine"), s->fine);
    gl_draw_fullscreen(c);
}

unsigned shell_splat_count(GLuint cmd, unsigned capacity)
{
    GLuint c[4] = {0, 0, 0, 0};
    if (cmd) glGetNamedBufferSubData(cmd, 0, sizeof c, c);
    return c[1] < capacity ? c[1] : capacity;
}

long long shell_splat_fragments(shell_targets *s)
{
    if (!s || !s->query || !s->query_pending) return -1;
    GLuint64 n = 0;
    glGetQueryObjectui64v(s->query, GL_QUERY_RESULT, &n);
    return (long long)n;
}


