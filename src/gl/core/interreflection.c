/* gl/core/interreflection.c — light between surfaces after the first subsurface event, for every
 * technique that reads the illumination pass (docs/interreflection.md).
 *
 * Instant radiosity (Keller 1997): each object's surface is cut into triangles (the
 * budget interreflection_sources shared out over the objects); each triangle is a virtual point light
 * whose flux comes from the scene's lights through the shadow maps, like a reflective shadow map's
 * texel (Dachsbacher & Stamminger 2005) but including the surfaces the lights do not see directly:
 *   diffuse   M_j = albedo E_j
 *   subsurface M_j = sum_k F_t E_k A_k R'_d(|x_j - x_k|, A_k)   over the object's own triangles
 * (R'_d the disc mean of the kernel LUT, Maisch & Ropinski 2020, Eq. 5: the light that enters at one
 * triangle and leaves at another, the glow of a back-lit ear included). Every visible pixel then
 * receives E = sum_j M_j A_j / pi cos_i cos_j / (d^2 + A_j / pi), the irradiance of a disc of area A_j
 * on its axis (bounded where a receiver touches a source), at every stride-th pixel, upsampled by
 * position and normal. With interreflection_bounces > 1 the sources are first lit again by the virtual
 * lights of the bounce before (bounce_relight.comp.glsl). No visibility between source and receiver: the cosines remove the pairs that face
 * away, the rest may leak (documented). Diffuse surfaces are cut finer near the subsurface objects,
 * whose light they receive and return.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/vecmath.h"
#include "gl/core/gl_core.h"

/* ---- The sources: triangles of every surface (CPU, once per GPU scene) ------------------------ */

/* One triangle in object space as the shaders read it (std430: four vec4):
 * a.w object index, b.w first triangle of the object, c.w the object's triangle count, n object normal. */
typedef struct bounce_tri {
    float a[4], b[4], c[4], n[4];
} bounce_tri;

typedef struct tri_list {
    bounce_tri *items;
    double *priority;
    size_t count, capacity;
} tri_list;

static double dist_to_box(const double p[3], const double lo[3], const double hi[3])
{
    double s = 0.0;
    for (int k = 0; k < 3; k++) {
        double d = p[k] < lo[k] ? lo[k] - p[k] : p[k] > hi[k] ? p[k] - hi[k] : 0.0;
        s += d * d;
    }
    return sqrt(s);
}

/* The subsurface objects' world boxes, which diffuse surfaces are cut finer towards. */
typedef struct box_set {
    double (*lo)[3], (*hi)[3];
    int count;
} box_set;

/* The world area of the object-space triangle v under the object's transform; its centroid into c. */
static double world_triangle(const sss_scene_object *so, const float *const v[3], double c[3])
{
    double w[3][3], e1[3], e2[3], cr[3];
    for (int k = 0; k < 3; k++) {
        double p[3] = {v[k][0], v[k][1], v[k][2]};
        sss_transform_point(so->transform.matrix, p, w[k]);
    }
    for (int k = 0; k < 3; k++) {
        e1[k] = w[1][k] - w[0][k];
        e2[k] = w[2][k] - w[0][k];
        c[k] = (w[0][k] + w[1][k] + w[2][k]) / 3.0;
    }
    v3_cross(e1, e2, cr);
    return 0.5 * v3_len(cr);
}

/* Splitting priority: the world area, over (d^2 + s^2) on diffuse surfaces, d the distance to the
 * nearest subsurface object's box and s its half diagonal (about the solid angle the triangle fills
 * seen from that object, which is what it exchanges light with). */
static double tri_priority(const sss_scene_object *so, const bounce_tri *t, const box_set *boxes, int subsurface)
{
    const float *v[3] = {t->a, t->b, t->c};
    double c[3], area = world_triangle(so, v, c);
    if (subsurface || boxes->count == 0) return area;
    double best = 0.0;
    for (int i = 0; i < boxes->count; i++) {
        double d = dist_to_box(c, boxes->lo[i], boxes->hi[i]), s2 = 0.0;
        for (int k = 0; k < 3; k++) s2 += 0.25 * (boxes->hi[i][k] - boxes->lo[i][k]) * (boxes->hi[i][k] - boxes->lo[i][k]);
        double pr = area / (d * d + s2 + 1e-30);
        if (pr > best) best = pr;
    }
    return best;
}

