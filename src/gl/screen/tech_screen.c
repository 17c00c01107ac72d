/* gl/tech_screen.c — technique "screen": the screen-space part of Maisch & Ropinski 2020 alone
 * (section 4; the 'Screen' competitor of its section 8), i.e. maisch2020 without the translucency
 * pass. It runs maisch2020's own code (tech_maisch2020.c, through gl_technique_maisch2020's callbacks)
 * so both stay the same algorithm: around each call the renderer's parameter array is laid out as
 * maisch2020's table expects it (by name: this technique's values where it has the parameter, maisch's
 * defaults elsewhere, translucency = 0, screen_space = 1) and restored afterwards. Without
 * GL_NEED_SPLAT_MESHES the scene has no splat meshes, so maisch2020 allocates no splat storage. */
#include <stdlib.h>
#include <string.h>

#include "gl/gl_internal.h"

extern const gl_technique gl_technique_maisch2020;

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
};
#define PARAM_COUNT ((int)(sizeof params / sizeof params[0]))

/* preset=paper: maisch2020's published screen-space part (the same departures as tech_maisch2020.c). */
static const sss_gl_param_value paper[] = {
    {"brightening", 1},  {"layer_distance_bound", 0}, {"footprint_split", 1}, {"grazing_sources", 0},
    {"support_cutoff", 0}, {"lut_sqrt_axes", 0},      {"lut_levels", 1},      {"lut_energy", 0},
    {"layers_to_reach", 0},
};

typedef struct screen_state {
    void *inner; /* maisch2020's state */
    double saved[GL_MAX_PARAMS];
} screen_state;

/* Lays r->params out as maisch2020's table (saving ours). */
static void enter(sss_gl_renderer *r, screen_state *s)
{
    memcpy(s->saved, r->params, sizeof s->saved);
    const sss_gl_technique_info *mi = &gl_technique_maisch2020.info;
    for (int i = 0; i < mi->param_count && i < GL_MAX_PARAMS; i++) {
        const char *name = mi->params[i].name;
        double v = mi->params[i].default_value;
        for (int j = 0; j < PARAM_COUNT; j++)
            if (strcmp(params[j].name, name) == 0) v = s->saved[j];
        if (strcmp(name, "translucency") == 0) v = 0.0;
        if (strcmp(name, "screen_space") == 0) v = 1.0;
        r->params[i] = v;
    }
}

static void leave(sss_gl_renderer *r, screen_state *s) { memcpy(r->params, s->saved, sizeof s->saved); }

static sss_result screen_create(sss_gl_renderer *r, void *state, sss_error *err)
{
    screen_state *s = state;
    s->inner = calloc(1, gl_technique_maisch2020.state_size);
    if (!s->inner) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (technique state)");
    enter(r, s);
    sss_result res = gl_technique_maisch2020.create(r, s->inner, err);
    leave(r, s);
    return res;
}

static sss_result screen_resize(sss_gl_renderer *r, void *state, sss_error *err)
{
    screen_state *s = state;
    if (!s->inner) return SSS_OK;
    enter(r, s);
    sss_result res = gl_technique_maisch2020.resize(r, s->inner, err);
    leave(r, s);
    return res;
}

static sss_result screen_render(sss_gl_renderer *r, void *state, sss_error *err)
{
    screen_state *s = state;
    enter(r, s);
    sss_result res = gl_technique_maisch2020.render(r, s->inner, err);
    leave(r, s);
    return res;
}

static void screen_destroy(sss_gl_renderer *r, void *state)
{
    screen_state *s = state;
    if (s->inner) {
        enter(r, s);
        gl_technique_maisch2020.destroy(r, s->inner);
        leave(r, s);
    }
    free(s->inner);
    s->inner = NULL;
}

static GLuint screen_buffer(sss_gl_renderer *r, void *state, const char *name)
{
    screen_state *s = state;
    if (strcmp(name, "screen") != 0 || !s->inner) return 0; /* no translucency buffers here */
    return gl_technique_maisch2020.buffer(r, s->inner, name);
}

static void screen_stats(sss_gl_renderer *r, void *state, sss_gl_stats *out)
{
    screen_state *s = state;
    if (!s->inner) return;
    enter(r, s);
    gl_technique_maisch2020.stats(r, s->inner, out);
    leave(r, s);
    out->per_splat_bytes = 0;
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
    .buffer = screen_buffer,
    .stats = screen_stats,
    .paper = paper,
    .paper_count = (int)(sizeof paper / sizeof paper[0]),
};
