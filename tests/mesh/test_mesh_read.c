/* The readers on small hand-written files: counts, coordinates and faces as written in the file
 * (ascii PLY, binary little- and big-endian PLY built byte by byte here, OBJ with every face syntax). */
#include <stdio.h>

#include "check.h"
#include "mesh_test_util.h"
#include "sss/mesh.h"

#define DATA SSS_TEST_DATA "/meshes/"

static int tri_equals(const sss_mesh *m, uint32_t t, uint32_t a, uint32_t b, uint32_t c)
{
    const uint32_t *x = m->indices + 3 * (size_t)t;
    return x[0] == a && x[1] == b && x[2] == c;
}

static void test_ascii_box(void)
{
    sss_mesh m;
    sss_error err = {0};
    sss_result r = sss_mesh_read(DATA "box_ascii.ply", &m, &err);
    CHECK_MSG(r == SSS_OK, "%s", err.message);
    if (r != SSS_OK) return;
    CHECK(m.vertex_count == 8);
    CHECK(m.triangle_count == 12); /* six quads, fan-triangulated */
    static const float expect[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 2, 0}, {0, 2, 0},
                                       {0, 0, 3}, {1, 0, 3}, {1, 2, 3}, {0, 2, 3}};
    int same = 1;
    for (int v = 0; v < 8; v++)
        for (int k = 0; k < 3; k++) same &= m.positions[3 * v + k] == expect[v][k];
    CHECK_MSG(same, "positions as written (the skipped 'confidence' property sits between y and z)");
    static const uint32_t quads[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                         {3, 7, 6, 2}, {0, 4, 7, 3}, {1, 2, 6, 5}};
    int fans = 1;
    for (int f = 0; f < 6; f++) {
        fans &= tri_equals(&m, 2 * (uint32_t)f, quads[f][0], quads[f][1], quads[f][2]);
        fans &= tri_equals(&m, 2 * (uint32_t)f + 1, quads[f][0], quads[f][2], quads[f][3]);
    }
    CHECK_MSG(fans, "each quad becomes (a b c) (a c d)");
    CHECK(m.uvs == NULL);
    CHECK(m.source_flags == 0);
    CHECK(mesh_is_sane(&m));
    /* A closed 1 x 2 x 3 box: closed-form area and volume. */
    CHECK_NEAR(sss_mesh_surface_area(&m), 2.0 * (1 * 2 + 2 * 3 + 1 * 3), 1e-9);
    CHECK_NEAR(sss_mesh_signed_volume(&m), 6.0, 1e-9);
    float lo[3], hi[3];
    sss_mesh_bounds(&m, lo, hi);
    CHECK(lo[0] == 0 && lo[1] == 0 && lo[2] == 0 && hi[0] == 1 && hi[1] == 2 && hi[2] == 3);
    sss_mesh_free(&m);
    CHECK(m.positions == NULL && m.vertex_count == 0);
    sss_mesh_free(&m); /* twice is harmless */
}

static void test_ascii_normals_uv(void)
{
    sss_mesh m;
    sss_error err = {0};
    sss_result r = sss_mesh_read(DATA "tetra_normals_uv.ply", &m, &err);
    CHECK_MSG(r == SSS_OK, "%s", err.message);
    if (r != SSS_OK) return;
    CHECK(m.vertex_count == 4 && m.triangle_count == 4);
    CHECK(m.source_flags == (SSS_MESH_FROM_FILE_NORMALS | SSS_MESH_FROM_FILE_UVS));
    CHECK(m.uvs != NULL);
    if (m.uvs) {
        CHECK(m.uvs[0] == 0.0f && m.uvs[1] == 0.0f && m.uvs[2] == 1.0f && m.uvs[3] == 0.0f);
        CHECK(m.uvs[4] == 0.0f && m.uvs[5] == 1.0f && m.uvs[6] == 0.5f && m.uvs[7] == 0.5f);
    }
    CHECK(tri_equals(&m, 0, 0, 2, 1) && tri_equals(&m, 3, 1, 2, 3));
    /* Given normals are normalised: (-2,-2,-2) -> -(1,1,1)/sqrt 3, (0,3,0) -> +y, (0,0,0.5) -> +z. */
    double s = 1.0 / sqrt(3.0);
    CHECK_NEAR(m.normals[0], -s, 1e-6);
    CHECK_NEAR(m.normals[1], -s, 1e-6);
    CHECK_NEAR(m.normals[2], -s, 1e-6);
    CHECK_NEAR(m.normals[7], 1.0, 1e-6);
    CHECK_NEAR(m.normals[11], 1.0, 1e-6);
    /* Vertex 1's zero normal is recomputed, area-weighted: faces -z and -y (area 1/2 each) and the
     * slanted face (area sqrt(3)/2, normal (1,1,1)/sqrt 3) sum to (1/2, 0, 0) by hand -> +x. */
    CHECK_NEAR(m.normals[3], 1.0, 1e-6);
    CHECK_NEAR(m.normals[4], 0.0, 1e-6);
    CHECK_NEAR(m.normals[5], 0.0, 1e-6);
    CHECK(mesh_is_sane(&m));
    CHECK_NEAR(sss_mesh_signed_volume(&m), 1.0 / 6.0, 1e-9);
    sss_mesh_free(&m);
}