static int list_push(tri_list *l, const bounce_tri *t, double priority)
{
    if (l->count == l->capacity) {
        size_t cap = l->capacity ? 2 * l->capacity : 256;
        bounce_tri *items = realloc(l->items, cap * sizeof *items);
        if (!items) return 0;
        l->items = items;
        double *pr = realloc(l->priority, cap * sizeof *pr);
        if (!pr) return 0;
        l->priority = pr;
        l->capacity = cap;
    }
    l->items[l->count] = *t;
    l->priority[l->count++] = priority;
    return 1;
}

static void set3(float *d, const float *s) { d[0] = s[0], d[1] = s[1], d[2] = s[2]; }

static void face_normal(bounce_tri *t)
{
    float e1[3], e2[3];
    for (int k = 0; k < 3; k++) e1[k] = t->b[k] - t->a[k], e2[k] = t->c[k] - t->a[k];
    float n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    float len = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; k++) t->n[k] = len > 0.0f ? n[k] / len : 0.0f;
}

/* Halves the highest-priority triangle at the midpoint of its longest edge until `target` triangles. */
static int list_refine(tri_list *l, size_t first, size_t target, const sss_scene_object *so, const box_set *boxes,
                       int subsurface)
{
    while (l->count - first < target) {
        size_t best = first;
        for (size_t i = first + 1; i < l->count; i++)
            if (l->priority[i] > l->priority[best]) best = i;
        if (!(l->priority[best] > 0.0)) return 1; /* nothing left to split */
        bounce_tri t = l->items[best];
        float *v[3] = {t.a, t.b, t.c};
        int e = 0;
        float longest = -1.0f;
        for (int k = 0; k < 3; k++) {
            const float *p = v[k], *q = v[(k + 1) % 3];
            float d = (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]);
            if (d > longest) longest = d, e = k;
        }
        float m[3];
        for (int k = 0; k < 3; k++) m[k] = 0.5f * (v[e][k] + v[(e + 1) % 3][k]);
        bounce_tri h1 = t, h2 = t; /* (p_e, m, p_e+2) and (m, p_e+1, p_e+2) keep the winding */
        float *w1[3] = {h1.a, h1.b, h1.c}, *w2[3] = {h2.a, h2.b, h2.c};
        set3(w1[(e + 1) % 3], m);
        set3(w2[e], m);
        l->items[best] = h1;
        l->priority[best] = tri_priority(so, &h1, boxes, subsurface);
        if (!list_push(l, &h2, tri_priority(so, &h2, boxes, subsurface))) return 0;
    }
    return 1;
}

/* Appends the object's triangles: its mesh (its splat mesh, or simplified to the budget when larger),
 * then halved where the priority is highest until the budget. */
static sss_result object_triangles(const sss_scene_object *so, int index, int subsurface, size_t budget,
                                   const box_set *boxes, tri_list *l, sss_error *err)
{
    const sss_mesh *m = so->splat_mesh.triangle_count > 0 ? &so->splat_mesh : &so->mesh;
    sss_mesh simplified;
    memset(&simplified, 0, sizeof simplified);
    if (m->triangle_count > budget) {
        sss_result res = sss_mesh_simplify(m, (uint32_t)budget, &simplified, err);
        if (res == SSS_ERROR_NUMERIC) return SSS_OK; /* no mesh within a tiny share: the object sends no light */
        if (res != SSS_OK) {
            sss_error_prefix(err, "interreflection sources (simplification)");
            return res;
        }
        m = &simplified;
    }
    size_t first = l->count;
    int ok = 1;
    for (uint32_t t = 0; t < m->triangle_count && ok; t++) {
        bounce_tri bt;
        memset(&bt, 0, sizeof bt);
        float *v[3] = {bt.a, bt.b, bt.c};
        for (int k = 0; k < 3; k++) set3(v[k], m->positions + 3 * (size_t)m->indices[3 * (size_t)t + (size_t)k]);
        face_normal(&bt);
        double pr = tri_priority(so, &bt, boxes, subsurface);
        if (pr > 0.0) ok = list_push(l, &bt, pr);
    }
    sss_mesh_free(&simplified);
    if (ok) ok = list_refine(l, first, budget, so, boxes, subsurface);
    if (!ok) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (interreflection sources)");
    for (size_t i = first; i < l->count; i++) {
        l->items[i].a[3] = (float)index;
        l->items[i].b[3] = (float)first;
        l->items[i].c[3] = (float)(l->count - first);
    }
    return SSS_OK;
}

