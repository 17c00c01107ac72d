/* Vertex adjacency: symmetric, sorted, no self loops or duplicates, every triangle edge present; on
 * closed manifold meshes the Euler characteristic V - E + F is 2 (sphere) or 0 (torus, trefoil),
 * with E counted from the adjacency and cross-checked against the topology statistics. */
#include <stdio.h>

#include "check.h"
#include "mesh_test_util.h"
#include "sss/mesh.h"

static int has_neighbor(const sss_mesh_adjacency *a, uint32_t v, uint32_t u)
{
    for (uint32_t i = a->offsets[v]; i < a->offsets[v + 1]; i++)
        if (a->neighbors[i] == u) return 1;
    return 0;
}

/* Checks the structural properties; returns the number of undirected edges. */
static uint64_t check_adjacency(const sss_mesh *m, const char *label)
{
    sss_mesh_adjacency a;
    sss_error err = {0};
    sss_result r = sss_mesh_adjacency_build(m, &a, &err);
    CHECK_MSG(r == SSS_OK, "%s: %s", label, err.message);
    if (r != SSS_OK) return 0;
    CHECK(a.vertex_count == m->vertex_count && a.offsets[0] == 0);
    int sorted = 1, no_self = 1, symmetric = 1, edges_in = 1;
    for (uint32_t v = 0; v < a.vertex_count; v++) {
        CHECK(a.offsets[v] <= a.offsets[v + 1]);
        for (uint32_t i = a.offsets[v]; i < a.offsets[v + 1]; i++) {
            uint32_t u = a.neighbors[i];
            if (i > a.offsets[v]) sorted &= a.neighbors[i - 1] < u; /* strictly: no duplicates */
            no_self &= u != v;
            symmetric &= u < a.vertex_count && has_neighbor(&a, u, v);
        }
    }
    for (uint32_t t = 0; t < m->triangle_count; t++)
        for (int k = 0; k < 3; k++) {
            uint32_t x = m->indices[3 * t + (uint32_t)k], y = m->indices[3 * t + (uint32_t)(k + 1) % 3];
            if (x != y) edges_in &= has_neighbor(&a, x, y);
        }
    CHECK_MSG(sorted, "%s: rows sorted without duplicates", label);
    CHECK_MSG(no_self, "%s: no vertex is its own neighbour", label);
    CHECK_MSG(symmetric, "%s: u in N(v) iff v in N(u)", label);
    CHECK_MSG(edges_in, "%s: every triangle edge is present", label);
    uint64_t directed = a.offsets[a.vertex_count];
    CHECK(directed % 2 == 0);
    sss_mesh_adjacency_free(&a);
    sss_mesh_adjacency_free(&a);
    return directed / 2;
}

static void check_euler(const sss_mesh *m, int expected, const char *label)
{
    uint64_t e = check_adjacency(m, label);
    long long chi = (long long)m->vertex_count - (long long)e + (long long)m->triangle_count;
    CHECK_MSG(chi == expected, "%s: V - E + F = %lld, expected %d", label, chi, expected);
    sss_mesh_topology topo;
    CHECK(sss_mesh_topology_compute(m, &topo, NULL) == SSS_OK);
    CHECK_MSG(topo.edge_count == e && topo.boundary_edges == 0 && topo.nonmanifold_edges == 0,
              "%s: closed 2-manifold (edges %llu, boundary %llu)", label, (unsigned long long)topo.edge_count,
              (unsigned long long)topo.boundary_edges);
    /* closed triangle mesh: 3F = 2E */
    CHECK(3 * (uint64_t)m->triangle_count == 2 * e);
    CHECK(topo.degenerate_triangles == 0);
}

int main(void)
{
    char label[64];
    for (int s = 0; s <= 4; s++) {
        sss_mesh m;
        if (sss_mesh_sphere(1.0, s, &m, NULL) != SSS_OK) {
            CHECK(0);
            continue;
        }
        snprintf(label, sizeof label, "sphere s=%d", s);
        check_euler(&m, 2, label);
        sss_mesh_free(&m);
    }
    for (int n = 3; n <= 48; n += 9) {
        sss_mesh m;
        if (sss_mesh_torus(2.0, 0.5, n, &m, NULL) != SSS_OK) {
            CHECK(0);
            continue;
        }
        snprintf(label, sizeof label, "torus n=%d", n);
        check_euler(&m, 0, label);
        sss_mesh_free(&m);
    }
    sss_mesh m;
    if (sss_mesh_trefoil(1.0, 0.1, 96, &m, NULL) == SSS_OK) {
        check_euler(&m, 0, "trefoil");
        sss_mesh_free(&m);
    }
    /* the welded 1 x 2 x 3 box read from ascii PLY is a closed genus-0 surface */
    if (sss_mesh_read(SSS_TEST_DATA "/meshes/box_ascii.ply", &m, NULL) == SSS_OK) {
        check_euler(&m, 2, "box_ascii.ply");
        sss_mesh_free(&m);
    }
    /* the procedural box has split (flat-shaded) corners: six separate quads, open */
    const double size[3] = {1, 1, 1};
    if (sss_mesh_box(size, &m, NULL) == SSS_OK) {
        CHECK(check_adjacency(&m, "box") == 6 * 5);
        sss_mesh_topology topo;
        CHECK(sss_mesh_topology_compute(&m, &topo, NULL) == SSS_OK && topo.boundary_edges == 24);
        sss_mesh_free(&m);
    }
    /* degenerate triangles (repeated index) add no self loops; a lone vertex has no neighbours */
    float pos[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 5, 5, 5};
    uint32_t idx[6] = {0, 1, 2, 1, 1, 2};
    sss_mesh d = {4, 2, pos, NULL, NULL, idx, 0};
    check_adjacency(&d, "degenerate");
    sss_mesh_adjacency a;
    if (sss_mesh_adjacency_build(&d, &a, NULL) == SSS_OK) {
        CHECK(a.offsets[4] - a.offsets[3] == 0);
        CHECK(a.offsets[2] - a.offsets[1] == 2);
        sss_mesh_adjacency_free(&a);
    }
    sss_mesh_topology topo;
    CHECK(sss_mesh_topology_compute(&d, &topo, NULL) == SSS_OK && topo.degenerate_triangles == 1);
    /* an index out of range is refused */
    idx[5] = 7;
    CHECK(sss_mesh_adjacency_build(&d, &a, NULL) == SSS_ERROR_INVALID_ARGUMENT);
    return CHECK_DONE();
}
