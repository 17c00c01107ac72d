/* sam/sam_back.c — the lower-tessellation back-side mesh of Maisch & Ropinski 2017 (section 4.4: "a proof of concept
 * that works on a lower triangulation for back side information", detailed in the paper's appendix,
 * which our copy lacks). Design: the receivers v_o stay the render mesh's vertices (the translucency
 * of Eq. 12 is still per rendered vertex); the sources v_i of Eq. 8-12 are the vertices of a coarser
 * mesh of the same surface, with their reduced fans (Eq. 16) as the regions F'_i of Eq. 11 and the
 * criteria of Eq. 13-14 against their positions and normals. Eq. 8 holds for any partition of the back
 * surface into fans, so a coarse mesh changes only how well the constant-L_d assumption of Eq. 9 holds
 * (worse: larger fans) and how much of the back side n links cover (much more: section 3.5 asks for
 * "either a higher number of samples or larger triangles"). The search visits far fewer candidates,
 * which is the appendix's lower precomputation time. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sam/sam_internal.h"

/* A deep copy of the fields the map needs; a mesh without normals gets area-weighted ones. */
static sss_result copy_mesh(const sss_mesh *m, sss_mesh *out, sss_error *err)
{
    memset(out, 0, sizeof *out);
    size_t nv = m->vertex_count, nt = m->triangle_count;
    out->vertex_count = m->vertex_count;
    out->triangle_count = m->triangle_count;
    out->positions = malloc(sizeof(float) * 3 * nv);
    out->indices = malloc(sizeof(uint32_t) * 3 * nt);
    if (m->normals) out->normals = malloc(sizeof(float) * 3 * nv);
    if (m->uvs) out->uvs = malloc(sizeof(float) * 2 * nv);
    if (!out->positions || !out->indices || (m->normals && !out->normals) || (m->uvs && !out->uvs)) {
        sss_mesh_free(out);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "sam: out of memory (back-side mesh)");
    }
    memcpy(out->positions, m->positions, sizeof(float) * 3 * nv);
    memcpy(out->indices, m->indices, sizeof(uint32_t) * 3 * nt);
    if (m->normals) memcpy(out->normals, m->normals, sizeof(float) * 3 * nv);
    if (m->uvs) memcpy(out->uvs, m->uvs, sizeof(float) * 2 * nv);
    if (!m->normals) {
        sss_result res = sss_mesh_compute_normals(out, err);
        if (res != SSS_OK) sss_mesh_free(out);
        return res;
    }
    return SSS_OK;
}

sss_result sam_back_prepare(const sss_mesh *mesh, const sss_sam_desc *desc, sss_mesh *out, sss_error *err)
{
    memset(out, 0, sizeof *out);
    if (desc->backside && desc->backside_triangles > 0)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                             "sam: a back-side mesh and a back-side triangle count exclude each other");
    sss_result res = SSS_OK;
    if (desc->backside) {
        const sss_mesh *b = desc->backside;
        if (!b->positions || !b->indices || b->vertex_count == 0 || b->triangle_count == 0)
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sam: the back-side mesh is empty");
        if (b->vertex_count > SSS_MESH_MAX_VERTICES || b->triangle_count > SSS_MESH_MAX_TRIANGLES)
            return sss_error_set(err, SSS_ERROR_LIMIT, "sam: the back-side mesh is too large (%u vertices, %u triangles)",
                                 b->vertex_count, b->triangle_count);
        for (size_t i = 0; i < 3 * (size_t)b->triangle_count; i++)
            if (b->indices[i] >= b->vertex_count)
                return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                                     "sam: back-side mesh: triangle %zu: index %u out of range (%u vertices)", i / 3,
                                     b->indices[i], b->vertex_count);
        res = copy_mesh(b, out, err);
    } else if (desc->backside_triangles > 0) {
        /* at or above the mesh's count the mesh is its own back side (a version-1 map) */
        if (desc->backside_triangles >= mesh->triangle_count) return SSS_OK;
        res = sss_mesh_simplify(mesh, desc->backside_triangles, out, err);
        if (res != SSS_OK) sss_error_prefix(err, "sam: back-side mesh");
    }
    if (res != SSS_OK || out->vertex_count == 0) return res;
    for (size_t v = 0; v < out->vertex_count; v++) {
        int finite = 1;
        for (int k = 0; k < 3; k++) finite &= isfinite(out->positions[3 * v + k]) && isfinite(out->normals[3 * v + k]);
        if (out->uvs) finite &= isfinite(out->uvs[2 * v]) && isfinite(out->uvs[2 * v + 1]);
        if (!finite) {
            sss_mesh_free(out);
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sam: back-side mesh: vertex %zu is not finite", v);
        }
    }
    return SSS_OK;
}

sss_result sam_back_store(sss_sam *sam, const sss_mesh *back, const float *fan_area, sss_error *err)
{
    size_t nv = back->vertex_count, nt = back->triangle_count;
    sam->back_vertex_count = back->vertex_count;
    sam->back_triangle_count = back->triangle_count;
    sam->back_hash = sss_sam_mesh_hash(back);
    sam->back_positions = malloc(sizeof(float) * 3 * nv);
    sam->back_normals = malloc(sizeof(float) * 3 * nv);
    sam->back_fan_area = malloc(sizeof(float) * nv);
    sam->back_indices = malloc(sizeof(uint32_t) * 3 * nt);
    if (back->uvs) sam->back_uvs = malloc(sizeof(float) * 2 * nv);
    if (!sam->back_positions || !sam->back_normals || !sam->back_fan_area || !sam->back_indices ||
        (back->uvs && !sam->back_uvs))
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "sam: out of memory (back-side mesh)");
    memcpy(sam->back_positions, back->positions, sizeof(float) * 3 * nv);
    memcpy(sam->back_normals, back->normals, sizeof(float) * 3 * nv);
    memcpy(sam->back_fan_area, fan_area, sizeof(float) * nv);
    memcpy(sam->back_indices, back->indices, sizeof(uint32_t) * 3 * nt);
    if (back->uvs) memcpy(sam->back_uvs, back->uvs, sizeof(float) * 2 * nv);
    return SSS_OK;
}

int sss_sam_back_mesh(const sss_sam *sam, sss_mesh *view)
{
    memset(view, 0, sizeof *view);
    if (!sam || sam->back_vertex_count == 0) return 0;
    view->vertex_count = sam->back_vertex_count;
    view->triangle_count = sam->back_triangle_count;
    view->positions = sam->back_positions;
    view->normals = sam->back_normals;
    view->uvs = sam->back_uvs;
    view->indices = sam->back_indices;
    return 1;
}