static sss_result subsurface_boxes(const sss_scene *s, const gl_scene *gs, box_set *b, sss_error *err)
{
    b->lo = calloc(s->object_count ? s->object_count : 1, sizeof *b->lo);
    b->hi = calloc(s->object_count ? s->object_count : 1, sizeof *b->hi);
    if (!b->lo || !b->hi) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (interreflection)");
    for (size_t i = 0; i < s->object_count; i++) {
        if (!gs->objects[i].subsurface) continue;
        const sss_scene_object *so = &s->objects[i];
        double *lo = b->lo[b->count], *hi = b->hi[b->count];
        for (int k = 0; k < 3; k++) lo[k] = INFINITY, hi[k] = -INFINITY;
        for (int c = 0; c < 8; c++) { /* the transformed corners of the object's box */
            double p[3] = {(c & 1) ? so->bounds_max[0] : so->bounds_min[0], (c & 2) ? so->bounds_max[1] : so->bounds_min[1],
                           (c & 4) ? so->bounds_max[2] : so->bounds_min[2]}, w[3];
            sss_transform_point(so->transform.matrix, p, w);
            for (int k = 0; k < 3; k++) lo[k] = fmin(lo[k], w[k]), hi[k] = fmax(hi[k], w[k]);
        }
        b->count++;
    }
    return SSS_OK;
}

static double world_area(const sss_scene_object *so)
{
    const sss_mesh *m = &so->mesh;
    double area = 0.0, c[3];
    for (uint32_t t = 0; t < m->triangle_count; t++) {
        const float *v[3];
        for (int k = 0; k < 3; k++) v[k] = m->positions + 3 * (size_t)m->indices[3 * (size_t)t + (size_t)k];
        area += world_triangle(so, v, c);
    }
    return area;
}

/* Each object's share of the budget: equal while every object gets at least 8 triangles (a small
 * object near a large one matters as much as it), else by world area, rounded down (among many small
 * objects the large ones carry the bounce, and the total stays within the budget). */
static sss_result object_shares(const sss_scene *s, size_t total, size_t *share, sss_error *err)
{
    size_t objects = 0;
    for (size_t i = 0; i < s->object_count; i++) objects += s->objects[i].mesh.triangle_count > 0;
    if (objects == 0) return SSS_OK;
    if (objects * 8 <= total) {
        for (size_t i = 0; i < s->object_count; i++) share[i] = s->objects[i].mesh.triangle_count > 0 ? total / objects : 0;
        return SSS_OK;
    }
    double *area = calloc(s->object_count, sizeof *area), sum = 0.0;
    if (!area) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (interreflection)");
    for (size_t i = 0; i < s->object_count; i++) sum += area[i] = world_area(&s->objects[i]);
    for (size_t i = 0; i < s->object_count; i++) {
        double n = sum > 0.0 ? floor((double)total * area[i] / sum) : 0.0;
        share[i] = n >= 2.0 ? (size_t)n : 0;
    }
    free(area);
    return SSS_OK;
}

static GLuint bounce_buffer(const void *data, size_t bytes, size_t *counter)
{
    GLuint b = 0;
    glCreateBuffers(1, &b);
    gl_mem_buffer_storage(b, (GLsizeiptr)bytes, data, data ? 0 : GL_DYNAMIC_STORAGE_BIT);
    *counter += bytes;
    return b;
}

