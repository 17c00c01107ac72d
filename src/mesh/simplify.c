/* mesh/simplify.c — reduction to a target triangle count with meshoptimizer.
 *
 * meshopt_simplify collapses edges while keeping the topology; it stops early when borders or
 * attribute seams block further collapses. Then meshopt_simplifySloppy (vertex clustering on a grid,
 * topology not kept) takes over, with a shrinking goal until the count is at most the target.
 * Degenerate triangles and unused vertices are dropped and normals recomputed (area-weighted); UVs follow their vertices.
 */
#include <meshoptimizer.h>
#include <stdlib.h>
#include <string.h>

#include "mesh/mesh_internal.h"

/* Relative error budget (a fraction of the mesh extent): large, so only the target count stops the
 * topology-preserving pass. */
#define SIMPLIFY_MAX_ERROR 1.0f

sss_result sss_mesh_simplify(const sss_mesh *mesh, uint32_t target_triangles, sss_mesh *out, sss_error *err)
{
    memset(out, 0, sizeof *out);
    if (!mesh || !mesh->positions || !mesh->indices || mesh->vertex_count == 0 || mesh->triangle_count == 0)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "simplify: empty mesh");
    if (target_triangles == 0)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "simplify: the target must be at least 1 triangle");
    size_t nv = mesh->vertex_count, index_count = (size_t)mesh->triangle_count * 3;
    for (size_t i = 0; i < index_count; i++)
        if (mesh->indices[i] >= nv)
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "simplify: triangle %zu: index out of range", i / 3);
    unsigned int *dst = malloc(index_count * sizeof *dst); /* meshoptimizer may use up to index_count */
    uint32_t *remap = malloc(nv * sizeof *remap);
    if (!dst || !remap) {
        free(dst);
        free(remap);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "simplify: out of memory");
    }
    size_t target = (size_t)target_triangles * 3, n;
    if (target >= index_count) {
        memcpy(dst, mesh->indices, index_count * sizeof *dst);
        n = index_count;
    } else {
        n = meshopt_simplify(dst, mesh->indices, index_count, mesh->positions, nv, 3 * sizeof(float), target,
                             SIMPLIFY_MAX_ERROR, 0, NULL);
        /* The sloppy pass may overshoot its goal slightly: lower the goal until the result fits. */
        size_t goal = target;
        for (int attempt = 0; n > target && attempt < 16 && goal >= 3; attempt++) {
            n = meshopt_simplifySloppy(dst, mesh->indices, index_count, mesh->positions, nv, 3 * sizeof(float), goal,
                                       SIMPLIFY_MAX_ERROR, NULL);
            goal = goal * 3 / 4 / 3 * 3;
        }
    }
    /* Collapses can leave triangles with collinear corners: they add nothing but trouble (zero-length
     * face normals downstream), so drop them. */
    size_t good = 0;
    for (size_t i = 0; i < n; i += 3)
        if (!mesh_triangle_degenerate(mesh->positions, dst[i], dst[i + 1], dst[i + 2])) {
            memmove(dst + good, dst + i, 3 * sizeof *dst);
            good += 3;
        }
    n = good;
    sss_result r = SSS_OK;
    if (n > target)
        r = sss_error_set(err, SSS_ERROR_NUMERIC, "simplify: could not reach %u triangles (best %zu)", target_triangles,
                          n / 3);
    else if (n == 0)
        r = sss_error_set(err, SSS_ERROR_NUMERIC, "simplify: %u triangles is too few for this mesh (nothing left)",
                          target_triangles);
    uint32_t kept = 0;
    if (r == SSS_OK) {
        /* Compact: number the vertices the result uses in order of first use. */
        memset(remap, 0xff, nv * sizeof *remap);
        for (size_t i = 0; i < n; i++)
            if (remap[dst[i]] == UINT32_MAX) remap[dst[i]] = kept++;
        r = mesh_alloc(out, kept, (uint32_t)(n / 3), 1, mesh->uvs != NULL, "simplify", err);
    }
    if (r == SSS_OK) {
        for (size_t v = 0; v < nv; v++) {
            uint32_t w = remap[v];
            if (w == UINT32_MAX) continue;
            memcpy(out->positions + 3 * (size_t)w, mesh->positions + 3 * v, 3 * sizeof(float));
            if (out->uvs) memcpy(out->uvs + 2 * (size_t)w, mesh->uvs + 2 * v, 2 * sizeof(float));
        }
        for (size_t i = 0; i < n; i++) out->indices[i] = remap[dst[i]];
        out->source_flags = mesh->source_flags & SSS_MESH_FROM_FILE_UVS;
        r = sss_mesh_compute_normals(out, err);
    }
    free(dst);
    free(remap);
    if (r != SSS_OK) sss_mesh_free(out);
    return r;
}
