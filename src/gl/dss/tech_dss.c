/* gl/tech_dss.c — Deep Screen Space subsurface scattering (Nalbach, Ritschel & Seidel 2014) as Maisch & Ropinski 2020
 * configures it for its comparisons (sections 5 and 8): splats from every triangle of the
 * low-resolution splat mesh, tessellated by camera distance and area (a compute pass subdivides large
 * triangles into sub-surfels instead of the hardware tessellator), splatted additively into a
 * multi-resolution G-buffer with l_max = 3 levels and epsilon = 0.1 (tech_dss_shells.h), no view-based
 * culling, only irradiance culling. Surfels the camera sees are moved from the splat mesh's chords onto
 * the rendered surface (surface_snap, dss_generate.comp.glsl): DSS tessellates the rendered geometry,
 * and the chords of a coarse splat mesh lie farther from it than short kernels reach. A surfel's kernel
 * is R_d averaged over a tapered footprint sized by the surfel lattice's spacing (footprint,
 * dss_splat.frag.glsl), not over a disc of its own area, which printed the lattice (docs/dss.md).
 *
 * Passes after the shared G-buffer / shadows / illumination: "surfels" (generation + irradiance),
 * "receivers" (the pyramid), "splatting" (all levels), "resolve" (upsampling, sum, exit factor). */
#include <string.h>

#include "gl/dss/tech_dss_shells.h"

enum { P_LEVELS = 0, P_EPSILON, P_SURFEL_PIXELS, P_MAX_TESS, P_PREINTEGRATED, P_IRRADIANCE_CULL, P_SHADOW_OFFSET,
       P_SNAP, P_MAX_SURFELS, P_FINE, P_FOOTPRINT, P_COUNT };

static const sss_gl_param_info params[P_COUNT] = {
    [P_LEVELS] = {"levels", SSS_GL_PARAM_INT, 3, 1, SHELL_MAX_LEVELS,
                  "levels of the multi-resolution G-buffer, l_max (Maisch & Ropinski 2020, section 8: 3)"},
    [P_EPSILON] = {"epsilon", SSS_GL_PARAM_FLOAT, 0.1, 1e-3, 1,
                   "level l (2^l output pixels) serves receivers at least 2^l pixels / epsilon away (Maisch & Ropinski 2020, "
                   "section 8: 0.1)"},
    [P_SURFEL_PIXELS] = {"surfel_pixels", SSS_GL_PARAM_FLOAT, 4, 0.5, 1024,
                         "tessellation target: projected edge length of a surfel in (output) pixels (DSS: by "
                         "distance and area)"},
    [P_MAX_TESS] = {"max_tessellation", SSS_GL_PARAM_INT, 64, 1, 64,
                    "largest subdivision of a triangle edge (the hardware tessellation limit, 64)"},
    [P_PREINTEGRATED] = {"preintegrated", SSS_GL_PARAM_BOOL, 1, 0, 1,
                         "1: the disc-integrated R'_d(r, A) of Maisch & Ropinski 2020; 0: R_d at the surfel centre (DSS)"},
    [P_IRRADIANCE_CULL] = {"irradiance_cull", SSS_GL_PARAM_FLOAT, 0, 0, 1e30,
                           "surfels whose largest F_t E channel is at most this are culled (DSS)"},
    [P_SHADOW_OFFSET] = {"splat_shadow_offset", SSS_GL_PARAM_FLOAT, 0.5, 0, 10,
                         "surfel irradiance looked up this many sqrt(triangle area) above the surface"},
    [P_SNAP] = {"surface_snap", SSS_GL_PARAM_FLOAT, 0.5, 0, 10,
                "visible surfels within this many sqrt(triangle area) of the rendered surface (G-buffer) move onto "
                "it and take its F_t E (DSS surfels lie on the rendered geometry); 0: all stay on the splat "
                "mesh's chords"},
    [P_MAX_SURFELS] = {"max_surfels", SSS_GL_PARAM_INT, 1048576, 1, 16777216,
                       "capacity of the surfel buffer (48 bytes each); surfels beyond it are dropped"},
    [P_FINE] = {"fine_radius", SSS_GL_PARAM_FLOAT, 2.5, 0, 64,
                "with supersampling (k > 1): receivers within this many output pixels of a surfel are splatted per "
                "render pixel (an extra level; the sharp near field antialiased, 5-10% more splatting on the "
                "eval scenes), at most level 0's 2 / epsilon; 0: the k = 1 image, antialiased at edges only "
                "(docs/supersampling.md)"},
    [P_FOOTPRINT] = {"footprint", SSS_GL_PARAM_FLOAT, 1, 0, 8,
                     "a surfel's transport is R_d averaged over three discs of radii 0.5, 0.75 and 1 times f h (h: "
                     "the surfel's spacing, its sub-triangle's longest edge; f = this), so that overlapping surfels "
                     "sum to a smooth field: one disc of the surfel's own area printed their lattice into the image "
                     "(docs/dss.md); 0: that one disc; with preintegrated only"},
};

