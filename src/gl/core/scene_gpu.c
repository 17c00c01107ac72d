/* gl/scene_gpu.c — uploads a scene: meshes (rest pose; animation runs in the shaders), one material
 * record per distinct material with its kernel LUT (one layer of a 2D array texture each, Maisch & Ropinski 2020
 * section 7.1), albedo textures, and the low-resolution splat meshes (on demand).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/vecmath.h"
#include "gl/core/gl_core.h"
#include "sss/profile.h"

static GLuint make_buffer(const void *data, size_t bytes, size_t *counter)
{
    GLuint b = 0;
    glCreateBuffers(1, &b);
    glNamedBufferStorage(b, (GLsizeiptr)(bytes ? bytes : 4), data, 0);
    if (counter) *counter += bytes;
    return b;
}

static void upload_mesh(gl_scene *gs, gl_object *o, const sss_mesh *m)
{
    o->vertex_count = m->vertex_count;
    o->triangle_count = m->triangle_count;
    o->has_uv = m->uvs != NULL;
    o->pos = make_buffer(m->positions, sizeof(float) * 3 * m->vertex_count, &gs->buffer_bytes);
    o->nrm = make_buffer(m->normals, sizeof(float) * 3 * m->vertex_count, &gs->buffer_bytes);
    o->idx = make_buffer(m->indices, sizeof(uint32_t) * 3 * m->triangle_count, &gs->buffer_bytes);
    if (m->uvs) o->uv = make_buffer(m->uvs, sizeof(float) * 2 * m->vertex_count, &gs->buffer_bytes);
    glCreateVertexArrays(1, &o->vao);
    glVertexArrayVertexBuffer(o->vao, 0, o->pos, 0, 3 * sizeof(float));
    glVertexArrayAttribFormat(o->vao, 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(o->vao, 0, 0);
    glEnableVertexArrayAttrib(o->vao, 0);
    glVertexArrayVertexBuffer(o->vao, 1, o->nrm, 0, 3 * sizeof(float));
    glVertexArrayAttribFormat(o->vao, 1, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(o->vao, 1, 1);
    glEnableVertexArrayAttrib(o->vao, 1);
    if (o->uv) {
        glVertexArrayVertexBuffer(o->vao, 2, o->uv, 0, 2 * sizeof(float));
        glVertexArrayAttribFormat(o->vao, 2, 2, GL_FLOAT, GL_FALSE, 0);
        glVertexArrayAttribBinding(o->vao, 2, 2);
        glEnableVertexArrayAttrib(o->vao, 2);
    }
    glVertexArrayElementBuffer(o->vao, o->idx);
}

/* Two subsurface materials share a LUT when their optics and profile agree exactly. */
static int same_material(const sss_scene_material *a, const sss_scene_material *b)
{
    if (a->type != b->type) return 0;
    if (a->type == SSS_SCENE_MATERIAL_DIFFUSE)
        return memcmp(a->albedo, b->albedo, sizeof a->albedo) == 0;
    return memcmp(&a->optical, &b->optical, sizeof a->optical) == 0 && a->profile == b->profile &&
           (a->texture == NULL) == (b->texture == NULL) && (!a->texture || strcmp(a->texture, b->texture) == 0) &&
           a->has_specular == b->has_specular && a->roughness == b->roughness &&
           (a->profile != SSS_SCENE_PROFILE_ARTIST || memcmp(&a->artist, &b->artist, sizeof a->artist) == 0);
}

/* What an upload collects on the CPU before it creates the buffers. */
typedef struct upload_work {
    gl_object_record *orec;
    gl_material_record *mrec;
    float *transmit;                      /* per GL material: gl_scene_materials.ssbo_transmit */
    const sss_scene_material **mref;      /* per GL material of a scene object */
    const gl_lut_cascade **cascades;      /* per subsurface material, in LUT layer order */
    gl_lut_cascade *owned;                /* the cascades computed here (not from tables) */
    int cascade_count, owned_count;
} upload_work;

static void work_free(upload_work *w)
{
    for (int i = 0; w->owned && i < w->owned_count; i++) gl_lut_cascade_free(&w->owned[i]);
    free(w->orec);
    free(w->mrec);
    free(w->transmit);
    free(w->mref);
    free(w->cascades);
    free(w->owned);
    memset(w, 0, sizeof *w);
}

