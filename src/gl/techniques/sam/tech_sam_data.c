/* gl/tech_sam_data.c — the GPU side of a Spatial Adjacency Map (Maisch & Ropinski 2017, section 4.1 and Fig. 4): per
 * vertex the n back-side links and their coefficients, the one-ring adjacency and the incident
 * triangles (for Eq. 16 and the updates of section 3.4), the radial profile table, and the buffers of
 * the per-frame passes. The map comes from a .sam file when one is given and matches the object
 * (mesh, material, transform), else it is built here on the CPU (sss_sam_build_object). A map with a
 * back-side mesh (section 4.4) also uploads that mesh in object space, with its own topology, so that
 * the same deformation, fan-area and lighting passes run on its vertices. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gl/techniques/sam/tech_sam.h"
#include "sss/scene.h"

static GLuint buffer(const void *data, size_t bytes, GLbitfield flags, size_t *count)
{
    GLuint b = 0;
    glCreateBuffers(1, &b);
    glNamedBufferStorage(b, (GLsizeiptr)(bytes ? bytes : 4), data, flags);
    *count += bytes;
    return b;
}

void sam_object_free(sam_object *o)
{
    GLuint b[12] = {o->topo, o->geom, o->links, o->coef, o->ld, o->trans, o->rd,
                    o->back_topo, o->back_geom, o->back_pos, o->back_nrm, o->back_uv};
    for (int i = 0; i < 12; i++)
        if (b[i]) glDeleteBuffers(1, &b[i]);
    memset(o, 0, sizeof *o);
}

/* Topology buffer: [adjacency offsets (V + 1) | neighbours | incidence offsets (V + 1) | triangles |
 * indices (3 T)]. */
static sss_result upload_topology(const sss_mesh *m, sam_topo_offsets *o, GLuint *topo, size_t *bytes, sss_error *err)
{
    sss_mesh_adjacency adj;
    sss_result res = sss_mesh_adjacency_build(m, &adj, err);
    if (res != SSS_OK) return res;
    uint32_t V = m->vertex_count, T = m->triangle_count, na = adj.offsets[V];
    size_t total = (size_t)(V + 1) * 2 + na + 3 * (size_t)T + 3 * (size_t)T;
    uint32_t *t = malloc(total * sizeof *t);
    uint32_t *cnt = calloc((size_t)V + 1, sizeof *cnt);
    if (!t || !cnt) {
        free(t);
        free(cnt);
        sss_mesh_adjacency_free(&adj);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "sam: out of memory (topology)");
    }
    memcpy(t, adj.offsets, sizeof(uint32_t) * (V + 1));
    memcpy(t + V + 1, adj.neighbors, sizeof(uint32_t) * na);
    o->adj_list = V + 1;
    o->inc_off = V + 1 + na;
    o->inc_list = o->inc_off + V + 1;
    o->idx = o->inc_list + 3 * T;
    uint32_t *off = t + o->inc_off, *lst = t + o->inc_list;
    for (size_t i = 0; i < 3 * (size_t)T; i++) cnt[m->indices[i] + 1]++;
    off[0] = 0;
    for (uint32_t v = 0; v < V; v++) off[v + 1] = off[v] + cnt[v + 1];
    memset(cnt, 0, sizeof(uint32_t) * (V + 1));
    for (uint32_t tri = 0; tri < T; tri++)
        for (int k = 0; k < 3; k++) {
            uint32_t v = m->indices[3 * (size_t)tri + k];
            lst[off[v] + cnt[v]++] = tri;
        }
    memcpy(t + o->idx, m->indices, sizeof(uint32_t) * 3 * T);
    *topo = buffer(t, total * sizeof *t, 0, bytes);
    free(t);
    free(cnt);
    sss_mesh_adjacency_free(&adj);
    return SSS_OK;
}

/* The back-side mesh in object space (the map holds it at rest in scene units): p = A^-1 (x - t) and
 * n ~ A^T n_world with M = [A | t] the map's transform, so that the object's animation and transform
 * (object_to_world in common.glsl) pose it exactly as the object's own mesh. */