typedef struct dss_state {
    shell_targets shells; /* first: shell_targets_of() */
    GLuint prog_gen;
    GLuint splats, cmd;
    unsigned capacity;
} dss_state;

static sss_result make_buffer(sss_gl_renderer *r, dss_state *s, sss_error *err)
{
    unsigned cap = (unsigned)gl_param(r, P_MAX_SURFELS);
    if (s->splats && cap == s->capacity) return SSS_OK;
    if (s->splats) glDeleteBuffers(1, &s->splats);
    s->capacity = cap;
    glCreateBuffers(1, &s->splats);
    glNamedBufferStorage(s->splats, (GLsizeiptr)SHELL_SPLAT_BYTES * cap, NULL, 0);
    return gl_check(r->ctx, "dss: surfel buffer", err);
}

static sss_result dss_create(sss_gl_renderer *r, void *state, sss_error *err)
{
    dss_state *s = state;
    sss_result res = gl_program_compute("dss_generate.comp.glsl", NULL, &s->prog_gen, err);
    if (res == SSS_OK) res = shell_create(&s->shells, err);
    if (res != SSS_OK) return res;
    glCreateBuffers(1, &s->cmd);
    glNamedBufferStorage(s->cmd, 4 * sizeof(GLuint), NULL, GL_DYNAMIC_STORAGE_BIT);
    res = make_buffer(r, s, err);
    if (res == SSS_OK) res = shell_resize(r, &s->shells, (int)gl_param(r, P_LEVELS), gl_param(r, P_FINE), err);
    return res;
}

static sss_result dss_resize(sss_gl_renderer *r, void *state, sss_error *err)
{
    dss_state *s = state;
    sss_result res = make_buffer(r, s, err);
    if (res == SSS_OK) res = shell_resize(r, &s->shells, (int)gl_param(r, P_LEVELS), gl_param(r, P_FINE), err);
    return res;
}

static void set_i(GLuint prog, const char *name, int v) { glUniform1i(glGetUniformLocation(prog, name), v); }
static void set_f(GLuint prog, const char *name, double v) { glUniform1f(glGetUniformLocation(prog, name), (float)v); }

