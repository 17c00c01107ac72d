/* gl/tech_local.c — technique "local": subsurface pixels show c_o F_t E(x_o) rho_eff, the limit of a
 * vanishing scattering distance (no transport between points). A baseline for comparisons and the
 * smallest user of the shared passes (G-buffer, shadows, illumination). */
#include "gl/gl_internal.h"

typedef struct local_state {
    GLuint prog;
} local_state;

static sss_result local_create(sss_gl_renderer *r, void *state, sss_error *err)
{
    (void)r;
    local_state *s = state;
    return gl_program_vf("fullscreen.vert.glsl", "local.frag.glsl", NULL, &s->prog, err);
}

static sss_result local_render(sss_gl_renderer *r, void *state, sss_error *err)
{
    local_state *s = state;
    gl_timer_begin(&r->timer, "combine");
    glBindFramebuffer(GL_FRAMEBUFFER, r->frame.fbo_final);
    glViewport(0, 0, r->width, r->height);
    glDisable(GL_BLEND);
    glUseProgram(s->prog);
    glBindTextureUnit(0, r->frame.pos);
    glBindTextureUnit(1, r->frame.nrm);
    glBindTextureUnit(2, r->frame.albedo);
    glBindTextureUnit(3, r->frame.irr);
    glBindTextureUnit(4, r->frame.refl);
    gl_draw_fullscreen(r);
    gl_timer_end(&r->timer);
    return gl_check(r->ctx, "local: combine", err);
}

static void local_destroy(sss_gl_renderer *r, void *state)
{
    (void)r;
    local_state *s = state;
    if (s->prog) glDeleteProgram(s->prog);
}

const gl_technique gl_technique_local = {
    .info = {"local", "no transport between points: c_o F_t E rho_eff per pixel (zero scattering distance)",
             NULL, 0},
    .needs = GL_NEED_GBUFFER | GL_NEED_SHADOWS | GL_NEED_ILLUMINATION,
    .state_size = sizeof(local_state),
    .create = local_create,
    .render = local_render,
    .destroy = local_destroy,
    .materials_changed = gl_materials_read_at_render,
};
