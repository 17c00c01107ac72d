/* gl/tech_sam.c — technique "sam": Spatial Adjacency Maps (Maisch & Ropinski 2017).
 *
 * Translucency per vertex from n precomputed back-side links (Eq. 12) plus a surface-diffusion
 * technique for the front side (section 3.2: L_o = c_o (L_o+ + L_o-)). Passes after the shared
 * G-buffer, shadows and illumination:
 *   sam_deform     per vertex: world position and normal at time t (compute)
 *   sam_update     deforming objects only: fan areas (Eq. 16) and the link update of section 3.4
 *   sam_light      per vertex: L_d = F_t E sqrt(albedo) from every light (shared shadow maps)
 *   sam_transfer   per vertex: Eq. 12 (Eq. 15 for deforming objects), blended in time (Eq. 17-18)
 *   surface        the front side: a whole surface technique run in place (ssss, its transmittance
 *                  off, as the paper pairs SAM with SSSS; or the screen-space part of maisch2020)
 *   sam_raster     the per-vertex translucency rasterised (barycentric blend) at full resolution
 *   sam_combine    frame.final += c_o sqrt(albedo) L~_o-
 * The maps come from a .sam file (sss sam build) when the renderer is given one, else they are built
 * at creation with the parameters n and samples (and backside_triangles / backside_splat). A map with
 * a lower-tessellation back-side mesh (Maisch & Ropinski 2017, section 4.4) runs sam_deform on both meshes, and
 * sam_update's fan areas and sam_light on the back-side mesh, whose vertices are the sources of Eq. 12.
 *
 * Time (Eq. 17-18): alpha = 1 - base^dt with dt the animation time since the previous frame of this
 * renderer. The first frame has no previous value: dt is taken as infinite, alpha = 1, so a
 * single-frame render shows exactly the current Eq. 12 (no history). A frame at the same time as the
 * previous one keeps the previous value (alpha = 0: nothing moved). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl/techniques/sam/tech_sam.h"

#define SAM_PARAMS(X)                                                                                             \
    X(n, SSS_GL_PARAM_INT, 3, 1, SSS_SAM_MAX_N,                                                                   \
      "back-side vertices per vertex when the map is built at creation (Maisch & Ropinski 2017, 4.1: 3)")         \
    X(samples, SSS_GL_PARAM_INT, 64, 1, SSS_SAM_MAX_SAMPLES,                                                      \
      "Monte Carlo pairs per form factor of Eq. 11 when the map is built at creation")                            \
    X(seed, SSS_GL_PARAM_INT, 0, 0, 1e9, "seed of the Monte Carlo shifts when the map is built")                  \
    X(surface, SSS_GL_PARAM_INT, 1, 0, 2,                                                                         \
      "front side (L_o+, section 3.2): 0 none, 1 ssss (Jimenez et al. 2019, transmittance off; the paper's "      \
      "pairing), 2 screen-space pattern of maisch2020 (Maisch & Ropinski 2020, section 4)")                       \
    X(translucency, SSS_GL_PARAM_BOOL, 1, 0, 1, "include the SAM translucency L_o- (Eq. 12)")                     \
    X(temporal, SSS_GL_PARAM_BOOL, 1, 0, 1, "blend with the previous frame (Eq. 17); the first frame is never blended") \
    X(blend_base, SSS_GL_PARAM_FLOAT, 1e-10, 1e-30, 1,                                                            \
      "alpha = 1 - base^dt, dt the animation time between frames in seconds (Eq. 18: 1e-10)")                     \
    X(update_steps, SSS_GL_PARAM_INT, 1, 0, 64,                                                                   \
      "link updates per frame of deforming objects through adjacency (section 3.4: 1)")                           \
    X(backside_triangles, SSS_GL_PARAM_INT, 0, 0, 1e9,                                                            \
      "maps built at creation: back side on the mesh simplified to this many triangles (Maisch & Ropinski 2017, " \
      "4.4 and appendix); 0: the mesh itself. A .sam file carries its own")                                       \
    X(backside_splat, SSS_GL_PARAM_BOOL, 0, 0, 1,                                                                 \
      "maps built at creation: back side on the object's splat_mesh (or its mesh simplified to "                  \
      "splat_triangles)")

GL_PARAM_STRUCT(sam_params, SAM_PARAMS);

static const sss_gl_param_info params[] = {SAM_PARAMS(GL_PARAM_INFO)};

/* ---- The surface technique ------------------------------------------------------------------- */

