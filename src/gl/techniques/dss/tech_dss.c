/* gl/tech_dss.c — Deep Screen Space subsurface scattering (Nalbach, Ritschel & Seidel 2014) as Maisch & Ropinski 2020
 * configures it for its comparisons (sections 5 and 8): splats from every triangle of the
 * low-resolution splat mesh, tessellated by camera distance and area (a compute pass subdivides large
 * triangles into sub-surfels instead of the hardware tessellator), splatted additively into a
 * multi-resolution G-buffer with l_max = 3 levels and epsilon = 0.1 (common/shells.h), no view-based
 * culling, only irradiance culling. Surfels the camera sees are moved from the splat mesh's chords onto
 * the rendered surface (surface_snap, dss_generate.comp.glsl): DSS tessellates the rendered geometry,
 * and the chords of a coarse splat mesh lie farther from it than short kernels reach. A surfel's kernel
 * is R_d averaged over a tapered footprint sized by the surfel lattice's spacing (footprint,
 * shell_splat.frag.glsl), not over a disc of its own area, which printed the lattice (docs/dss.md).
 *
 * Passes after the shared G-buffer / shadows / illumination: "surfels" (generation + irradiance),
 * "receivers" (the pyramid), "splatting" (all levels), "resolve" (upsampling, sum, exit factor). */
#include <string.h>

#include "gl/common/shells.h"

#define DSS_PARAMS(X) \
    X(levels, SSS_GL_PARAM_INT, 3, 1, SHELL_MAX_LEVELS, "levels of the multi-resolution G-buffer, l_max (Maisch & Ropinski 2020, section 8: 3)") \
    X(epsilon, SSS_GL_PARAM_FLOAT, 0.1, 1e-3, 1, "level l (2^l output pixels) serves receivers at least 2^l pixels / epsilon away (Maisch & Ropinski 2020, " "section 8: 0.1)") \
    X(surfel_pixels, SSS_GL_PARAM_FLOAT, 4, 0.5, 1024, "tessellation target: projected edge length of a surfel in (output) pixels (DSS: by " "distance and area)") \
    X(max_tessellation, SSS_GL_PARAM_INT, 64, 1, 64, "largest subdivision of a triangle edge (the hardware tessellation limit, 64)") \
    X(preintegrated, SSS_GL_PARAM_BOOL, 1, 0, 1, "1: the disc-integrated R'_d(r, A) of Maisch & Ropinski 2020; 0: R_d at the surfel centre (DSS)") \
    X(irradiance_cull, SSS_GL_PARAM_FLOAT, 0, 0, 1e30, "surfels whose largest F_t E channel is at most this are culled (DSS)") \
    X(splat_shadow_offset, SSS_GL_PARAM_FLOAT, 0.5, 0, 10, "surfel irradiance looked up this many sqrt(triangle area) above the surface") \
    X(surface_snap, SSS_GL_PARAM_FLOAT, 0.5, 0, 10, "visible surfels within this many sqrt(triangle area) of the rendered surface (G-buffer) move onto " "it and take its F_t E (DSS surfels lie on the rendered geometry); 0: all stay on the splat " "mesh's chords") \
    X(max_surfels, SSS_GL_PARAM_INT, 1048576, 1, 16777216, "capacity of the surfel buffer (48 bytes each); surfels beyond it are dropped") \
    X(fine_radius, SSS_GL_PARAM_FLOAT, 2.5, 0, 64, "with supersampling (k > 1): receivers within this many output pixels of a surfel are splatted per " "render pixel (an extra level; the sharp near field antialiased, 5-10% more splatting on the " "eval scenes), at most level 0's 2 / epsilon; 0: the k = 1 image, antialiased at edges only " "(docs/supersampling.md)") \
    X(footprint, SSS_GL_PARAM_FLOAT, 1, 0, 8, "a surfel's transport is R_d averaged over three discs of radii 0.5, 0.75 and 1 times f h (h: " "the surfel's spacing, its sub-triangle's longest edge; f = this), so that overlapping surfels " "sum to a smooth field: one disc of the surfel's own area printed their lattice into the image " "(docs/dss.md); 0: that one disc; with preintegrated only")

GL_PARAM_STRUCT(dss_params, DSS_PARAMS);

static const sss_gl_param_info params[] = {DSS_PARAMS(GL_PARAM_INFO)};

typedef struct dss_state {
    shell_targets shells;
    GLuint prog_gen;
    GLuint splats, cmd;
    unsigned capacity;
} dss_state;

static sss_result make_buffer(const gl_tech_ctx *c, dss_state *s, sss_error *err)
{
    const dss_params *p = c->params;
    unsigned cap = (unsigned)p->max_surfels;
    if (s->splats && cap == s->capacity) return SSS_OK;
    if (s->splats) glDeleteBuffers(1, &s->splats);
    s->capacity = cap;
    glCreateBuffers(1, &s->splats);
    glNamedBufferStorage(s->splats, (GLsizeiptr)SHELL_SPLAT_BYTES * cap, NULL, 0);
    return gl_check(c->gl, "dss: surfel buffer", err);
}

static sss_result dss_create(const gl_tech_ctx *c, void *state, sss_error *err)
{
    const dss_params *p = c->params;
    dss_state *s = state;
    sss_result res = gl_program_compute("dss_generate.comp.glsl", NULL, &s->prog_gen, err);
    if (res == SSS_OK) res = shell_create(&s->shells, err);
    if (res != SSS_OK) return res;
    glCreateBuffers(1, &s->cmd);
    glNamedBufferStorage(s->cmd, 4 * sizeof(GLuint), NULL, GL_DYNAMIC_STORAGE_BIT);
    res = make_buffer(c, s, err);
    if (res == SSS_OK) res = shell_resize(c, &s->shells, (int)p->levels, p->fine_radius, err);
    return res;
}

