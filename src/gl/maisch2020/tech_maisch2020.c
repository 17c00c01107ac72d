/* gl/tech_maisch2020.c — Maisch & Ropinski 2020: screen-space subsurface scattering with
 * the layered pattern (section 4) plus quarter-resolution splatting translucency (section 5), both
 * with the disc-integrated kernel R'_d(r, A) (section 3.2).
 *
 * The seven passes of section 3.3: (1) G-buffer, (2) shadow maps, (3) illumination + mip chains (the
 * renderer's shared passes), then here: (4) translucency = splat generation/culling (compute) +
 * receivers + additive splatting at 1/divisor resolution, (5) bicubic upsampling, (6) screen-space
 * pattern, (7) combination. */
#include <stdio.h>
#include <string.h>

#include "gl/gl_internal.h"

enum {
    P_N = 0,
    P_NL,
    P_LAYERS,
    P_BRIGHTENING,
    P_PREINTEGRATED,
    P_SCREEN,
    P_TRANSLUCENCY,
    P_DIVISOR,
    P_GRAZING,
    P_CULL_RULE,
    P_IRRADIANCE_CULL,
    P_DISC,
    P_BICUBIC,
    P_SHADOW_OFFSET,
    P_FILTERED,
    P_SPLAT_PREINTEGRATED,
    P_SCREEN_BOUND,
    P_OCCLUDED,
    P_SPLIT,
    P_GRAZING_SOURCES,
    P_SUPPORT_CUTOFF,
    P_OFFSCREEN,
    P_LAYERS_TO_REACH,
    P_LAYER_SPLIT,
    P_OUTER_DIVISOR,
    P_COUNT
};

