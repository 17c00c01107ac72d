/* sam/sam_update.c — deforming meshes (Maisch & Ropinski 2017, section 3.4): the approximate form factors of Eq. 15
 * (K' times the current fan area and R_d at the current vertex distance) and the per-frame move of
 * each link to a better one-ring neighbour. src/gl/techniques/sam/sam_vertex.comp.glsl does the same on the GPU.
 * With a back-side mesh (sam_back.c) the links, their one-rings and the fan areas are the back-side
 * mesh's; the receivers stay the mesh's vertices. */
#include <math.h>
#include <string.h>

#include "sam/sam_internal.h"

/* F'_j R_d(|v_j - v_o|) summed over channels for receiver o of m and source j of src; -1 when j fails
 * Eq. 13-14. */
static double score(const sss_mesh *m, const sss_mesh *src, const float *area, const sss_sam_profile_table *t,
                    uint32_t o, uint32_t j)
{
    const float *xo = m->positions + 3 * (size_t)o, *xj = src->positions + 3 * (size_t)j;
    if (!sss_sam_is_back(xo, m->normals + 3 * (size_t)o, xj, src->normals + 3 * (size_t)j)) return -1.0;
    double dx = xj[0] - xo[0], dy = xj[1] - xo[1], dz = xj[2] - xo[2], rd[3];
    sss_sam_profile_table_eval(t, sqrt(dx * dx + dy * dy + dz * dz), rd);
    return area[j] * (rd[0] + rd[1] + rd[2]);
}

/* The update of section 3.4 with sources `src` (the deformed mesh itself or the back-side mesh),
 * their adjacency and (deformed) fan areas. */
static uint64_t update_links(sss_sam *sam, const sss_mesh *deformed, const sss_mesh *src, int same,
                             const sss_mesh_adjacency *adj, const sss_sam_profile_table *table, const float *area)
{
    uint64_t moved = 0;
    uint32_t n = sam->n;
    for (uint32_t o = 0; o < sam->vertex_count; o++) {
        uint32_t *links = sam->links + (size_t)o * n;
        for (uint32_t k = 0; k < n; k++) {
            uint32_t b = links[k];
            if (b == SSS_SAM_NONE) continue;
            uint32_t best = b;
            double best_s = score(deformed, src, area, table, o, b);
            for (uint32_t e = adj->offsets[b]; e < adj->offsets[b + 1]; e++) {
                uint32_t j = adj->neighbors[e];
                int taken = 0;
                for (uint32_t q = 0; q < n && !taken; q++) taken = links[q] == j;
                if (taken || (same && j == o)) continue;
                double s = score(deformed, src, area, table, o, j);
                if (s > best_s) {
                    best_s = s;
                    best = j;
                }
            }
            /* A link with no valid candidate stays (it may become valid again) and contributes 0. */
            if (best != b) {
                links[k] = best;
                moved++;
            }
        }
    }
    return moved;
}

uint64_t sss_sam_update(sss_sam *sam, const sss_mesh *deformed, const sss_mesh_adjacency *adj,
                        const sss_sam_profile_table *table, float *fan_area)
{
    if (!sam || sam->back_vertex_count || !deformed || !adj || !table || deformed->vertex_count != sam->vertex_count ||
        adj->vertex_count != sam->vertex_count)
        return 0;
    float *area = fan_area;
    if (!area) area = sam->fan_area; /* no room given: score with the rest areas */
    else sss_sam_fan_areas(deformed, area); /* Eq. 16 on the deformed positions */
    return update_links(sam, deformed, deformed, 1, adj, table, area);
}

uint64_t sss_sam_update_back(sss_sam *sam, const sss_mesh *deformed, const sss_mesh *back,
                             const sss_mesh_adjacency *back_adj, const sss_sam_profile_table *table,
                             float *back_fan_area)
{
    if (!back) return sss_sam_update(sam, deformed, back_adj, table, back_fan_area);
    if (!sam || !sam->back_vertex_count || !deformed || !back_adj || !table || deformed->vertex_count != sam->vertex_count ||
        back->vertex_count != sam->back_vertex_count || back_adj->vertex_count != sam->back_vertex_count)
        return 0;
    float *area = back_fan_area;
    if (!area) area = sam->back_fan_area;
    else sss_sam_fan_areas(back, area); /* Eq. 16 on the deformed back-side mesh */
    return update_links(sam, deformed, back, 0, back_adj, table, area);
}

/* Eq. 15 for every slot with sources `src` and their fan areas. */
static void approximate(const sss_sam *sam, const sss_mesh *mesh, const sss_mesh *src, const float *area,
                        const sss_sam_profile_table *table, float *out)
{
    for (uint32_t o = 0; o < sam->vertex_count; o++)
        for (uint32_t k = 0; k < sam->n; k++) {
            size_t slot = (size_t)o * sam->n + k;
            uint32_t b = sam->links[slot];
            for (int c = 0; c < 3; c++) out[3 * slot + c] = 0.0f;
            if (b == SSS_SAM_NONE || b >= src->vertex_count) continue;
            const float *xo = mesh->positions + 3 * (size_t)o, *xb = src->positions + 3 * (size_t)b;
            if (!sss_sam_is_back(xo, mesh->normals + 3 * (size_t)o, xb, src->normals + 3 * (size_t)b)) continue;
            double dx = xb[0] - xo[0], dy = xb[1] - xo[1], dz = xb[2] - xo[2], rd[3];
            sss_sam_profile_table_eval(table, sqrt(dx * dx + dy * dy + dz * dz), rd);
            for (int c = 0; c < 3; c++) out[3 * slot + c] = (float)(sam->kprime[3 * slot + c] * area[b] * rd[c]);
        }
}

void sss_sam_approximate(const sss_sam *sam, const sss_mesh *mesh, const float *fan_area,
                         const sss_sam_profile_table *table, float *out)
{
    if (sam->back_vertex_count) {
        memset(out, 0, sizeof(float) * 3 * (size_t)sam->vertex_count * sam->n);
        return;
    }
    approximate(sam, mesh, mesh, fan_area ? fan_area : sam->fan_area, table, out);
}

void sss_sam_approximate_back(const sss_sam *sam, const sss_mesh *mesh, const sss_mesh *back,
                              const float *back_fan_area, const sss_sam_profile_table *table, float *out)
{
    if (!back) {
        sss_sam_approximate(sam, mesh, back_fan_area, table, out);
        return;
    }
    if (!sam->back_vertex_count || back->vertex_count != sam->back_vertex_count) {
        memset(out, 0, sizeof(float) * 3 * (size_t)sam->vertex_count * sam->n);
        return;
    }
    approximate(sam, mesh, back, back_fan_area ? back_fan_area : sam->back_fan_area, table, out);
}