static sss_result dss_resize(const gl_tech_ctx *c, void *state, sss_error *err)
{
    const dss_params *p = c->params;
    dss_state *s = state;
    sss_result res = make_buffer(c, s, err);
    if (res == SSS_OK) res = shell_resize(c, &s->shells, (int)p->levels, p->fine_radius, err);
    return res;
}


static sss_result dss_render(const gl_tech_ctx *c, void *state, sss_error *err)
{
    const dss_params *p = c->params;
    dss_state *s = state;
    sss_result res = dss_resize(c, s, err);
    if (res != SSS_OK) return res;
    const GLuint reset[4] = {4, 0, 0, 0}; /* triangle strip of 4 vertices per instance */
    glNamedBufferSubData(s->cmd, 0, sizeof reset, reset);
    gl_timer_begin(c->timer, "surfels");
    glUseProgram(s->prog_gen);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GL_SSBO_SPLATS, s->splats);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GL_SSBO_SPLAT_COUNT, s->cmd);
    glUniform1ui(glGetUniformLocation(s->prog_gen, "u_capacity"), s->capacity);
    gl_uniform_f(s->prog_gen, "u_irradiance_cull", p->irradiance_cull);
    gl_uniform_f(s->prog_gen, "u_shadow_offset", p->splat_shadow_offset);
    /* surfel_pixels counts output pixels: k render pixels each, so supersampling keeps the surfels
     * (docs/supersampling.md; in render pixels k = 2 made k^2 the surfels) */
    gl_uniform_f(s->prog_gen, "u_surfel_pixels", p->surfel_pixels * c->supersample);
    gl_uniform_i(s->prog_gen, "u_max_tess", (int)p->max_tessellation);
    gl_uniform_f(s->prog_gen, "u_snap", p->surface_snap);
    glBindTextureUnit(0, c->frame.pos);
    glBindTextureUnit(1, c->frame.nrm);
    glBindTextureUnit(2, c->frame.irr);
    gl_dispatch_splat_triangles(c, s->prog_gen);
    res = gl_check(c->gl, "dss: surfel generation", err);
    if (res != SSS_OK) return res;

    gl_timer_begin(c->timer, "receivers");
    shell_receivers(c, &s->shells);
    res = gl_check(c->gl, "dss: receivers", err);
    if (res != SSS_OK) return res;

    gl_timer_begin(c->timer, "splatting");
    s->shells.footprint = (float)p->footprint;
    shell_splat(c, &s->shells, s->splats, s->cmd, s->capacity, p->epsilon,
                (int)p->preintegrated);
    res = gl_check(c->gl, "dss: splatting", err);
    if (res != SSS_OK) return res;

    gl_timer_begin(c->timer, "resolve");
    shell_resolve(c, &s->shells);
    gl_timer_end(c->timer);
    return gl_check(c->gl, "dss: resolve", err);
}

static void dss_destroy(void *state)
{
    dss_state *s = state;
    shell_free(&s->shells);
    if (s->prog_gen) glDeleteProgram(s->prog_gen);
    if (s->splats) glDeleteBuffers(1, &s->splats);
    if (s->cmd) glDeleteBuffers(1, &s->cmd);
}

static const char *const targets[] = {"translucency", NULL};

static GLuint dss_target(void *state, const char *name)
{
    dss_state *s = state;
    /* "translucency": the finest level's accumulation (F_t E A R_d sums, before c_o) */
    if (strcmp(name, "translucency") == 0) return s->shells.accum[0];
    return 0;
}

static void dss_stats(const gl_tech_ctx *c, void *state, sss_gl_stats *out)
{
    dss_state *s = state;
    out->texture_bytes += s->shells.bytes;
    out->buffer_bytes += (size_t)SHELL_SPLAT_BYTES * s->capacity + 16;
    out->per_pixel_bytes += s->shells.bytes / ((size_t)c->width * (size_t)c->height);
    out->per_splat_bytes = SHELL_SPLAT_BYTES;
    out->splat_drawn = c->frame_rendered ? shell_splat_count(s->cmd, s->capacity) : 0;
    out->splat_fragments = c->frame_rendered ? shell_splat_fragments(&s->shells) : -1;
}

/* preset=paper: DSS's own surfels (docs/dss.md): the kernel at the surfel centre, surfels on the splat
 * mesh, one disc each. */
static const sss_gl_param_value paper[] = {{"preintegrated", 0}, {"surface_snap", 0}, {"footprint", 0}};

const gl_technique gl_technique_dss = {
    .info = {"dss",
             "Nalbach et al. 2014 Deep Screen Space as Maisch & Ropinski 2020 compare it: tessellated surfels of every "
             "triangle, shell splatting into a 3-level G-buffer",
             params, (int)(sizeof params / sizeof params[0])},
    .reads = GL_READ_GBUFFER | GL_READ_ILLUMINATION | GL_READ_SPLAT_MESHES | GL_READ_LIGHTS,
    .targets = targets,
    .state_size = sizeof(dss_state),
    .create = dss_create,
    .resize = dss_resize,
    .render = dss_render,
    .destroy = dss_destroy,
    .materials_changed = gl_materials_read_at_render,
    .target = dss_target,
    .stats = dss_stats,
    .paper = paper,
    .paper_count = (int)(sizeof paper / sizeof paper[0]),
};
