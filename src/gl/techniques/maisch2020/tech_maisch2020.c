/* gl/tech_maisch2020.c — Maisch & Ropinski 2020: screen-space subsurface scattering with
 * the layered pattern (section 4) plus quarter-resolution splatting translucency (section 5), both
 * with the disc-integrated kernel R'_d(r, A) (section 3.2).
 *
 * The seven passes of section 3.3: (1) G-buffer, (2) shadow maps, (3) illumination + mip chains (the
 * renderer's shared passes), then here: (4) translucency = splat generation/culling (compute) +
 * receivers + additive splatting at 1/divisor resolution, (5) bicubic upsampling, (6) screen-space
 * pattern, (7) combination. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "gl/techniques/maisch2020/maisch2020_params.h"

static const sss_gl_param_info params[] = {MAISCH2020_PARAMS(GL_PARAM_INFO)};

/* preset=paper: Maisch & Ropinski 2020 as published (docs/maisch2020.md lists each departure). */
static const sss_gl_param_value paper[] = {
    {"brightening", 1},          /* section 6.1: layer i times sqrt(i) */
    {"layer_distance_bound", 0}, /* outer samples at their cell's mean position */
    {"disc_adjust", 1},          /* Eq. 9 as printed */
    {"occluded_margin", 0},      /* splats: back-facing or grazing only (Eq. 2 and 8) */
    {"footprint_split", 1},      /* one disc per sample (Eq. 6) */
    {"grazing_sources", 0},      /* pixels with n.v < 0.2 leave the screen-space sum (Eq. 8) */
    {"support_cutoff", 0},       /* every layer read at every pixel (exact either way) */
    {"lut_sqrt_axes", 0},        /* one linear table (section 7.1) */
    {"lut_levels", 1},
    {"lut_energy", 0},           /* r_max from Q(r_max) = 1e-7 alone (section 7.1) */
    {"splat_energy", 1},         /* splats reach r_max */
    {"offscreen_splats", 0},     /* splats: surface hidden on screen, not off it */
    {"offscreen_pieces", 0},     /* one splat per splat-mesh triangle */
    {"layers_to_reach", 0},      /* 4.2: ten layers */
    {"outer_divisor", 1},        /* the whole pattern at every pixel */
};

#define SPLAT_BYTES 48 /* three vec4: centre + area, normal + object, F_t E + disc radius */
#define SPLAT_LIMIT (1u << 21) /* most splats the buffer grows to (96 MB) */

typedef struct maisch_state {
    GLuint prog_gen, prog_recv, prog_splat, prog_up, prog_combine;
    /* the screen-space pass per filtered_layers and split (0: none; 1: footprint_split > 1, inner pixels;
     * 2: and layer_split > 1, outer cells), built when first used: the choices are compiled in because
     * llvmpipe runs every side of a branch on a uniform */
    GLuint prog_ss[3][3][3]; /* [filtered_layers][split][OUTER_PASS] */
    GLuint prog_grazing;  /* grazing_sources: areas of the grazing pixels (built when first used) */
    GLuint splats, cmd;
    unsigned capacity;
    int low_w, low_h;
    int outer_w, outer_h; /* outer_divisor > 1: the blocks' targets (0 x 0 without) */
    GLuint tex_recv, tex_accum, tex_trans, tex_screen, tex_outer, tex_outer_pos;
    GLuint fbo_recv, fbo_accum, fbo_trans, fbo_screen, fbo_outer;
    size_t bytes;
} maisch_state;

static void free_targets(maisch_state *s)
{
    GLuint f[5] = {s->fbo_recv, s->fbo_accum, s->fbo_trans, s->fbo_screen, s->fbo_outer};
    GLuint t[6] = {s->tex_recv, s->tex_accum, s->tex_trans, s->tex_screen, s->tex_outer, s->tex_outer_pos};
    for (int i = 0; i < 6; i++) {
        if (i < 5 && f[i]) glDeleteFramebuffers(1, &f[i]);
        if (t[i]) glDeleteTextures(1, &t[i]);
    }
    s->fbo_recv = s->fbo_accum = s->fbo_trans = s->fbo_screen = s->fbo_outer = 0;
    s->tex_recv = s->tex_accum = s->tex_trans = s->tex_screen = s->tex_outer = s->tex_outer_pos = 0;
    s->bytes = 0;
}

