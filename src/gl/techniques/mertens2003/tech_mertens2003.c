/* gl/tech_mertens2003.c — Mertens, Kautz, Bekaert, Van Reeth & Seidel 2003: image-space
 * integration of the subsurface integral with exact importance sampling of the profile.
 *
 * Per pixel x_o: samples in its tangent plane, radii importance-sampled per colour channel from
 * R_d(c) 2 pi r / rho (section 4; tables of the physics module's exact sampler, tech_mertens2003.h)
 * plus uniform samples over a disc, combined by the balance heuristic (section 6.1); each sample is
 * projected into the camera's irradiance image (the shared illumination pass) and weighted by
 * R_d(c) / (combined density at r') — Eq. 9's R_d(r_i) / R_d(r'_i) — and optionally the Jacobian of
 * section 5. Interleaved sampling (section 6.1): a pattern x pattern block of pixels uses disjoint
 * strata of the sample sets and a blur over the block (same object, similar normals) recombines them.
 * Back lighting (section 7.1): each light's view gets its own irradiance image; a sample also looks
 * there, and the lit surface point it finds counts when the camera does not see that point (the
 * camera image already holds the points it sees), so the two images partition the surface.
 *
 * Passes: "light_views", "estimate", "resolve" (blur + exit factor c_o sqrt(albedo) + reflection). */
#include <stdlib.h>
#include <string.h>

#include "gl/common/tsm.h"
#include "gl/techniques/mertens2003/tech_mertens2003.h"

#define MAX_VIEWS 4
#define SSBO_TABLES 10 /* binding of the sampling tables (mertens2003_estimate.frag.glsl) */

#define MERTENS2003_PARAMS(X) \
    X(samples, SSS_GL_PARAM_INT, 24, 0, 768, "importance samples per pixel, spread over the colour channels (Mertens et al. 2003, section 4)") \
    X(uniform_samples, SSS_GL_PARAM_INT, 8, 0, 256, "uniform samples per pixel over the disc A' (section 6.1, balance heuristic)") \
    X(uniform_radius, SSS_GL_PARAM_FLOAT, 1, 0.01, 100, "radius R' of the uniform disc in units of the kernel's reach (section 5)") \
    X(pattern, SSS_GL_PARAM_INT, 4, 1, 8, "interleaved sampling over pattern x pattern pixel blocks (section 6.1; 1: off)") \
    X(blur, SSS_GL_PARAM_BOOL, 1, 0, 1, "recombine the interleaved block by a blur over the same object and similar normals") \
    X(blur_normal, SSS_GL_PARAM_FLOAT, 0.8, -1, 1, "blur partners need n . n_q at least this") \
    X(jacobian, SSS_GL_PARAM_BOOL, 0, 0, 1, "multiply by |dA_p / dA_p'| of the projection (section 5; the paper omits it, 6.2)") \
    X(renormalize, SSS_GL_PARAM_BOOL, 1, 0, 1, "divide the camera-image sum by the fraction of samples that found the object (6.2)") \
    X(light_views, SSS_GL_PARAM_INT, 2, 0, MAX_VIEWS, "irradiance images from the first N lights' views for back lighting (section 7.1)") \
    X(light_view_size, SSS_GL_PARAM_INT, 1024, 16, 8192, "texels per side of each light-view irradiance image") \
    X(jitter, SSS_GL_PARAM_BOOL, 1, 0, 1, "random offsets within the strata and a random rotation per pixel (0: stratum centres)") \
    X(seed, SSS_GL_PARAM_INT, 0, 0, 1000000, "seed of the per-pixel random offsets")

GL_PARAM_STRUCT(mertens2003_params, MERTENS2003_PARAMS);

static const sss_gl_param_info params[] = {MERTENS2003_PARAMS(GL_PARAM_INFO)};

typedef struct mertens_state {
    GLuint prog_est, prog_resolve, prog_tsm;
    GLuint tables;
    GLuint tex_est, fbo_est;
    GLuint view_pos, view_irr, view_nrm, view_depth;
    GLuint view_fbo[MAX_VIEWS];
    int views, view_size;
    size_t bytes, view_bytes;
    tsm_bounds bounds;
} mertens_state;

