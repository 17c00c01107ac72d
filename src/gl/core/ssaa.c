/* gl/ssaa.c — supersampling antialiasing (SSAA). With sss_gl_renderer_desc.supersample = k > 1 the
 * renderer's frame targets, and every technique's, are k x the output size (core->width, core->height), so
 * every pass runs on k^2 samples per output pixel; this file owns the output-size image and its pass,
 * "resolve_ssaa": the k x k box filter of the linear result (ssaa_resolve.frag.glsl), before any tone
 * mapping. Read-back and presentation use the output image. Technique parameters counted in pixels
 * scale with k through gl_tech_ctx.supersample (docs/supersampling.md lists them). */
#include "gl/core/gl_core.h"

sss_result gl_ssaa_check(const sss_gl_context *ctx, int width, int height, int k, sss_error *err)
{
    if (k < 1 || k > SSS_GL_MAX_SUPERSAMPLE)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                             "supersample = %d is outside 1..%d (the SSAA factor per axis; 0: default = 1 = off)", k,
                             SSS_GL_MAX_SUPERSAMPLE);
    long long w = (long long)width * k, h = (long long)height * k;
    if (w > ctx->max_texture_size || h > ctx->max_texture_size || w > ctx->max_viewport[0] || h > ctx->max_viewport[1])
        return sss_error_set(err, SSS_ERROR_LIMIT,
                             "supersample = %d: the %dx%d image renders at %lldx%lld, beyond this GL's limits "
                             "(GL_MAX_TEXTURE_SIZE %d, GL_MAX_VIEWPORT_DIMS %dx%d); use a smaller supersample or image",
                             k, width, height, w, h, ctx->max_texture_size, ctx->max_viewport[0], ctx->max_viewport[1]);
    return SSS_OK;
}

static void free_target(gl_core *core)
{
    if (core->ssaa_fbo) glDeleteFramebuffers(1, &core->ssaa_fbo);
    if (core->ssaa_tex) glDeleteTextures(1, &core->ssaa_tex);
    core->ssaa_fbo = core->ssaa_tex = 0;
    core->ssaa_bytes = 0;
}

void gl_ssaa_free(gl_core *core)
{
    free_target(core);
    if (core->prog_ssaa) glDeleteProgram(core->prog_ssaa);
    core->prog_ssaa = 0;
}

sss_result gl_ssaa_resize(gl_core *core, sss_error *err)
{
    if (core->supersample == 1) {
        free_target(core); /* the output image is frame.final itself */
        return SSS_OK;
    }
    if (!core->prog_ssaa) {
        sss_result res = gl_program_vf("fullscreen.vert.glsl", "ssaa_resolve.frag.glsl", NULL, &core->prog_ssaa, err);
        if (res != SSS_OK) return res;
    }
    if (core->ssaa_tex) {
        GLint w = 0, h = 0;
        glGetTextureLevelParameteriv(core->ssaa_tex, 0, GL_TEXTURE_WIDTH, &w);
        glGetTextureLevelParameteriv(core->ssaa_tex, 0, GL_TEXTURE_HEIGHT, &h);
        if (w == core->out_width && h == core->out_height) return SSS_OK;
    }
    free_target(core);
    core->ssaa_tex = gl_texture_2d(GL_RGBA32F, core->out_width, core->out_height, 1, &core->ssaa_bytes);
    glCreateFramebuffers(1, &core->ssaa_fbo);
    glNamedFramebufferTexture(core->ssaa_fbo, GL_COLOR_ATTACHMENT0, core->ssaa_tex, 0);
    glNamedFramebufferDrawBuffer(core->ssaa_fbo, GL_COLOR_ATTACHMENT0);
    GLenum st = glCheckNamedFramebufferStatus(core->ssaa_fbo, GL_FRAMEBUFFER);
    if (st != GL_FRAMEBUFFER_COMPLETE) {
        free_target(core);
        return sss_error_set(err, SSS_ERROR_UNSUPPORTED, "OpenGL: the %dx%d SSAA output target is incomplete (0x%x)",
                             core->out_width, core->out_height, (unsigned)st);
    }
    return gl_check(core->ctx, "the SSAA output target", err);
}

sss_result gl_ssaa_resolve(gl_core *core, sss_error *err)
{
    int k = core->supersample;
    if (k == 1) return SSS_OK;
    gl_timer_begin(&core->timer, "resolve_ssaa");
    glBindFramebuffer(GL_FRAMEBUFFER, core->ssaa_fbo);
    glViewport(0, 0, core->out_width, core->out_height);
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);
    glUseProgram(core->prog_ssaa);
    glBindTextureUnit(0, core->frame.final);
    glUniform1i(glGetUniformLocation(core->prog_ssaa, "u_k"), k);
    gl_fullscreen_triangle(core->vao_empty);
    gl_timer_end(&core->timer);
    return gl_check(core->ctx, "the SSAA resolve", err);
}

GLuint gl_core_output(const gl_core *core)
{
    return core->supersample > 1 && core->ssaa_tex ? core->ssaa_tex : core->frame.final;
}