/* The material's LUT cascade: from core->luts when they hold it, else computed. */
static sss_result take_cascade(const gl_core *core, gl_scene_materials *mat, upload_work *w,
                               const sss_scene_material *sm, sss_error *err)
{
    const gl_lut_cascade *c = gl_lut_set_find(core->luts, core->shared, sm);
    if (c) {
        mat->luts_precomputed++;
    } else {
        sss_result res = gl_lut_cascade_build(core->shared, sm, &w->owned[w->owned_count], err);
        if (res != SSS_OK) {
            sss_error_prefix(err, "kernel LUT");
            return res;
        }
        c = &w->owned[w->owned_count++];
    }
    w->cascades[w->cascade_count++] = c;
    return SSS_OK;
}

/* The GL material of a scene material: an identical one already recorded, or a new record. */
static sss_result add_material(const gl_core *core, const sss_scene *s, gl_scene_materials *mat, upload_work *w,
                               const sss_scene_material *sm, int *index, sss_error *err)
{
    for (int k = 0; k < mat->count; k++)
        if (w->mref[k] && same_material(w->mref[k], sm)) return *index = k, SSS_OK;
    int mi = *index = mat->count++;
    w->mref[mi] = sm;
    gl_material *gm = &mat->items[mi];
    gl_material_record *rec = &w->mrec[mi];
    gm->subsurface = sm->type == SSS_SCENE_MATERIAL_SUBSURFACE;
    for (int c = 0; c < 3; c++) rec->albedo[c] = (float)sm->albedo[c];
    rec->albedo[3] = gm->subsurface ? 0.0f : 1.0f;
    rec->params[2] = -1.0f;
    rec->params[3] = -1.0f;
    if (!gm->subsurface) return SSS_OK;
    w->transmit[mi] = (float)(1.0 - 2.0 * sss_fresnel_moment1(sm->optical.eta));
    rec->params[0] = (float)sm->optical.eta;
    rec->params[1] = (float)sss_bssrdf_normalization(sm->optical.eta);
    sss_result res = take_cascade(core, mat, w, sm, err);
    if (res != SSS_OK) return res;
    const gl_lut_cascade *c = w->cascades[w->cascade_count - 1];
    gm->lut_layer = (w->cascade_count - 1) * c->levels;
    gm->r_max = c->r_max;
    gm->a_max = c->a_max;
    gm->axes = c->axes;
    rec->params[2] = (float)gm->lut_layer;
    rec->lut[0] = (float)gm->r_max;
    rec->lut[1] = (float)gm->a_max;
    rec->lut[2] = gm->axes == SSS_LUT_AXES_SQRT ? 1.0f : 0.0f;
    rec->lut[3] = (float)c->size;
    rec->spec[0] = sm->has_specular ? 1.0f : 0.0f;
    rec->spec[1] = (float)sm->roughness;
    rec->spec[2] = (float)c->levels;
    /* splat reach: r_max, or less when a smaller radius already holds splat_energy */
    double reach = sss_profile_reach(&sm->rd, core->shared[GL_P_SPLAT_ENERGY]);
    rec->spec[3] = (float)(reach > 0.0 && reach < gm->r_max ? reach : gm->r_max);
    for (size_t t = 0; sm->texture_image && t < s->texture_count; t++)
        if (&s->textures[t].image == sm->texture_image) rec->params[3] = (float)t; /* its layer */
    return SSS_OK;
}

/* The world bounds being grown by an upload's records. */
typedef struct bounds3 {
    float lo[3], hi[3];
} bounds3;

static void bounds_grow(bounds3 *b, const float p[3])
{
    for (int k = 0; k < 3; k++) {
        if (p[k] < b->lo[k]) b->lo[k] = p[k];
        if (p[k] > b->hi[k]) b->hi[k] = p[k];
    }
}

