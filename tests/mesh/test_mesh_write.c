/* PLY writer: write then read gives identical positions, normals, UVs and indices (binary float32 is
 * exact); the file is binary little-endian whatever the host; bad meshes and bad paths fail without
 * leaving a file behind. */
#include <stdio.h>
#include <unistd.h>

#include "check.h"
#include "mesh_test_util.h"
#include "sss/mesh.h"

static const char *const OUT = "test_mesh_write_out.ply";

static void round_trip(const sss_mesh *m, const char *label)
{
    sss_error err = {0};
    sss_result r = sss_mesh_write_ply(OUT, m, &err);
    CHECK_MSG(r == SSS_OK, "%s: %s", label, err.message);
    sss_mesh back;
    r = sss_mesh_read(OUT, &back, &err);
    CHECK_MSG(r == SSS_OK, "%s: %s", label, err.message);
    if (r != SSS_OK) return;
    CHECK(back.vertex_count == m->vertex_count && back.triangle_count == m->triangle_count);
    if (back.vertex_count == m->vertex_count && back.triangle_count == m->triangle_count) {
        CHECK_MSG(memcmp(back.positions, m->positions, (size_t)m->vertex_count * 12) == 0, "%s: positions", label);
        CHECK_MSG(memcmp(back.indices, m->indices, (size_t)m->triangle_count * 12) == 0, "%s: indices", label);
        /* unit normals survive normalisation on reading up to rounding */
        double worst = 0.0;
        for (size_t i = 0; i < (size_t)m->vertex_count * 3; i++) worst = fmax(worst, fabs(back.normals[i] - m->normals[i]));
        CHECK_MSG(worst < 1e-6, "%s: normals differ by %g", label, worst);
        CHECK(back.source_flags & SSS_MESH_FROM_FILE_NORMALS);
        CHECK((back.uvs != NULL) == (m->uvs != NULL));
        if (back.uvs && m->uvs) CHECK(memcmp(back.uvs, m->uvs, (size_t)m->vertex_count * 8) == 0);
    }
    sss_mesh_free(&back);
}

static void test_round_trips(void)
{
    sss_mesh m;
    if (sss_mesh_sphere(0.3, 3, &m, NULL) == SSS_OK) {
        round_trip(&m, "sphere");
        sss_mesh_free(&m);
    }
    if (sss_mesh_plane(1.0, &m, NULL) == SSS_OK) {
        round_trip(&m, "plane (uvs)");
        sss_mesh_free(&m);
    }
    if (sss_mesh_read(SSS_TEST_DATA "/meshes/cube_faces.obj", &m, NULL) == SSS_OK) {
        round_trip(&m, "obj cube");
        sss_mesh_free(&m);
    }
}

static void test_layout(void)
{
    /* one triangle: the header announces float x y z nx ny nz and uchar/uint lists, then
     * 3 * 24 + 13 bytes of little-endian data */
    float pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0}, nrm[9] = {0, 0, 1, 0, 0, 1, 0, 0, 1};
    uint32_t idx[3] = {0, 1, 2};
    sss_mesh m = {3, 1, pos, nrm, NULL, idx, 0};
    CHECK(sss_mesh_write_ply(OUT, &m, NULL) == SSS_OK);
    FILE *f = fopen(OUT, "rb");
    unsigned char buf[1024];
    size_t n = f ? fread(buf, 1, sizeof buf, f) : 0;
    if (f) fclose(f);
    buf[n < sizeof buf ? n : sizeof buf - 1] = 0;
    const char *end = strstr((const char *)buf, "end_header\n");
    CHECK(strncmp((const char *)buf, "ply\nformat binary_little_endian 1.0\n", 36) == 0);
    CHECK(strstr((const char *)buf, "property list uchar uint vertex_indices\n") != NULL);
    CHECK(end != NULL);
    if (end) {
        size_t body = (size_t)(end - (const char *)buf) + 11;
        CHECK(n - body == 3 * 24 + 13);
        /* vertex 1's x = 1.0f = 0x3f800000, little-endian */
        CHECK(buf[body + 24] == 0x00 && buf[body + 25] == 0x00 && buf[body + 26] == 0x80 && buf[body + 27] == 0x3f);
        CHECK(buf[body + 72] == 3 && buf[body + 73 + 4] == 1 && buf[body + 73 + 8] == 2);
    }
}

static void test_failures(void)
{
    float pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    uint32_t idx[3] = {0, 1, 3};
    sss_mesh bad = {3, 1, pos, NULL, NULL, idx, 0};
    sss_error err = {0};
    remove("test_mesh_write_bad.ply");
    CHECK(sss_mesh_write_ply("test_mesh_write_bad.ply", &bad, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(err.message, "test_mesh_write_bad.ply") != NULL);
    CHECK(access("test_mesh_write_bad.ply", F_OK) != 0);
    idx[2] = 2;
    pos[4] = NAN;
    CHECK(sss_mesh_write_ply("test_mesh_write_bad.ply", &bad, &err) == SSS_ERROR_NUMERIC);
    CHECK(access("test_mesh_write_bad.ply", F_OK) != 0);
    sss_mesh empty = {0};
    CHECK(sss_mesh_write_ply("test_mesh_write_bad.ply", &empty, &err) == SSS_ERROR_INVALID_ARGUMENT);
    pos[4] = 0;
    CHECK(sss_mesh_write_ply("no-such-dir/x.ply", &bad, &err) == SSS_ERROR_IO);
    CHECK(strstr(err.message, "no-such-dir/x.ply") != NULL);
}

int main(void)
{
    test_round_trips();
    test_layout();
    test_failures();
    remove(OUT);
    return CHECK_DONE();
}
