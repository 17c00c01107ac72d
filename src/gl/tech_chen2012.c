/* gl/tech_chen2012.c — multiresolution splatting from a translucent shadow map (Chen, Peers, Zhang &
 * Tong 2012) as seed 000 configures it for its comparisons (section 8): per light an irradiance buffer
 * of 2048 x 2048 texels rendered from the light's view (positions, normals, transmitted irradiance;
 * tech_chen2012_tsm.h) with 3 mip levels; splats are selected from it, one per texel of the level
 * chosen by the splat's required radius (chen_select.comp.glsl), and splatted additively into the
 * camera view through the multi-resolution receiver pyramid shared with dss (tech_dss_shells.h),
 * with the profile at the splat centre (default, as the paper) or the disc-integrated R'_d(r, A).
 *
 * Several lights: one buffer, reused light after light (the splats of all lights are collected, then
 * splatted in one pass), for the first max_lights lights; area lights count as their virtual point
 * lights and environment maps as their directional lights (lights.c), so their cost multiplies.
 * Passes: "irradiance_buffers" (per light: render, mips, selection), "receivers", "splatting",
 * "resolve". */
#include <string.h>

#include "gl/tech_chen2012_tsm.h"
#include "gl/tech_dss_shells.h"

enum { P_SIZE = 0, P_BUFFER_LEVELS, P_TEXEL_FRACTION, P_MAX_LIGHTS, P_PREINTEGRATED, P_IRRADIANCE_CULL,
       P_VIEW_LEVELS, P_VIEW_EPSILON, P_MAX_SPLATS, P_COUNT };

static const sss_gl_param_info params[P_COUNT] = {
    [P_SIZE] = {"buffer_size", SSS_GL_PARAM_INT, 2048, 16, 8192,
                "texels per side of each light's irradiance buffer (seed 000, section 8: 2048)"},
    [P_BUFFER_LEVELS] = {"buffer_levels", SSS_GL_PARAM_INT, 3, 1, 4,
                         "mip levels of the irradiance buffer splats are chosen from (seed 000, section 8: 3)"},
    [P_TEXEL_FRACTION] = {"texel_fraction", SSS_GL_PARAM_FLOAT, 0.125, 1e-4, 1,
                          "a splat's texel is at most this fraction of its required radius (the kernel's reach)"},
    [P_MAX_LIGHTS] = {"max_lights", SSS_GL_PARAM_INT, 64, 1, 4096,
                      "irradiance buffers for the first N lights (virtual lights included); the rest are skipped"},
    [P_PREINTEGRATED] = {"preintegrated", SSS_GL_PARAM_BOOL, 1, 0, 1,
                         "1: the disc-integrated R'_d(r, A) of seed 000; 0: R_d at the splat centre (Chen et al.)"},
    [P_IRRADIANCE_CULL] = {"irradiance_cull", SSS_GL_PARAM_FLOAT, 0, 0, 1e30,
                           "texels whose largest F_t E channel is at most this make no splat"},
    [P_VIEW_LEVELS] = {"view_levels", SSS_GL_PARAM_INT, 4, 1, SHELL_MAX_LEVELS,
                       "levels of the camera-side splatting buffer (multiresolution splatting)"},
    [P_VIEW_EPSILON] = {"view_epsilon", SSS_GL_PARAM_FLOAT, 0.1, 1e-3, 1,
                        "camera level l serves receivers at least 2^l pixels / epsilon from the splat"},
    [P_MAX_SPLATS] = {"max_splats", SSS_GL_PARAM_INT, 1048576, 1, 16777216,
                      "capacity of the splat buffer (48 bytes each, all lights); splats beyond it are dropped"},
};

typedef struct chen_state {
    GLuint prog_tsm, prog_reduce, prog_select;
    GLuint tex_pos, tex_irr, tex_nrm, tex_depth, fbo;
    int size, levels;
    size_t tsm_bytes;
    GLuint splats, cmd;
    unsigned capacity;
    shell_targets shells;
    tsm_bounds bounds;
    int lights_used;
} chen_state;

static void free_tsm(chen_state *s)
{
    GLuint t[4] = {s->tex_pos, s->tex_irr, s->tex_nrm, s->tex_depth};
    for (int i = 0; i < 4; i++)
        if (t[i]) glDeleteTextures(1, &t[i]);
    if (s->fbo) glDeleteFramebuffers(1, &s->fbo);
    s->tex_pos = s->tex_irr = s->tex_nrm = s->tex_depth = s->fbo = 0;
    s->tsm_bytes = 0;
    s->size = s->levels = 0;
}

