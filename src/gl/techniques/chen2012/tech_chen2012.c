/* gl/tech_chen2012.c — multiresolution splatting from a translucent shadow map (Chen, Peers, Zhang &
 * Tong 2012) as Maisch & Ropinski 2020 configure it for its comparisons (section 8): per light an irradiance buffer
 * of 2048 x 2048 texels rendered from the light's view (positions, normals, transmitted irradiance;
 * common/tsm.h) with 3 mip levels; splats are selected from it, one per texel of the level
 * chosen by the splat's required radius (chen2012_select.comp.glsl), and splatted additively into the
 * camera view through the multi-resolution receiver pyramid shared with dss (common/shells.h),
 * with the profile at the splat centre (default, as the paper) or the disc-integrated R'_d(r, A).
 *
 * Several lights: one buffer, reused light after light (the splats of all lights are collected, then
 * splatted in one pass), for the first max_lights lights; area lights count as their virtual point
 * lights and environment maps as their directional lights (lights.c), so their cost multiplies.
 * The splat buffer grows to what the lights select (up to max_splats): a fixed capacity silently
 * dropped the splats of the last lights, whole lights at a time (under an environment map's 32
 * directions the point light after them and half the directions vanished).
 *
 * Environment maps: Maisch & Ropinski 2020 do not say how Chen et al. handle them. Their directional lights each
 * carry a small share of the map and their buffers' splats overlap from many directions, so they get
 * their own, smaller irradiance buffer (env_buffer_size, 256 by default: measured on eval_skin_env,
 * see the parameter); point, spot, area and scene directional lights keep buffer_size. Merging the
 * directions instead (env_lights 8 or 16 at buffer sizes 256..1024) measured worse there: DSSIM
 * 0.0222..0.0228 and 0.0203..0.0208 against 0.0202 for 32 directions at 256.
 * Passes: "irradiance_buffers" (per light: render, mips, selection), "receivers", "splatting",
 * "resolve". */
#include <math.h>
#include <string.h>

#include "gl/common/tsm.h"
#include "gl/common/shells.h"

/* eval_skin_env (384^2, 32 directions + a point light), DSSIM / ms per frame on llvmpipe in one run:
     * 128: 0.0213 / 18.8 s, 256: 0.0202 / 35.4 s, 512: 0.0198 / 91.9 s, 1024: 0.0200 / 101 s,
     * 2048 (= buffer_size): 0.0197 / 214 s (the splatting pass is ~80% of it, linear in the splats).
     * 256 is within 0.0005 of the full-size buffers at a sixth of the time (128 loses 0.0016). */
/* The splat buffer's first capacity (12 MB); it grows when the lights select more, up to max_splats. */
#define INITIAL_SPLATS 262144u

#define CHEN2012_PARAMS(X) \
    X(buffer_size, SSS_GL_PARAM_INT, 2048, 16, 8192, "texels per side of each light's irradiance buffer (Maisch & Ropinski 2020, section 8: 2048)") \
    X(buffer_levels, SSS_GL_PARAM_INT, 3, 1, 4, "mip levels of the irradiance buffer splats are chosen from (Maisch & Ropinski 2020, section 8: 3)") \
    X(texel_fraction, SSS_GL_PARAM_FLOAT, 0.125, 1e-4, 1, "a splat's texel is at most this fraction of its required radius (the kernel's reach)") \
    X(max_lights, SSS_GL_PARAM_INT, 64, 1, 4096, "irradiance buffers for the first N lights (virtual lights included); the rest are skipped") \
    X(preintegrated, SSS_GL_PARAM_BOOL, 1, 0, 1, "1: the disc-integrated R'_d(r, A) of Maisch & Ropinski 2020; 0: R_d at the splat centre (Chen et al.)") \
    X(irradiance_cull, SSS_GL_PARAM_FLOAT, 0, 0, 1e30, "texels whose largest F_t E channel is at most this make no splat") \
    X(view_levels, SSS_GL_PARAM_INT, 4, 1, SHELL_MAX_LEVELS, "levels of the camera-side splatting buffer (multiresolution splatting)") \
    X(view_epsilon, SSS_GL_PARAM_FLOAT, 0.1, 1e-3, 1, "camera level l (2^l output pixels) serves receivers at least 2^l pixels / epsilon from " "the splat") \
    X(max_splats, SSS_GL_PARAM_INT, 8388608, 1, 16777216, "largest splat buffer (48 bytes a splat, all lights): it grows to what the lights select, " "up to this; splats beyond it are dropped") \
    X(env_buffer_size, SSS_GL_PARAM_INT, 256, 16, 8192, "texels per side of the irradiance buffer of an environment map's directional lights") \
    X(view_fine_radius, SSS_GL_PARAM_FLOAT, 2.5, 0, 64, "with supersampling (k > 1): receivers within this many output pixels of a splat are splatted per " "render pixel (an extra camera level; the sharp near field antialiased, 5-10% more splatting on " "the eval scenes), at most level 0's 2 / view_epsilon; 0: the k = 1 image, antialiased at edges only " "(docs/supersampling.md)")

