/* gl/screen/tech_screen.c — technique "screen": the screen-space part of Maisch & Ropinski 2020 alone
 * (section 4; the 'Screen' competitor of its section 8), i.e. maisch2020 without the translucency
 * pass. It runs maisch2020's own passes (gl_inner_maisch2020) so both stay the same algorithm, with
 * maisch2020's parameters laid out from ours (by name: this technique's values where it has the
 * parameter, maisch's defaults elsewhere, translucency = 0, screen_space = 1). Without
 * GL_NEED_SPLAT_MESHES the scene has no splat meshes, so maisch2020 allocates no splat storage. */
#include <stdlib.h>
#include <string.h>

#include "gl/gl_internal.h"

extern const gl_technique gl_technique_screen;

/* The screen-space parameters of maisch2020 (same names, defaults, ranges; test_screen checks it). */
static const sss_gl_param_info params[] = {
    {"n", SSS_GL_PARAM_INT, 2, 0, 32, "inner kernel of (2n+1)^2 full-resolution samples (Maisch & Ropinski 2020, 4.2)"},
    {"n_l", SSS_GL_PARAM_INT, 5, 3, 33, "layer width in samples: 4(n_l - 1) samples per layer (Eq. 7)"},
    {"layers", SSS_GL_PARAM_INT, 10, 0, 64, "outer layers of the screen-space pattern (4.2: 10)"},
    {"brightening", SSS_GL_PARAM_BOOL, 0, 0, 1, "multiply layer i by sqrt(i) (section 6.1; the paper: 1)"},
    {"preintegrated", SSS_GL_PARAM_BOOL, 1, 0, 1,
     "1: disc-integrated kernel R'_d(r, A) (Eq. 5-6); 0: naive centre sample R_d(r) (Fig. 2)"},
    {"grazing_cutoff", SSS_GL_PARAM_FLOAT, 0.2, 0, 1,
     "n.v below which pixels leave the screen-space sum (Eq. 8, 6.2)"},
    {"filtered_layers", SSS_GL_PARAM_INT, 1, 0, 2,
     "outer samples: 1 bilinear within their mip level; 2 the same, but texels whose mean positions "
     "disagree (two surfaces) each at their own position; 0 texelFetch (blocky copies)"},
    {"layer_distance_bound", SSS_GL_PARAM_BOOL, 1, 0, 1,
     "outer samples at least d_(i-1)/2 pixels (at their depth) from x_o, where their cell lies"},
    {"footprint_split", SSS_GL_PARAM_INT, 8, 1, 64,
     "samples seen obliquely (a pixel at n.v = c; a cell whose area is e x its face-on area) count as "
     "round(min(1/c or e, this)) pieces along their foreshortened axis, the strip capped at this many widths; "
     "1: one disc per sample (the paper, Eq. 6)"},
    {"grazing_sources", SSS_GL_PARAM_FLOAT, 0.05, 0, 1,
     "visible pixels with this <= |n.v| < grazing_cutoff stay in the screen-space sum (area w^2/|n.v|, mips "
     "rebuilt); 0: off (the paper, Eq. 8)"},
    {"support_cutoff", SSS_GL_PARAM_BOOL, 1, 0, 1,
     "skip outer layers wholly beyond the kernel's support r_max at the pixel's depth (exact: "
     "their samples add 0; needs layer_distance_bound); 0: read every layer"},
    {"layers_to_reach", SSS_GL_PARAM_BOOL, 1, 0, 1,
     "continue the pattern past `layers` until it covers the image or (support_cutoff) the kernel's support, " \
     "at most 64 layers: a close object's kernel reaches farther; 0: exactly `layers` (the paper)"},
    {"layer_split", SSS_GL_PARAM_INT, 8, 1, 64,
     "most pieces per oblique outer-layer cell (e x its face-on area), at most footprint_split: the split loop "
     "runs to the largest count among neighbouring pixels; 1: one disc per cell (the outer layers' cost halves)"},
    {"outer_divisor", SSS_GL_PARAM_INT, 4, 1, 4,
     "outer layers evaluated once per d x d block of pixels and upsampled (object- and depth-aware; pixels no "
     "block matches evaluate them); the inner (2n+1)^2 block stays per pixel; 1: every pixel (the paper)"},
};
#define PARAM_COUNT ((int)(sizeof params / sizeof params[0]))