extern const gl_technique gl_technique_ssss, gl_technique_screen;

static sss_result surface_create(const gl_tech_ctx *c, sam_state *s, sss_error *err)
{
    const sam_params *p = c->params;
    int kind = (int)p->surface;
    if (kind == 0) return SSS_OK;
    gl_sub_init(&s->surface, kind == 1 ? &gl_technique_ssss : &gl_technique_screen);
    const sss_gl_technique_info *info = &s->surface.tech->info;
    /* SAM replaces the translucency of the surface techniques */
    gl_params_set(info, s->surface.params, "transmittance", 0.0);
    gl_params_set(info, s->surface.params, "translucency", 0.0);
    /* Maisch & Ropinski 2020's brightening term compensates for light its translucency pass misses; the front side
     * alone is what SAM needs */
    gl_params_set(info, s->surface.params, "brightening", 0.0);
    return gl_sub_create(&s->surface, c, err);
}

static void surface_destroy(sam_state *s)
{
    if (s->surface.tech) gl_sub_destroy(&s->surface);
    s->surface.tech = NULL;
}

/* ---- Targets ----------------------------------------------------------------------------------- */

static void free_targets(sam_state *s)
{
    if (s->fbo) glDeleteFramebuffers(1, &s->fbo);
    if (s->tex_trans) glDeleteTextures(1, &s->tex_trans);
    if (s->tex_depth) glDeleteTextures(1, &s->tex_depth);
    s->fbo = s->tex_trans = s->tex_depth = 0;
    s->target_bytes = 0;
}

