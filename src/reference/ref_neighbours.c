/* reference/ref_neighbours.c — for every transport sample of a subsurface object, the transport samples
 * within a radius of it on the same side (ref_bounce.c averages their T for the near part of the
 * exitance). A hash grid of cells as wide as the radius: the neighbours lie in the 27 cells around. */
#include <stdlib.h>

#include "reference/ref_internal.h"

typedef struct grid {
    double inv_cell;
    size_t mask;    /* table size - 1 (a power of two) */
    uint32_t *head; /* per hash slot: the last sample inserted, or UINT32_MAX */
    uint32_t *next; /* per sample: the one inserted before it in its slot */
} grid;

static void cell_of(const grid *g, const float p[3], int64_t c[3])
{
    for (int k = 0; k < 3; k++) c[k] = (int64_t)floor(p[k] * g->inv_cell);
}

static size_t slot_of(const grid *g, const int64_t c[3])
{
    uint64_t h = (uint64_t)c[0] * 73856093ull ^ (uint64_t)c[1] * 19349663ull ^ (uint64_t)c[2] * 83492791ull;
    return (size_t)(ref_hash64(h) & g->mask);
}

/* Sample i's neighbours (itself included) into out (may be NULL: counts only); returns the count.
 * The order is fixed by the insertion order, so sums over them do not depend on the threads. */
static uint32_t neighbours_of(const grid *g, const ref_bsample *bs, size_t i, double radius, uint32_t *out)
{
    int64_t c[3];
    cell_of(g, bs[i].p, c);
    uint32_t count = 0;
    for (int k = 0; k < 27; k++) {
        int64_t d[3] = {c[0] + k % 3 - 1, c[1] + (k / 3) % 3 - 1, c[2] + k / 9 - 1};
        for (uint32_t j = g->head[slot_of(g, d)]; j != UINT32_MAX; j = g->next[j]) {
            int64_t cj[3];
            cell_of(g, bs[j].p, cj);
            if (cj[0] != d[0] || cj[1] != d[1] || cj[2] != d[2]) continue; /* another cell in the slot */
            double r2 = 0.0, dot = 0.0;
            for (int a = 0; a < 3; a++) {
                double e = (double)bs[j].p[a] - bs[i].p[a];
                r2 += e * e;
                dot += (double)bs[j].ng[a] * bs[i].ng[a];
            }
            if (r2 > radius * radius || dot < 0.5) continue; /* farther, or the other side of a thin part */
            if (out) out[count] = j;
            count++;
        }
    }
    return count;
}

sss_result ref_neighbours_build(ref_object *ro, double radius, sss_error *err)
{
    const size_t n = ro->bs_count;
    grid g = {1.0 / radius, 1, NULL, NULL};
    while (g.mask + 1 < 2 * n) g.mask = 2 * g.mask + 1;
    g.head = malloc(sizeof(uint32_t) * (g.mask + 1));
    g.next = malloc(sizeof(uint32_t) * (n ? n : 1));
    ro->nb_offset = calloc(n + 1, sizeof(uint64_t));
    if (!g.head || !g.next || !ro->nb_offset) {
        free(g.head), free(g.next);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "reference: out of memory (sample neighbours)");
    }
    for (size_t s = 0; s <= g.mask; s++) g.head[s] = UINT32_MAX;
    for (size_t i = 0; i < n; i++) {
        int64_t c[3];
        cell_of(&g, ro->bs[i].p, c);
        size_t s = slot_of(&g, c);
        g.next[i] = g.head[s];
        g.head[s] = (uint32_t)i;
    }
#pragma omp parallel for schedule(dynamic, 1024)
    for (int64_t i = 0; i < (int64_t)n; i++) ro->nb_offset[i + 1] = neighbours_of(&g, ro->bs, (size_t)i, radius, NULL);
    for (size_t i = 0; i < n; i++) ro->nb_offset[i + 1] += ro->nb_offset[i];
    ro->nb_index = malloc(sizeof(uint32_t) * (ro->nb_offset[n] ? ro->nb_offset[n] : 1));
    if (ro->nb_index) {
#pragma omp parallel for schedule(dynamic, 1024)
        for (int64_t i = 0; i < (int64_t)n; i++)
            neighbours_of(&g, ro->bs, (size_t)i, radius, ro->nb_index + ro->nb_offset[i]);
    }
    free(g.head), free(g.next);
    if (!ro->nb_index) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "reference: out of memory (sample neighbours)");
    return SSS_OK;
}