static const sss_gl_param_info params[P_COUNT] = {
    [P_N] = {"n", SSS_GL_PARAM_INT, 2, 0, 32, "inner kernel of (2n+1)^2 full-resolution samples (Maisch & Ropinski 2020, 4.2)"},
    [P_NL] = {"n_l", SSS_GL_PARAM_INT, 5, 3, 33, "layer width in samples: 4(n_l - 1) samples per layer (Eq. 7)"},
    [P_LAYERS] = {"layers", SSS_GL_PARAM_INT, 10, 0, 64, "outer layers of the screen-space pattern (4.2: 10)"},
    [P_BRIGHTENING] = {"brightening", SSS_GL_PARAM_BOOL, 0, 0, 1, "multiply layer i by sqrt(i) (section 6.1; the paper: 1)"},
    [P_PREINTEGRATED] = {"preintegrated", SSS_GL_PARAM_BOOL, 1, 0, 1,
                         "1: disc-integrated kernel R'_d(r, A) (Eq. 5-6); 0: naive centre sample R_d(r) (Fig. 2)"},
    [P_SCREEN] = {"screen_space", SSS_GL_PARAM_BOOL, 1, 0, 1, "include the screen-space part (section 4)"},
    [P_TRANSLUCENCY] = {"translucency", SSS_GL_PARAM_BOOL, 1, 0, 1, "include the splatted translucency (section 5)"},
    [P_DIVISOR] = {"translucency_divisor", SSS_GL_PARAM_INT, 4, 1, 16,
                   "translucency at width/d x height/d (section 5: a quarter of the resolution)"},
    [P_GRAZING] = {"grazing_cutoff", SSS_GL_PARAM_FLOAT, 0.2, 0, 1,
                   "n.v below which pixels leave the screen-space sum and splats are kept (Eq. 8, 6.2)"},
    [P_CULL_RULE] = {"cull_rule", SSS_GL_PARAM_INT, 0, 0, 1,
                     "splats kept: 0 behind x_o AND n.v < cutoff (Eq. 2 and 8); 1: behind OR grazing"},
    [P_IRRADIANCE_CULL] = {"irradiance_cull", SSS_GL_PARAM_FLOAT, 0, 0, 1e30,
                           "splats whose largest F_t E channel is at most this are culled (section 5)"},
    [P_DISC] = {"disc_adjust", SSS_GL_PARAM_INT, 2, 0, 2,
                "splat distance: 1 from the disc-adjusted position x'_i (Eq. 9); 0 from the centre x_i; "
                "2 Eq. 9 + disc radius (the coplanar disc whose nearest point is x'_i)"},
    [P_BICUBIC] = {"bicubic", SSS_GL_PARAM_BOOL, 1, 0, 1,
                   "bicubic B-spline upsampling (Sigg & Hadwiger, 4 taps); 0: bilinear"},
    [P_SHADOW_OFFSET] = {"splat_shadow_offset", SSS_GL_PARAM_FLOAT, 0.5, 0, 10,
                         "splat irradiance looked up this many sqrt(area) above the splat (self-shadowing)"},
    [P_FILTERED] = {"filtered_layers", SSS_GL_PARAM_INT, 1, 0, 2,
                    "outer samples: 1 bilinear within their mip level; 2 the same, but texels whose mean positions "
                    "disagree (two surfaces) each at their own position; 0 texelFetch (blocky copies)"},
    [P_SPLAT_PREINTEGRATED] = {"splat_preintegrated", SSS_GL_PARAM_BOOL, 1, 0, 1,
                               "splats read R'_d(r', A) (1, Maisch & Ropinski 2020) or R_d(r') at the disc-adjusted distance"},
    [P_SCREEN_BOUND] = {"layer_distance_bound", SSS_GL_PARAM_BOOL, 1, 0, 1,
                        "outer samples at least d_(i-1)/2 pixels (at their depth) from x_o, where their cell lies"},
    [P_OCCLUDED] = {"occluded_margin", SSS_GL_PARAM_FLOAT, 3, 0, 100,
                    "also splat front-facing triangles more than this many sqrt(area) behind the visible surface "
                    "(hidden by another part or object); 0: off (the paper: back-facing only)"},
    [P_SPLIT] = {"footprint_split", SSS_GL_PARAM_INT, 8, 1, 64,
                 "samples seen obliquely (a pixel at n.v = c; a cell whose area is e x its face-on area) count as "
                 "round(min(1/c or e, this)) pieces along their foreshortened axis, the strip capped at this many "
                 "widths; 1: one disc per sample (the paper, Eq. 6)"},
    [P_GRAZING_SOURCES] = {"grazing_sources", SSS_GL_PARAM_FLOAT, 0.05, 0, 1,
                           "visible pixels with this <= |n.v| < grazing_cutoff stay in the screen-space sum (area "
                           "w^2/|n.v|, mips rebuilt) and splats need n.v below this instead; 0: off (the paper, Eq. 8)"},
    [P_SUPPORT_CUTOFF] = {"support_cutoff", SSS_GL_PARAM_BOOL, 1, 0, 1,
                          "skip outer layers wholly beyond the kernel's support r_max at the pixel's depth (exact: "
                          "their samples add 0; needs layer_distance_bound); 0: read every layer"},
    [P_OFFSCREEN] = {"offscreen_splats", SSS_GL_PARAM_BOOL, 1, 0, 1,
                     "also splat surface outside the view (front-facing parts off the image, which neither part "
                     "gathers otherwise: colour drifts under zoom); 0: off (the paper: the back side only)"},
    [P_LAYERS_TO_REACH] = {"layers_to_reach", SSS_GL_PARAM_BOOL, 1, 0, 1,
                           "continue the pattern past `layers` until it covers the image or (support_cutoff) the kernel's support, " \
                           "at most 64 layers: a close object's kernel reaches farther; 0: exactly `layers` (the paper)"},
    [P_LAYER_SPLIT] = {"layer_split", SSS_GL_PARAM_INT, 8, 1, 64,
     "most pieces per oblique outer-layer cell (e x its face-on area), at most footprint_split: the split loop "
     "runs to the largest count among neighbouring pixels; 1: one disc per cell (the outer layers' cost halves)"},
    [P_OUTER_DIVISOR] = {"outer_divisor", SSS_GL_PARAM_INT, 4, 1, 4,
     "outer layers evaluated once per d x d block of pixels and upsampled (object- and depth-aware; pixels no "
     "block matches evaluate them); the inner (2n+1)^2 block stays per pixel; 1: every pixel (the paper)"},
};

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
    {"layers_to_reach", 0},      /* 4.2: ten layers */
    {"outer_divisor", 1},        /* the whole pattern at every pixel */
};

#define SPLAT_BYTES 48 /* three vec4: centre + area, normal + object, F_t E + disc radius */

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
static int divisor(const sss_gl_renderer *r, const double *p) { return (int)p[P_DIVISOR] * gl_supersample(r); }

/* The outer layers' block side in render pixels (outer_divisor counts output pixels, as above); 0 at
 * outer_divisor 1, where every pixel evaluates them. */