/* Object i's record (its material mi), and its world bounds (animation included) grown into b. */
static sss_result object_record(const sss_scene *s, size_t i, const gl_object *o, int mi, int subsurface,
                                gl_object_record *rec, bounds3 *b, sss_error *err)
{
    const sss_scene_object *so = &s->objects[i];
    m4_from_rows(so->transform.matrix, rec->model);
    for (int a = 0; a < 3; a++)
        for (int c = 0; c < 3; c++) rec->normal_matrix[4 * c + a] = (float)so->transform.normal_matrix[3 * a + c];
    rec->normal_matrix[15] = 1.0f;
    for (int k = 0; k < 3; k++) {
        rec->bounds_min[k] = so->bounds_min[k];
        rec->bounds_max[k] = so->bounds_max[k];
    }
    rec->bounds_min[3] = (float)so->animation.type;
    rec->bounds_max[3] = (float)so->animation.amplitude;
    rec->anim[0] = so->animation.period > 0.0 ? (float)so->animation.period : 1.0f;
    rec->anim[1] = (float)mi;
    rec->anim[2] = subsurface ? 1.0f : 0.0f;
    rec->anim[3] = o->has_uv ? 1.0f : 0.0f;
    float lo[3], hi[3];
    sss_scene_object_animated_bounds(so, lo, hi);
    for (int c = 0; c < 8; c++) {
        double p[3] = {(c & 1) ? hi[0] : lo[0], (c & 2) ? hi[1] : lo[1], (c & 4) ? hi[2] : lo[2]}, w[3];
        sss_transform_point(so->transform.matrix, p, w);
        /* GL works in float: positions beyond ~1e18 leave no room for products (areas, depth); the
         * loader refuses such objects, scenes built in code are caught here */
        double reach = fmax(fabs(w[0]), fmax(fabs(w[1]), fabs(w[2])));
        if (!isfinite(w[0]) || !isfinite(w[1]) || !isfinite(w[2]) || !(reach <= SSS_SCENE_MAX_WORLD_COORD))
            return sss_error_set(err, SSS_ERROR_LIMIT,
                                 "%s: objects[%zu]: world-space positions reach %g, beyond %g (single precision)",
                                 s->name ? s->name : "scene", i, reach, SSS_SCENE_MAX_WORLD_COORD);
        float wf[3] = {(float)w[0], (float)w[1], (float)w[2]};
        bounds_grow(b, wf);
    }
    return SSS_OK;
}

/* Meshes of the scene's objects (rest pose). */
static sss_result object_meshes(const sss_scene *s, gl_scene *gs, sss_error *err)
{
    for (size_t i = 0; i < s->object_count; i++) {
        const sss_scene_object *so = &s->objects[i];
        gl_object *o = &gs->objects[i];
        if (so->mesh.vertex_count == 0 || so->mesh.triangle_count == 0 || !so->mesh.normals)
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "%s: objects[%zu] has no mesh loaded",
                                 s->name ? s->name : "scene", i);
        upload_mesh(gs, o, &so->mesh);
        memcpy(o->uploaded_matrix, so->transform.matrix, sizeof o->uploaded_matrix);
        o->uploaded_animation = so->animation;
        o->animated = so->animation.type != SSS_ANIMATION_NONE;
    }
    return SSS_OK;
}

static sss_result object_materials(const gl_core *core, const sss_scene *s, gl_scene_materials *mat, upload_work *w,
                                   bounds3 *b, sss_error *err)
{
    sss_result res = SSS_OK;
    for (size_t i = 0; i < s->object_count && res == SSS_OK; i++) {
        res = add_material(core, s, mat, w, &s->objects[i].material, &mat->of_object[i], err);
        if (res != SSS_OK) break;
        int mi = mat->of_object[i];
        res = object_record(s, i, &core->gs.objects[i], mi, mat->items[mi].subsurface, &w->orec[i], b, err);
    }
    return res;
}

/* Emitters: one quad per area light, emitting its radiance towards u x v (or both sides). */
static void emitter_quad(const sss_light *L, float pos[12], float nrm[12])
{
    double n[3] = {L->u[1] * L->v[2] - L->u[2] * L->v[1], L->u[2] * L->v[0] - L->u[0] * L->v[2],
                   L->u[0] * L->v[1] - L->u[1] * L->v[0]};
    double nl = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    static const double su[4] = {-1, 1, 1, -1}, sv[4] = {-1, -1, 1, 1};
    for (int c = 0; c < 4; c++)
        for (int k = 0; k < 3; k++) {
            pos[3 * c + k] = (float)(L->center[k] + su[c] * L->u[k] + sv[c] * L->v[k]);
            nrm[3 * c + k] = (float)(nl > 0.0 ? n[k] / nl : 0.0);
        }
}

/* The emitters' quads (after the objects in gs->objects). */
static void emitter_meshes(const sss_scene *s, gl_scene *gs)
{
    size_t e = s->object_count;
    for (size_t i = 0; i < s->light_count; i++) {
        const sss_light *L = &s->lights[i];
        if (L->type != SSS_LIGHT_AREA) continue;
        float pos[12], nrm[12];
        uint32_t idx[6] = {0, 1, 2, 0, 2, 3};
        emitter_quad(L, pos, nrm);
        sss_mesh quad;
        memset(&quad, 0, sizeof quad);
        quad.vertex_count = 4;
        quad.triangle_count = 2;
        quad.positions = pos;
        quad.normals = nrm;
        quad.indices = idx;
        upload_mesh(gs, &gs->objects[e], &quad);
        gs->objects[e++].emitter = 1;
    }
}

