/* gl/techniques/burley/tech_burley.c — technique "burley": screen-space subsurface scattering with
 * Burley's normalized diffusion profile as today's engines ship it (Unity HDRP, Blender EEVEE, Unreal's
 * Subsurface Profile; Golubev 2018 for HDRP), with A and d fitted to each material (Christensen &
 * Burley 2015; burley_fit.c) and transmission through thin parts. docs/burley.md measures it.
 * Passes after the shared G-buffer, shadows and illumination:
 *   burley_prepare  the signal: transmitted irradiance plus the transmission from behind (thick: the
 *                   shadow map's thickness; thin: a thickness), and the mask of subsurface pixels;
 *   burley_scatter  the importance-sampled disc integral of the profile per pixel (sample count from
 *                   the kernel's projected size, golden-angle pattern, bilateral depth and object weights);
 *   combine         reflected light + c_o sqrt(albedo) x the scattered light (common/resolve.glsl). */
#include <stdlib.h>
#include <string.h>

#include "gl/techniques/burley/tech_burley.h"

static const sss_gl_param_info burley_params_info[] = {BURLEY_PARAMS(GL_PARAM_INFO)};


static void free_targets(burley_state *s)
{
    GLuint f[2] = {s->fbo_signal, s->fbo_scatter}, t[2] = {s->tex_signal, s->tex_scatter};
    for (int i = 0; i < 2; i++) {
        if (f[i]) glDeleteFramebuffers(1, &f[i]);
        if (t[i]) glDeleteTextures(1, &t[i]);
    }
    s->fbo_signal = s->fbo_scatter = s->tex_signal = s->tex_scatter = 0;
    s->target_bytes = 0;
    s->width = s->height = 0;
}

