/* gl/own_passes.c — the renderer's own frame: G-buffer (Maisch & Ropinski 2020, pass 1), illumination
 * (pass 3), present, object ids (own_passes.h). */
#include <stdlib.h>
#include <string.h>

#include "gl/own_passes.h"

sss_result gl_own_programs_build(gl_own_programs *p, sss_error *err)
{
    memset(p, 0, sizeof *p);
    sss_result res = gl_program_vf("gbuffer.vert.glsl", "gbuffer.frag.glsl", NULL, &p->gbuffer, err);
    if (res == SSS_OK) res = gl_program_vf("fullscreen.vert.glsl", "illumination.frag.glsl", NULL, &p->illumination, err);
    if (res == SSS_OK) res = gl_program_vf("fullscreen.vert.glsl", "present.frag.glsl", NULL, &p->present, err);
    return res;
}

void gl_own_programs_free(gl_own_programs *p)
{
    GLuint progs[3] = {p->gbuffer, p->illumination, p->present};
    for (int i = 0; i < 3; i++)
        if (progs[i]) glDeleteProgram(progs[i]);
    memset(p, 0, sizeof *p);
}

sss_result gl_own_gbuffer(gl_core *core, const gl_own_programs *p, sss_error *err)
{
    gl_timer_begin(&core->timer, "gbuffer");
    const gl_frame *f = &core->frame;
    glBindFramebuffer(GL_FRAMEBUFFER, f->fbo_gbuffer);
    glViewport(0, 0, f->width, f->height);
    const float zero[4] = {0, 0, 0, 0};
    for (int i = 0; i < 3; i++) glClearBufferfv(GL_COLOR, i, zero);
    glClearBufferfv(GL_DEPTH, 0, zero); /* reversed Z: 0 is infinitely far */
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE); /* open meshes (planes) are visible from both sides */
    glUseProgram(p->gbuffer);
    gl_scene_draw_objects(&core->gs, glGetUniformLocation(p->gbuffer, "u_object"), 0);
    glDisable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    return gl_check(core->ctx, "the G-buffer pass", err);
}

sss_result gl_own_illumination(gl_core *core, const gl_own_programs *p, sss_error *err)
{
    gl_timer_begin(&core->timer, "illumination");
    const gl_frame *f = &core->frame;
    glBindFramebuffer(GL_FRAMEBUFFER, f->fbo_light);
    glViewport(0, 0, f->width, f->height);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glUseProgram(p->illumination);
    glBindTextureUnit(0, f->pos);
    glBindTextureUnit(1, f->nrm);
    glBindTextureUnit(2, f->albedo);
    glUniform1i(glGetUniformLocation(p->illumination, "u_has_env"), core->gs.env_tex != 0);
    glUniform1f(glGetUniformLocation(p->illumination, "u_env_rotate"), core->gs.env_rotate_y);
    glUniform3fv(glGetUniformLocation(p->illumination, "u_env_scale"), 1, core->gs.env_scale);
    gl_fullscreen_triangle(core->vao_empty);
    return gl_check(core->ctx, "the illumination pass", err);
}

sss_result gl_own_present(const gl_core *core, const gl_own_programs *p, sss_error *err)
{
    if (!core->ctx->window) return sss_error_set(err, SSS_ERROR_UNSUPPORTED, "present needs a window context");
    int w = 0, h = 0;
    sss_gl_window_size(core->ctx, &w, &h);
    if (w < 1 || h < 1) return SSS_OK;
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, w, h);
    glUseProgram(p->present);
    glBindTextureUnit(0, gl_core_output(core));
    glUniform2f(glGetUniformLocation(p->present, "u_scale"), (float)core->out_width / w, (float)core->out_height / h);
    gl_fullscreen_triangle(core->vao_empty);
    return gl_check(core->ctx, "present", err);
}

sss_result gl_own_read_object_ids(const gl_core *core, sss_image *out, sss_error *err)
{
    int w = core->frame.width, h = core->frame.height;
    if (!core->frame.nrm)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "the frame has no G-buffer");
    sss_result res = sss_image_create(out, w, h, err);
    if (res != SSS_OK) return res;
    size_t n = (size_t)w * (size_t)h;
    float *rgba = malloc(n * 4 * sizeof(float));
    if (!rgba) {
        sss_image_free(out);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (read-back of %dx%d)", w, h);
    }
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glGetTextureImage(core->frame.nrm, 0, GL_RGBA, GL_FLOAT, (GLsizei)(n * 4 * sizeof(float)), rgba);
    for (int y = 0; y < h; y++) /* GL rows run bottom-up */
        for (int x = 0; x < w; x++)
            for (int c = 0; c < 3; c++)
                out->pixels[((size_t)y * (size_t)w + (size_t)x) * 3 + (size_t)c] =
                    rgba[((size_t)(h - 1 - y) * (size_t)w + (size_t)x) * 4 + 3];
    free(rgba);
    res = gl_check(core->ctx, "the object id read-back", err);
    if (res != SSS_OK) sss_image_free(out);
    return res;
}
