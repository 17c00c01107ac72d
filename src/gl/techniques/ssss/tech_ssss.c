/* gl/tech_ssss.c — Separable Subsurface Scattering (Jimenez et al. 2019) and its two baselines:
 *   ssss         two 1D passes (horizontal, vertical) of one separable kernel: pre-integrated (Eq. 4-5),
 *                artist-friendly (Eq. 6, Table 2) or guided rank-1 (Appendix A, Eq. 8-9);
 *   ssss-gauss6  the six-Gaussian sum of d'Eon et al. 2007: 12 1D passes;
 *   ssss-svd     the rank-N SVD of the discretised profile (Jimenez et al. 2019, section 3): 2N 1D passes.
 * Passes after the shared G-buffer, shadows and illumination: (1) prepare: the transmitted irradiance
 * plus the transmittance through thin parts (Jimenez et al. 2010 from the shadow maps) and the object
 * mask; (2) per separable term a horizontal and a vertical pass (src/gl/techniques/ssss/ssss_blur.frag.glsl: screen
 * projection of world-space tap offsets, depth correction of Eq. 7, stochastic rotation of section 6),
 * the vertical ones summed additively; (3) combine: c_o sqrt(albedo) x total reflectance x the sum.
 * The kernels are built on the CPU once per parameter set (tech_ssss_kernel.c). */
#include <math.h>
#include <string.h>

#include "gl/techniques/ssss/tech_ssss.h"

#define TRANS_DEFINE "#define SSSS_TRANS_SIZE 256\n"

/* ---- Parameters ------------------------------------------------------------------------------ */

static const sss_gl_param_info ssss_params_info[] = {SSSS_PARAMS(GL_PARAM_INFO)};
static const sss_gl_param_info gauss6_params_info[] = {SSSS_GAUSS6_PARAMS(GL_PARAM_INFO)};
static const sss_gl_param_info svd_params_info[] = {SSSS_SVD_PARAMS(GL_PARAM_INFO)};

/* ---- State ----------------------------------------------------------------------------------- */

typedef struct ssss_state {
    ssss_variant variant;
    GLuint prog_prep, prog_blur, prog_combine;
    GLuint ssbo, trans_tex, samp_cube, samp_2d;
    GLuint tex_prep, tex_tmp, tex_sum;
    GLuint fbo_prep, fbo_tmp, fbo_sum;
    int width, height, terms, have_kernel;
    ssss_kernel_opts built;
    size_t target_bytes, kernel_bytes;
} ssss_state;

/* What the passes read of a variant's parameters. */
typedef struct ssss_settings {
    ssss_kernel_opts opts;
    int follow_surface, transmittance;
    double rotation;
} ssss_settings;

/* The settings of the variant's parameter struct (ssss_params, ssss_gauss6_params or ssss_svd_params). */
static void settings_of(const ssss_state *s, const void *params, ssss_settings *out)
{
    memset(out, 0, sizeof *out);
    ssss_kernel_opts *o = &out->opts;
    o->variant = s->variant;
    o->taps = 7;
    o->guide_k = 2;
    o->guide_b_mm = 50;
    o->rank = 3;
    o->grid = 24;
    if (s->variant == SSSS_VARIANT_SEPARABLE) {
        const ssss_params *p = params;
        o->taps = (int)p->taps;
        o->kernel = (int)p->kernel;
        o->preset = (int)p->artist_preset;
        o->guide_k = p->guide_k;
        o->guide_b_mm = p->guide_b;
        out->follow_surface = (int)p->follow_surface, out->rotation = p->rotation, out->transmittance = (int)p->transmittance;
    } else if (s->variant == SSSS_VARIANT_GAUSS6) {
        const ssss_gauss6_params *p = params;
        o->taps = (int)p->taps;
        out->follow_surface = (int)p->follow_surface, out->rotation = p->rotation, out->transmittance = (int)p->transmittance;
    } else {
        const ssss_svd_params *p = params;
        o->rank = (int)p->rank;
        o->grid = (int)p->svd_grid;
        out->follow_surface = (int)p->follow_surface, out->rotation = p->rotation, out->transmittance = (int)p->transmittance;
    }
}

static void free_targets(ssss_state *s)
{
    GLuint f[3] = {s->fbo_prep, s->fbo_tmp, s->fbo_sum}, t[3] = {s->tex_prep, s->tex_tmp, s->tex_sum};
    for (int i = 0; i < 3; i++) {
        if (f[i]) glDeleteFramebuffers(1, &f[i]);
        if (t[i]) glDeleteTextures(1, &t[i]);
    }
    s->fbo_prep = s->fbo_tmp = s->fbo_sum = s->tex_prep = s->tex_tmp = s->tex_sum = 0;
    s->target_bytes = 0;
    s->width = s->height = 0;
}

