/* gl/techniques/screen/tech_screen.c — technique "screen": the screen-space part of Maisch & Ropinski 2020
 * alone (section 4; the 'Screen' competitor of its section 8), i.e. maisch2020 without the translucency
 * pass. Its parameters are maisch2020's screen-space rows (maisch2020_params.h), and it runs maisch2020
 * itself through the technique interface (gl_sub_technique), so both stay the same algorithm: its
 * values where it has the parameter, maisch2020's defaults elsewhere, translucency = 0, screen_space = 1.
 * It reads no splat meshes, so the scene has none and maisch2020 allocates no splat storage. */
#include "gl/techniques/maisch2020/maisch2020_params.h"

#define SCREEN_PARAMS MAISCH2020_SCREEN_PARAMS
GL_PARAM_STRUCT(screen_params, SCREEN_PARAMS);

static const sss_gl_param_info params[] = {SCREEN_PARAMS(GL_PARAM_INFO)};

/* preset=paper: maisch2020's published screen-space part (the same departures as tech_maisch2020.c). */
static const sss_gl_param_value paper[] = {
    {"brightening", 1},  {"layer_distance_bound", 0}, {"footprint_split", 1}, {"grazing_sources", 0},
    {"support_cutoff", 0}, {"lut_sqrt_axes", 0},      {"lut_levels", 1},      {"lut_energy", 0},
    {"layers_to_reach", 0}, {"outer_divisor", 1},
};

typedef struct screen_state {
    gl_sub_technique maisch; /* maisch2020, with the parameters below */
} screen_state;

/* maisch2020's parameters for ours: ours where maisch2020 has them (all of them), its defaults
 * elsewhere, the screen-space part on and the translucency off. */
static void inner_params(screen_state *s, const screen_params *p)
{
    maisch2020_params *m = (maisch2020_params *)s->maisch.params;
    gl_params_defaults(&gl_technique_maisch2020.info, s->maisch.params);
#define COPY(name, type, def, lo, hi, doc) m->name = p->name;
    SCREEN_PARAMS(COPY)
#undef COPY
    m->translucency = 0.0;
    m->screen_space = 1.0;
}

static sss_result screen_create(const gl_tech_ctx *c, void *state, sss_error *err)
{
    screen_state *s = state;
    gl_sub_init(&s->maisch, &gl_technique_maisch2020);
    inner_params(s, c->params);
    return gl_sub_create(&s->maisch, c, err);
}

static sss_result screen_resize(const gl_tech_ctx *c, void *state, sss_error *err)
{
    screen_state *s = state;
    inner_params(s, c->params);
    return gl_sub_resize(&s->maisch, c, err);
}

static sss_result screen_render(const gl_tech_ctx *c, void *state, sss_error *err)
{
    screen_state *s = state;
    inner_params(s, c->params);
    return gl_sub_render(&s->maisch, c, err);
}

static void screen_stats(const gl_tech_ctx *c, void *state, sss_gl_stats *out)
{
    screen_state *s = state;
    inner_params(s, c->params);
    gl_sub_stats(&s->maisch, c, out);
    out->per_splat_bytes = 0;
}

static void screen_destroy(void *state)
{
    screen_state *s = state;
    gl_sub_destroy(&s->maisch);
}

static const char *const targets[] = {"screen", NULL}; /* no translucency here */

static GLuint screen_target(void *state, const char *name)
{
    screen_state *s = state;
    return gl_sub_target(&s->maisch, name);
}

static double screen_grazing_cutoff(const void *values) { return ((const screen_params *)values)->grazing_cutoff; }

const gl_technique gl_technique_screen = {
    .info = {"screen",
             "Maisch & Ropinski 2020's screen-space part alone (maisch2020 without translucency): layered pattern, "
             "disc-integrated kernel",
             params, (int)(sizeof params / sizeof params[0])},
    .reads = GL_READ_GBUFFER | GL_READ_ILLUMINATION | GL_READ_MIPS,
    .targets = targets,
    .state_size = sizeof(screen_state),
    .create = screen_create,
    .resize = screen_resize,
    .render = screen_render,
    .destroy = screen_destroy,
    .materials_changed = gl_materials_read_at_render,
    .target = screen_target,
    .stats = screen_stats,
    .grazing_cutoff = screen_grazing_cutoff,
    .paper = paper,
    .paper_count = (int)(sizeof paper / sizeof paper[0]),
};