static sss_result make_targets(const gl_tech_ctx *c, sam_state *s, sss_error *err)
{
    if (s->fbo && s->w == c->width && s->h == c->height) return SSS_OK;
    free_targets(s);
    s->w = c->width;
    s->h = c->height;
    s->tex_trans = gl_texture_2d(GL_RGBA32F, s->w, s->h, 1, &s->target_bytes);
    s->tex_depth = gl_texture_2d(GL_DEPTH_COMPONENT32F, s->w, s->h, 1, &s->target_bytes);
    glCreateFramebuffers(1, &s->fbo);
    glNamedFramebufferTexture(s->fbo, GL_COLOR_ATTACHMENT0, s->tex_trans, 0);
    glNamedFramebufferTexture(s->fbo, GL_DEPTH_ATTACHMENT, s->tex_depth, 0);
    if (glCheckNamedFramebufferStatus(s->fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return sss_error_set(err, SSS_ERROR_UNSUPPORTED, "sam: incomplete render target");
    return gl_check(c->gl, "sam: targets", err);
}

/* ---- Callbacks ---------------------------------------------------------------------------------- */

static void free_maps(sam_state *s)
{
    for (int i = 0; i < s->count; i++) sam_object_free(&s->objs[i]);
    free(s->objs);
    s->objs = NULL;
    s->count = 0;
    s->build_seconds = 0.0;
    s->have_last = 0;
}

/* The parameters the maps are made for (tech_sam.h: key). */
static void map_key(const sam_params *p, double key[SAM_KEYS])
{
    double k[SAM_KEYS] = {p->n, p->samples, p->seed, p->translucency, p->backside_triangles, p->backside_splat};
    memcpy(key, k, sizeof k);
}

/* How the maps are made under r's parameters n, samples, seed, backside_* and data file. */
static sss_result map_desc(const gl_tech_ctx *c, sam_data_desc *d, sss_error *err)
{
    const sam_params *p = c->params;
    memset(d, 0, sizeof *d);
    d->n = (uint32_t)p->n;
    d->samples = (uint32_t)p->samples;
    d->seed = (uint64_t)p->seed;
    d->backside_triangles = (uint32_t)p->backside_triangles;
    d->backside_splat = (int)p->backside_splat;
    if (d->backside_triangles > 0 && d->backside_splat)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                             "parameters backside_triangles and backside_splat exclude each other");
    d->file = c->data_file;
    return SSS_OK;
}

/* sss_gl_tables: the maps of every subsurface object built without GL (a worker of the viewer builds
 * them with the LUTs), per scene object (vertex_count 0 for the others). Not with a .sam file, whose
 * read is cheap, nor without translucency (no map is needed). */
typedef struct sam_tables {
    size_t count;
    sss_sam *maps;
} sam_tables;

static void sam_tables_free(void *data)
{
    sam_tables *t = data;
    if (!t) return;
    for (size_t i = 0; i < t->count; i++) sss_sam_free(&t->maps[i]);
    free(t->maps);
    free(t);
}

static sss_result sam_tables_build(const gl_tech_ctx *c, void **out, sss_error *err)
{
    const sam_params *p = c->params;
    *out = NULL;
    sam_data_desc d;
    sss_result res = map_desc(c, &d, err);
    if (res != SSS_OK || d.file || p->translucency == 0.0) return res;
    sam_tables *t = calloc(1, sizeof *t);
    size_t n = c->scene->object_count;
    if (t) t->maps = calloc(n ? n : 1, sizeof *t->maps);
    if (!t || !t->maps) {
        sam_tables_free(t);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (sam maps)");
    }
    t->count = n;
    for (size_t i = 0; i < n && res == SSS_OK; i++) {
        if (c->scene->objects[i].material.type != SSS_SCENE_MATERIAL_SUBSURFACE) continue;
        int from_file = 0;
        double seconds = 0.0;
        res = sam_map_build(c->scene, (int)i, &d, &t->maps[i], &from_file, &seconds, err);
    }
    if (res != SSS_OK) sam_tables_free(t);
    else *out = t;
    return res;
}

/* The maps of every subsurface object, for the parameters n, samples, seed, backside_* (key remembered
 * so that a change of them rebuilds the maps at the next resize/render). */
static sss_result make_maps(const gl_tech_ctx *c, sam_state *s, sss_error *err)
{
    const sam_params *p = c->params;
    free_maps(s);
    map_key(p, s->key);
    int subsurface = 0;
    for (size_t i = 0; i < c->scene->object_count; i++)
        subsurface += c->scene->objects[i].material.type == SSS_SCENE_MATERIAL_SUBSURFACE;
    s->objs = calloc(subsurface ? (size_t)subsurface : 1, sizeof *s->objs);
    if (!s->objs) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (sam objects)");
    sam_data_desc d;
    sss_result res = map_desc(c, &d, err);
    if (res != SSS_OK) return res;
    const sam_tables *pre = c->tables_data;
    if (pre && pre->count == c->scene->object_count) d.prebuilt = pre->maps;
    sss_error mismatch = {0};
    d.mismatch = &mismatch;
    int from_file = 0;
    /* without translucency no map is needed (nothing is built) */
    for (size_t i = 0; i < c->scene->object_count && res == SSS_OK && p->translucency != 0.0; i++) {
        if (c->scene->objects[i].material.type != SSS_SCENE_MATERIAL_SUBSURFACE) continue;
        res = sam_object_create(c, (int)i, &d, &s->objs[s->count], err);
        if (res == SSS_OK) {
            from_file += s->objs[s->count].from_file;
            s->build_seconds += s->objs[s->count++].build_seconds;
        }
        else {
            char what[64];
            snprintf(what, sizeof what, "objects[%zu]", i);
            sss_error_prefix(err, what);
        }
    }
    /* a file that fits none of the objects is a mistake worth reporting (not a silent rebuild) */
    if (res == SSS_OK && c->data_file && s->count > 0 && from_file == 0)
        res = sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "%s", mismatch.message);
    return res;
}