static int outer_block(const sss_gl_renderer *r, const double *p)
{
    return (int)p[P_OUTER_DIVISOR] > 1 ? (int)p[P_OUTER_DIVISOR] * gl_supersample(r) : 0;
}

static int blocks(int size, int block) { return block ? (size + block - 1) / block : 0; }

static sss_result make_targets(sss_gl_renderer *r, maisch_state *s, const double *p, sss_error *err)
{
    free_targets(s);
    int d = divisor(r, p);
    s->low_w = (r->width + d - 1) / d;
    s->low_h = (r->height + d - 1) / d;
    s->tex_recv = gl_texture_2d(GL_RGBA32F, s->low_w, s->low_h, 1, &s->bytes);
    s->tex_accum = gl_texture_2d(GL_RGBA32F, s->low_w, s->low_h, 1, &s->bytes);
    glTextureParameteri(s->tex_accum, GL_TEXTURE_MIN_FILTER, GL_LINEAR); /* bilinear taps of the upsampler */
    glTextureParameteri(s->tex_accum, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    s->tex_trans = gl_texture_2d(GL_RGBA16F, r->width, r->height, 1, &s->bytes);
    s->tex_screen = gl_texture_2d(GL_RGBA32F, r->width, r->height, 1, &s->bytes);
    GLuint ra[2] = {s->tex_recv, s->tex_accum};
    s->fbo_recv = fbo_for(ra, 2);
    s->fbo_accum = fbo_for(&s->tex_accum, 1);
    s->fbo_trans = fbo_for(&s->tex_trans, 1);
    s->fbo_screen = fbo_for(&s->tex_screen, 1);
    int b = outer_block(r, p);
    s->outer_w = blocks(r->width, b);
    s->outer_h = blocks(r->height, b);
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
    return gl_check(r->ctx, "maisch2020: targets", err);
}

static sss_result maisch2020_create(sss_gl_renderer *r, void *state, const double *p, sss_error *err)
{
    maisch_state *s = state;
    sss_result res = gl_program_compute("maisch2020_splat_generate.comp.glsl", NULL, &s->prog_gen, err);
    if (res == SSS_OK) res = gl_program_vf("fullscreen.vert.glsl", "maisch2020_receivers.frag.glsl", NULL, &s->prog_recv, err);
    if (res == SSS_OK) res = gl_program_vf("maisch2020_splat.vert.glsl", "maisch2020_splat.frag.glsl", NULL, &s->prog_splat, err);
    if (res == SSS_OK) res = gl_program_vf("fullscreen.vert.glsl", "maisch2020_upsample.frag.glsl", NULL, &s->prog_up, err);
    if (res == SSS_OK) res = gl_program_vf("fullscreen.vert.glsl", "combine.frag.glsl", NULL, &s->prog_combine, err);
    if (res != SSS_OK) return res;
    s->capacity = r->gs.splat_total;
    glCreateBuffers(1, &s->splats);
    glNamedBufferStorage(s->splats, (GLsizeiptr)SPLAT_BYTES * (s->capacity ? s->capacity : 1), NULL, 0);
    glCreateBuffers(1, &s->cmd);
    glNamedBufferStorage(s->cmd, 4 * sizeof(GLuint), NULL, GL_DYNAMIC_STORAGE_BIT);
    return make_targets(r, s, p, err);
}

static sss_result maisch2020_resize(sss_gl_renderer *r, void *state, const double *p, sss_error *err)
{
    maisch_state *s = state;
    int d = divisor(r, p);
    int b = outer_block(r, p);
    if (s->tex_screen && s->low_w == (r->width + d - 1) / d && s->low_h == (r->height + d - 1) / d &&
        s->outer_w == blocks(r->width, b) && s->outer_h == blocks(r->height, b)) {
        GLint w = 0;
        glGetTextureLevelParameteriv(s->tex_screen, 0, GL_TEXTURE_WIDTH, &w);
        if (w == r->width) return SSS_OK;
    }
    return make_targets(r, s, p, err);
}

static void set_i(GLuint prog, const char *name, int v) { glUniform1i(glGetUniformLocation(prog, name), v); }
static void set_f(GLuint prog, const char *name, float v) { glUniform1f(glGetUniformLocation(prog, name), v); }

static sss_result pass_splats(sss_gl_renderer *r, maisch_state *s, const double *p, sss_error *err)
{
    const GLuint reset[4] = {4, 0, 0, 0}; /* triangle strip of 4 vertices per instance */
    glNamedBufferSubData(s->cmd, 0, sizeof reset, reset);
    gl_timer_begin(&r->timer, "splat_cull");
    glUseProgram(s->prog_gen);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GL_SSBO_SPLATS, s->splats);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GL_SSBO_SPLAT_COUNT, s->cmd);
    glBindTextureUnit(0, r->frame.pos);
    glBindTextureUnit(1, r->frame.nrm);
    set_i(s->prog_gen, "u_cull_rule", (int)p[P_CULL_RULE]);
    set_f(s->prog_gen, "u_irradiance_cull", (float)p[P_IRRADIANCE_CULL]);
    set_f(s->prog_gen, "u_shadow_offset", (float)p[P_SHADOW_OFFSET]);
    set_f(s->prog_gen, "u_occluded_margin", (float)p[P_OCCLUDED]);
    set_i(s->prog_gen, "u_offscreen", (int)p[P_OFFSCREEN]);
    set_f(s->prog_gen, "u_grazing_sources", (float)p[P_GRAZING_SOURCES]);
    glUniform1ui(glGetUniformLocation(s->prog_gen, "u_capacity"), s->capacity);
    gl_dispatch_splat_triangles(r, s->prog_gen);
    sss_result res = gl_check(r->ctx, "maisch2020: splat generation", err);
    if (res != SSS_OK) return res;

    gl_timer_begin(&r->timer, "translucency");
    glBindFramebuffer(GL_FRAMEBUFFER, s->fbo_recv);
    glViewport(0, 0, s->low_w, s->low_h);
    glDisable(GL_BLEND);
    glUseProgram(s->prog_recv);
    set_i(s->prog_recv, "u_divisor", divisor(r, p));
    gl_draw_fullscreen(r);
    /* additive splatting into the accumulation target (float blending, no clamping) */
    glBindFramebuffer(GL_FRAMEBUFFER, s->fbo_accum);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    glUseProgram(s->prog_splat);
    glBindTextureUnit(0, s->tex_recv);
    set_i(s->prog_splat, "u_preintegrated",
          (int)p[P_PREINTEGRATED] && (int)p[P_SPLAT_PREINTEGRATED]);
    set_i(s->prog_splat, "u_disc_adjust", (int)p[P_DISC]);
    glBindVertexArray(r->vao_empty);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, s->cmd);
    glDrawArraysIndirect(GL_TRIANGLE_STRIP, NULL);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    glBindVertexArray(0);
    glDisable(GL_BLEND);
    res = gl_check(r->ctx, "maisch2020: translucency splatting", err);
    if (res != SSS_OK) return res;

    gl_timer_begin(&r->timer, "upsample");
    glBindFramebuffer(GL_FRAMEBUFFER, s->fbo_trans);
    glViewport(0, 0, r->width, r->height);
    glUseProgram(s->prog_up);
    glBindTextureUnit(0, s->tex_accum);
    set_i(s->prog_up, "u_bicubic", (int)p[P_BICUBIC]);
    glUniform2f(glGetUniformLocation(s->prog_up, "u_full_size"), (float)r->width, (float)r->height);
    gl_draw_fullscreen(r);
    return gl_check(r->ctx, "maisch2020: upsampling", err);
}