static sss_result make_resources(sss_gl_renderer *r, chen_state *s, sss_error *err)
{
    int size = (int)gl_param(r, P_SIZE), levels = (int)gl_param(r, P_BUFFER_LEVELS);
    if (size > r->ctx->max_texture_size)
        return sss_error_set(err, SSS_ERROR_LIMIT, "chen2012: buffer_size %d exceeds the GL texture limit %d", size,
                             r->ctx->max_texture_size);
    int max_levels = gl_mip_levels(size, size);
    if (levels > max_levels) levels = max_levels;
    if (s->size != size || s->levels != levels) {
        free_tsm(s);
        s->size = size;
        s->levels = levels;
        s->tex_pos = gl_texture_2d(GL_RGBA32F, size, size, levels, &s->tsm_bytes);
        s->tex_irr = gl_texture_2d(GL_RGBA32F, size, size, levels, &s->tsm_bytes);
        s->tex_nrm = gl_texture_2d(GL_RGBA32F, size, size, levels, &s->tsm_bytes);
        s->tex_depth = gl_texture_2d(GL_DEPTH_COMPONENT32F, size, size, 1, &s->tsm_bytes);
        glCreateFramebuffers(1, &s->fbo);
        GLuint col[3] = {s->tex_pos, s->tex_irr, s->tex_nrm};
        GLenum bufs[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
        for (int i = 0; i < 3; i++) glNamedFramebufferTexture(s->fbo, bufs[i], col[i], 0);
        glNamedFramebufferTexture(s->fbo, GL_DEPTH_ATTACHMENT, s->tex_depth, 0);
        glNamedFramebufferDrawBuffers(s->fbo, 3, bufs);
        if (glCheckNamedFramebufferStatus(s->fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            return sss_error_set(err, SSS_ERROR_UNSUPPORTED, "chen2012: incomplete %dx%d irradiance buffer", size, size);
    }
    unsigned cap = (unsigned)gl_param(r, P_MAX_SPLATS);
    if (!s->splats || cap != s->capacity) {
        if (s->splats) glDeleteBuffers(1, &s->splats);
        s->capacity = cap;
        glCreateBuffers(1, &s->splats);
        glNamedBufferStorage(s->splats, (GLsizeiptr)SHELL_SPLAT_BYTES * cap, NULL, 0);
    }
    sss_result res = gl_check(r->ctx, "chen2012: irradiance buffer", err);
    if (res == SSS_OK) res = shell_resize(r, &s->shells, (int)gl_param(r, P_VIEW_LEVELS), err);
    return res;
}

static sss_result chen_create(sss_gl_renderer *r, void *state, sss_error *err)
{
    chen_state *s = state;
    sss_result res = tsm_program(&s->prog_tsm, err);
    if (res == SSS_OK) res = gl_program_compute("mip_reduce.comp.glsl", "#define WITH_NORMALS 1\n", &s->prog_reduce, err);
    if (res == SSS_OK) res = gl_program_compute("chen_select.comp.glsl", NULL, &s->prog_select, err);
    if (res == SSS_OK) res = shell_create(&s->shells, err);
    if (res != SSS_OK) return res;
    glCreateBuffers(1, &s->cmd);
    glNamedBufferStorage(s->cmd, 4 * sizeof(GLuint), NULL, GL_DYNAMIC_STORAGE_BIT);
    tsm_bounds_compute(r, &s->bounds);
    return make_resources(r, s, err);
}

static sss_result chen_resize(sss_gl_renderer *r, void *state, sss_error *err)
{
    return make_resources(r, state, err);
}

/* Area-weighted mip chains of the buffer (mip_reduce.comp.glsl, as the camera's shared pass). */
static void reduce(chen_state *s)
{
    glUseProgram(s->prog_reduce);
    GLint u_pre = glGetUniformLocation(s->prog_reduce, "u_src_premultiplied");
    GLint u_level = glGetUniformLocation(s->prog_reduce, "u_dst_level");
    glUniform2i(glGetUniformLocation(s->prog_reduce, "u_base_size"), s->size, s->size);
    int w = s->size;
    for (int l = 1; l < s->levels; l++) {
        int dw = w > 1 ? w / 2 : 1;
        glBindImageTexture(0, s->tex_pos, l - 1, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
        glBindImageTexture(1, s->tex_irr, l - 1, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
        glBindImageTexture(2, s->tex_pos, l, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        glBindImageTexture(3, s->tex_irr, l, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        glBindImageTexture(4, s->tex_nrm, l - 1, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
        glBindImageTexture(5, s->tex_nrm, l, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        glUniform1i(u_pre, l > 1);
        glUniform1i(u_level, l);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
        glDispatchCompute((GLuint)(dw + 7) / 8, (GLuint)(dw + 7) / 8, 1);
        w = dw;
    }
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

static void select_splats(sss_gl_renderer *r, chen_state *s)
{
    glUseProgram(s->prog_select);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GL_SSBO_SPLATS, s->splats);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GL_SSBO_SPLAT_COUNT, s->cmd);
    glBindTextureUnit(0, s->tex_pos);
    glBindTextureUnit(1, s->tex_irr);
    glBindTextureUnit(2, s->tex_nrm);
    glUniform1i(glGetUniformLocation(s->prog_select, "u_top"), s->levels - 1);
    glUniform1f(glGetUniformLocation(s->prog_select, "u_texel_fraction"), (float)gl_param(r, P_TEXEL_FRACTION));
    glUniform1f(glGetUniformLocation(s->prog_select, "u_irradiance_cull"), (float)gl_param(r, P_IRRADIANCE_CULL));
    glUniform1ui(glGetUniformLocation(s->prog_select, "u_capacity"), s->capacity);
    glUniform1i(glGetUniformLocation(s->prog_select, "u_size"), s->size);
    int top = s->size >> (s->levels - 1);
    if (top < 1) top = 1;
    glDispatchCompute((GLuint)(top + 7) / 8, (GLuint)(top + 7) / 8, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
}

static sss_result chen_render(sss_gl_renderer *r, void *state, sss_error *err)
{
    chen_state *s = state;
    sss_result res = make_resources(r, s, err);
    if (res != SSS_OK) return res;
    const GLuint reset[4] = {4, 0, 0, 0};
    glNamedBufferSubData(s->cmd, 0, sizeof reset, reset);
    gl_timer_begin(&r->timer, "irradiance_buffers");
    int n = r->gs.light_count < (int)gl_param(r, P_MAX_LIGHTS) ? r->gs.light_count : (int)gl_param(r, P_MAX_LIGHTS);
    s->lights_used = 0;
    for (int i = 0; i < n; i++) {
        float vp[16];
        if (!tsm_light_matrix(r, &s->bounds, i, vp)) continue;
        tsm_render(r, s->prog_tsm, s->fbo, s->size, i, vp);
        reduce(s);
        select_splats(r, s);
        s->lights_used++;
        res = gl_check(r->ctx, "chen2012: irradiance buffer", err);
        if (res != SSS_OK) return res;
    }
    gl_timer_begin(&r->timer, "receivers");
    shell_receivers(r, &s->shells);
    res = gl_check(r->ctx, "chen2012: receivers", err);
    if (res != SSS_OK) return res;
    gl_timer_begin(&r->timer, "splatting");
    shell_splat(r, &s->shells, s->splats, s->cmd, s->capacity, gl_param(r, P_VIEW_EPSILON),
                (int)gl_param(r, P_PREINTEGRATED));
    res = gl_check(r->ctx, "chen2012: splatting", err);
    if (res != SSS_OK) return res;
    gl_timer_begin(&r->timer, "resolve");
    shell_resolve(r, &s->shells);
    gl_timer_end(&r->timer);
    return gl_check(r->ctx, "chen2012: resolve", err);
}

static void chen_destroy(sss_gl_renderer *r, void *state)
{
    (void)r;
    chen_state *s = state;
    free_tsm(s);
    shell_free(&s->shells);
    GLuint p[3] = {s->prog_tsm, s->prog_reduce, s->prog_select};
    for (int i = 0; i < 3; i++)
        if (p[i]) glDeleteProgram(p[i]);
    if (s->splats) glDeleteBuffers(1, &s->splats);
    if (s->cmd) glDeleteBuffers(1, &s->cmd);
}

static GLuint chen_buffer(sss_gl_renderer *r, void *state, const char *name)
{
    (void)r;
    chen_state *s = state;
    if (strcmp(name, "translucency") == 0) return s->shells.accum[0];
    if (strcmp(name, "light_irradiance") == 0) return s->tex_irr; /* the last light's buffer, level 0 */
    if (strcmp(name, "light_positions") == 0) return s->tex_pos;
    return 0;
}

static void chen_stats(sss_gl_renderer *r, void *state, sss_gl_stats *out)
{
    chen_state *s = state;
    out->texture_bytes += s->shells.bytes + s->tsm_bytes;
    out->buffer_bytes += (size_t)SHELL_SPLAT_BYTES * s->capacity + 16;
    out->per_pixel_bytes += s->shells.bytes / ((size_t)r->width * (size_t)r->height);
    out->per_splat_bytes = SHELL_SPLAT_BYTES;
    out->splat_drawn = r->frame_rendered ? shell_splat_count(s->cmd, s->capacity) : 0;
}

const gl_technique gl_technique_chen2012 = {
    .info = {"chen2012",
             "Chen et al. 2012 as seed 000 compares it: splats from a 2048^2 light-view irradiance buffer "
             "(3 mip levels) per light, multiresolution additive splatting",
             params, P_COUNT},
    .needs = GL_NEED_GBUFFER | GL_NEED_SHADOWS | GL_NEED_ILLUMINATION,
    .state_size = sizeof(chen_state),
    .create = chen_create,
    .resize = chen_resize,
    .render = chen_render,
    .destroy = chen_destroy,
    .buffer = chen_buffer,
    .stats = chen_stats,
};