static sss_result sam_create(const gl_tech_ctx *c, void *state, sss_error *err)
{
    sam_state *s = state;
    static const char *defines[SAM_PASS_COUNT] = {"#define PASS 0\n", "#define PASS 1\n", "#define PASS 2\n",
                                              "#define PASS 3\n", "#define PASS 4\n"};
    sss_result res = SSS_OK;
    for (int i = 0; i < SAM_PASS_COUNT && res == SSS_OK; i++)
        res = gl_program_compute("sam_vertex.comp.glsl", defines[i], &s->prog[i], err);
    if (res == SSS_OK) res = gl_program_vf("sam_raster.vert.glsl", "sam_raster.frag.glsl", NULL, &s->prog_raster, err);
    if (res == SSS_OK) res = gl_program_vf("fullscreen.vert.glsl", "sam_add.frag.glsl", NULL, &s->prog_add, err);
    if (res == SSS_OK) res = gl_program_vf("fullscreen.vert.glsl", "combine.frag.glsl", NULL, &s->prog_combine, err);
    if (res != SSS_OK) return res;
    res = make_maps(c, s, err);
    if (res == SSS_OK) res = make_targets(c, s, err);
    if (res == SSS_OK) res = surface_create(c, s, err);
    s->surface_kind = (int)((const sam_params *)c->params)->surface;
    return res;
}

/* New materials (sss_gl_renderer_update_materials): the maps again (their kernel), the front side's
 * material state; programs and targets stay. */
static sss_result sam_materials_changed(const gl_tech_ctx *c, void *state, sss_error *err)
{
    sam_state *s = state;
    sss_result res = make_maps(c, s, err);
    if (res == SSS_OK && s->surface.tech) {
        res = gl_sub_materials_changed(&s->surface, c, err);
        if (res != SSS_OK) sss_error_prefix(err, s->surface.tech->info.name);
    }
    return res;
}

static sss_result sam_resize(const gl_tech_ctx *c, void *state, sss_error *err)
{
    const sam_params *p = c->params;
    sam_state *s = state;
    sss_result res = SSS_OK;
    double key[SAM_KEYS];
    map_key(p, key);
    int stale = memcmp(key, s->key, sizeof key) != 0;
    if (stale) res = make_maps(c, s, err);
    if (res == SSS_OK && s->surface_kind != (int)p->surface) {
        surface_destroy(s);
        res = surface_create(c, s, err);
        s->surface_kind = (int)p->surface;
        if (res != SSS_OK) return res;
    }
    if (res == SSS_OK) res = make_targets(c, s, err);
    if (res == SSS_OK && s->surface.tech) res = gl_sub_resize(&s->surface, c, err);
    return res;
}

/* Binds one object's buffers. The per-vertex passes 0, 1, 3 run on the vertex set bound at 10, 11,
 * 17-19: the back-side mesh's when `back` and the map has one (section 4.4), else the render mesh's.
 * The sources of Eq. 12 (20, 21) are always the back-side mesh when there is one. */