static sss_result upload_back(const sss_sam *sam, sam_object *o, sss_error *err)
{
    const double *m = sam->transform;
    double a[9] = {m[0], m[1], m[2], m[4], m[5], m[6], m[8], m[9], m[10]}, inv[9];
    double det = a[0] * (a[4] * a[8] - a[5] * a[7]) - a[1] * (a[3] * a[8] - a[5] * a[6]) + a[2] * (a[3] * a[7] - a[4] * a[6]);
    if (!(fabs(det) > 0.0) || !isfinite(det))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sam: the map's transform is singular");
    inv[0] = (a[4] * a[8] - a[5] * a[7]) / det;
    inv[1] = (a[2] * a[7] - a[1] * a[8]) / det;
    inv[2] = (a[1] * a[5] - a[2] * a[4]) / det;
    inv[3] = (a[5] * a[6] - a[3] * a[8]) / det;
    inv[4] = (a[0] * a[8] - a[2] * a[6]) / det;
    inv[5] = (a[2] * a[3] - a[0] * a[5]) / det;
    inv[6] = (a[3] * a[7] - a[4] * a[6]) / det;
    inv[7] = (a[1] * a[6] - a[0] * a[7]) / det;
    inv[8] = (a[0] * a[4] - a[1] * a[3]) / det;
    uint32_t V = sam->back_vertex_count;
    float *pos = malloc(sizeof(float) * 3 * V), *nrm = malloc(sizeof(float) * 3 * V);
    float *geom = calloc(8 * (size_t)V, sizeof(float));
    if (!pos || !nrm || !geom) {
        free(pos);
        free(nrm);
        free(geom);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "sam: out of memory (back-side mesh)");
    }
    for (uint32_t v = 0; v < V; v++) {
        const float *x = sam->back_positions + 3 * (size_t)v, *nw = sam->back_normals + 3 * (size_t)v;
        double d[3] = {x[0] - m[3], x[1] - m[7], x[2] - m[11]}, n[3], len = 0.0;
        for (int i = 0; i < 3; i++) {
            pos[3 * (size_t)v + i] = (float)(inv[3 * i] * d[0] + inv[3 * i + 1] * d[1] + inv[3 * i + 2] * d[2]);
            n[i] = a[i] * nw[0] + a[3 + i] * nw[1] + a[6 + i] * nw[2]; /* A^T n */
            len += n[i] * n[i];
        }
        len = sqrt(len);
        for (int i = 0; i < 3; i++) nrm[3 * (size_t)v + i] = len > 0.0 ? (float)(n[i] / len) : (i == 1 ? 1.0f : 0.0f);
        geom[8 * (size_t)v + 3] = sam->back_fan_area[v]; /* F' at rest */
    }
    o->has_back = 1;
    o->back_vertices = V;
    o->back_pos = buffer(pos, sizeof(float) * 3 * V, 0, &o->bytes);
    o->back_nrm = buffer(nrm, sizeof(float) * 3 * V, 0, &o->bytes);
    o->back_geom = buffer(geom, sizeof(float) * 8 * V, GL_DYNAMIC_STORAGE_BIT, &o->bytes);
    if (sam->back_uvs) o->back_uv = buffer(sam->back_uvs, sizeof(float) * 2 * V, 0, &o->bytes);
    free(pos);
    free(nrm);
    free(geom);
    sss_mesh view;
    sss_sam_back_mesh(sam, &view);
    return upload_topology(&view, &o->back_off, &o->back_topo, &o->bytes, err);
}

sss_result sam_map_build(const sss_scene *scene, int index, const sam_data_desc *d, sss_sam *sam, int *from_file,
                         double *seconds, sss_error *err)
{
    const sss_scene_object *so = &scene->objects[index];
    sss_result res = SSS_ERROR_INVALID_ARGUMENT;
    *from_file = 0;
    *seconds = 0.0;
    if (d->file) {
        /* Used when it belongs to this object; otherwise the map is built (the file may be another
         * object's). A corrupted or unreadable file is an error. */
        sss_error e2 = {0};
        res = sss_sam_read_object(d->file, scene, (size_t)index, sam, &e2);
        if (res != SSS_OK && res != SSS_ERROR_INVALID_ARGUMENT) {
            if (err) *err = e2;
            return res;
        }
        if (res != SSS_OK && d->mismatch && d->mismatch->code == SSS_OK) *d->mismatch = e2;
        *from_file = res == SSS_OK;
    }
    if (res == SSS_OK) return res;
    sss_sam_desc bd;
    memset(&bd, 0, sizeof bd);
    bd.n = d->n;
    bd.samples = d->samples;
    bd.seed = d->seed;
    bd.backside_triangles = d->backside_triangles;
    if (d->backside_splat) {
        /* the scene's low-resolution mesh of the object (docs/scene-format.md: splat_mesh, splat_triangles) */
        if (so->splat_mesh.vertex_count) bd.backside = &so->splat_mesh;
        else if (so->splat_triangles) bd.backside_triangles = so->splat_triangles;
        else
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                                 "backside_splat: the object has neither splat_mesh nor splat_triangles");
    }
    sss_sam_stats st;
    res = sss_sam_build_object(scene, (size_t)index, &bd, sam, &st, err);
    if (res == SSS_OK) *seconds = st.seconds;
    return res;
}