/* One sampling table per GL material (zeros for the non-scattering ones). */
static sss_result upload_tables(const gl_tech_ctx *c, mertens_state *s, sss_error *err)
{
    int nm = c->gs->mat.count > 0 ? c->gs->mat.count : 1;
    float *data = calloc((size_t)nm * MERTENS_TABLE_FLOATS, sizeof *data);
    if (!data) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (mertens2003 tables)");
    sss_result res = SSS_OK;
    for (int mi = 0; mi < c->gs->mat.count && res == SSS_OK; mi++) {
        if (!c->gs->mat.items[mi].subsurface) continue;
        for (size_t i = 0; i < c->scene->object_count; i++) {
            if (c->gs->objects[i].material != mi) continue;
            const sss_scene_material *m = &c->scene->objects[i].material;
            res = mertens_table_build(&m->rd, data + (size_t)mi * MERTENS_TABLE_FLOATS, err);
            break;
        }
    }
    if (res == SSS_OK) {
        glCreateBuffers(1, &s->tables);
        glNamedBufferStorage(s->tables, (GLsizeiptr)(sizeof *data * (size_t)nm * MERTENS_TABLE_FLOATS), data, 0);
        s->bytes = sizeof *data * (size_t)nm * MERTENS_TABLE_FLOATS;
    }
    free(data);
    return res;
}

static void free_views(mertens_state *s)
{
    GLuint t[4] = {s->view_pos, s->view_irr, s->view_nrm, s->view_depth};
    for (int i = 0; i < 4; i++)
        if (t[i]) glDeleteTextures(1, &t[i]);
    for (int v = 0; v < MAX_VIEWS; v++)
        if (s->view_fbo[v]) glDeleteFramebuffers(1, &s->view_fbo[v]);
    memset(s->view_fbo, 0, sizeof s->view_fbo);
    s->view_pos = s->view_irr = s->view_nrm = s->view_depth = 0;
    s->view_bytes = 0;
}

static GLuint array_texture(GLenum format, int size, int layers, size_t *bytes)
{
    GLuint t = 0;
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &t);
    glTextureStorage3D(t, 1, format, size, size, layers);
    glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    *bytes += gl_format_bytes(format) * (size_t)size * size * (size_t)layers;
    return t;
}

