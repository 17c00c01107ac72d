/* gl/techniques/local/tech_local.c — technique "local": subsurface pixels show c_o F_t E(x_o) rho_eff, the
 * limit of a vanishing scattering distance (no transport between points). A baseline for comparisons,
 * and the smallest technique: the model for a new one (docs/integration.md, "Adding a technique"). */
#include "gl/technique.h"

/* Its state: what it owns. */
typedef struct local_state {
    GLuint prog;
} local_state;

static sss_result local_create(const gl_tech_ctx *c, void *state, sss_error *err)
{
    (void)c;
    local_state *s = state;
    return gl_program_vf("fullscreen.vert.glsl", "local.frag.glsl", NULL, &s->prog, err);
}

/* One pass: frame.final = reflected light + c_o F_t E rho_eff (local.frag.glsl). */
static sss_result local_render(const gl_tech_ctx *c, void *state, sss_error *err)
{
    local_state *s = state;
    gl_timer_begin(c->timer, "combine");
    glBindFramebuffer(GL_FRAMEBUFFER, c->frame.fbo_final);
    glViewport(0, 0, c->width, c->height);
    glDisable(GL_BLEND);
    glUseProgram(s->prog);
    glBindTextureUnit(0, c->frame.pos);
    glBindTextureUnit(1, c->frame.nrm);
    glBindTextureUnit(2, c->frame.albedo);
    glBindTextureUnit(3, c->frame.irr);
    glBindTextureUnit(4, c->frame.refl);
    gl_draw_fullscreen(c);
    gl_timer_end(c->timer);
    return gl_check(c->gl, "local: combine", err);
}

static void local_destroy(void *state)
{
    local_state *s = state;
    if (s->prog) glDeleteProgram(s->prog);
}

const gl_technique gl_technique_local = {
    .info = {"local", "no transport between points: c_o F_t E rho_eff per pixel (zero scattering distance)",
             NULL, 0},
    .reads = GL_READ_GBUFFER | GL_READ_ILLUMINATION,
    .state_size = sizeof(local_state),
    .create = local_create,
    .render = local_render,
    .destroy = local_destroy,
    .materials_changed = gl_materials_read_at_render,
};
