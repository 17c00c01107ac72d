/* Simplification: at most the target triangles, valid indices, no unused vertices, unit normals,
 * and the shape kept (bounding box and area close to the original's); the sloppy fallback reaches
 * targets the topology-preserving pass cannot; impossible targets fail instead of giving nothing. */
#include <stdio.h>

#include "check.h"
#include "mesh_test_util.h"
#include "sss/mesh.h"

static void check_result(const sss_mesh *orig, const sss_mesh *s, uint32_t target, double bbox_tol, const char *label)
{
    CHECK_MSG(s->triangle_count <= target && s->triangle_count > 0, "%s: %u triangles for target %u", label,
              s->triangle_count, target);
    CHECK_MSG(mesh_is_sane(s), "%s: indices, positions, normals", label);
    /* compaction: every vertex is used */
    char *used = calloc(s->vertex_count, 1);
    if (used) {
        for (size_t i = 0; i < (size_t)s->triangle_count * 3; i++) used[s->indices[i]] = 1;
        int all = 1;
        for (size_t v = 0; v < s->vertex_count; v++) all &= used[v];
        CHECK_MSG(all, "%s: no unused vertices", label);
        free(used);
    }
    float lo0[3], hi0[3], lo[3], hi[3];
    sss_mesh_bounds(orig, lo0, hi0);
    sss_mesh_bounds(s, lo, hi);
    double diag = sqrt(pow(hi0[0] - lo0[0], 2) + pow(hi0[1] - lo0[1], 2) + pow(hi0[2] - lo0[2], 2));
    double worst = 0.0;
    for (int k = 0; k < 3; k++) worst = fmax(worst, fmax(fabs(lo[k] - lo0[k]), fabs(hi[k] - hi0[k])));
    CHECK_MSG(worst <= bbox_tol * diag, "%s: bounding box moved by %.3g of the diagonal", label, worst / diag);
    CHECK((s->uvs != NULL) == (orig->uvs != NULL));
    sss_mesh_topology topo;
    CHECK(sss_mesh_topology_compute(s, &topo, NULL) == SSS_OK);
    CHECK_MSG(topo.degenerate_triangles == 0, "%s: %llu degenerate triangles", label,
              (unsigned long long)topo.degenerate_triangles);
}

static void test_sphere(void)
{
    sss_mesh m, s;
    sss_error err = {0};
    if (sss_mesh_sphere(1.0, 5, &m, &err) != SSS_OK) {
        CHECK(0);
        return;
    }
    static const uint32_t targets[] = {10000, 1000, 200, 50};
    for (size_t i = 0; i < sizeof targets / sizeof targets[0]; i++) {
        char label[64];
        snprintf(label, sizeof label, "sphere -> %u", targets[i]);
        sss_result r = sss_mesh_simplify(&m, targets[i], &s, &err);
        CHECK_MSG(r == SSS_OK, "%s: %s", label, err.message);
        if (r != SSS_OK) continue;
        check_result(&m, &s, targets[i], 0.1, label);
        /* still a closed outward surface of about the sphere's size */
        CHECK(sss_mesh_signed_volume(&s) > 0);
        CHECK_REL(sss_mesh_surface_area(&s), sss_mesh_surface_area(&m), targets[i] >= 1000 ? 0.02 : 0.25);
        if (targets[i] >= 1000) CHECK(s.triangle_count >= targets[i] * 9 / 10); /* close to the target, not far below */
        sss_mesh_free(&s);
    }
    /* a target at or above the count leaves the mesh as it is */
    if (sss_mesh_simplify(&m, m.triangle_count + 5, &s, &err) == SSS_OK) {
        CHECK(s.triangle_count == m.triangle_count && s.vertex_count == m.vertex_count);
        sss_mesh_free(&s);
    }
    CHECK(sss_mesh_simplify(&m, 0, &s, &err) == SSS_ERROR_INVALID_ARGUMENT);
    sss_mesh_free(&m);
}