static sss_result make_target(GLuint *tex, GLuint *fbo, int w, int h, size_t *bytes, sss_error *err)
{
    *tex = gl_texture_2d(GL_RGBA32F, w, h, 1, bytes);
    glCreateFramebuffers(1, fbo);
    glNamedFramebufferTexture(*fbo, GL_COLOR_ATTACHMENT0, *tex, 0);
    glNamedFramebufferDrawBuffer(*fbo, GL_COLOR_ATTACHMENT0);
    if (glCheckNamedFramebufferStatus(*fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return sss_error_set(err, SSS_ERROR_UNSUPPORTED, "burley: incomplete render target");
    return SSS_OK;
}

/* The material block again when the materials or the parameters it depends on changed. */
static sss_result make_block(const gl_tech_ctx *c, burley_state *s, sss_error *err)
{
    const burley_params *p = c->params;
    if (s->have_block && s->built_fit == p->fit && s->built_cdf == p->filter_cdf) return SSS_OK;
    float *block = NULL;
    int n = 0;
    sss_result res = burley_block_build(c, &block, &n, err);
    if (res != SSS_OK) return res;
    if (s->ssbo) glDeleteBuffers(1, &s->ssbo);
    glCreateBuffers(1, &s->ssbo);
    s->block_bytes = sizeof(float) * 4 * (size_t)n;
    glNamedBufferStorage(s->ssbo, (GLsizeiptr)s->block_bytes, block, 0);
    free(block);
    s->built_fit = p->fit;
    s->built_cdf = p->filter_cdf;
    s->have_block = 1;
    return gl_check(c->gl, "burley: material block", err);
}

static sss_result burley_resize(const gl_tech_ctx *c, void *state, sss_error *err)
{
    burley_state *s = state;
    sss_result res = SSS_OK;
    if (s->width != c->width || s->height != c->height || !s->tex_signal) {
        free_targets(s);
        res = make_target(&s->tex_signal, &s->fbo_signal, c->width, c->height, &s->target_bytes, err);
        if (res == SSS_OK) res = make_target(&s->tex_scatter, &s->fbo_scatter, c->width, c->height, &s->target_bytes, err);
        s->width = c->width;
        s->height = c->height;
        if (res == SSS_OK) res = gl_check(c->gl, "burley: targets", err);
    }
    if (res == SSS_OK) res = make_block(c, s, err);
    return res;
}

static sss_result burley_create(const gl_tech_ctx *c, void *state, sss_error *err)
{
    burley_state *s = state;
    sss_result res = gl_program_vf("fullscreen.vert.glsl", "burley_prepare.frag.glsl", NULL, &s->prog_prep, err);
    if (res == SSS_OK) res = gl_program_vf("fullscreen.vert.glsl", "burley_scatter.frag.glsl", NULL, &s->prog_scatter, err);
    if (res == SSS_OK) res = gl_program_vf("fullscreen.vert.glsl", "burley_resolve.frag.glsl", NULL, &s->prog_resolve, err);
    if (res != SSS_OK) return res;
    /* the shadow maps read as plain depth for the thickness (shadow_thickness.glsl): sampler objects turn
     * the textures' comparison off on our units only */
    GLuint samp[2];
    glCreateSamplers(2, samp);
    for (int i = 0; i < 2; i++) {
        glSamplerParameteri(samp[i], GL_TEXTURE_COMPARE_MODE, GL_NONE);
        glSamplerParameteri(samp[i], GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glSamplerParameteri(samp[i], GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glSamplerParameteri(samp[i], GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glSamplerParameteri(samp[i], GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    }
    s->samp_cube = samp[0];
    s->samp_2d = samp[1];
    return burley_resize(c, s, err);
}

/* New materials: the block again; targets and programs stay. */
static sss_result burley_materials_changed(const gl_tech_ctx *c, void *state, sss_error *err)
{
    burley_state *s = state;
    s->have_block = 0;
    return make_block(c, s, err);
}


static sss_result pass_prepare(const gl_tech_ctx *c, burley_state *s, sss_error *err)
{
    const burley_params *p = c->params;
    gl_timer_begin(c->timer, "burley_prepare");
    glBindFramebuffer(GL_FRAMEBUFFER, s->fbo_signal);
    glUseProgram(s->prog_prep);
    glBindTextureUnit(0, c->frame.pos);
    glBindTextureUnit(1, c->frame.nrm);
    glBindTextureUnit(2, c->frame.albedo);
    glBindTextureUnit(3, c->frame.irr);
    glBindTextureUnit(6, c->gs->shadow_cube);
    glBindSampler(6, s->samp_cube);
    glBindTextureUnit(7, c->gs->shadow_2d);
    glBindSampler(7, s->samp_2d);
    gl_uniform_i(s->prog_prep, "u_mode", c->gs->light_count > 0 ? (int)p->transmission : BURLEY_TRANS_OFF);
    gl_uniform_f(s->prog_prep, "u_thickness", p->thickness);
    gl_uniform_f(s->prog_prep, "u_wrap", p->transmission_wrap);
    gl_draw_fullscreen(c);
    glBindSampler(6, 0);
    glBindSampler(7, 0);
    return gl_check(c->gl, "burley: prepare pass", err);
}

static sss_result pass_scatter(const gl_tech_ctx *c, burley_state *s, sss_error *err)
{
    const burley_params *p = c->params;
    gl_timer_begin(c->timer, "burley_scatter");
    glBindFramebuffer(GL_FRAMEBUFFER, s->fbo_scatter);
    glUseProgram(s->prog_scatter);
    glBindTextureUnit(0, s->tex_signal);
    glBindTextureUnit(1, c->frame.pos);
    gl_uniform_i(s->prog_scatter, "u_samples", (int)p->samples);
    gl_uniform_f(s->prog_scatter, "u_pps", p->pixels_per_sample);
    gl_uniform_f(s->prog_scatter, "u_supersample", c->supersample);
    gl_uniform_i(s->prog_scatter, "u_rotate", (int)p->rotation);
    gl_uniform_i(s->prog_scatter, "u_bilateral", (int)p->bilateral);
    gl_uniform_i(s->prog_scatter, "u_center", (int)p->center);
    gl_draw_fullscreen(c);
    return gl_check(c->gl, "burley: scatter pass", err);
}

static sss_result burley_render(const gl_tech_ctx *c, void *state, sss_error *err)
{
    burley_state *s = state;
    sss_result res = burley_resize(c, s, err);
    if (res != SSS_OK) return res;
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BURLEY_SSBO_BINDING, s->ssbo);
    glViewport(0, 0, c->width, c->height);
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);
    res = pass_prepare(c, s, err);
    if (res == SSS_OK) res = pass_scatter(c, s, err);
    if (res != SSS_OK) return res;
    gl_timer_begin(c->timer, "combine");
    gl_resolve_begin(c, s->prog_resolve);
    glBindTextureUnit(4, s->tex_scatter);
    gl_draw_fullscreen(c);
    gl_timer_end(c->timer);
    return gl_check(c->gl, "burley: combine", err);
}

static void burley_destroy(void *state)
{
    burley_state *s = state;
    free_targets(s);
    GLuint p[3] = {s->prog_prep, s->prog_scatter, s->prog_resolve};
    gl_delete_programs(p, 3);
    if (s->ssbo) glDeleteBuffers(1, &s->ssbo);
    GLuint samp[2] = {s->samp_cube, s->samp_2d};
    gl_delete_samplers(samp, 2);
}

static const char *const targets[] = {"burley_signal", "burley_scatter", NULL};

static GLuint burley_target(void *state, const char *name)
{
    burley_state *s = state;
    if (strcmp(name, "burley_signal") == 0) return s->tex_signal;   /* irradiance + transmission, object mask */
    if (strcmp(name, "burley_scatter") == 0) return s->tex_scatter; /* A int R^ E dA; a: the sample count */
    return 0;
}

static void burley_stats(const gl_tech_ctx *c, void *state, sss_gl_stats *out)
{
    burley_state *s = state;
    out->texture_bytes += s->target_bytes;
    out->buffer_bytes += s->block_bytes;
    out->per_pixel_bytes += s->target_bytes / ((size_t)c->width * (size_t)c->height);
}

/* preset=paper = preset=hdrp: HDRP as published (Golubev 2018 and HDRP's defaults: medium quality's 40 samples,
 * SSS_PIXELS_PER_SAMPLE 4, the 0.997 radius, random rotation, bilateral depth weights, every sample from
 * the whole profile, thick transmission from the shadow map, the 15-degree wrap). HDRP's artist sets d
 * directly; here Christensen & Burley's fit for perpendicular illumination gives it, the configuration of
 * the ground truth's photon beam diffusion (docs/burley.md). The defaults depart in three parameters,
 * each measured on the eval scenes (docs/burley.md): */
static const sss_gl_param_value paper[] = {{"fit", BURLEY_FIT_SEARCHLIGHT}, {"bilateral", 1}, {"center", 0}};

/* Support (technique.h): the disc gather reads the visible surface of the same object only (the
 * object weights), so, as ssss, no farther than about the object's mean chord. */
static double burley_support(const double *params, const sss_scene *scene, int object, int width, int height)
{
    (void)params, (void)width, (void)height;
    return gl_object_mean_chord(scene, object);
}

const gl_technique gl_technique_burley = {
    .info = {"burley",
             "Burley's normalized diffusion as engines ship it (HDRP, EEVEE; Golubev 2018): importance-sampled "
             "screen-space disc, A and d fitted per material (Christensen & Burley 2015), transmission",
             burley_params_info, (int)(sizeof burley_params_info / sizeof burley_params_info[0])},
    .reads = GL_READ_GBUFFER | GL_READ_ILLUMINATION | GL_READ_LIGHTS,
    .targets = targets,
    .state_size = sizeof(burley_state),
    .create = burley_create,
    .resize = burley_resize,
    .render = burley_render,
    .destroy = burley_destroy,
    .materials_changed = burley_materials_changed,
    .target = burley_target,
    .stats = burley_stats,
    .paper = paper,
    .paper_count = (int)(sizeof paper / sizeof paper[0]),
    .paper_is_hdrp = 1,
    .support = burley_support,
};