sss_result sam_object_create(const gl_tech_ctx *c, int index, const sam_data_desc *d, sam_object *out, sss_error *err)
{
    memset(out, 0, sizeof *out);
    const sss_scene *scene = c->scene;
    const sss_scene_object *so = &scene->objects[index];
    out->index = index;
    out->deforming = so->animation.type != SSS_ANIMATION_NONE;
    sss_sam sam;
    const sss_sam *prebuilt = d->prebuilt && d->prebuilt[index].vertex_count ? &d->prebuilt[index] : NULL;
    sss_result res = SSS_OK;
    if (prebuilt) sam = *prebuilt; /* borrowed: the tables own it */
    else res = sam_map_build(scene, index, d, &sam, &out->from_file, &out->build_seconds, err);
    if (res != SSS_OK) return res;
    sss_profile prof;
    sss_sam_profile_table table;
    memset(&table, 0, sizeof table);
    res = sss_sam_object_profile(so, &prof, err);
    if (res == SSS_OK) res = sss_sam_profile_table_build(&prof, sam.energy, 0, &table, err);
    sam_topo_offsets off;
    if (res == SSS_OK) res = upload_topology(&so->mesh, &off, &out->topo, &out->bytes, err);
    if (res == SSS_OK) {
        out->adj_list = off.adj_list;
        out->inc_off = off.inc_off;
        out->inc_list = off.inc_list;
        out->idx = off.idx;
        out->back_vertices = sam.vertex_count;
        out->back_off = off;
    }
    if (res == SSS_OK && sam.back_vertex_count) res = upload_back(&sam, out, err);
    if (res == SSS_OK) {
        uint32_t V = sam.vertex_count;
        out->vertices = V;
        out->n = sam.n;
        size_t slots = (size_t)V * sam.n;
        float *geom = calloc(8 * (size_t)V, sizeof(float));
        if (!geom) res = sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "sam: out of memory");
        else {
            for (uint32_t v = 0; v < V; v++) geom[8 * (size_t)v + 3] = sam.fan_area[v]; /* F' at rest */
            out->geom = buffer(geom, sizeof(float) * 8 * V, GL_DYNAMIC_STORAGE_BIT, &out->bytes);
            free(geom);
        }
        for (uint32_t v = 0; v < V; v++) {
            int any = 0;
            for (uint32_t k = 0; k < sam.n; k++) any |= sam.links[(size_t)v * sam.n + k] != SSS_SAM_NONE;
            out->linked += (uint32_t)any;
        }
        /* static objects use K directly; deforming ones K' (Eq. 15) */
        out->links = buffer(sam.links, sizeof(uint32_t) * slots, 0, &out->bytes);
        out->coef = buffer(out->deforming ? sam.kprime : sam.form_factor, sizeof(float) * 3 * slots, 0, &out->bytes);
        out->ld = buffer(NULL, sizeof(float) * 4 * out->back_vertices, 0, &out->bytes); /* L_d per source */
        out->trans = buffer(NULL, sizeof(float) * 4 * V, 0, &out->bytes);
        out->rd = buffer(table.rgb, sizeof(float) * 3 * (size_t)table.size, 0, &out->bytes);
        out->rd_rmax = (float)table.r_max;
        out->rd_size = table.size;
    }
    sss_sam_profile_table_free(&table);
    if (!prebuilt) sss_sam_free(&sam);
    if (res != SSS_OK) {
        sam_object_free(out);
        return res;
    }
    return gl_check(c->gl, "sam: buffers", err);
}