static GLuint fbo_for(const GLuint *tex, int count)
{
    GLuint fbo;
    glCreateFramebuffers(1, &fbo);
    GLenum bufs[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    for (int i = 0; i < count; i++) glNamedFramebufferTexture(fbo, bufs[i], tex[i], 0);
    glNamedFramebufferDrawBuffers(fbo, count, bufs);
    return fbo;
}

/* The translucency divisor in render pixels: translucency_divisor counts output pixels, so with
 * supersampling (k) the low-resolution buffer keeps its size, width/d x height/d of the output, and the
 * image and the splatting cost stay those of k = 1 (docs/supersampling.md). */
static int divisor(const gl_tech_ctx *c, const maisch2020_params *p) { return (int)p->translucency_divisor * c->supersample; }

/* The outer layers' block side in render pixels (outer_divisor counts output pixels, as above); 0 at
 * outer_divisor 1, where every pixel evaluates them. */
static int outer_block(const gl_tech_ctx *c, const maisch2020_params *p)
{
    return (int)p->outer_divisor > 1 ? (int)p->outer_divisor * c->supersample : 0;
}

static int blocks(int size, int block) { return block ? (size + block - 1) / block : 0; }

static sss_result make_targets(const gl_tech_ctx *c, maisch_state *s, const maisch2020_params *p, sss_error *err)
{
    free_targets(s);
    int d = divisor(c, p);
    s->low_w = (c->width + d - 1) / d;
    s->low_h = (c->height + d - 1) / d;
    s->tex_recv = gl_texture_2d(GL_RGBA32F, s->low_w, s->low_h, 1, &s->bytes);
    s->tex_accum = gl_texture_2d(GL_RGBA32F, s->low_w, s->low_h, 1, &s->bytes);
    glTextureParameteri(s->tex_accum, GL_TEXTURE_MIN_FILTER, GL_LINEAR); /* bilinear taps of the upsampler */
    glTextureParameteri(s->tex_accum, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    s->tex_trans = gl_texture_2d(GL_RGBA16F, c->width, c->height, 1, &s->bytes);
    s->tex_screen = gl_texture_2d(GL_RGBA32F, c->width, c->height, 1, &s->bytes);
    GLuint ra[2] = {s->tex_recv, s->tex_accum};
    s->fbo_recv = fbo_for(ra, 2);
    s->fbo_accum = fbo_for(&s->tex_accum, 1);
    s->fbo_trans = fbo_for(&s->tex_trans, 1);
    s->fbo_screen = fbo_for(&s->tex_screen, 1);
    int b = outer_block(c, p);
    s->outer_w = blocks(c->width, b);
    s->outer_h = blocks(c->height, b);
    if (b) {
        s->tex_outer = gl_texture_2d(GL_RGBA32F, s->outer_w, s->outer_h, 1, &s->bytes);
        s->tex_outer_pos = gl_texture_2d(GL_RGBA32F, s->outer_w, s->outer_h, 1, &s->bytes);
        GLuint o[2] = {s->tex_outer, s->tex_outer_pos};
        s->fbo_outer = fbo_for(o, 2);
    }
    GLuint f[5] = {s->fbo_recv, s->fbo_accum, s->fbo_trans, s->fbo_screen, s->fbo_outer};
    for (int i = 0; i < 5; i++)
        if (f[i] && glCheckNamedFramebufferStatus(f[i], GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            return sss_error_set(err, SSS_ERROR_UNSUPPORTED, "maisch2020: incomplete render target");
    return gl_check(c->gl, "maisch2020: targets", err);
}

/* A splat buffer of cap splats (its contents are made again each frame). */
static void resize_splats(maisch_state *s, unsigned cap)
{
    if (s->splats) glDeleteBuffers(1, &s->splats);
    glCreateBuffers(1, &s->splats);
    glNamedBufferStorage(s->splats, (GLsizeiptr)SPLAT_BYTES * (cap ? cap : 1), NULL, 0);
    s->capacity = cap;
}

static sss_result maisch2020_create(const gl_tech_ctx *c, void *state, sss_error *err)
{
    maisch_state *s = state;
    const maisch2020_params *p = c->params;
    sss_result res = gl_program_compute("maisch2020_splat_generate.comp.glsl", NULL, &s->prog_gen, err);
    if (res == SSS_OK) res = gl_program_vf("fullscreen.vert.glsl", "maisch2020_receivers.frag.glsl", NULL, &s->prog_recv, err);
    if (res == SSS_OK) res = gl_program_vf("maisch2020_splat.vert.glsl", "maisch2020_splat.frag.glsl", NULL, &s->prog_splat, err);
    if (res == SSS_OK) res = gl_program_vf("fullscreen.vert.glsl", "maisch2020_upsample.frag.glsl", NULL, &s->prog_up, err);
    if (res == SSS_OK) res = gl_program_vf("fullscreen.vert.glsl", "combine.frag.glsl", NULL, &s->prog_combine, err);
    if (res != SSS_OK) return res;
    resize_splats(s, c->gs->splat_total);
    glCreateBuffers(1, &s->cmd);
    glNamedBufferStorage(s->cmd, 4 * sizeof(GLuint), NULL, GL_DYNAMIC_STORAGE_BIT);
    return make_targets(c, s, p, err);
}

static sss_result maisch2020_resize(const gl_tech_ctx *c, void *state, sss_error *err)
{
    maisch_state *s = state;
    const maisch2020_params *p = c->params;
    int d = divisor(c, p);
    int b = outer_block(c, p);
    if (s->tex_screen && s->low_w == (c->width + d - 1) / d && s->low_h == (c->height + d - 1) / d &&
        s->outer_w == blocks(c->width, b) && s->outer_h == blocks(c->height, b)) {
        GLint w = 0;
        glGetTextureLevelParameteriv(s->tex_screen, 0, GL_TEXTURE_WIDTH, &w);
        if (w == c->width) return SSS_OK;
    }
    return make_targets(c, s, p, err);
}


/* Splat generation (maisch2020_splat_generate.comp.glsl) into the buffer; returns how many splats it made,
 * which may exceed the capacity (those beyond it were not stored). */
static unsigned generate_splats(const gl_tech_ctx *c, maisch_state *s, const maisch2020_params *p)
{
    const GLuint reset[4] = {4, 0, 0, 0}; /* triangle strip of 4 vertices per instance */
    glNamedBufferSubData(s->cmd, 0, sizeof reset, reset);
    glUseProgram(s->prog_gen);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GL_SSBO_SPLATS, s->splats);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GL_SSBO_SPLAT_COUNT, s->cmd);
    glBindTextureUnit(0, c->frame.pos);
    glBindTextureUnit(1, c->frame.nrm);
    gl_uniform_i(s->prog_gen, "u_cull_rule", (int)p->cull_rule);
    gl_uniform_f(s->prog_gen, "u_irradiance_cull", (float)p->irradiance_cull);
    gl_uniform_f(s->prog_gen, "u_shadow_offset", (float)p->splat_shadow_offset);
    gl_uniform_f(s->prog_gen, "u_occluded_margin", (float)p->occluded_margin);
    gl_uniform_i(s->prog_gen, "u_offscreen", (int)p->offscreen_splats);
    gl_uniform_f(s->prog_gen, "u_piece_ratio", (float)p->offscreen_pieces);
    gl_uniform_i(s->prog_gen, "u_divisor", divisor(c, p));
    gl_uniform_f(s->prog_gen, "u_grazing_sources", (float)p->grazing_sources);
    glUniform1ui(glGetUniformLocation(s->prog_gen, "u_capacity"), s->capacity);
    gl_dispatch_splat_triangles(c, s->prog_gen);
    GLuint cmd[4] = {0, 0, 0, 0};
    glGetNamedBufferSubData(s->cmd, 0, sizeof cmd, cmd);
    return cmd[1];
}

/* Pass 4's splats: one per splat-mesh triangle, or with offscreen_pieces several for a triangle not wholly
 * in the view, so the buffer grows (up to SPLAT_LIMIT) when a frame makes more than it holds, and that
 * frame's splats are made again; beyond the limit the last ones are dropped. */
static sss_result make_splats(const gl_tech_ctx *c, maisch_state *s, const maisch2020_params *p, sss_error *err)
{
    unsigned made = generate_splats(c, s, p);
    if (made > s->capacity && s->capacity < SPLAT_LIMIT) {
        double want = fmax(1.25 * made, 2.0 * s->capacity);
        resize_splats(s, want < (double)SPLAT_LIMIT ? (unsigned)want : SPLAT_LIMIT);
        made = generate_splats(c, s, p);
    }
    if (made > s->capacity) { /* draw the stored ones only */
        GLuint stored = s->capacity;
        glNamedBufferSubData(s->cmd, sizeof(GLuint), sizeof stored, &stored);
    }
    return gl_check(c->gl, "maisch2020: splat generation", err);
}

static sss_result pass_splats(const gl_tech_ctx *c, maisch_state *s, const maisch2020_params *p, sss_error *err)
{
    gl_timer_begin(c->timer, "splat_cull");
    sss_result res = make_splats(c, s, p, err);
    if (res != SSS_OK) return res;

    gl_timer_begin(c->timer, "translucency");
    glBindFramebuffer(GL_FRAMEBUFFER, s->fbo_recv);
    glViewport(0, 0, s->low_w, s->low_h);
    glDisable(GL_BLEND);
    glUseProgram(s->prog_recv);
    gl_uniform_i(s->prog_recv, "u_divisor", divisor(c, p));
    gl_draw_fullscreen(c);
    /* additive splatting into the accumulation target (float blending, no clamping) */
    glBindFramebuffer(GL_FRAMEBUFFER, s->fbo_accum);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    glUseProgram(s->prog_splat);
    glBindTextureUnit(0, s->tex_recv);
    gl_uniform_i(s->prog_splat, "u_preintegrated",
          (int)p->preintegrated && (int)p->splat_preintegrated);
    gl_uniform_i(s->prog_splat, "u_disc_adjust", (int)p->disc_adjust);
    glBindVertexArray(c->vao_empty);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, s->cmd);
    glDrawArraysIndirect(GL_TRIANGLE_STRIP, NULL);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    glBindVertexArray(0);
    glDisable(GL_BLEND);
    res = gl_check(c->gl, "maisch2020: translucency splatting", err);
    if (res != SSS_OK) return res;

    gl_timer_begin(c->timer, "upsample");
    glBindFramebuffer(GL_FRAMEBUFFER, s->fbo_trans);
    glViewport(0, 0, c->width, c->height);
    glUseProgram(s->prog_up);
    glBindTextureUnit(0, s->tex_accum);
    gl_uniform_i(s->prog_up, "u_bicubic", (int)p->bicubic);
    glUniform2f(glGetUniformLocation(s->prog_up, "u_full_size"), (float)c->width, (float)c->height);
    gl_draw_fullscreen(c);
    return gl_check(c->gl, "maisch2020: upsampling", err);
}

/* grazing_sources: the visible pixels Eq. 8 took out of the screen-space sum get their projected area
 * back in level 0 of the position chain (maisch2020_grazing_area.comp.glsl) and the mip chain is rebuilt from it,
 * so inner samples and outer layers both see them; the splats' Eq. 8 cut-off drops to match. */
static sss_result pass_grazing(const gl_tech_ctx *c, maisch_state *s, const maisch2020_params *p, sss_error *err)
{
    double gs = p->grazing_sources;
    if (!(gs > 0.0) || !(gs < p->grazing_cutoff)) return SSS_OK;
    if (!s->prog_grazing) {
        sss_result res = gl_program_compute("maisch2020_grazing_area.comp.glsl", NULL, &s->prog_grazing, err);
        if (res != SSS_OK) return res;
    }
    gl_timer_begin(c->timer, "grazing_area");
    glUseProgram(s->prog_grazing);
    glBindImageTexture(0, c->frame.pos, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
    glBindTextureUnit(1, c->frame.nrm);
    gl_uniform_f(s->prog_grazing, "u_grazing_sources", (float)gs);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    glDispatchCompute((GLuint)(c->frame.width + 7) / 8, (GLuint)(c->frame.height + 7) / 8, 1);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    sss_result res = gl_check(c->gl, "maisch2020: grazing areas", err);
    if (res == SSS_OK) res = gl_frame_mipmaps(c->gl, &c->frame, c->prog_mips, err);
    return res;
}

/* The screen-space program for filtered_layers (0-2), split (0-2, FOOTPRINT_SPLIT) and OUTER_PASS (0: the
 * whole pattern; 1: the outer layers per block; 2: the inner block + the blocks upsampled). */
static sss_result screen_program(maisch_state *s, int filtered, int split, int outer, GLuint *out, sss_error *err)
{
    GLuint *prog = &s->prog_ss[filtered][split][outer];
    if (!*prog) {
        char defines[128];
        snprintf(defines, sizeof defines, "#define FILTERED_LAYERS %d\n#define FOOTPRINT_SPLIT %d\n#define OUTER_PASS %d\n",
                 filtered, split, outer);
        sss_result res = gl_program_vf("fullscreen.vert.glsl", "maisch2020_screen.frag.glsl", defines, prog, err);
        if (res != SSS_OK) return res;
    }
    *out = *prog;
    return SSS_OK;
}

/* Binds the G-buffer chains and sets the pattern's uniforms of a screen-space program. */
static void use_screen_program(const gl_tech_ctx *c, GLuint prog, const maisch2020_params *p, int layer_split)
{
    glUseProgram(prog);
    glBindTextureUnit(0, c->frame.pos);
    glBindTextureUnit(1, c->frame.irr);
    glBindTextureUnit(2, c->frame.nrm);
    gl_uniform_i(prog, "u_split", (int)p->footprint_split);
    gl_uniform_i(prog, "u_layer_split", layer_split);
    gl_uniform_i(prog, "u_n", (int)p->n);
    gl_uniform_i(prog, "u_nl", (int)p->n_l);
    gl_uniform_i(prog, "u_layers", (int)p->layers);
    gl_uniform_i(prog, "u_brightening", (int)p->brightening);
    gl_uniform_i(prog, "u_preintegrated", (int)p->preintegrated);
    gl_uniform_i(prog, "u_screen_bound", (int)p->layer_distance_bound);
    gl_uniform_i(prog, "u_support_cutoff", (int)p->support_cutoff);
    gl_uniform_i(prog, "u_layers_to_reach", (int)p->layers_to_reach);
    gl_uniform_i(prog, "u_outer_divisor", outer_block(c, p));
    /* the pattern's sizes count output pixels (docs/supersampling.md) */
    gl_uniform_i(prog, "u_supersample", c->supersample);
}

/* Pass 6, the screen-space pattern; with outer_divisor > 1 first its outer layers once per block. */
static sss_result pass_screen(const gl_tech_ctx *c, maisch_state *s, const maisch2020_params *p, sss_error *err)
{
    gl_timer_begin(c->timer, "screen_space");
    glDisable(GL_BLEND);
    int filtered = (int)p->filtered_layers;
    int layer_split = (int)(p->layer_split < p->footprint_split ? p->layer_split : p->footprint_split);
    int split = (int)p->footprint_split > 1 ? 1 + (layer_split > 1) : 0;
    int outer = outer_block(c, p) ? 2 : 0;
    GLuint prog = 0;
    sss_result res = SSS_OK;
    if (outer) {
        res = screen_program(s, filtered, split, 1, &prog, err);
        if (res != SSS_OK) return res;
        glBindFramebuffer(GL_FRAMEBUFFER, s->fbo_outer);
        glViewport(0, 0, s->outer_w, s->outer_h);
        use_screen_program(c, prog, p, layer_split);
        gl_draw_fullscreen(c);
        res = gl_check(c->gl, "maisch2020: screen-space outer layers", err);
        if (res != SSS_OK) return res;
    }
    res = screen_program(s, filtered, split, outer, &prog, err);
    if (res != SSS_OK) return res;
    glBindFramebuffer(GL_FRAMEBUFFER, s->fbo_screen);
    glViewport(0, 0, c->width, c->height);
    use_screen_program(c, prog, p, layer_split);
    glBindTextureUnit(3, s->tex_outer);
    glBindTextureUnit(4, s->tex_outer_pos);
    gl_draw_fullscreen(c);
    return gl_check(c->gl, "maisch2020: screen-space pass", err);
}

static sss_result maisch2020_render(const gl_tech_ctx *c, void *state, sss_error *err)
{
    maisch_state *s = state;
    const maisch2020_params *p = c->params;
    sss_result res = maisch2020_resize(c, s, err);
    if (res != SSS_OK) return res;
    if ((int)p->screen_space) {
        res = pass_grazing(c, s, p, err);
        if (res != SSS_OK) return res;
    }
    int use_trans = (int)p->translucency && s->capacity > 0;
    int use_screen = (int)p->screen_space;
    if (use_trans) {
        res = pass_splats(c, s, p, err);
        if (res != SSS_OK) return res;
    }
    if (use_screen) {
        res = pass_screen(c, s, p, err);
        if (res != SSS_OK) return res;
    }
    gl_timer_begin(c->timer, "combine");
    gl_resolve_begin(c, s->prog_combine);
    glBindTextureUnit(4, s->tex_screen);
    glBindTextureUnit(5, s->tex_trans);
    gl_uniform_i(s->prog_combine, "u_use_screen", use_screen);
    gl_uniform_i(s->prog_combine, "u_use_trans", use_trans);
    gl_draw_fullscreen(c);
    gl_timer_end(c->timer);
    return gl_check(c->gl, "maisch2020: combination", err);
}

static void maisch2020_destroy(void *state)
{
    maisch_state *s = state;
    free_targets(s);
    GLuint p[6] = {s->prog_gen, s->prog_recv, s->prog_splat, s->prog_up, s->prog_combine, s->prog_grazing};
    gl_delete_programs(p, 6);
    for (int f = 0; f < 3; f++)
        for (int k = 0; k < 3; k++)
            for (int o = 0; o < 3; o++)
                if (s->prog_ss[f][k][o]) glDeleteProgram(s->prog_ss[f][k][o]);
    if (s->splats) glDeleteBuffers(1, &s->splats);
    if (s->cmd) glDeleteBuffers(1, &s->cmd);
}

static const char *const targets[] = {"translucency", "translucency_full", "screen", NULL};

static GLuint maisch2020_target(void *state, const char *name)
{
    maisch_state *s = state;
    if (strcmp(name, "translucency") == 0) return s->tex_accum;
    if (strcmp(name, "translucency_full") == 0) return s->tex_trans;
    if (strcmp(name, "screen") == 0) return s->tex_screen;
    return 0;
}

static void maisch2020_stats(const gl_tech_ctx *c, void *state, sss_gl_stats *out)
{
    maisch_state *s = state;
    const maisch2020_params *p = c->params;
    out->texture_bytes += s->bytes;
    out->buffer_bytes += (size_t)SPLAT_BYTES * s->capacity + 16;
    out->per_pixel_bytes += s->bytes / ((size_t)c->width * (size_t)c->height);
    out->per_splat_bytes = SPLAT_BYTES;
    GLuint cmd[4] = {0, 0, 0, 0};
    if (s->cmd && c->frame_rendered && p->translucency != 0.0) glGetNamedBufferSubData(s->cmd, 0, sizeof cmd, cmd);
    out->splat_drawn = cmd[1];
}

static double maisch2020_grazing_cutoff(const void *values)
{
    return ((const maisch2020_params *)values)->grazing_cutoff;
}

const gl_technique gl_technique_maisch2020 = {
    .info = {"maisch2020",
             "Maisch & Ropinski 2020: layered screen-space pattern + quarter-resolution splat translucency, "
             "disc-integrated kernel",
             params, (int)(sizeof params / sizeof params[0])},
    .reads = GL_READ_GBUFFER | GL_READ_ILLUMINATION | GL_READ_MIPS | GL_READ_SPLAT_MESHES | GL_READ_LIGHTS,
    .targets = targets,
    .state_size = sizeof(maisch_state),
    .create = maisch2020_create,
    .resize = maisch2020_resize,
    .render = maisch2020_render,
    .destroy = maisch2020_destroy,
    .materials_changed = gl_materials_read_at_render,
    .target = maisch2020_target,
    .stats = maisch2020_stats,
    .grazing_cutoff = maisch2020_grazing_cutoff,
    .paper = paper,
    .paper_count = (int)(sizeof paper / sizeof paper[0]),
};