/* The emitters' materials (their radiance) and records. */
static void emitter_materials(const sss_scene *s, gl_scene_materials *mat, upload_work *w, bounds3 *b)
{
    size_t e = s->object_count;
    for (size_t i = 0; i < s->light_count; i++) {
        const sss_light *L = &s->lights[i];
        if (L->type != SSS_LIGHT_AREA) continue;
        float pos[12], nrm[12];
        emitter_quad(L, pos, nrm);
        int mi = mat->count++;
        mat->of_object[e] = mi;
        gl_material_record *m = &w->mrec[mi];
        for (int c = 0; c < 3; c++) m->albedo[c] = (float)L->radiance[c];
        m->albedo[3] = 2.0f;
        m->params[0] = 1.0f;
        m->params[2] = m->params[3] = -1.0f;
        m->spec[0] = L->two_sided ? 1.0f : 0.0f;
        gl_object_record *rec = &w->orec[e];
        for (int k = 0; k < 4; k++) rec->model[5 * k] = rec->normal_matrix[5 * k] = 1.0f;
        rec->anim[0] = 1.0f;
        rec->anim[1] = (float)mi;
        for (int c = 0; c < 4; c++) bounds_grow(b, pos + 3 * c);
        e++;
    }
}

/* The LUT array (a 1x1 zero layer when no material scatters, so the sampler is always complete) and
 * its scales. The LUT's bytes matter for speed: the screen-space and splat passes read it at scattered
 * places (llvmpipe, 960x540 dragon: 512^2 texels 5.3 s, 256^2 2.9 s for the screen-space pass). */