static void bind_object(const gl_tech_ctx *c, const sam_object *o, int back)
{
    const gl_object *go = &c->gs->objects[o->index];
    int b = back && o->has_back;
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SAM_SSBO_TOPO, b ? o->back_topo : o->topo);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SAM_SSBO_GEOM, b ? o->back_geom : o->geom);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SAM_SSBO_LINKS, o->links);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SAM_SSBO_COEF, o->coef);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SAM_SSBO_LD, o->ld);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SAM_SSBO_TRANS, o->trans);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SAM_SSBO_RD, o->rd);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SAM_SSBO_POS, b ? o->back_pos : go->pos);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SAM_SSBO_NRM, b ? o->back_nrm : go->nrm);
    GLuint uv = b ? (o->back_uv ? o->back_uv : o->back_pos) : (go->uv ? go->uv : go->pos);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SAM_SSBO_UV, uv);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SAM_SSBO_SRC_GEOM, o->has_back ? o->back_geom : o->geom);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SAM_SSBO_SRC_TOPO, o->has_back ? o->back_topo : o->topo);
}

static void dispatch(const gl_tech_ctx *c, GLuint prog, const sam_object *o, float alpha, int back)
{
    int b = back && o->has_back;
    uint32_t count = b ? o->back_vertices : o->vertices;
    sam_topo_offsets off = {o->adj_list, o->inc_off, o->inc_list, o->idx};
    if (b) off = o->back_off;
    glUseProgram(prog);
    glUniform1ui(glGetUniformLocation(prog, "u_vertices"), count);
    glUniform1ui(glGetUniformLocation(prog, "u_n"), o->n);
    glUniform1i(glGetUniformLocation(prog, "u_object"), o->index);
    glUniform1ui(glGetUniformLocation(prog, "u_adj_list"), off.adj_list);
    glUniform1ui(glGetUniformLocation(prog, "u_inc_off"), off.inc_off);
    glUniform1ui(glGetUniformLocation(prog, "u_inc_list"), off.inc_list);
    glUniform1ui(glGetUniformLocation(prog, "u_idx"), off.idx);
    glUniform1ui(glGetUniformLocation(prog, "u_src_adj_list"), o->has_back ? o->back_off.adj_list : o->adj_list);
    glUniform1i(glGetUniformLocation(prog, "u_same"), !o->has_back);
    glUniform1f(glGetUniformLocation(prog, "u_rd_rmax"), o->rd_rmax);
    glUniform1i(glGetUniformLocation(prog, "u_rd_size"), o->rd_size);
    glUniform1i(glGetUniformLocation(prog, "u_deforming"), o->deforming);
    glUniform1f(glGetUniformLocation(prog, "u_alpha"), alpha);
    glUniform1i(glGetUniformLocation(prog, "u_has_uv"), b ? o->back_uv != 0 : c->gs->objects[o->index].uv != 0);
    glDispatchCompute((count + 63) / 64, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

/* Eq. 18 with dt the animation time since the previous frame; the first frame is not blended. */
static float blend_alpha(const gl_tech_ctx *c, sam_state *s)
{
    const sam_params *p = c->params;
    double dt = s->have_last ? c->view->time - s->last_time : INFINITY;
    if (!(int)p->temporal || !(dt >= 0.0)) return 1.0f; /* off, or time went backwards */
    double a = 1.0 - pow(p->blend_base, dt);
    return (float)(a < 0.0 ? 0.0 : a > 1.0 ? 1.0 : a);
}

static sss_result pass_vertices(const gl_tech_ctx *c, sam_state *s, sss_error *err)
{
    const sam_params *p = c->params;
    float alpha = blend_alpha(c, s);
    int steps = (int)p->update_steps;
    gl_timer_begin(c->timer, "sam_deform");
    for (int i = 0; i < s->count; i++) {
        const sam_object *o = &s->objs[i];
        bind_object(c, o, 0);
        dispatch(c, s->prog[SAM_PASS_DEFORM], o, alpha, 0); /* receivers */
        if (o->has_back) { /* sources: the back-side mesh follows the same animation */
            bind_object(c, o, 1);
            dispatch(c, s->prog[SAM_PASS_DEFORM], o, alpha, 1);
        }
    }
    sss_result res = gl_check(c->gl, "sam: deformation", err);
    if (res != SSS_OK) return res;
    gl_timer_begin(c->timer, "sam_update");
    for (int i = 0; i < s->count; i++) {
        const sam_object *o = &s->objs[i];
        if (!o->deforming) continue;
        bind_object(c, o, 1);
        dispatch(c, s->prog[SAM_PASS_AREA], o, alpha, 1); /* F' of the sources (Eq. 16) */
        bind_object(c, o, 0);
        for (int k = 0; k < steps; k++) dispatch(c, s->prog[SAM_PASS_UPDATE], o, alpha, 0);
    }
    res = gl_check(c->gl, "sam: link update", err);
    if (res != SSS_OK) return res;
    gl_timer_begin(c->timer, "sam_light");
    for (int i = 0; i < s->count; i++) {
        bind_object(c, &s->objs[i], 1);
        dispatch(c, s->prog[SAM_PASS_LIGHT], &s->objs[i], alpha, 1); /* L_d at the sources */
    }
    res = gl_check(c->gl, "sam: vertex irradiance", err);
    if (res != SSS_OK) return res;
    gl_timer_begin(c->timer, "sam_transfer");
    for (int i = 0; i < s->count; i++) {
        bind_object(c, &s->objs[i], 0);
        dispatch(c, s->prog[SAM_PASS_TRANSFER], &s->objs[i], alpha, 0);
    }
    s->last_time = c->view->time;
    s->have_last = 1;
    return gl_check(c->gl, "sam: transfer", err);
}

static sss_result pass_raster(const gl_tech_ctx *c, sam_state *s, sss_error *err)
{
    gl_timer_begin(c->timer, "sam_raster");
    glBindFramebuffer(GL_FRAMEBUFFER, s->fbo);
    glViewport(0, 0, s->w, s->h);
    const float zero[4] = {0, 0, 0, 0};
    glClearBufferfv(GL_COLOR, 0, zero);
    glClearBufferfv(GL_DEPTH, 0, zero); /* reversed Z, as the G-buffer (core/gl_base.h) */
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glUseProgram(s->prog_raster);
    GLint loc = glGetUniformLocation(s->prog_raster, "u_object");
    for (int i = 0; i < s->count; i++) {
        const gl_object *go = &c->gs->objects[s->objs[i].index];
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SAM_SSBO_TRANS, s->objs[i].trans);
        glUniform1i(loc, s->objs[i].index);
        glBindVertexArray(go->vao);
        glDrawElements(GL_TRIANGLES, (GLsizei)(3 * go->triangle_count), GL_UNSIGNED_INT, NULL);
    }
    glBindVertexArray(0);
    glDisable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    return gl_check(c->gl, "sam: rasterisation", err);
}

static sss_result sam_render(const gl_tech_ctx *c, void *state, sss_error *err)
{
    const sam_params *p = c->params;
    sam_state *s = state;
    sss_result res = make_targets(c, s, err);
    int use_trans = (int)p->translucency && s->count > 0;
    if (res == SSS_OK && use_trans) res = pass_vertices(c, s, err);
    if (res == SSS_OK && use_trans) res = pass_raster(c, s, err);
    if (res != SSS_OK) return res;
    if (!use_trans) {
        const float zero[4] = {0, 0, 0, 0};
        glClearTexImage(s->tex_trans, 0, GL_RGBA, GL_FLOAT, zero);
    }
    if (s->surface.tech) {
        /* the surface technique writes frame.final (reflected light + c_o sqrt(albedo) L_o+) ... */
        res = gl_sub_render(&s->surface, c, err);
        if (res != SSS_OK) return res;
        /* ... and the translucency is added to it */
        gl_timer_begin(c->timer, "sam_combine");
        glBindFramebuffer(GL_FRAMEBUFFER, c->frame.fbo_final);
        glViewport(0, 0, c->width, c->height);
        glEnable(GL_BLEND);
        glBlendEquation(GL_FUNC_ADD);
        glBlendFunc(GL_ONE, GL_ONE);
        glUseProgram(s->prog_add);
        glBindTextureUnit(0, c->frame.pos);
        glBindTextureUnit(1, c->frame.nrm);
        glBindTextureUnit(2, c->frame.albedo);
        glBindTextureUnit(3, s->tex_trans);
        gl_draw_fullscreen(c);
        glDisable(GL_BLEND);
    } else {
        gl_timer_begin(c->timer, "sam_combine");
        glDisable(GL_BLEND);
        gl_resolve_begin(c, s->prog_combine);
        glBindTextureUnit(4, s->tex_trans);
        glBindTextureUnit(5, s->tex_trans);
        glUniform1i(glGetUniformLocation(s->prog_combine, "u_use_screen"), 0);
        glUniform1i(glGetUniformLocation(s->prog_combine, "u_use_trans"), 1);
        gl_draw_fullscreen(c);
    }
    gl_timer_end(c->timer);
    return gl_check(c->gl, "sam: combination", err);
}

static void sam_destroy(void *state)
{
    sam_state *s = state;
    surface_destroy(s);
    free_maps(s);
    free_targets(s);
    for (int p = 0; p < SAM_PASS_COUNT; p++)
        if (s->prog[p]) glDeleteProgram(s->prog[p]);
    GLuint p3[3] = {s->prog_raster, s->prog_add, s->prog_combine};
    for (int p = 0; p < 3; p++)
        if (p3[p]) glDeleteProgram(p3[p]);
}

static const char *const targets[] = {"translucency", "translucency_full", "ssss_signal", "ssss_horizontal",
                                     "ssss_sum", "screen", NULL};

static GLuint sam_target(void *state, const char *name)
{
    sam_state *s = state;
    if (strcmp(name, "translucency") == 0 || strcmp(name, "translucency_full") == 0) return s->tex_trans;
    return s->surface.tech ? gl_sub_target(&s->surface, name) : 0;
}

static void sam_stats(const gl_tech_ctx *c, void *state, sss_gl_stats *out)
{
    sam_state *s = state;
    if (s->surface.tech) gl_sub_stats(&s->surface, c, out);
    size_t bytes = 0;
    for (int i = 0; i < s->count; i++) bytes += s->objs[i].bytes;
    out->buffer_bytes += bytes;
    out->texture_bytes += s->target_bytes;
    out->per_pixel_bytes += s->target_bytes / ((size_t)c->width * (size_t)c->height);
}

/* Support (technique.h): the back-side links carry light through the object, but along the front only
 * the surface technique does: ssss as far as it reaches (the object's mean chord), none as one pixel,
 * maisch2020's screen-space pattern across the object. */
static double sam_support(const double *values, const sss_scene *scene, int object, int width, int height)
{
    const sam_params *p = (const sam_params *)values;
    if (p->surface == 1) return gl_object_mean_chord(scene, object);
    if (p->surface == 0) return gl_object_pixel_size(scene, object, width, height);
    return INFINITY;
}

const gl_technique gl_technique_sam = {
    .info = {"sam",
             "Maisch & Ropinski 2017: per-vertex translucency from n back-side links with precomputed form "
             "factors (Spatial Adjacency Maps) + ssss for the front side",
             params, (int)(sizeof params / sizeof params[0])},
    .reads = GL_READ_GBUFFER | GL_READ_ILLUMINATION | GL_READ_MIPS | GL_READ_LIGHTS,
    .targets = targets,
    .state_size = sizeof(sam_state),
    .create = sam_create,
    .resize = sam_resize,
    .render = sam_render,
    .destroy = sam_destroy,
    .materials_changed = sam_materials_changed,
    .tables_build = sam_tables_build,
    .tables_free = sam_tables_free,
    .target = sam_target,
    .stats = sam_stats,
    .support = sam_support,
};