/* preset=paper: maisch2020's published screen-space part (the same departures as tech_maisch2020.c). */
static const sss_gl_param_value paper[] = {
    {"brightening", 1},  {"layer_distance_bound", 0}, {"footprint_split", 1}, {"grazing_sources", 0},
    {"support_cutoff", 0}, {"lut_sqrt_axes", 0},      {"lut_levels", 1},      {"lut_energy", 0},
    {"layers_to_reach", 0}, {"outer_divisor", 1},
};

typedef struct screen_state {
    void *inner;                        /* maisch2020's state */
    double inner_params[GL_MAX_PARAMS]; /* in maisch2020's table order */
} screen_state;

/* maisch2020's parameter values for ours: same-named ones carried over, its defaults elsewhere, the
 * screen-space part on and the translucency off. */
static const double *inner_params(screen_state *s, const double *values)
{
    const sss_gl_technique_info *mi = &gl_inner_maisch2020.tech->info;
    gl_params_by_name(mi, s->inner_params, &gl_technique_screen.info, values);
    gl_params_set(mi, s->inner_params, "translucency", 0.0);
    gl_params_set(mi, s->inner_params, "screen_space", 1.0);
    return s->inner_params;
}

static sss_result screen_create_with(sss_gl_renderer *r, void *state, const double *values, sss_error *err)
{
    screen_state *s = state;
    s->inner = calloc(1, gl_inner_maisch2020.tech->state_size);
    if (!s->inner) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (technique state)");
    return gl_inner_maisch2020.create(r, s->inner, inner_params(s, values), err);
}

static sss_result screen_resize_with(sss_gl_renderer *r, void *state, const double *values, sss_error *err)
{
    screen_state *s = state;
    return s->inner ? gl_inner_maisch2020.resize(r, s->inner, inner_params(s, values), err) : SSS_OK;
}

static sss_result screen_render_with(sss_gl_renderer *r, void *state, const double *values, sss_error *err)
{
    screen_state *s = state;
    return gl_inner_maisch2020.render(r, s->inner, inner_params(s, values), err);
}

static void screen_stats_with(sss_gl_renderer *r, void *state, const double *values, sss_gl_stats *out)
{
    screen_state *s = state;
    if (!s->inner) return;
    gl_inner_maisch2020.stats(r, s->inner, inner_params(s, values), out);
    out->per_splat_bytes = 0;
}

static void screen_destroy(sss_gl_renderer *r, void *state)
{
    screen_state *s = state;
    if (s->inner) gl_inner_maisch2020.destroy(r, s->inner);
    free(s->inner);
    s->inner = NULL;
}

static GLuint screen_buffer(sss_gl_renderer *r, void *state, const char *name)
{
    screen_state *s = state;
    if (strcmp(name, "screen") != 0 || !s->inner) return 0; /* no translucency buffers here */
    return gl_inner_maisch2020.buffer(r, s->inner, name);
}

static sss_result screen_create(sss_gl_renderer *r, void *state, sss_error *err)
{
    return screen_create_with(r, state, r->params, err);
}

static sss_result screen_resize(sss_gl_renderer *r, void *state, sss_error *err)
{
    return screen_resize_with(r, state, r->params, err);
}

static sss_result screen_render(sss_gl_renderer *r, void *state, sss_error *err)
{
    return screen_render_with(r, state, r->params, err);
}

static void screen_stats(sss_gl_renderer *r, void *state, sss_gl_stats *out)
{
    screen_stats_with(r, state, r->params, out);
}

const gl_technique gl_technique_screen = {
    .info = {"screen",
             "Maisch & Ropinski 2020's screen-space part alone (maisch2020 without translucency): layered pattern, "
             "disc-integrated kernel",
             params, PARAM_COUNT},
    .needs = GL_NEED_GBUFFER | GL_NEED_SHADOWS | GL_NEED_ILLUMINATION | GL_NEED_MIPS,
    .state_size = sizeof(screen_state),
    .create = screen_create,
    .resize = screen_resize,
    .render = screen_render,
    .destroy = screen_destroy,
    .materials_changed = gl_materials_read_at_render,
    .buffer = screen_buffer,
    .stats = screen_stats,
    .paper = paper,
    .paper_count = (int)(sizeof paper / sizeof paper[0]),
};

const gl_inner_technique gl_inner_screen = {
    &gl_technique_screen, screen_create_with, screen_resize_with, screen_render_with, screen_stats_with,
    screen_destroy, screen_buffer, NULL,
};