static sss_result upload_luts(gl_scene_materials *mat, const upload_work *w, sss_error *err)
{
    int size = w->cascade_count ? w->cascades[0]->size : 1;
    int levels = w->cascade_count ? w->cascades[0]->levels : 1;
    for (int i = 0; i < w->cascade_count; i++)
        if (w->cascades[i]->size != size || w->cascades[i]->levels != levels)
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "kernel LUTs of different sizes");
    mat->lut_size = size;
    mat->lut_layers = w->cascade_count ? w->cascade_count * levels : 1;
    float *scales = calloc((size_t)mat->lut_layers, sizeof *scales);
    if (!scales) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (LUT upload)");
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &mat->lut_array);
    glTextureStorage3D(mat->lut_array, 1, GL_RGBA32F, size, size, mat->lut_layers);
    glTextureParameteri(mat->lut_array, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(mat->lut_array, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(mat->lut_array, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(mat->lut_array, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    mat->lut_bytes = (size_t)size * size * 16 * (size_t)mat->lut_layers;
    if (!w->cascade_count) {
        float z[4] = {0, 0, 0, 0};
        glTextureSubImage3D(mat->lut_array, 0, 0, 0, 0, 1, 1, 1, GL_RGBA, GL_FLOAT, z);
        scales[0] = 1.0f;
    }
    for (int i = 0; i < w->cascade_count; i++) {
        const gl_lut_cascade *c = w->cascades[i];
        glTextureSubImage3D(mat->lut_array, 0, 0, 0, i * levels, size, size, levels, GL_RGBA, GL_FLOAT, c->rgba);
        memcpy(scales + (size_t)i * levels, c->scales, sizeof *scales * (size_t)levels);
    }
    size_t scale_bytes = sizeof *scales * (size_t)mat->lut_layers;
    mat->ssbo_lut_scales = make_buffer(scales, scale_bytes, NULL);
    mat->record_bytes += scale_bytes;
    free(scales);
    return SSS_OK;
}

static void delete_buffer(GLuint *b)
{
    if (*b) glDeleteBuffers(1, b);
    *b = 0;
}

static void materials_free(gl_scene_materials *mat)
{
    free(mat->items);
    free(mat->of_object);
    delete_buffer(&mat->ssbo_objects);
    delete_buffer(&mat->ssbo_materials);
    delete_buffer(&mat->ssbo_lut_scales);
    delete_buffer(&mat->ssbo_transmit);
    if (mat->lut_array) glDeleteTextures(1, &mat->lut_array);
    memset(mat, 0, sizeof *mat);
}

/* The material part of scene s into mat (records, materials and LUTs of every object and emitter, then
 * the buffers), the objects' world bounds into b. Reads the core's gs->objects (their meshes, which are
 * s's); writes nothing of the core. On failure mat holds nothing. */
static sss_result build_materials(const gl_core *core, const sss_scene *s, gl_scene_materials *mat, bounds3 *b,
                                  sss_error *err)
{
    size_t n_obj = (size_t)core->gs.object_count;
    upload_work w;
    memset(&w, 0, sizeof w);
    memset(mat, 0, sizeof *mat);
    mat->items = calloc(n_obj, sizeof *mat->items);
    mat->of_object = calloc(n_obj, sizeof *mat->of_object);
    w.orec = calloc(n_obj, sizeof *w.orec);
    w.mrec = calloc(n_obj, sizeof *w.mrec);
    w.transmit = calloc(n_obj, sizeof *w.transmit);
    w.mref = calloc(n_obj, sizeof *w.mref);
    w.cascades = calloc(n_obj, sizeof *w.cascades);
    w.owned = calloc(n_obj, sizeof *w.owned);
    sss_result res = SSS_OK;
    if (!mat->items || !mat->of_object || !w.orec || !w.mrec || !w.transmit || !w.mref || !w.cascades || !w.owned)
        res = sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (scene upload)");
    for (int k = 0; k < 3; k++) {
        b->lo[k] = INFINITY;
        b->hi[k] = -INFINITY;
    }
    if (res == SSS_OK) res = object_materials(core, s, mat, &w, b, err);
    if (res == SSS_OK) emitter_materials(s, mat, &w, b);
    if (res == SSS_OK) res = upload_luts(mat, &w, err);
    if (res == SSS_OK) {
        size_t ob = sizeof *w.orec * n_obj, mb = sizeof *w.mrec * (size_t)mat->count;
        size_t tb = sizeof *w.transmit * (size_t)mat->count;
        mat->ssbo_objects = make_buffer(w.orec, ob, NULL);
        mat->ssbo_materials = make_buffer(w.mrec, mb, NULL);
        mat->ssbo_transmit = make_buffer(w.transmit, tb, NULL);
        mat->record_bytes += ob + mb + tb;
    }
    work_free(&w);
    if (res != SSS_OK) materials_free(mat);
    return res;
}

/* Puts mat in place of the scene's material part (whose resources go) and gives the objects theirs. */
static void materials_commit(gl_scene *gs, gl_scene_materials *mat)
{
    materials_free(&gs->mat);
    gs->mat = *mat;
    memset(mat, 0, sizeof *mat);
    for (int i = 0; i < gs->object_count; i++) {
        gs->objects[i].material = gs->mat.of_object[i];
        gs->objects[i].subsurface = gs->mat.items[gs->objects[i].material].subsurface;
    }
}

sss_result gl_scene_upload(gl_core *core, sss_error *err)
{
    const sss_scene *s = core->scene;
    gl_scene *gs = &core->gs;
    if (s->object_count == 0 || s->object_count > 65535)
        return sss_error_set(err, SSS_ERROR_LIMIT, "%s: %zu objects (the GL renderer takes 1..65535)",
                             s->name ? s->name : "scene", s->object_count);
    size_t n_area = 0;
    for (size_t i = 0; i < s->light_count; i++) n_area += s->lights[i].type == SSS_LIGHT_AREA;
    gs->object_count = (int)(s->object_count + n_area); /* area lights are visible rectangles (sss/reference.h) */
    gs->objects = calloc((size_t)gs->object_count, sizeof *gs->objects);
    if (!gs->objects) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (scene upload)");
    sss_result res = object_meshes(s, gs, err);
    if (res == SSS_OK) emitter_meshes(s, gs);
    gl_scene_materials mat;
    bounds3 b;
    if (res == SSS_OK) res = build_materials(core, s, &mat, &b, err);
    if (res == SSS_OK) {
        materials_commit(gs, &mat);
        memcpy(gs->bounds_min, b.lo, sizeof b.lo);
        memcpy(gs->bounds_max, b.hi, sizeof b.hi);
        res = gl_albedo_upload(gs, s->textures, s->texture_count, err);
    }
    if (res != SSS_OK) return res;
    return gl_check(core->ctx, "the scene upload", err);
}

sss_result gl_scene_update_materials(gl_core *core, const sss_scene *scene, sss_error *err)
{
    gl_scene_materials mat;
    bounds3 b; /* the upload's: the geometry is the same */
    sss_result res = build_materials(core, scene, &mat, &b, err);
    if (res == SSS_OK) res = gl_check(core->ctx, "the material upload", err);
    if (res == SSS_OK) materials_commit(&core->gs, &mat);
    else materials_free(&mat);
    return res;
}

sss_result gl_scene_prepare_splats(gl_core *core, sss_error *err)
{
    gl_scene *gs = &core->gs;
    if (gs->splats_ready) return SSS_OK;
    gs->splat_total = 0;
    for (int i = 0; i < gs->object_count; i++) {
        gl_object *o = &gs->objects[i];
        if (!o->subsurface) continue;
        const sss_scene_object *so = &core->scene->objects[i];
        const sss_mesh *m = &so->mesh;
        sss_mesh simplified;
        memset(&simplified, 0, sizeof simplified);
        if (so->splat_mesh.triangle_count > 0) {
            m = &so->splat_mesh;
        } else {
            uint32_t budget = so->splat_triangles ? so->splat_triangles : (uint32_t)core->shared[GL_P_SPLAT_TRIANGLES];
            if (m->triangle_count > budget) {
                sss_result res = sss_mesh_simplify(m, budget, &simplified, err);
                if (res != SSS_OK) {
                    sss_error_prefix(err, "splat mesh (simplification)");
                    return res;
                }
                m = &simplified;
            }
        }
        o->splat_vertex_count = m->vertex_count;
        o->splat_triangle_count = m->triangle_count;
        o->splat_pos = make_buffer(m->positions, sizeof(float) * 3 * m->vertex_count, &gs->buffer_bytes);
        o->splat_idx = make_buffer(m->indices, sizeof(uint32_t) * 3 * m->triangle_count, &gs->buffer_bytes);
        if (m->uvs) o->splat_uv = make_buffer(m->uvs, sizeof(float) * 2 * m->vertex_count, &gs->buffer_bytes);
        gs->splat_total += m->triangle_count;
        sss_mesh_free(&simplified);
    }
    gs->splats_ready = 1;
    return gl_check(core->ctx, "the splat mesh upload", err);
}

void gl_scene_free(gl_scene *gs)
{
    for (int i = 0; gs->objects && i < gs->object_count; i++) {
        gl_object *o = &gs->objects[i];
        if (o->vao) glDeleteVertexArrays(1, &o->vao);
        delete_buffer(&o->pos);
        delete_buffer(&o->nrm);
        delete_buffer(&o->uv);
        delete_buffer(&o->idx);
        delete_buffer(&o->splat_pos);
        delete_buffer(&o->splat_idx);
        delete_buffer(&o->splat_uv);
    }
    free(gs->objects);
    delete_buffer(&gs->bounce_tris);
    delete_buffer(&gs->bounce_sources);
    delete_buffer(&gs->bounce_vpls);
    materials_free(&gs->mat);
    free(gs->lights);
    free(gs->light_kinds);
    gl_env_cache_free(gs);
    delete_buffer(&gs->ssbo_lights);
    GLuint t[4] = {gs->albedo_array, gs->shadow_cube, gs->shadow_2d, gs->env_tex};
    for (int i = 0; i < 4; i++)
        if (t[i]) glDeleteTextures(1, &t[i]);
    if (gs->shadow_fbo) glDeleteFramebuffers(1, &gs->shadow_fbo);
    memset(gs, 0, sizeof *gs);
}

void gl_scene_bind(const gl_core *core)
{
    const gl_scene *gs = &core->gs;
    glBindBufferBase(GL_UNIFORM_BUFFER, GL_UBO_FRAME, core->ubo_frame);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GL_SSBO_OBJECTS, gs->mat.ssbo_objects);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GL_SSBO_MATERIALS, gs->mat.ssbo_materials);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GL_SSBO_LIGHTS, gs->ssbo_lights);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GL_SSBO_LUT_SCALES, gs->mat.ssbo_lut_scales);
    glBindTextureUnit(GL_UNIT_LUT, gs->mat.lut_array);
    glBindTextureUnit(GL_UNIT_SHADOW_CUBE, gs->shadow_cube);
    glBindTextureUnit(GL_UNIT_SHADOW_2D, gs->shadow_2d);
    glBindTextureUnit(GL_UNIT_ALBEDO, gs->albedo_array);
    glBindTextureUnit(GL_UNIT_ENV, gs->env_tex);
}