static sss_result dss_render(sss_gl_renderer *r, void *state, sss_error *err)
{
    dss_state *s = state;
    sss_result res = dss_resize(r, s, err);
    if (res != SSS_OK) return res;
    const GLuint reset[4] = {4, 0, 0, 0}; /* triangle strip of 4 vertices per instance */
    glNamedBufferSubData(s->cmd, 0, sizeof reset, reset);
    gl_timer_begin(&r->timer, "surfels");
    glUseProgram(s->prog_gen);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GL_SSBO_SPLATS, s->splats);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GL_SSBO_SPLAT_COUNT, s->cmd);
    glUniform1ui(glGetUniformLocation(s->prog_gen, "u_capacity"), s->capacity);
    set_f(s->prog_gen, "u_irradiance_cull", gl_param(r, P_IRRADIANCE_CULL));
    set_f(s->prog_gen, "u_shadow_offset", gl_param(r, P_SHADOW_OFFSET));
    /* surfel_pixels counts output pixels: k render pixels each, so supersampling keeps the surfels
     * (docs/supersampling.md; in render pixels k = 2 made k^2 the surfels) */
    set_f(s->prog_gen, "u_surfel_pixels", gl_param(r, P_SURFEL_PIXELS) * gl_supersample(r));
    set_i(s->prog_gen, "u_max_tess", (int)gl_param(r, P_MAX_TESS));
    set_f(s->prog_gen, "u_snap", gl_param(r, P_SNAP));
    glBindTextureUnit(0, r->frame.pos);
    glBindTextureUnit(1, r->frame.nrm);
    glBindTextureUnit(2, r->frame.irr);
    gl_dispatch_splat_triangles(r, s->prog_gen);
    res = gl_check(r->ctx, "dss: surfel generation", err);
    if (res != SSS_OK) return res;

    gl_timer_begin(&r->timer, "receivers");
    shell_receivers(r, &s->shells);
    res = gl_check(r->ctx, "dss: receivers", err);
    if (res != SSS_OK) return res;

    gl_timer_begin(&r->timer, "splatting");
    s->shells.footprint = (float)gl_param(r, P_FOOTPRINT);
    shell_splat(r, &s->shells, s->splats, s->cmd, s->capacity, gl_param(r, P_EPSILON),
                (int)gl_param(r, P_PREINTEGRATED));
    res = gl_check(r->ctx, "dss: splatting", err);
    if (res != SSS_OK) return res;

    gl_timer_begin(&r->timer, "resolve");
    shell_resolve(r, &s->shells);
    gl_timer_end(&r->timer);
    return gl_check(r->ctx, "dss: resolve", err);
}

static void dss_destroy(sss_gl_renderer *r, void *state)
{
    (void)r;
    dss_state *s = state;
    shell_free(&s->shells);
    if (s->prog_gen) glDeleteProgram(s->prog_gen);
    if (s->splats) glDeleteBuffers(1, &s->splats);
    if (s->cmd) glDeleteBuffers(1, &s->cmd);
}

static GLuint dss_buffer(sss_gl_renderer *r, void *state, const char *name)
{
    (void)r;
    dss_state *s = state;
    /* "translucency": the finest level's accumulation (F_t E A R_d sums, before c_o) */
    if (strcmp(name, "translucency") == 0) return s->shells.accum[0];
    return 0;
}

static void dss_stats(sss_gl_renderer *r, void *state, sss_gl_stats *out)
{
    dss_state *s = state;
    out->texture_bytes += s->shells.bytes;
    out->buffer_bytes += (size_t)SHELL_SPLAT_BYTES * s->capacity + 16;
    out->per_pixel_bytes += s->shells.bytes / ((size_t)r->width * (size_t)r->height);
    out->per_splat_bytes = SHELL_SPLAT_BYTES;
    out->splat_drawn = r->frame_rendered ? shell_splat_count(s->cmd, s->capacity) : 0;
}

/* preset=paper: DSS's own surfels (docs/dss.md): the kernel at the surfel centre, surfels on the splat
 * mesh, one disc each. */
static const sss_gl_param_value paper[] = {{"preintegrated", 0}, {"surface_snap", 0}, {"footprint", 0}};

const gl_technique gl_technique_dss = {
    .info = {"dss",
             "Nalbach et al. 2014 Deep Screen Space as Maisch & Ropinski 2020 compare it: tessellated surfels of every "
             "triangle, shell splatting into a 3-level G-buffer",
             params, P_COUNT},
    .needs = GL_NEED_GBUFFER | GL_NEED_SHADOWS | GL_NEED_ILLUMINATION | GL_NEED_SPLAT_MESHES | GL_NEED_LIGHTS,
    .state_size = sizeof(dss_state),
    .create = dss_create,
    .resize = dss_resize,
    .render = dss_render,
    .destroy = dss_destroy,
    .materials_changed = gl_materials_read_at_render,
    .buffer = dss_buffer,
    .stats = dss_stats,
    .paper = paper,
    .paper_count = (int)(sizeof paper / sizeof paper[0]),
};
