/* mesh/adjacency.c — vertex adjacency (one-ring neighbours) in compressed sparse rows. */
#include <stdlib.h>
#include <string.h>

#include "mesh/mesh_internal.h"

static int cmp_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return x < y ? -1 : x > y;
}

sss_result sss_mesh_adjacency_build(const sss_mesh *mesh, sss_mesh_adjacency *out, sss_error *err)
{
    memset(out, 0, sizeof *out);
    uint32_t nv = mesh->vertex_count;
    size_t nt = mesh->triangle_count;
    for (size_t i = 0; i < nt * 3; i++)
        if (mesh->indices[i] >= nv)
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "mesh: triangle %zu: index %u out of range", i / 3,
                                 mesh->indices[i]);
    /* Each triangle edge is entered in both rows; duplicates (edges shared by two triangles) are
     * removed after sorting each row. 6 * SSS_MESH_MAX_TRIANGLES < 2^32, so offsets fit in 32 bits. */
    size_t *start = calloc((size_t)nv + 1, sizeof *start);
    uint32_t *nbr = malloc((nt * 6 + 1) * sizeof *nbr);
    uint32_t *offsets = malloc(((size_t)nv + 1) * sizeof *offsets);
    if (!start || !nbr || !offsets) {
        free(start);
        free(nbr);
        free(offsets);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "mesh: out of memory for adjacency");
    }
    for (size_t t = 0; t < nt; t++)
        for (int k = 0; k < 3; k++) {
            uint32_t a = mesh->indices[3 * t + (size_t)k], b = mesh->indices[3 * t + (size_t)(k + 1) % 3];
            if (a == b) continue;
            start[a + 1]++;
            start[b + 1]++;
        }
    for (uint32_t v = 0; v < nv; v++) start[v + 1] += start[v];
    size_t *fill = malloc(((size_t)nv + 1) * sizeof *fill);
    if (!fill) {
        free(start);
        free(nbr);
        free(offsets);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "mesh: out of memory for adjacency");
    }
    memcpy(fill, start, ((size_t)nv + 1) * sizeof *fill);
    for (size_t t = 0; t < nt; t++)
        for (int k = 0; k < 3; k++) {
            uint32_t a = mesh->indices[3 * t + (size_t)k], b = mesh->indices[3 * t + (size_t)(k + 1) % 3];
            if (a == b) continue;
            nbr[fill[a]++] = b;
            nbr[fill[b]++] = a;
        }
    free(fill);
    /* Sort and deduplicate each row, compacting in place (rows only move left). */
    size_t w = 0;
    for (uint32_t v = 0; v < nv; v++) {
        size_t s = start[v], e = start[v + 1];
        qsort(nbr + s, e - s, sizeof *nbr, cmp_u32);
        offsets[v] = (uint32_t)w;
        for (size_t i = s; i < e; i++)
            if (w == offsets[v] || nbr[i] != nbr[w - 1]) nbr[w++] = nbr[i];
    }
    offsets[nv] = (uint32_t)w;
    free(start);
    uint32_t *shrunk = realloc(nbr, (w + 1) * sizeof *nbr);
    out->vertex_count = nv;
    out->offsets = offsets;
    out->neighbors = shrunk ? shrunk : nbr;
    return SSS_OK;
}

void sss_mesh_adjacency_free(sss_mesh_adjacency *adj)
{
    if (!adj) return;
    free(adj->offsets);
    free(adj->neighbors);
    memset(adj, 0, sizeof *adj);
}