sss_result gl_scene_prepare_bounce(gl_core *core, sss_error *err)
{
    gl_scene *gs = &core->gs;
    if (gs->bounce_ready) return SSS_OK;
    const sss_scene *s = core->scene;
    size_t *share = calloc(s->object_count ? s->object_count : 1, sizeof *share);
    if (!share) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (interreflection)");
    box_set boxes = {0};
    tri_list l = {0};
    sss_result res = object_shares(s, (size_t)core->shared[GL_P_INTERREFLECTION_SOURCES], share, err);
    if (res == SSS_OK) res = subsurface_boxes(s, gs, &boxes, err);
    for (size_t i = 0; i < s->object_count && res == SSS_OK; i++)
        if (share[i] > 0)
            res = object_triangles(&s->objects[i], (int)i, gs->objects[i].subsurface, share[i], &boxes, &l, err);
    free(share);
    free(boxes.lo);
    free(boxes.hi);
    if (res == SSS_OK && l.count > 0) {
        gs->bounce_tris = bounce_buffer(l.items, l.count * sizeof *l.items, &gs->buffer_bytes);
        gs->bounce_sources = bounce_buffer(NULL, l.count * 16 * sizeof(float), &gs->buffer_bytes);
        gs->bounce_vpls = bounce_buffer(NULL, l.count * 12 * sizeof(float), &gs->buffer_bytes);
    }
    gs->bounce_count = (int)l.count;
    free(l.items);
    free(l.priority);
    if (res != SSS_OK) return res;
    gs->bounce_ready = 1;
    return gl_check(core->ctx, "the interreflection sources", err);
}

/* ---- The stage's GL objects ---------------------------------------------------------------------- */

int gl_bounce_enabled(const gl_core *core)
{
    return core->shared[GL_P_INTERREFLECTION] > 0.5 && !core->external && (core->reads & GL_READ_ILLUMINATION);
}

void gl_bounce_free(gl_bounce *b)
{
    GLuint progs[5] = {b->prog_sources, b->prog_exitance, b->prog_relight, b->prog_gather, b->prog_apply};
    for (int i = 0; i < 5; i++)
        if (progs[i]) glDeleteProgram(progs[i]);
    if (b->tex) gl_mem_delete_textures(1, &b->tex);
    if (b->tex_plane) gl_mem_delete_textures(1, &b->tex_plane);
    if (b->fbo) glDeleteFramebuffers(1, &b->fbo);
    memset(b, 0, sizeof *b);
}

static sss_result bounce_programs(gl_bounce *b, sss_error *err)
{
    if (b->prog_apply) return SSS_OK;
    sss_result res = gl_program_compute("bounce_sources.comp.glsl", NULL, &b->prog_sources, err);
    if (res == SSS_OK) res = gl_program_compute("bounce_exitance.comp.glsl", NULL, &b->prog_exitance, err);
    if (res == SSS_OK) res = gl_program_compute("bounce_relight.comp.glsl", NULL, &b->prog_relight, err);
    if (res == SSS_OK) res = gl_program_vf("fullscreen.vert.glsl", "bounce_gather.frag.glsl", NULL, &b->prog_gather, err);
    if (res == SSS_OK) res = gl_program_vf("fullscreen.vert.glsl", "bounce_apply.frag.glsl", NULL, &b->prog_apply, err);
    return res;
}

/* The reduced target for the frame size and stride (recreated when either changed). */
static sss_result bounce_target(gl_core *core, int stride, sss_error *err)
{
    gl_bounce *b = &core->bounce;
    int w = (core->width + stride - 1) / stride, h = (core->height + stride - 1) / stride;
    if (b->tex && b->width == w && b->height == h && b->stride == stride) return SSS_OK;
    if (b->tex) gl_mem_delete_textures(1, &b->tex);
    if (b->tex_plane) gl_mem_delete_textures(1, &b->tex_plane);
    if (b->fbo) glDeleteFramebuffers(1, &b->fbo);
    b->bytes = 0;
    b->tex = gl_texture_2d(GL_RGBA32F, w, h, 1, &b->bytes);
    b->tex_plane = gl_texture_2d(GL_RGBA32F, w, h, 1, &b->bytes);
    GLuint targets[2] = {b->tex, b->tex_plane};
    b->fbo = gl_framebuffer(targets, 2, 0);
    b->width = w, b->height = h, b->stride = stride;
    return gl_check(core->ctx, "the interreflection target", err);
}

/* ---- The frame ------------------------------------------------------------------------------------ */