/* A sphere as a triangle soup (every triangle has its own three vertices): every edge is a border,
 * so the topology-preserving pass cannot collapse anything; only the sloppy fallback (vertex
 * clustering) reaches the target. */
static void test_fallback(void)
{
    sss_mesh sphere;
    if (sss_mesh_sphere(1.0, 4, &sphere, NULL) != SSS_OK) {
        CHECK(0);
        return;
    }
    sss_mesh m = {0};
    m.vertex_count = sphere.triangle_count * 3;
    m.triangle_count = sphere.triangle_count;
    m.positions = malloc(sizeof(float) * 3 * m.vertex_count);
    m.indices = malloc(sizeof(uint32_t) * 3 * m.triangle_count);
    if (!m.positions || !m.indices) {
        CHECK(0);
        sss_mesh_free(&m);
        sss_mesh_free(&sphere);
        return;
    }
    for (uint32_t i = 0; i < m.vertex_count; i++) {
        memcpy(m.positions + 3 * (size_t)i, sphere.positions + 3 * (size_t)sphere.indices[i], 3 * sizeof(float));
        m.indices[i] = i;
    }
    CHECK(sss_mesh_compute_normals(&m, NULL) == SSS_OK);
    sss_mesh s;
    sss_error err = {0};
    static const uint32_t targets[] = {2000, 500, 100};
    for (size_t i = 0; i < sizeof targets / sizeof targets[0]; i++) {
        sss_result r = sss_mesh_simplify(&m, targets[i], &s, &err);
        CHECK_MSG(r == SSS_OK, "%s", err.message);
        if (r != SSS_OK) continue;
        check_result(&m, &s, targets[i], 0.15, "soup sphere");
        CHECK(s.vertex_count < m.vertex_count);
        sss_mesh_free(&s);
    }
    /* far below what clustering can keep: an error, never an empty mesh */
    sss_result r = sss_mesh_simplify(&m, 1, &s, &err);
    if (r != SSS_OK) CHECK(s.positions == NULL && strstr(err.message, "simplify") != NULL);
    else {
        CHECK(s.triangle_count == 1);
        sss_mesh_free(&s);
    }
    sss_mesh_free(&m);
    sss_mesh_free(&sphere);
}

static void test_uvs_and_bad_input(void)
{
    sss_mesh m, s;
    sss_error err = {0};
    if (sss_mesh_torus(1.0, 0.25, 64, &m, &err) == SSS_OK) {
        /* UVs follow their vertices when present */
        m.uvs = malloc(sizeof(float) * 2 * m.vertex_count);
        for (size_t v = 0; m.uvs && v < m.vertex_count; v++) {
            m.uvs[2 * v] = m.positions[3 * v];
            m.uvs[2 * v + 1] = m.positions[3 * v + 2];
        }
        if (m.uvs && sss_mesh_simplify(&m, 1500, &s, &err) == SSS_OK) {
            check_result(&m, &s, 1500, 0.05, "torus -> 1500");
            int follow = 1;
            for (size_t v = 0; v < s.vertex_count; v++)
                follow &= s.uvs[2 * v] == s.positions[3 * v] && s.uvs[2 * v + 1] == s.positions[3 * v + 2];
            CHECK_MSG(follow, "each UV stays with its vertex");
            sss_mesh_free(&s);
        }
        sss_mesh_free(&m);
    }
    sss_mesh empty = {0};
    CHECK(sss_mesh_simplify(&empty, 10, &s, &err) == SSS_ERROR_INVALID_ARGUMENT);
    float pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    uint32_t idx[3] = {0, 1, 5};
    sss_mesh bad = {3, 1, pos, NULL, NULL, idx, 0};
    CHECK(sss_mesh_simplify(&bad, 1, &s, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(s.positions == NULL);
}

int main(void)
{
    test_sphere();
    test_fallback();
    test_uvs_and_bad_input();
    return CHECK_DONE();
}