static void test_crlf(void)
{
    sss_mesh m;
    sss_error err = {0};
    sss_result r = sss_mesh_read(DATA "triangle_crlf.ply", &m, &err);
    CHECK_MSG(r == SSS_OK, "%s", err.message);
    if (r != SSS_OK) return;
    CHECK(m.vertex_count == 3 && m.triangle_count == 1 && m.positions[3] == 1.0f && m.positions[7] == 1.0f);
    /* a single triangle in the xy-plane, counter-clockwise seen from +z */
    CHECK_NEAR(m.normals[2], 1.0, 1e-6);
    sss_mesh_free(&m);
}

/* The tetrahedron again in binary little-endian: float x y z with an extra uchar between y and z,
 * an extra element with a list property (skipped), uchar/int triangle lists. */
static void build_tetra_le(bytes *b)
{
    b->size = 0;
    put_text(b, "ply\nformat binary_little_endian 1.0\ncomment built by test_mesh_read\n"
                "element vertex 4\nproperty float x\nproperty float y\nproperty uchar alpha\nproperty float z\n"
                "element edge 2\nproperty int vertex1\nproperty list ushort short path\n"
                "element face 4\nproperty list uchar int vertex_indices\nend_header\n");
    static const float p[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (int v = 0; v < 4; v++) {
        put_f32(b, p[v][0], 0);
        put_f32(b, p[v][1], 0);
        put_uint(b, 200, 1, 0);
        put_f32(b, p[v][2], 0);
    }
    put_uint(b, 0, 4, 0); /* edge 0: vertex1 0, list of 2 shorts */
    put_uint(b, 2, 2, 0);
    put_uint(b, 5, 2, 0);
    put_uint(b, 0xfffe, 2, 0);
    put_uint(b, 1, 4, 0); /* edge 1: empty list */
    put_uint(b, 0, 2, 0);
    static const int f[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    for (int t = 0; t < 4; t++) {
        put_uint(b, 3, 1, 0);
        for (int k = 0; k < 3; k++) put_uint(b, (uint64_t)f[t][k], 4, 0);
    }
}

static void test_binary_le(void)
{
    bytes b;
    build_tetra_le(&b);
    sss_mesh m;
    sss_error err = {0};
    sss_result r = sss_mesh_parse_ply(b.data, b.size, "tetra_le", &m, &err);
    CHECK_MSG(r == SSS_OK, "%s", err.message);
    if (r != SSS_OK) return;
    CHECK(m.vertex_count == 4 && m.triangle_count == 4);
    CHECK(m.positions[3] == 1.0f && m.positions[7] == 1.0f && m.positions[11] == 1.0f && m.positions[0] == 0.0f);
    CHECK(tri_equals(&m, 0, 0, 2, 1) && tri_equals(&m, 1, 0, 1, 3) && tri_equals(&m, 3, 1, 2, 3));
    CHECK(mesh_is_sane(&m));
    CHECK_NEAR(sss_mesh_signed_volume(&m), 1.0 / 6.0, 1e-9);
    sss_mesh_free(&m);
}

/* A unit square pyramid in big-endian: double positions, float normals (nx ny nz), texture_u/v,
 * ushort count + uint indices, with a quad base (two triangles) and four triangles. */
static void test_binary_be(void)
{
    bytes b = {{0}, 0};
    put_text(&b, "ply\nformat binary_big_endian 1.0\nelement vertex 5\nproperty double x\nproperty double y\n"
                 "property double z\nproperty int16 extra\nproperty float32 texture_u\nproperty float32 texture_v\n"
                 "element face 5\nproperty list uint16 uint32 vertex_indices\nproperty list uint8 float texcoord\n"
                 "end_header\n");
    static const double p[5][3] = {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}, {0.5, 1, 0.5}};
    for (int v = 0; v < 5; v++) {
        for (int k = 0; k < 3; k++) put_f64(&b, p[v][k], 1);
        put_uint(&b, (uint64_t)(uint16_t)-7, 2, 1);
        put_f32(&b, (float)v / 4.0f, 1);
        put_f32(&b, 1.0f - (float)v / 4.0f, 1);
    }
    /* base quad seen from below (-y): 0 1 2 3 is counter-clockwise from -y */
    static const int faces[5][4] = {{0, 1, 2, 3}, {0, 4, 1, -1}, {1, 4, 2, -1}, {2, 4, 3, -1}, {3, 4, 0, -1}};
    for (int f = 0; f < 5; f++) {
        int n = faces[f][3] < 0 ? 3 : 4;
        put_uint(&b, (uint64_t)n, 2, 1);
        for (int k = 0; k < n; k++) put_uint(&b, (uint64_t)faces[f][k], 4, 1);
        put_uint(&b, 2, 1, 1); /* a skipped list of two floats */
        put_f32(&b, 0.25f, 1);
        put_f32(&b, 0.75f, 1);
    }
    sss_mesh m;
    sss_error err = {0};
    sss_result r = sss_mesh_parse_ply(b.data, b.size, "pyramid_be", &m, &err);
    CHECK_MSG(r == SSS_OK, "%s", err.message);
    if (r != SSS_OK) return;
    CHECK(m.vertex_count == 5 && m.triangle_count == 6);
    int same = 1;
    for (int v = 0; v < 5; v++)
        for (int k = 0; k < 3; k++) same &= m.positions[3 * v + k] == (float)p[v][k];
    CHECK_MSG(same, "big-endian doubles read back as written");
    CHECK(m.uvs && m.uvs[2 * 4] == 1.0f && m.uvs[2 * 4 + 1] == 0.0f && m.uvs[2] == 0.25f);
    CHECK(m.source_flags == SSS_MESH_FROM_FILE_UVS);
    CHECK(tri_equals(&m, 0, 0, 1, 2) && tri_equals(&m, 1, 0, 2, 3) && tri_equals(&m, 2, 0, 4, 1));
    /* unit square base, apex height 1: volume 1/3 */
    CHECK_NEAR(sss_mesh_signed_volume(&m), 1.0 / 3.0, 1e-9);
    CHECK(mesh_is_sane(&m));
    sss_mesh_free(&m);
}

static int near3(const float *a, double x, double y, double z)
{
    return fabs(a[0] - x) < 1e-6 && fabs(a[1] - y) < 1e-6 && fabs(a[2] - z) < 1e-6;
}

static void test_obj(void)
{
    sss_mesh m;
    sss_error err = {0};
    sss_result r = sss_mesh_read(DATA "cube_faces.obj", &m, &err);
    CHECK_MSG(r == SSS_OK, "%s", err.message);
    if (r != SSS_OK) return;
    /* 5 quads and 2 triangles; distinct (v, vt, vn) corners: 4 per quad, 3 + 1 for the two
     * triangles that share two corners. */
    CHECK(m.triangle_count == 12);
    CHECK(m.vertex_count == 24);
    CHECK(m.uvs != NULL);
    CHECK(m.source_flags == (SSS_MESH_FROM_FILE_NORMALS | SSS_MESH_FROM_FILE_UVS));
    /* The corners of each face as written (1-based v indices in the file, negative ones resolved). */
    static const int written[7][4] = {{1, 4, 3, 2}, {5, 6, 7, 8}, {1, 2, 6, 5}, {4, 8, 7, 3},
                                      {1, 5, 8, 0}, {1, 8, 4, 0}, {2, 3, 7, 6}};
    static const float v[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    uint32_t t = 0;
    int ok = 1;
    for (int f = 0; f < 7; f++) {
        int n = written[f][3] ? 4 : 3;
        for (int k = 2; k < n; k++, t++) {
            int corner[3] = {written[f][0], written[f][k - 1], written[f][k]};
            for (int c = 0; c < 3; c++) {
                const float *pos = m.positions + 3 * (size_t)m.indices[3 * t + (uint32_t)c];
                ok &= near3(pos, v[corner[c] - 1][0], v[corner[c] - 1][1], v[corner[c] - 1][2]);
            }
        }
    }
    CHECK_MSG(ok, "triangle corners sit at the positions the file's faces name");
    /* face 3 (v//vn, vn 3 = -y) and the negative-index triangles (vn -2 = -x) keep file normals;
     * face 1 has none, so its corners get the computed -z normal. */
    CHECK(near3(m.normals + 3 * (size_t)m.indices[3 * 4], 0, -1, 0));
    CHECK(near3(m.normals + 3 * (size_t)m.indices[3 * 8], -1, 0, 0));
    CHECK(near3(m.normals + 3 * (size_t)m.indices[0], 0, 0, -1));
    /* UVs: +z face corner 6/2 -> vt 2 = (1, 0); negative vt -1 = vt 4 = (0, 1) on the -x triangle */
    const float *uv = m.uvs + 2 * (size_t)m.indices[3 * 2 + 1];
    CHECK(uv[0] == 1.0f && uv[1] == 0.0f);
    uv = m.uvs + 2 * (size_t)m.indices[3 * 9 + 2];
    CHECK(uv[0] == 0.0f && uv[1] == 1.0f);
    CHECK_NEAR(sss_mesh_surface_area(&m), 6.0, 1e-9);
    CHECK_NEAR(sss_mesh_signed_volume(&m), 1.0, 1e-9);
    CHECK(mesh_is_sane(&m));
    sss_mesh_free(&m);
}

static void test_obj_memory(void)
{
    /* 'v x y z w', 'vt u' (v defaults to 0), tabs, comments after statements, a pentagon, no final newline */
    const char *text = "v 0 0 0 1\nv\t2 0 0\nv 2 1 0 # a comment\nv 1 2 0\nv 0 1 0\nvt 0.5\n"
                       "f 1/1 2/1 3/1 4/1 5/1";
    sss_mesh m;
    sss_error err = {0};
    sss_result r = sss_mesh_parse_obj(text, strlen(text), "pentagon", &m, &err);
    CHECK_MSG(r == SSS_OK, "%s", err.message);
    if (r != SSS_OK) return;
    CHECK(m.vertex_count == 5 && m.triangle_count == 3);
    CHECK(tri_equals(&m, 0, 0, 1, 2) && tri_equals(&m, 2, 0, 3, 4));
    CHECK(m.uvs && m.uvs[0] == 0.5f && m.uvs[1] == 0.0f);
    /* pentagon area by the shoelace formula: (0,0) (2,0) (2,1) (1,2) (0,1) -> (0 + 2 + 3 + 1 + 0) / 2 = 3 */
    CHECK_NEAR(sss_mesh_surface_area(&m), 3.0, 1e-9);
    CHECK_NEAR(m.normals[2], 1.0, 1e-6);
    sss_mesh_free(&m);
}

static void test_unknown_extension(void)
{
    sss_mesh m;
    sss_error err = {0};
    CHECK(sss_mesh_read(DATA "box.stl", &m, &err) == SSS_ERROR_UNSUPPORTED);
    CHECK(strstr(err.message, "box.stl") != NULL);
    CHECK(sss_mesh_read(DATA "missing.ply", &m, &err) == SSS_ERROR_IO);
    CHECK(strstr(err.message, "missing.ply") != NULL);
}

int main(void)
{
    test_ascii_box();
    test_ascii_normals_uv();
    test_crlf();
    test_binary_le();
    test_binary_be();
    test_obj();
    test_obj_memory();
    test_unknown_extension();
    return CHECK_DONE();
}