static void uniform_u(GLuint prog, const char *name, unsigned v) { glProgramUniform1ui(prog, glGetUniformLocation(prog, name), v); }
static void uniform_i(GLuint prog, const char *name, int v) { glProgramUniform1i(prog, glGetUniformLocation(prog, name), v); }

static void bounce_lights(gl_core *core)
{
    const gl_scene *gs = &core->gs;
    gl_bounce *b = &core->bounce;
    unsigned n = (unsigned)gs->bounce_count, groups = (n + 63u) / 64u;
    gl_timer_begin(&core->timer, "bounce_sources");
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GL_SSBO_BOUNCE_TRIANGLES, gs->bounce_tris);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GL_SSBO_BOUNCE_SOURCES, gs->bounce_sources);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GL_SSBO_BOUNCE_VPLS, gs->bounce_vpls);
    glUseProgram(b->prog_sources);
    uniform_u(b->prog_sources, "u_count", n);
    glDispatchCompute(groups, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GL_SSBO_BOUNCE_TRANSMIT, gs->mat.ssbo_transmit);
    uniform_u(b->prog_exitance, "u_count", n);
    uniform_u(b->prog_relight, "u_count", n);
    int bounces = (int)core->shared[GL_P_INTERREFLECTION_BOUNCES];
    for (int k = 0; k < bounces; k++) {
        if (k > 0) { /* the sources lit again by the virtual lights of bounce k */
            glUseProgram(b->prog_relight);
            glDispatchCompute(groups, 1, 1);
            glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        }
        glUseProgram(b->prog_exitance);
        glDispatchCompute(groups, 1, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
}

static void bounce_gather(gl_core *core)
{
    gl_bounce *b = &core->bounce;
    const gl_frame *f = &core->frame;
    gl_timer_begin(&core->timer, "bounce_gather");
    glBindFramebuffer(GL_FRAMEBUFFER, b->fbo);
    glViewport(0, 0, b->width, b->height);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glUseProgram(b->prog_gather);
    glBindTextureUnit(0, f->pos);
    glBindTextureUnit(1, f->nrm);
    uniform_u(b->prog_gather, "u_count", (unsigned)core->gs.bounce_count);
    uniform_i(b->prog_gather, "u_stride", b->stride);
    gl_fullscreen_triangle(core->vao_empty);
}

/* Adds the upsampled bounce to the illumination pass's targets (blending: + 0 leaves them as they were). */
static void bounce_apply(gl_core *core)
{
    gl_bounce *b = &core->bounce;
    const gl_frame *f = &core->frame;
    gl_timer_begin(&core->timer, "bounce_apply");
    glBindFramebuffer(GL_FRAMEBUFFER, f->fbo_light);
    glViewport(0, 0, f->width, f->height);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    glUseProgram(b->prog_apply);
    glBindTextureUnit(0, f->pos);
    glBindTextureUnit(1, f->nrm);
    glBindTextureUnit(2, f->albedo);
    glBindTextureUnit(3, b->tex);
    glBindTextureUnit(4, b->tex_plane);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GL_SSBO_BOUNCE_TRANSMIT, core->gs.mat.ssbo_transmit);
    uniform_u(b->prog_apply, "u_count", (unsigned)core->gs.bounce_count);
    uniform_i(b->prog_apply, "u_stride", b->stride);
    gl_fullscreen_triangle(core->vao_empty);
    glDisable(GL_BLEND);
}

sss_result gl_bounce_frame(gl_core *core, sss_error *err)
{
    sss_result res = gl_scene_prepare_bounce(core, err);
    if (res == SSS_OK) res = bounce_programs(&core->bounce, err);
    /* a stride in proportion to the image: the same gathered points per object at every size */
    int stride = (int)floor(core->height / core->shared[GL_P_INTERREFLECTION_ROWS] + 0.5);
    if (res == SSS_OK) res = bounce_target(core, stride < 1 ? 1 : stride, err);
    if (res != SSS_OK || core->gs.bounce_count == 0) return res;
    gl_scene_bind(core);
    bounce_lights(core);
    bounce_gather(core);
    bounce_apply(core);
    return gl_check(core->ctx, "the interreflection stage", err);
}
