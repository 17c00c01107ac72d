/* The bundled assets: readable, sane, wound counter-clockwise outward (signed volume > 0) with
 * normals on the outer side, triangle counts within the ranges asked of them, the bunny a closed
 * genus-0 surface (Euler characteristic 2), and simplification of the dragon keeping its extent. */
#include <stdio.h>

#include "check.h"
#include "mesh_test_util.h"
#include "sss/mesh.h"

#define ASSETS SSS_SOURCE_DIR "/assets/"

typedef struct asset {
    const char *file;
    uint32_t min_triangles, max_triangles;
    int solid; /* the head is a hollow shell: its inner wall's normals face the centroid */
} asset;

static const asset assets[] = {
    {"bunny.ply", 1000, 10000, 1},
    {"dragon.ply", 90000, 100000, 1},   /* "around 100k" */
    {"dragon_low.ply", 5000, 12000, 1}, /* "~5-10k", the lowest shipped resolution */
    {"head.ply", 10000, 200000, 0},
};

/* Fraction of vertices whose normal points away from the centroid of the mesh: for these star-ish
 * shapes most of them must (a mesh turned inside out would give nearly none). */
static double outward_fraction(const sss_mesh *m)
{
    double c[3] = {0, 0, 0};
    for (size_t v = 0; v < m->vertex_count; v++)
        for (int k = 0; k < 3; k++) c[k] += m->positions[3 * v + (size_t)k] / m->vertex_count;
    size_t out = 0;
    for (size_t v = 0; v < m->vertex_count; v++) {
        double d = 0;
        for (int k = 0; k < 3; k++) d += (m->positions[3 * v + (size_t)k] - c[k]) * m->normals[3 * v + (size_t)k];
        out += d > 0;
    }
    return (double)out / m->vertex_count;
}

int main(void)
{
    for (size_t i = 0; i < sizeof assets / sizeof assets[0]; i++) {
        char path[1024];
        snprintf(path, sizeof path, "%s%s", ASSETS, assets[i].file);
        sss_mesh m;
        sss_error err = {0};
        sss_result r = sss_mesh_read(path, &m, &err);
        CHECK_MSG(r == SSS_OK, "%s", err.message);
        if (r != SSS_OK) continue;
        CHECK_MSG(m.triangle_count >= assets[i].min_triangles && m.triangle_count <= assets[i].max_triangles,
                  "%s: %u triangles", assets[i].file, m.triangle_count);
        CHECK_MSG(mesh_is_sane(&m), "%s: sane", assets[i].file);
        CHECK_MSG(m.source_flags & SSS_MESH_FROM_FILE_NORMALS, "%s: normals stored", assets[i].file);
        CHECK_MSG(sss_mesh_signed_volume(&m) > 0, "%s: counter-clockwise outward", assets[i].file);
        double f = outward_fraction(&m);
        if (assets[i].solid) CHECK_MSG(f > 0.6, "%s: only %.2f of the normals point away from the centroid", assets[i].file, f);
        /* stored normals agree with the winding */
        sss_mesh copy = m;
        copy.normals = malloc(sizeof(float) * 3 * m.vertex_count);
        if (copy.normals && sss_mesh_compute_normals(&copy, NULL) == SSS_OK) {
            size_t agree = 0;
            for (size_t v = 0; v < m.vertex_count; v++) {
                double d = 0;
                for (int k = 0; k < 3; k++) d += (double)m.normals[3 * v + (size_t)k] * copy.normals[3 * v + (size_t)k];
                agree += d > 0.99;
            }
            CHECK_MSG(agree == m.vertex_count, "%s: %zu of %u stored normals match the winding", assets[i].file, agree,
                      m.vertex_count);
        }
        free(copy.normals);
        sss_mesh_topology topo;
        CHECK(sss_mesh_topology_compute(&m, &topo, NULL) == SSS_OK);
        CHECK_MSG(topo.degenerate_triangles == 0, "%s: degenerate triangles", assets[i].file);
        if (i == 0) {
            CHECK(topo.boundary_edges == 0 && topo.nonmanifold_edges == 0);
            long long chi = (long long)m.vertex_count - (long long)topo.edge_count + m.triangle_count;
            CHECK_MSG(chi == 2, "bunny: V - E + F = %lld", chi);
        }
        if (i == 1) {
            sss_mesh s;
            r = sss_mesh_simplify(&m, 5000, &s, &err);
            CHECK_MSG(r == SSS_OK, "%s", err.message);
            if (r == SSS_OK) {
                CHECK(s.triangle_count <= 5000 && s.triangle_count >= 4000 && mesh_is_sane(&s));
                float lo0[3], hi0[3], lo[3], hi[3];
                sss_mesh_bounds(&m, lo0, hi0);
                sss_mesh_bounds(&s, lo, hi);
                for (int k = 0; k < 3; k++)
                    CHECK(fabs(lo[k] - lo0[k]) < 0.03 * (hi0[k] - lo0[k]) && fabs(hi[k] - hi0[k]) < 0.03 * (hi0[k] - lo0[k]));
                CHECK_REL(sss_mesh_surface_area(&s), sss_mesh_surface_area(&m), 0.1);
                sss_mesh_free(&s);
            }
        }
        sss_mesh_free(&m);
    }
    return CHECK_DONE();
}