static GLuint fbo_for(GLuint tex)
{
    GLuint fbo;
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, tex, 0);
    glNamedFramebufferDrawBuffer(fbo, GL_COLOR_ATTACHMENT0);
    return fbo;
}

static sss_result make_targets(const gl_tech_ctx *c, ssss_state *s, sss_error *err)
{
    free_targets(s);
    s->tex_prep = gl_texture_2d(GL_RGBA32F, c->width, c->height, 1, &s->target_bytes);
    s->tex_tmp = gl_texture_2d(GL_RGBA32F, c->width, c->height, 1, &s->target_bytes);
    s->tex_sum = gl_texture_2d(GL_RGBA32F, c->width, c->height, 1, &s->target_bytes);
    /* the taps read the signal bilinearly (fractional projected offsets) */
    GLuint lin[2] = {s->tex_prep, s->tex_tmp};
    for (int i = 0; i < 2; i++) {
        glTextureParameteri(lin[i], GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(lin[i], GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    }
    s->fbo_prep = fbo_for(s->tex_prep);
    s->fbo_tmp = fbo_for(s->tex_tmp);
    s->fbo_sum = fbo_for(s->tex_sum);
    GLuint f[3] = {s->fbo_prep, s->fbo_tmp, s->fbo_sum};
    for (int i = 0; i < 3; i++)
        if (glCheckNamedFramebufferStatus(f[i], GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            return sss_error_set(err, SSS_ERROR_UNSUPPORTED, "incomplete render target");
    s->width = c->width;
    s->height = c->height;
    return gl_check(c->gl, "ssss: targets", err);
}

/* (Re)builds the kernel block and the T(s) table when the kernel parameters changed. */
static sss_result make_kernel(const gl_tech_ctx *c, ssss_state *s, sss_error *err)
{
    ssss_settings set;
    settings_of(s, c->params, &set);
    ssss_kernel_opts o = set.opts;
    if (s->have_kernel && memcmp(&o, &s->built, sizeof o) == 0) return SSS_OK;
    ssss_kernel_data d;
    sss_result res = ssss_kernel_build(c, &o, &d, err);
    if (res != SSS_OK) return res;
    if (s->ssbo) glDeleteBuffers(1, &s->ssbo);
    if (s->trans_tex) glDeleteTextures(1, &s->trans_tex);
    glCreateBuffers(1, &s->ssbo);
    glNamedBufferStorage(s->ssbo, (GLsizeiptr)sizeof(float) * 4 * d.vec4_count, d.block, 0);
    glCreateTextures(GL_TEXTURE_2D, 1, &s->trans_tex);
    glTextureStorage2D(s->trans_tex, 1, GL_RGBA32F, SSSS_TRANS_SIZE, d.trans_rows);
    glTextureSubImage2D(s->trans_tex, 0, 0, 0, SSSS_TRANS_SIZE, d.trans_rows, GL_RGBA, GL_FLOAT, d.trans);
    glTextureParameteri(s->trans_tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(s->trans_tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(s->trans_tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(s->trans_tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    s->kernel_bytes = sizeof(float) * 4 * ((size_t)d.vec4_count + (size_t)SSSS_TRANS_SIZE * d.trans_rows);
    s->terms = d.terms;
    s->built = o;
    s->have_kernel = 1;
    ssss_kernel_data_free(&d);
    return gl_check(c->gl, "ssss: kernel upload", err);
}

static sss_result ssss_resize(const gl_tech_ctx *c, void *state, sss_error *err)
{
    ssss_state *s = state;
    sss_result res = SSS_OK;
    if (s->width != c->width || s->height != c->height || !s->tex_prep) res = make_targets(c, s, err);
    if (res == SSS_OK) res = make_kernel(c, s, err);
    return res;
}

static sss_result create_variant(const gl_tech_ctx *c, ssss_state *s, ssss_variant v, sss_error *err)
{
    s->variant = v;
    sss_result res = gl_program_vf("fullscreen.vert.glsl", "ssss_prepare.frag.glsl", TRANS_DEFINE, &s->prog_prep, err);
    if (res == SSS_OK) res = gl_program_vf("fullscreen.vert.glsl", "ssss_blur.frag.glsl", NULL, &s->prog_blur, err);
    if (res == SSS_OK)
        res = gl_program_vf("fullscreen.vert.glsl", "ssss_combine.frag.glsl", NULL, &s->prog_combine, err);
    if (res != SSS_OK) return res;
    /* the shadow maps read as plain depth (the renderer's units compare): sampler objects override the
     * textures' comparison mode on our units only */
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
    return ssss_resize(c, s, err);
}

static sss_result ssss_create(const gl_tech_ctx *c, void *state, sss_error *err)
{
    return create_variant(c, state, SSSS_VARIANT_SEPARABLE, err);
}
static sss_result gauss6_create(const gl_tech_ctx *c, void *state, sss_error *err)
{
    return create_variant(c, state, SSSS_VARIANT_GAUSS6, err);
}
static sss_result svd_create(const gl_tech_ctx *c, void *state, sss_error *err)
{
    return create_variant(c, state, SSSS_VARIANT_SVD, err);
}
/* New materials (sss_gl_renderer_update_materials): the kernels again, the targets and programs stay. */
static sss_result ssss_materials_changed(const gl_tech_ctx *c, void *state, sss_error *err)
{
    ssss_state *s = state;
    s->have_kernel = 0;
    return make_kernel(c, s, err);
}


/* One timer name per pass (at most 8 terms: svd rank <= 8, gauss6 6): tools that merge timings by name
 * over frames expect each name once per frame. */
static const char *const names_h[8] = {"ssss_blur_h1", "ssss_blur_h2", "ssss_blur_h3", "ssss_blur_h4",
                                       "ssss_blur_h5", "ssss_blur_h6", "ssss_blur_h7", "ssss_blur_h8"};
static const char *const names_v[8] = {"ssss_blur_v1", "ssss_blur_v2", "ssss_blur_v3", "ssss_blur_v4",
                                       "ssss_blur_v5", "ssss_blur_v6", "ssss_blur_v7", "ssss_blur_v8"};

static sss_result ssss_render(const gl_tech_ctx *c, void *state, sss_error *err)
{
    ssss_state *s = state;
    ssss_settings set;
    settings_of(s, c->params, &set);
    sss_result res = ssss_resize(c, s, err);
    if (res != SSS_OK) return res;
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SSSS_SSBO_BINDING, s->ssbo);
    glViewport(0, 0, c->width, c->height);
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);

    gl_timer_begin(c->timer, "ssss_prepare");
    glBindFramebuffer(GL_FRAMEBUFFER, s->fbo_prep);
    glUseProgram(s->prog_prep);
    glBindTextureUnit(0, c->frame.pos);
    glBindTextureUnit(1, c->frame.nrm);
    glBindTextureUnit(2, c->frame.albedo);
    glBindTextureUnit(3, c->frame.irr);
    glBindTextureUnit(5, s->trans_tex);
    glBindTextureUnit(6, c->gs->shadow_cube);
    glBindSampler(6, s->samp_cube);
    glBindTextureUnit(7, c->gs->shadow_2d);
    glBindSampler(7, s->samp_2d);
    gl_uniform_i(s->prog_prep, "u_transmittance", set.transmittance && c->gs->light_count > 0);
    gl_draw_fullscreen(c);
    glBindSampler(6, 0);
    glBindSampler(7, 0);
    res = gl_check(c->gl, "ssss: prepare pass", err);
    if (res != SSS_OK) return res;

    const float zero[4] = {0, 0, 0, 0};
    glClearNamedFramebufferfv(s->fbo_sum, GL_COLOR, 0, zero);
    glUseProgram(s->prog_blur);
    glBindTextureUnit(1, c->frame.pos);
    gl_uniform_i(s->prog_blur, "u_follow", set.follow_surface);
    glUniform1f(glGetUniformLocation(s->prog_blur, "u_rotate"), (float)set.rotation);
    GLint u_vertical = glGetUniformLocation(s->prog_blur, "u_vertical");
    GLint u_term = glGetUniformLocation(s->prog_blur, "u_term");
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    for (int t = 0; t < s->terms; t++) {
        gl_timer_begin(c->timer, names_h[t & 7]);
        glDisable(GL_BLEND);
        glBindFramebuffer(GL_FRAMEBUFFER, s->fbo_tmp);
        glBindTextureUnit(0, s->tex_prep);
        glUniform1i(u_vertical, 0);
        glUniform1i(u_term, t);
        gl_draw_fullscreen(c);
        gl_timer_begin(c->timer, names_v[t & 7]);
        /* the terms add up in the float target (blending does not clamp RGBA32F) */
        glEnable(GL_BLEND);
        glBindFramebuffer(GL_FRAMEBUFFER, s->fbo_sum);
        glBindTextureUnit(0, s->tex_tmp);
        glUniform1i(u_vertical, 1);
        gl_draw_fullscreen(c);
        glDisable(GL_BLEND);
        res = gl_check(c->gl, "ssss: separable passes", err);
        if (res != SSS_OK) return res;
    }

    gl_timer_begin(c->timer, "combine");
    gl_resolve_begin(c, s->prog_combine);
    glBindTextureUnit(4, s->tex_sum);
    glBindTextureUnit(5, s->tex_prep);
    gl_draw_fullscreen(c);
    gl_timer_end(c->timer);
    return gl_check(c->gl, "ssss: combination", err);
}

static void ssss_destroy(void *state)
{
    ssss_state *s = state;
    free_targets(s);
    GLuint p[3] = {s->prog_prep, s->prog_blur, s->prog_combine};
    gl_delete_programs(p, 3);
    if (s->ssbo) glDeleteBuffers(1, &s->ssbo);
    if (s->trans_tex) glDeleteTextures(1, &s->trans_tex);
    GLuint samp[2] = {s->samp_cube, s->samp_2d};
    gl_delete_samplers(samp, 2);
}

static const char *const targets[] = {"ssss_signal", "ssss_horizontal", "ssss_sum", NULL};

static GLuint ssss_target(void *state, const char *name)
{
    ssss_state *s = state;
    if (strcmp(name, "ssss_signal") == 0) return s->tex_prep;     /* irradiance + transmittance */
    if (strcmp(name, "ssss_horizontal") == 0) return s->tex_tmp;  /* last term's horizontal pass */
    if (strcmp(name, "ssss_sum") == 0) return s->tex_sum;         /* sum of the terms */
    return 0;
}

static void ssss_stats(const gl_tech_ctx *c, void *state, sss_gl_stats *out)
{
    ssss_state *s = state;
    out->texture_bytes += s->target_bytes + s->kernel_bytes;
    out->per_pixel_bytes += s->target_bytes / ((size_t)c->width * (size_t)c->height);
}

#define SSSS_READS (GL_READ_GBUFFER | GL_READ_ILLUMINATION | GL_READ_LIGHTS)

/* Support (technique.h): the blur gathers along the visible surface of the same object only (taps on
 * another object or the background take the centre colour), so light that the profile carries farther
 * than about the object's mean chord (round to the far side) never arrives. */
static double ssss_support(const double *params, const sss_scene *scene, int object, int width, int height)
{
    (void)params, (void)width, (void)height;
    return gl_object_mean_chord(scene, object);
}

/* ssss-gauss6 blurs with the skin fit whatever the material: also no farther than its widest Gaussian
 * reaches (3 sigma; variances in mm^2, the material's scale in mm per scene unit, as build_gauss6). */
static double gauss6_support(const double *params, const sss_scene *scene, int object, int width, int height)
{
    double v = 0.0, scale = scene->objects[object].material.scale;
    for (int i = 0; i < SSS_GAUSS6_TERMS; i++) v = fmax(v, sss_gauss6_variance_mm2[i]);
    double fit = 3.0 * sqrt(v) / (scale > 0.0 ? scale : 1.0);
    return fmin(fit, ssss_support(params, scene, object, width, height));
}

const gl_technique gl_technique_ssss = {
    .info = {"ssss",
             "Jimenez et al. 2019: separable SSS, two 1D passes of a pre-integrated, artist or guided kernel, "
             "transmittance from shadow maps",
             ssss_params_info, (int)(sizeof ssss_params_info / sizeof ssss_params_info[0])},
    .reads = SSSS_READS,
    .targets = targets,
    .state_size = sizeof(ssss_state),
    .create = ssss_create,
    .resize = ssss_resize,
    .render = ssss_render,
    .destroy = ssss_destroy,
    .materials_changed = ssss_materials_changed,
    .target = ssss_target,
    .stats = ssss_stats,
    .support = ssss_support,
};

const gl_technique gl_technique_ssss_gauss6 = {
    .info = {"ssss-gauss6", "d'Eon et al. 2007 six-Gaussian sum as 12 1D passes (the baseline of Jimenez et al. 2019)",
             gauss6_params_info, (int)(sizeof gauss6_params_info / sizeof gauss6_params_info[0])},
    .reads = SSSS_READS,
    .targets = targets,
    .state_size = sizeof(ssss_state),
    .create = gauss6_create,
    .resize = ssss_resize,
    .render = ssss_render,
    .destroy = ssss_destroy,
    .materials_changed = ssss_materials_changed,
    .target = ssss_target,
    .stats = ssss_stats,
    .support = gauss6_support,
};

const gl_technique gl_technique_ssss_svd = {
    .info = {"ssss-svd", "rank-N SVD of the discretised profile as 2N 1D passes (Jimenez et al. 2019, section 3)",
             svd_params_info, (int)(sizeof svd_params_info / sizeof svd_params_info[0])},
    .reads = SSSS_READS,
    .targets = targets,
    .state_size = sizeof(ssss_state),
    .create = svd_create,
    .resize = ssss_resize,
    .render = ssss_render,
    .destroy = ssss_destroy,
    .materials_changed = ssss_materials_changed,
    .target = ssss_target,
    .stats = ssss_stats,
    .support = ssss_support,
};