GL_PARAM_STRUCT(chen2012_params, CHEN2012_PARAMS);

static const sss_gl_param_info params[] = {CHEN2012_PARAMS(GL_PARAM_INFO)};

/* One light-view irradiance buffer (common/tsm.h) with its mip levels. */
typedef struct chen_tsm {
    GLuint tex_pos, tex_irr, tex_nrm, tex_depth, fbo;
    int size, levels;
    size_t bytes;
} chen_tsm;

typedef struct chen_state {
    shell_targets shells;
    GLuint prog_tsm, prog_reduce, prog_select;
    chen_tsm main, env; /* env: environment lights' buffer when env_buffer_size != buffer_size */
    const chen_tsm *last; /* the buffer of the last light rendered (chen_buffer) */
    GLuint splats, cmd;
    unsigned capacity;
    tsm_bounds bounds;
    int lights_used;
} chen_state;

static void free_tsm(chen_tsm *t)
{
    GLuint tex[4] = {t->tex_pos, t->tex_irr, t->tex_nrm, t->tex_depth};
    for (int i = 0; i < 4; i++)
        if (tex[i]) glDeleteTextures(1, &tex[i]);
    if (t->fbo) glDeleteFramebuffers(1, &t->fbo);
    memset(t, 0, sizeof *t);
}

/* (Re)creates t at size x size with `levels` mip levels (clamped to the chain) when it changed;
 * size 0 frees it. */
