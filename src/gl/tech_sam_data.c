/* gl/tech_sam_data.c — the GPU side of a Spatial Adjacency Map (seed 001, section 4.1 and Fig. 4): per
 * vertex the n back-side links and their coefficients, the one-ring adjacency and the incident
 * triangles (for Eq. 16 and the updates of section 3.4), the radial profile table, and the buffers of
 * the per-frame passes. The map comes from a .sam file when one is given and matches the object
 * (mesh, material, transform), else it is built here on the CPU (sss_sam_build_object). */
#include <stdlib.h>
#include <string.h>

#include "gl/tech_sam.h"
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
    GLuint b[7] = {o->topo, o->geom, o->links, o->coef, o->ld, o->trans, o->rd};
    for (int i = 0; i < 7; i++)
        if (b[i]) glDeleteBuffers(1, &b[i]);
    memset(o, 0, sizeof *o);
}

/* Topology buffer: [adjacency offsets (V + 1) | neighbours | incidence offsets (V + 1) | triangles |
 * indices (3 T)]. */
static sss_result upload_topology(const sss_mesh *m, sam_object *o, sss_error *err)
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
    o->topo = buffer(t, total * sizeof *t, 0, &o->bytes);
    free(t);
    free(cnt);
    sss_mesh_adjacency_free(&adj);
    return SSS_OK;
}

sss_result sam_object_create(sss_gl_renderer *r, int index, const sam_data_desc *d, sam_object *out, sss_error *err)
{
    memset(out, 0, sizeof *out);
    const sss_scene *scene = r->scene;
    const sss_scene_object *so = &scene->objects[index];
    out->index = index;
    out->deforming = so->animation.type != SSS_ANIMATION_NONE;
    sss_sam sam;
    sss_result res = SSS_ERROR_INVALID_ARGUMENT;
    if (d->file) {
        /* Used when it belongs to this object; otherwise the map is built (the file may be another
         * object's). A corrupted or unreadable file is an error. */
        sss_error e2 = {0};
        res = sss_sam_read_object(d->file, scene, (size_t)index, &sam, &e2);
        if (res != SSS_OK && res != SSS_ERROR_INVALID_ARGUMENT) {
            if (err) *err = e2;
            return res;
        }
        if (res != SSS_OK && d->mismatch && d->mismatch->code == SSS_OK) *d->mismatch = e2;
        out->from_file = res == SSS_OK;
    }
    if (res != SSS_OK) {
        sss_sam_desc bd;
        memset(&bd, 0, sizeof bd);
        bd.n = d->n;
        bd.samples = d->samples;
        bd.seed = d->seed;
        sss_sam_stats st;
        res = sss_sam_build_object(scene, (size_t)index, &bd, &sam, &st, err);
        if (res != SSS_OK) return res;
        out->build_seconds = st.seconds;
    }
    sss_profile prof;
    sss_sam_profile_table table;
    memset(&table, 0, sizeof table);
    res = sss_sam_object_profile(so, &prof, err);
    if (res == SSS_OK) res = sss_sam_profile_table_build(&prof, sam.energy, 0, &table, err);
    if (res == SSS_OK) res = upload_topology(&so->mesh, out, err);
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
        out->ld = buffer(NULL, sizeof(float) * 4 * V, 0, &out->bytes);
        out->trans = buffer(NULL, sizeof(float) * 4 * V, 0, &out->bytes);
        out->rd = buffer(table.rgb, sizeof(float) * 3 * (size_t)table.size, 0, &out->bytes);
        out->rd_rmax = (float)table.r_max;
        out->rd_size = table.size;
    }
    sss_sam_profile_table_free(&table);
    sss_sam_free(&sam);
    if (res != SSS_OK) {
        sam_object_free(out);
        return res;
    }
    return gl_check(r->ctx, "sam: buffers", err);
}