static sss_result make_targets(const gl_tech_ctx *c, mertens_state *s, sss_error *err)
{
    const mertens2003_params *p = c->params;
    GLint w = 0, h = 0;
    if (s->tex_est) {
        glGetTextureLevelParameteriv(s->tex_est, 0, GL_TEXTURE_WIDTH, &w);
        glGetTextureLevelParameteriv(s->tex_est, 0, GL_TEXTURE_HEIGHT, &h);
    }
    if (!s->tex_est || w != c->width || h != c->height) {
        if (s->tex_est) glDeleteTextures(1, &s->tex_est);
        if (s->fbo_est) glDeleteFramebuffers(1, &s->fbo_est);
        s->tex_est = gl_texture_2d(GL_RGBA32F, c->width, c->height, 1, NULL);
        glCreateFramebuffers(1, &s->fbo_est);
        glNamedFramebufferTexture(s->fbo_est, GL_COLOR_ATTACHMENT0, s->tex_est, 0);
        if (glCheckNamedFramebufferStatus(s->fbo_est, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            return sss_error_set(err, SSS_ERROR_UNSUPPORTED, "mertens2003: incomplete estimate target");
    }
    int views = (int)p->light_views;
    if (views > c->gs->light_count) views = c->gs->light_count;
    int size = views > 0 ? (int)p->light_view_size : 1;
    if (size > c->gl->max_texture_size)
        return sss_error_set(err, SSS_ERROR_LIMIT, "mertens2003: light_view_size %d exceeds the GL texture limit %d",
                             size, c->gl->max_texture_size);
    if (s->view_pos && views == s->views && size == s->view_size) return gl_check(c->gl, "mertens2003: targets", err);
    free_views(s);
    s->views = views;
    s->view_size = size;
    int layers = views > 0 ? views : 1; /* a 1x1 layer keeps the samplers complete */
    s->view_pos = array_texture(GL_RGBA32F, size, layers, &s->view_bytes);
    s->view_irr = array_texture(GL_RGBA32F, size, layers, &s->view_bytes);
    s->view_nrm = array_texture(GL_RGBA16F, size, layers, &s->view_bytes);
    s->view_depth = gl_texture_2d(GL_DEPTH_COMPONENT32F, size, size, 1, &s->view_bytes);
    GLenum bufs[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
    for (int v = 0; v < views; v++) {
        glCreateFramebuffers(1, &s->view_fbo[v]);
        glNamedFramebufferTextureLayer(s->view_fbo[v], bufs[0], s->view_pos, 0, v);
        glNamedFramebufferTextureLayer(s->view_fbo[v], bufs[1], s->view_irr, 0, v);
        glNamedFramebufferTextureLayer(s->view_fbo[v], bufs[2], s->view_nrm, 0, v);
        glNamedFramebufferTexture(s->view_fbo[v], GL_DEPTH_ATTACHMENT, s->view_depth, 0);
        glNamedFramebufferDrawBuffers(s->view_fbo[v], 3, bufs);
        if (glCheckNamedFramebufferStatus(s->view_fbo[v], GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            return sss_error_set(err, SSS_ERROR_UNSUPPORTED, "mertens2003: incomplete %dx%d light-view target", size,
                                 size);
    }
    return gl_check(c->gl, "mertens2003: targets", err);
}

static sss_result mertens_create(const gl_tech_ctx *c, void *state, sss_error *err)
{
    mertens_state *s = state;
    sss_result res = gl_program_vf("fullscreen.vert.glsl", "mertens2003_estimate.frag.glsl", NULL, &s->prog_est, err);
    if (res == SSS_OK)
        res = gl_program_vf("fullscreen.vert.glsl", "mertens2003_resolve.frag.glsl", NULL, &s->prog_resolve, err);
    if (res == SSS_OK) res = tsm_program(&s->prog_tsm, err);
    if (res == SSS_OK) res = upload_tables(c, s, err);
    if (res != SSS_OK) return res;
    tsm_bounds_compute(c, &s->bounds);
    return make_targets(c, s, err);
}

/* New materials (sss_gl_renderer_update_materials): new sampling tables, the rest stays. */
static sss_result mertens_materials_changed(const gl_tech_ctx *c, void *state, sss_error *err)
{
    mertens_state *s = state;
    GLuint old = s->tables;
    sss_result res = upload_tables(c, s, err); /* sets s->tables and s->bytes only when it succeeds */
    if (res == SSS_OK && old) glDeleteBuffers(1, &old);
    return res;
}

static sss_result mertens_resize(const gl_tech_ctx *c, void *state, sss_error *err)
{
    return make_targets(c, state, err);
}


/* The interleaving block in render pixels: `pattern` counts output pixels, so with supersampling (k)
 * the block and the blur that recombines it cover the same part of the image as at k = 1 (k^2 times
 * the strata, each render pixel still takes `samples`); pattern 1 (off: every pixel all strata, no
 * blur) stays off. docs/supersampling.md. */
static int pattern(const gl_tech_ctx *c)
{
    int block = (int)((const mertens2003_params *)c->params)->pattern;
    return block > 1 ? block * c->supersample : 1;
}

static sss_result mertens_render(const gl_tech_ctx *c, void *state, sss_error *err)
{
    mertens_state *s = state;
    sss_result res = make_targets(c, s, err);
    if (res != SSS_OK) return res;
    /* light-view irradiance images (section 7.1) */
    float vps[MAX_VIEWS][16];
    int view_light[MAX_VIEWS], nviews = 0;
    gl_timer_begin(c->timer, "light_views");
    for (int v = 0; v < s->views; v++) {
        if (!tsm_light_matrix(c, &s->bounds, v, vps[nviews])) continue;
        tsm_render(c, s->prog_tsm, s->view_fbo[nviews], s->view_size, v, vps[nviews]);
        view_light[nviews++] = v;
    }
    res = gl_check(c->gl, "mertens2003: light views", err);
    if (res != SSS_OK) return res;

    gl_timer_begin(c->timer, "estimate");
    glBindFramebuffer(GL_FRAMEBUFFER, s->fbo_est);
    glViewport(0, 0, c->width, c->height);
    glDisable(GL_BLEND);
    const float zero[4] = {0, 0, 0, 0};
    glClearBufferfv(GL_COLOR, 0, zero);
    const mertens2003_params *p = c->params;
    GLuint prog = s->prog_est;
    glUseProgram(prog);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SSBO_TABLES, s->tables);
    glBindTextureUnit(0, c->frame.pos);
    glBindTextureUnit(1, c->frame.nrm);
    glBindTextureUnit(2, c->frame.irr);
    glBindTextureUnit(3, s->view_pos);
    glBindTextureUnit(4, s->view_irr);
    glBindTextureUnit(5, s->view_nrm);
    gl_uniform_i(prog, "u_samples", (int)p->samples);
    gl_uniform_i(prog, "u_uniform", (int)p->uniform_samples);
    glUniform1f(glGetUniformLocation(prog, "u_uniform_radius"), (float)p->uniform_radius);
    gl_uniform_i(prog, "u_pattern", pattern(c));
    gl_uniform_i(prog, "u_jacobian", (int)p->jacobian);
    gl_uniform_i(prog, "u_renormalize", (int)p->renormalize);
    gl_uniform_i(prog, "u_jitter", (int)p->jitter);
    glUniform1ui(glGetUniformLocation(prog, "u_seed"), (GLuint)p->seed);
    gl_uniform_i(prog, "u_views", nviews);
    if (nviews > 0) {
        glUniformMatrix4fv(glGetUniformLocation(prog, "u_view_vp"), nviews, GL_FALSE, &vps[0][0]);
        glUniform1iv(glGetUniformLocation(prog, "u_view_light"), nviews, view_light);
    }
    gl_draw_fullscreen(c);
    res = gl_check(c->gl, "mertens2003: estimate", err);
    if (res != SSS_OK) return res;

    gl_timer_begin(c->timer, "resolve");
    prog = s->prog_resolve;
    gl_resolve_begin(c, prog);
    glBindTextureUnit(4, s->tex_est);
    gl_uniform_i(prog, "u_pattern", pattern(c));
    gl_uniform_i(prog, "u_blur", (int)p->blur);
    glUniform1f(glGetUniformLocation(prog, "u_blur_normal"), (float)p->blur_normal);
    gl_draw_fullscreen(c);
    gl_timer_end(c->timer);
    return gl_check(c->gl, "mertens2003: resolve", err);
}

static void mertens_destroy(void *state)
{
    mertens_state *s = state;
    free_views(s);
    GLuint p[3] = {s->prog_est, s->prog_resolve, s->prog_tsm};
    gl_delete_programs(p, 3);
    if (s->tables) glDeleteBuffers(1, &s->tables);
    if (s->tex_est) glDeleteTextures(1, &s->tex_est);
    if (s->fbo_est) glDeleteFramebuffers(1, &s->fbo_est);
}

static const char *const targets[] = {"estimate", NULL};

static GLuint mertens_target(void *state, const char *name)
{
    mertens_state *s = state;
    /* "estimate": the per-pixel integral B(x_o) before the interleave blur and c_o */
    if (strcmp(name, "estimate") == 0) return s->tex_est;
    return 0;
}

static void mertens_stats(const gl_tech_ctx *c, void *state, sss_gl_stats *out)
{
    mertens_state *s = state;
    size_t est = (size_t)c->width * c->height * 16;
    out->texture_bytes += est + s->view_bytes;
    out->buffer_bytes += s->bytes;
    out->per_pixel_bytes += 16;
}

const gl_technique gl_technique_mertens2003 = {
    .info = {"mertens2003",
             "Mertens et al. 2003: tangent-plane samples with exact importance sampling of R_d, projected into "
             "the camera's (and the lights') irradiance images",
             params, (int)(sizeof params / sizeof params[0])},
    .reads = GL_READ_GBUFFER | GL_READ_ILLUMINATION | GL_READ_LIGHTS,
    .targets = targets,
    .state_size = sizeof(mertens_state),
    .create = mertens_create,
    .resize = mertens_resize,
    .render = mertens_render,
    .destroy = mertens_destroy,
    .materials_changed = mertens_materials_changed,
    .target = mertens_target,
    .stats = mertens_stats,
};