static sss_result make_tsm(const gl_tech_ctx *c, chen_tsm *t, int size, int levels, sss_error *err)
{
    if (size <= 0) {
        free_tsm(t);
        return SSS_OK;
    }
    if (size > c->gl->max_texture_size)
        return sss_error_set(err, SSS_ERROR_LIMIT, "chen2012: buffer size %d exceeds the GL texture limit %d", size,
                             c->gl->max_texture_size);
    int max_levels = gl_mip_levels(size, size);
    if (levels > max_levels) levels = max_levels;
    if (t->size == size && t->levels == levels) return SSS_OK;
    free_tsm(t);
    t->size = size;
    t->levels = levels;
    t->tex_pos = gl_texture_2d(GL_RGBA32F, size, size, levels, &t->bytes);
    t->tex_irr = gl_texture_2d(GL_RGBA32F, size, size, levels, &t->bytes);
    t->tex_nrm = gl_texture_2d(GL_RGBA32F, size, size, levels, &t->bytes);
    t->tex_depth = gl_texture_2d(GL_DEPTH_COMPONENT32F, size, size, 1, &t->bytes);
    glCreateFramebuffers(1, &t->fbo);
    GLuint col[3] = {t->tex_pos, t->tex_irr, t->tex_nrm};
    GLenum bufs[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
    for (int i = 0; i < 3; i++) glNamedFramebufferTexture(t->fbo, bufs[i], col[i], 0);
    glNamedFramebufferTexture(t->fbo, GL_DEPTH_ATTACHMENT, t->tex_depth, 0);
    glNamedFramebufferDrawBuffers(t->fbo, 3, bufs);
    if (glCheckNamedFramebufferStatus(t->fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return sss_error_set(err, SSS_ERROR_UNSUPPORTED, "chen2012: incomplete %dx%d irradiance buffer", size, size);
    return SSS_OK;
}

static int is_env_light(const gl_tech_ctx *c, int i)
{
    const gl_light_record *L = &c->gs->lights[i];
    return (int)(L->position[3] + 0.5f) == GL_LIGHT_DIRECTIONAL && L->direction[3] == GL_LIGHT_FROM_ENVIRONMENT;
}

/* The first min(light_count, max_lights) lights. */
static int lights_considered(const gl_tech_ctx *c)
{
    const chen2012_params *p = c->params;
    int m = (int)p->max_lights;
    return c->gs->light_count < m ? c->gs->light_count : m;
}

/* A splat buffer of cap splats holding the first `keep` splats of the current one. */
static void resize_splats(chen_state *s, unsigned cap, unsigned keep)
{
    if (s->splats && cap == s->capacity) return;
    GLuint b;
    glCreateBuffers(1, &b);
    glNamedBufferStorage(b, (GLsizeiptr)SHELL_SPLAT_BYTES * cap, NULL, 0);
    if (s->splats && keep) {
        if (keep > cap) keep = cap;
        glCopyNamedBufferSubData(s->splats, b, 0, 0, (GLsizeiptr)SHELL_SPLAT_BYTES * keep);
    }
    if (s->splats) glDeleteBuffers(1, &s->splats);
    s->splats = b;
    s->capacity = cap;
}

static sss_result make_resources(const gl_tech_ctx *c, chen_state *s, sss_error *err)
{
    const chen2012_params *p = c->params;
    int size = (int)p->buffer_size, env_size = (int)p->env_buffer_size;
    int levels = (int)p->buffer_levels;
    /* the environment's buffer exists only when an environment light is drawn with another size */
    int need_env = 0;
    for (int i = 0; i < lights_considered(c); i++) need_env |= is_env_light(c, i);
    sss_result res = make_tsm(c, &s->main, size, levels, err);
    if (res == SSS_OK) res = make_tsm(c, &s->env, need_env && env_size != size ? env_size : 0, levels, err);
    if (s->last == &s->env && !s->env.size) s->last = NULL;
    if (res != SSS_OK) return res;
    unsigned limit = (unsigned)p->max_splats;
    resize_splats(s, !s->splats ? (limit < INITIAL_SPLATS ? limit : INITIAL_SPLATS)
                                : (s->capacity > limit ? limit : s->capacity), 0);
    res = gl_check(c->gl, "chen2012: irradiance buffer", err);
    if (res == SSS_OK) res = shell_resize(c, &s->shells, (int)p->view_levels, p->view_fine_radius, err);
    return res;
}

static sss_result chen_create(const gl_tech_ctx *c, void *state, sss_error *err)
{
    chen_state *s = state;
    sss_result res = tsm_program(&s->prog_tsm, err);
    if (res == SSS_OK) res = gl_program_compute("mip_reduce.comp.glsl", "#define WITH_NORMALS 1\n", &s->prog_reduce, err);
    if (res == SSS_OK) res = gl_program_compute("chen2012_select.comp.glsl", NULL, &s->prog_select, err);
    if (res == SSS_OK) res = shell_create(&s->shells, err);
    if (res != SSS_OK) return res;
    glCreateBuffers(1, &s->cmd);
    glNamedBufferStorage(s->cmd, 4 * sizeof(GLuint), NULL, GL_DYNAMIC_STORAGE_BIT);
    tsm_bounds_compute(c, &s->bounds);
    return make_resources(c, s, err);
}

static sss_result chen_resize(const gl_tech_ctx *c, void *state, sss_error *err)
{
    return make_resources(c, state, err);
}

/* Area-weighted mip chains of the buffer (mip_reduce.comp.glsl, as the camera's shared pass). */
static void reduce(chen_state *s, const chen_tsm *t)
{
    glUseProgram(s->prog_reduce);
    GLint u_pre = glGetUniformLocation(s->prog_reduce, "u_src_premultiplied");
    GLint u_level = glGetUniformLocation(s->prog_reduce, "u_dst_level");
    glUniform2i(glGetUniformLocation(s->prog_reduce, "u_base_size"), t->size, t->size);
    int w = t->size;
    for (int l = 1; l < t->levels; l++) {
        int dw = w > 1 ? w / 2 : 1;
        glBindImageTexture(0, t->tex_pos, l - 1, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
        glBindImageTexture(1, t->tex_irr, l - 1, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
        glBindImageTexture(2, t->tex_pos, l, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        glBindImageTexture(3, t->tex_irr, l, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        glBindImageTexture(4, t->tex_nrm, l - 1, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
        glBindImageTexture(5, t->tex_nrm, l, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        glUniform1i(u_pre, l > 1);
        glUniform1i(u_level, l);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
        glDispatchCompute((GLuint)(dw + 7) / 8, (GLuint)(dw + 7) / 8, 1);
        w = dw;
    }
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

static void select_splats(const gl_tech_ctx *c, chen_state *s, const chen_tsm *t)
{
    const chen2012_params *p = c->params;
    glUseProgram(s->prog_select);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GL_SSBO_SPLATS, s->splats);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GL_SSBO_SPLAT_COUNT, s->cmd);
    glBindTextureUnit(0, t->tex_pos);
    glBindTextureUnit(1, t->tex_irr);
    glBindTextureUnit(2, t->tex_nrm);
    glUniform1i(glGetUniformLocation(s->prog_select, "u_top"), t->levels - 1);
    glUniform1f(glGetUniformLocation(s->prog_select, "u_texel_fraction"), (float)p->texel_fraction);
    glUniform1f(glGetUniformLocation(s->prog_select, "u_irradiance_cull"), (float)p->irradiance_cull);
    glUniform1ui(glGetUniformLocation(s->prog_select, "u_capacity"), s->capacity);
    glUniform1i(glGetUniformLocation(s->prog_select, "u_size"), t->size);
    int top = t->size >> (t->levels - 1);
    if (top < 1) top = 1;
    glDispatchCompute((GLuint)(top + 7) / 8, (GLuint)(top + 7) / 8, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

static unsigned selected_count(const chen_state *s)
{
    GLuint c[4] = {0, 0, 0, 0};
    glGetNamedBufferSubData(s->cmd, 0, sizeof c, c);
    return c[1];
}

/* Every light's buffer: render, mips, selection. The splat buffer grows (up to max_splats) whenever a
 * light's selection overflows it: the splats of the lights before are kept and that light selects
 * again from its buffer, still in place. (A fixed capacity dropped the last lights' splats whole.) */
static sss_result irradiance_buffers(const gl_tech_ctx *c, chen_state *s, sss_error *err)
{
    const chen2012_params *p = c->params;
    const GLuint reset[4] = {4, 0, 0, 0};
    glNamedBufferSubData(s->cmd, 0, sizeof reset, reset);
    s->lights_used = 0;
    unsigned limit = (unsigned)p->max_splats, before = 0;
    for (int i = 0; i < lights_considered(c); i++) {
        float vp[16];
        if (!tsm_light_matrix(c, &s->bounds, i, vp)) continue;
        const chen_tsm *t = is_env_light(c, i) && s->env.size ? &s->env : &s->main;
        tsm_render(c, s->prog_tsm, t->fbo, t->size, i, vp);
        reduce(s, t);
        select_splats(c, s, t);
        unsigned now = selected_count(s);
        if (now > s->capacity && s->capacity < limit) {
            double want = fmax(1.25 * now, 2.0 * s->capacity); /* headroom for the lights to come */
            resize_splats(s, want < (double)limit ? (unsigned)want : limit, before);
            const GLuint back[4] = {4, before, 0, 0};
            glNamedBufferSubData(s->cmd, 0, sizeof back, back);
            select_splats(c, s, t);
            now = selected_count(s);
        }
        before = now;
        s->last = t;
        s->lights_used++;
        sss_result res = gl_check(c->gl, "chen2012: irradiance buffer", err);
        if (res != SSS_OK) return res;
    }
    return SSS_OK;
}

static sss_result chen_render(const gl_tech_ctx *c, void *state, sss_error *err)
{
    const chen2012_params *p = c->params;
    chen_state *s = state;
    sss_result res = make_resources(c, s, err);
    if (res != SSS_OK) return res;
    gl_timer_begin(c->timer, "irradiance_buffers");
    res = irradiance_buffers(c, s, err);
    if (res != SSS_OK) return res;
    gl_timer_begin(c->timer, "receivers");
    shell_receivers(c, &s->shells);
    res = gl_check(c->gl, "chen2012: receivers", err);
    if (res != SSS_OK) return res;
    gl_timer_begin(c->timer, "splatting");
    shell_splat(c, &s->shells, s->splats, s->cmd, s->capacity, p->view_epsilon,
                (int)p->preintegrated);
    res = gl_check(c->gl, "chen2012: splatting", err);
    if (res != SSS_OK) return res;
    gl_timer_begin(c->timer, "resolve");
    shell_resolve(c, &s->shells);
    gl_timer_end(c->timer);
    return gl_check(c->gl, "chen2012: resolve", err);
}

static void chen_destroy(void *state)
{
    chen_state *s = state;
    free_tsm(&s->main);
    free_tsm(&s->env);
    shell_free(&s->shells);
    GLuint p[3] = {s->prog_tsm, s->prog_reduce, s->prog_select};
    gl_delete_programs(p, 3);
    if (s->splats) glDeleteBuffers(1, &s->splats);
    if (s->cmd) glDeleteBuffers(1, &s->cmd);
}

static const char *const targets[] = {"translucency", "light_irradiance", "light_positions", NULL};

static GLuint chen_target(void *state, const char *name)
{
    chen_state *s = state;
    const chen_tsm *t = s->last ? s->last : &s->main;
    if (strcmp(name, "translucency") == 0) return s->shells.accum[0];
    if (strcmp(name, "light_irradiance") == 0) return t->tex_irr; /* the last light's buffer, level 0 */
    if (strcmp(name, "light_positions") == 0) return t->tex_pos;
    return 0;
}

static void chen_stats(const gl_tech_ctx *c, void *state, sss_gl_stats *out)
{
    chen_state *s = state;
    out->texture_bytes += s->shells.bytes + s->main.bytes + s->env.bytes;
    out->buffer_bytes += (size_t)SHELL_SPLAT_BYTES * s->capacity + 16;
    out->per_pixel_bytes += s->shells.bytes / ((size_t)c->width * (size_t)c->height);
    out->per_splat_bytes = SHELL_SPLAT_BYTES;
    out->splat_drawn = c->frame_rendered ? shell_splat_count(s->cmd, s->capacity) : 0;
    out->splat_fragments = c->frame_rendered ? shell_splat_fragments(&s->shells) : -1;
}

/* preset=paper: Chen et al.'s splats carry the kernel's value at their centre. */
static const sss_gl_param_value paper[] = {{"preintegrated", 0}};

const gl_technique gl_technique_chen2012 = {
    .info = {"chen2012",
             "Chen et al. 2012 as Maisch & Ropinski 2020 compare it: splats from a 2048^2 light-view irradiance buffer "
             "(3 mip levels) per light, multiresolution additive splatting",
             params, (int)(sizeof params / sizeof params[0])},
    .reads = GL_READ_GBUFFER | GL_READ_ILLUMINATION | GL_READ_LIGHTS,
    .targets = targets,
    .state_size = sizeof(chen_state),
    .create = chen_create,
    .resize = chen_resize,
    .render = chen_render,
    .destroy = chen_destroy,
    .materials_changed = gl_materials_read_at_render,
    .target = chen_target,
    .stats = chen_stats,
    .paper = paper,
    .paper_count = (int)(sizeof paper / sizeof paper[0]),
    /* Its sources are the texels of one light-view irradiance buffer per light (Chen et al. 2012, the
     * translucent shadow map of Dachsbacher & Stamminger 2003), back sides included; the camera's
     * irradiance (frame.irr, a sum over the lights of the surfaces the camera sees) has no place in
     * that, so the renderer never reads it either, and a pass would ignore the caller's. */
    .not_a_pass = "it lights its sources itself, in one light-view irradiance buffer per light (Chen et al. "
                  "2012), and never reads the frame's irradiance (a sum over the lights, seen from the camera); "
                  "dss and maisch2020 splat with the frame's irradiance",
};
