/* gl/ssaa.c — supersampling antialiasing (SSAA). With sss_gl_renderer_desc.supersample = k > 1 the
 * renderer's frame targets, and every technique's, are k x the output size (r->width, r->height), so
 * every pass runs on k^2 samples per output pixel; this file owns the output-size image and its pass,
 * "resolve_ssaa": the k x k box filter of the linear result (ssaa_resolve.frag.glsl), before any tone
 * mapping. Read-back and presentation use the output image. Technique parameters counted in pixels
 * scale with k through gl_supersample() (docs/supersampling.md lists them). */
#include "gl/gl_internal.h"

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

static void free_target(sss_gl_renderer *r)
{
    if (r->ssaa_fbo) glDeleteFramebuffers(1, &r->ssaa_fbo);
    if (r->ssaa_tex) glDeleteTextures(1, &r->ssaa_tex);
    r->ssaa_fbo = r->ssaa_tex = 0;
    r->ssaa_bytes = 0;
}

void gl_ssaa_free(sss_gl_renderer *r)
{
    free_target(r);
    if (r->prog_ssaa) glDeleteProgram(r->prog_ssaa);
    r->prog_ssaa = 0;
}

sss_result gl_ssaa_resize(sss_gl_renderer *r, sss_error *err)
{
    if (gl_supersample(r) == 1) {
        free_target(r); /* the output image is frame.final itself */
        return SSS_OK;
    }
    if (!r->prog_ssaa) {
        sss_result res = gl_program_vf("fullscreen.vert.glsl", "ssaa_resolve.frag.glsl", NULL, &r->prog_ssaa, err);
        if (res != SSS_OK) return res;
    }
    if (r->ssaa_tex) {
        GLint w = 0, h = 0;
        glGetTextureLevelParameteriv(r->ssaa_tex, 0, GL_TEXTURE_WIDTH, &w);
        glGetTextureLevelParameteriv(r->ssaa_tex, 0, GL_TEXTURE_HEIGHT, &h);
        if (w == r->out_width && h == r->out_height) return SSS_OK;
    }
    free_target(r);
    r->ssaa_tex = gl_texture_2d(GL_RGBA32F, r->out_width, r->out_height, 1, &r->ssaa_bytes);
    glCreateFramebuffers(1, &r->ssaa_fbo);
    glNamedFramebufferTexture(r->ssaa_fbo, GL_COLOR_ATTACHMENT0, r->ssaa_tex, 0);
    glNamedFramebufferDrawBuffer(r->ssaa_fbo, GL_COLOR_ATTACHMENT0);
    GLenum st = glCheckNamedFramebufferStatus(r->ssaa_fbo, GL_FRAMEBUFFER);
    if (st != GL_FRAMEBUFFER_COMPLETE) {
        free_target(r);
        return sss_error_set(err, SSS_ERROR_UNSUPPORTED, "OpenGL: the %dx%d SSAA output target is incomplete (0x%x)",
                             r->out_width, r->out_height, (unsigned)st);
    }
    return gl_check(r->ctx, "the SSAA output target", err);
}

sss_result gl_ssaa_resolve(sss_gl_renderer *r, sss_error *err)
{
    int k = gl_supersample(r);
    if (k == 1) return SSS_OK;
    gl_timer_begin(&r->timer, "resolve_ssaa");
    glBindFramebuffer(GL_FRAMEBUFFER, r->ssaa_fbo);
    glViewport(0, 0, r->out_width, r->out_height);
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);
    glUseProgram(r->prog_ssaa);
    glBindTextureUnit(0, r->frame.final);
    glUniform1i(glGetUniformLocation(r->prog_ssaa, "u_k"), k);
    gl_draw_fullscreen(r);
    gl_timer_end(&r->timer);
    return gl_check(r->ctx, "the SSAA resolve", err);
}

GLuint gl_output_texture(const sss_gl_renderer *r)
{
    return gl_supersample(r) > 1 && r->ssaa_tex ? r->ssaa_tex : r->frame.final;
}