/* grazing_sources: the visible pixels Eq. 8 took out of the screen-space sum get their projected area
 * back in level 0 of the position chain (maisch2020_grazing_area.comp.glsl) and the mip chain is rebuilt from it,
 * so inner samples and outer layers both see them; the splats' Eq. 8 cut-off drops to match. */
static sss_result pass_grazing(sss_gl_renderer *r, maisch_state *s, const double *p, sss_error *err)
{
    double gs = p[P_GRAZING_SOURCES];
    if (!(gs > 0.0) || !(gs < p[P_GRAZING])) return SSS_OK;
    if (!s->prog_grazing) {
        sss_result res = gl_program_compute("maisch2020_grazing_area.comp.glsl", NULL, &s->prog_grazing, err);
        if (res != SSS_OK) return res;
    }
    gl_timer_begin(&r->timer, "grazing_area");
    glUseProgram(s->prog_grazing);
    glBindImageTexture(0, r->frame.pos, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
    glBindTextureUnit(1, r->frame.nrm);
    set_f(s->prog_grazing, "u_grazing_sources", (float)gs);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    glDispatchCompute((GLuint)(r->frame.width + 7) / 8, (GLuint)(r->frame.height + 7) / 8, 1);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    sss_result res = gl_check(r->ctx, "maisch2020: grazing areas", err);
    if (res == SSS_OK) res = gl_pass_mipmaps(r, err);
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
static void use_screen_program(sss_gl_renderer *r, GLuint prog, const double *p, int layer_split)
{
    glUseProgram(prog);
    glBindTextureUnit(0, r->frame.pos);
    glBindTextureUnit(1, r->frame.irr);
    glBindTextureUnit(2, r->frame.nrm);
    set_i(prog, "u_split", (int)p[P_SPLIT]);
    set_i(prog, "u_layer_split", layer_split);
    set_i(prog, "u_n", (int)p[P_N]);
    set_i(prog, "u_nl", (int)p[P_NL]);
    set_i(prog, "u_layers", (int)p[P_LAYERS]);
    set_i(prog, "u_brightening", (int)p[P_BRIGHTENING]);
    set_i(prog, "u_preintegrated", (int)p[P_PREINTEGRATED]);
    set_i(prog, "u_screen_bound", (int)p[P_SCREEN_BOUND]);
    set_i(prog, "u_support_cutoff", (int)p[P_SUPPORT_CUTOFF]);
    set_i(prog, "u_layers_to_reach", (int)p[P_LAYERS_TO_REACH]);
    set_i(prog, "u_outer_divisor", outer_block(r, p));
    /* the pattern's sizes count output pixels (docs/supersampling.md) */
    set_i(prog, "u_supersample", gl_supersample(r));
}

/* Pass 6, the screen-space pattern; with outer_divisor > 1 first its outer layers once per block. */
static sss_result pass_screen(sss_gl_renderer *r, maisch_state *s, const double *p, sss_error *err)
{
    gl_timer_begin(&r->timer, "screen_space");
    glDisable(GL_BLEND);
    int filtered = (int)p[P_FILTERED];
    int layer_split = (int)(p[P_LAYER_SPLIT] < p[P_SPLIT] ? p[P_LAYER_SPLIT] : p[P_SPLIT]);
    int split = (int)p[P_SPLIT] > 1 ? 1 + (layer_split > 1) : 0;
    int outer = outer_block(r, p) ? 2 : 0;
    GLuint prog = 0;
    sss_result res = SSS_OK;
    if (outer) {
        res = screen_program(s, filtered, split, 1, &prog, err);
        if (res != SSS_OK) return res;
        glBindFramebuffer(GL_FRAMEBUFFER, s->fbo_outer);
        glViewport(0, 0, s->outer_w, s->outer_h);
        use_screen_program(r, prog, p, layer_split);
        gl_draw_fullscreen(r);
        res = gl_check(r->ctx, "maisch2020: screen-space outer layers", err);
        if (res != SSS_OK) return res;
    }
    res = screen_program(s, filtered, split, outer, &prog, err);
    if (res != SSS_OK) return res;
    glBindFramebuffer(GL_FRAMEBUFFER, s->fbo_screen);
    glViewport(0, 0, r->width, r->height);
    use_screen_program(r, prog, p, layer_split);
    glBindTextureUnit(3, s->tex_outer);
    glBindTextureUnit(4, s->tex_outer_pos);
    gl_draw_fullscreen(r);
    return gl_check(r->ctx, "maisch2020: screen-space pass", err);
}

static sss_result maisch2020_render(sss_gl_renderer *r, void *state, const double *p, sss_error *err)
{
    maisch_state *s = state;
    sss_result res = maisch2020_resize(r, s, p, err);
    if (res != SSS_OK) return res;
    if ((int)p[P_SCREEN]) {
        res = pass_grazing(r, s, p, err);
        if (res != SSS_OK) return res;
    }
    int use_trans = (int)p[P_TRANSLUCENCY] && s->capacity > 0;
    int use_screen = (int)p[P_SCREEN];
    if (use_trans) {
        res = pass_splats(r, s, p, err);
        if (res != SSS_OK) return res;
    }
    if (use_screen) {
        res = pass_screen(r, s, p, err);
        if (res != SSS_OK) return res;
    }
    gl_timer_begin(&r->timer, "combine");
    glBindFramebuffer(GL_FRAMEBUFFER, r->frame.fbo_final);
    glViewport(0, 0, r->width, r->height);
    glUseProgram(s->prog_combine);
    glBindTextureUnit(0, r->frame.pos);
    glBindTextureUnit(1, r->frame.nrm);
    glBindTextureUnit(2, r->frame.albedo);
    glBindTextureUnit(3, r->frame.refl);
    glBindTextureUnit(4, s->tex_screen);
    glBindTextureUnit(5, s->tex_trans);
    set_i(s->prog_combine, "u_use_screen", use_screen);
    set_i(s->prog_combine, "u_use_trans", use_trans);
    gl_draw_fullscreen(r);
    gl_timer_end(&r->timer);
    return gl_check(r->ctx, "maisch2020: combination", err);
}

static void maisch2020_destroy(sss_gl_renderer *r, void *state)
{
    (void)r;
    maisch_state *s = state;
    free_targets(s);
    GLuint p[6] = {s->prog_gen, s->prog_recv, s->prog_splat, s->prog_up, s->prog_combine, s->prog_grazing};
    for (int i = 0; i < 6; i++)
        if (p[i]) glDeleteProgram(p[i]);
    for (int f = 0; f < 3; f++)
        for (int k = 0; k < 3; k++)
            for (int o = 0; o < 3; o++)
                if (s->prog_ss[f][k][o]) glDeleteProgram(s->prog_ss[f][k][o]);
    if (s->splats) glDeleteBuffers(1, &s->splats);
    if (s->cmd) glDeleteBuffers(1, &s->cmd);
}

static GLuint maisch2020_buffer(sss_gl_renderer *r, void *state, const char *name)
{
    (void)r;
    maisch_state *s = state;
    if (strcmp(name, "translucency") == 0) return s->tex_accum;
    if (strcmp(name, "translucency_full") == 0) return s->tex_trans;
    if (strcmp(name, "screen") == 0) return s->tex_screen;
    return 0;
}

static void maisch2020_stats(sss_gl_renderer *r, void *state, const double *p, sss_gl_stats *out)
{
    maisch_state *s = state;
    out->texture_bytes += s->bytes;
    out->buffer_bytes += (size_t)SPLAT_BYTES * s->capacity + 16;
    out->per_pixel_bytes += s->bytes / ((size_t)r->width * (size_t)r->height);
    out->per_splat_bytes = SPLAT_BYTES;
    GLuint cmd[4] = {0, 0, 0, 0};
    if (s->cmd && r->frame_rendered && p[P_TRANSLUCENCY] != 0.0)
        glGetNamedBufferSubData(s->cmd, 0, sizeof cmd, cmd);
    out->splat_drawn = cmd[1];
}

static sss_result maisch_create(sss_gl_renderer *r, void *state, sss_error *err)
{
    return maisch2020_create(r, state, r->params, err);
}

static sss_result maisch_resize(sss_gl_renderer *r, void *state, sss_error *err)
{
    return maisch2020_resize(r, state, r->params, err);
}

static sss_result maisch_render(sss_gl_renderer *r, void *state, sss_error *err)
{
    return maisch2020_render(r, state, r->params, err);
}

static void maisch_stats(sss_gl_renderer *r, void *state, sss_gl_stats *out)
{
    maisch2020_stats(r, state, r->params, out);
}

const gl_technique gl_technique_maisch2020 = {
    .info = {"maisch2020",
             "Maisch & Ropinski 2020: layered screen-space pattern + quarter-resolution splat translucency, "
             "disc-integrated kernel",
             params, P_COUNT},
    .needs = GL_NEED_GBUFFER | GL_NEED_SHADOWS | GL_NEED_ILLUMINATION | GL_NEED_MIPS | GL_NEED_SPLAT_MESHES | GL_NEED_LIGHTS,
    .state_size = sizeof(maisch_state),
    .create = maisch_create,
    .resize = maisch_resize,
    .render = maisch_render,
    .destroy = maisch2020_destroy,
    .materials_changed = gl_materials_read_at_render,
    .buffer = maisch2020_buffer,
    .stats = maisch_stats,
    .paper = paper,
    .paper_count = (int)(sizeof paper / sizeof paper[0]),
};

const gl_inner_technique gl_inner_maisch2020 = {
    &gl_technique_maisch2020, maisch2020_create, maisch2020_resize, maisch2020_render, maisch2020_stats,
    maisch2020_destroy, maisch2020_buffer, NULL,
};
