/* Malformed meshes of every kind give an error naming the input -- never a crash, a leak (run under
 * ASan) or a half-filled mesh. Also: every prefix of valid files and single-byte corruptions either
 * parse into a sane mesh or fail cleanly. */
#include <stdio.h>

#include "check.h"
#include "mesh_test_util.h"
#include "sss/mesh.h"

#define HDR3 "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n" \
             "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
#define TRI "0 0 0\n1 0 0\n0 1 0\n"
/* blank lines: enough bytes to pass the size check so the reader reaches the bad line itself */
#define PAD "\n\n\n\n\n\n\n\n\n\n"

typedef struct text_case {
    const char *label;
    const char *text;
    sss_result code; /* expected code; SSS_OK here means "any error" */
} text_case;

static const text_case ply_cases[] = {
    {"empty file", "", SSS_ERROR_PARSE},
    {"not ply", "plx\nformat ascii 1.0\nend_header\n", SSS_ERROR_PARSE},
    {"no end_header", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n", SSS_ERROR_PARSE},
    {"header only", HDR3, SSS_ERROR_PARSE},
    {"no format", "ply\nelement vertex 3\nend_header\n", SSS_ERROR_PARSE},
    {"unknown format", "ply\nformat binary_middle_endian 1.0\nend_header\n", SSS_ERROR_UNSUPPORTED},
    {"unknown keyword", "ply\nformat ascii 1.0\nelephant vertex 3\nend_header\n", SSS_ERROR_PARSE},
    {"unknown type", "ply\nformat ascii 1.0\nelement vertex 3\nproperty real x\nend_header\n", SSS_ERROR_PARSE},
    {"float list count", "ply\nformat ascii 1.0\nelement face 1\nproperty list float int vertex_indices\nend_header\n",
     SSS_ERROR_PARSE},
    {"bad element count", "ply\nformat ascii 1.0\nelement vertex three\nend_header\n", SSS_ERROR_PARSE},
    {"negative element count", "ply\nformat ascii 1.0\nelement vertex -3\nend_header\n", SSS_ERROR_PARSE},
    {"count beyond 32 bits", "ply\nformat ascii 1.0\nelement vertex 4294967296\nend_header\n", SSS_ERROR_PARSE},
    {"property before element", "ply\nformat ascii 1.0\nproperty float x\nend_header\n", SSS_ERROR_PARSE},
    {"repeated property",
     "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float x\nend_header\n", SSS_ERROR_PARSE},
    {"missing z",
     "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nelement face 1\n"
     "property list uchar int vertex_indices\nend_header\n0 0\n1 0\n0 1\n3 0 1 2\n",
     SSS_ERROR_PARSE},
    {"x is a list",
     "ply\nformat ascii 1.0\nelement vertex 1\nproperty list uchar float x\nproperty float y\nproperty float z\n"
     "element face 1\nproperty list uchar int vertex_indices\nend_header\n1 0 0 0\n3 0 0 0\n",
     SSS_ERROR_PARSE},
    {"no face element",
     "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n" TRI,
     SSS_ERROR_PARSE},
    {"no index list",
     "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
     "element face 1\nproperty list uchar int corners\nend_header\n" TRI "3 0 1 2\n",
     SSS_ERROR_PARSE},
    {"zero vertices",
     "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\n"
     "element face 1\nproperty list uchar int vertex_indices\nend_header\n3 0 1 2\n",
     SSS_ERROR_PARSE},
    {"zero faces",
     "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
     "element face 0\nproperty list uchar int vertex_indices\nend_header\n" TRI,
     SSS_ERROR_PARSE},
    {"above vertex limit",
     "ply\nformat ascii 1.0\nelement vertex 100000000\nproperty float x\nproperty float y\nproperty float z\n"
     "element face 1\nproperty list uchar int vertex_indices\nend_header\n" TRI "3 0 1 2\n",
     SSS_ERROR_LIMIT},
    {"claims 2^31 vertices",
     "ply\nformat ascii 1.0\nelement vertex 2147483648\nproperty float x\nproperty float y\nproperty float z\n"
     "element face 1\nproperty list uchar int vertex_indices\nend_header\n" TRI "3 0 1 2\n",
     SSS_ERROR_LIMIT},
    {"claims 1e6 faces in a tiny file",
     "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
     "element face 1000000\nproperty list uchar int vertex_indices\nend_header\n" TRI "3 0 1 2\n",
     SSS_ERROR_PARSE},
    {"truncated (missing face line)", HDR3 TRI, SSS_ERROR_PARSE},
    {"truncated mid-line", HDR3 TRI "3 0 1", SSS_ERROR_PARSE},
    {"count too large (4 for 3 lines)",
     "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
     "element face 1\nproperty list uchar int vertex_indices\nend_header\n" TRI "3 0 1 2\n",
     SSS_ERROR_PARSE},
    {"count too small (data left over)", HDR3 TRI "3 0 1 2\n3 2 1 0\n", SSS_ERROR_PARSE},
    {"too many values on a line", HDR3 "0 0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", SSS_ERROR_PARSE},
    {"too few values on a line", HDR3 "0 0\n1 0 0\n0 1 0\n3 0 1 2\n" PAD, SSS_ERROR_PARSE},
    {"index out of range", HDR3 TRI "3 0 1 3\n", SSS_ERROR_PARSE},
    {"negative index", HDR3 TRI "3 0 -1 2\n", SSS_ERROR_PARSE},
    {"fractional index",
     "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
     "element face 1\nproperty list uchar float vertex_indices\nend_header\n" TRI "3 0 1.5 2\n",
     SSS_ERROR_PARSE},
    {"two-vertex face", HDR3 TRI "2 0 1\n" PAD, SSS_ERROR_PARSE},
    {"empty face", HDR3 TRI "0\n" PAD, SSS_ERROR_PARSE},
    {"count says 5 indices, line has 3", HDR3 TRI "5 0 1 2\n", SSS_ERROR_PARSE},
    {"uchar count out of range", HDR3 TRI "300 0 1 2\n", SSS_ERROR_PARSE},
    {"NaN coordinate", HDR3 "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", SSS_ERROR_PARSE},
    {"Inf coordinate", HDR3 "0 0 0\n1 0 -inf\n0 1 0\n3 0 1 2\n", SSS_ERROR_PARSE},
    {"coordinate beyond float", HDR3 "0 0 0\n1e39 0 0\n0 1 0\n3 0 1 2\n", SSS_ERROR_PARSE},
    {"malformed number", HDR3 "0 0 0\n1.0.0 0 0\n0 1 0\n3 0 1 2\n", SSS_ERROR_PARSE},
    {"garbage text", "ply\nformat ascii 1.0\nhello world\n", SSS_ERROR_PARSE},
    {"NaN normal",
     "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
     "property float nx\nproperty float ny\nproperty float nz\nelement face 1\n"
     "property list uchar int vertex_indices\nend_header\n0 0 0 0 0 1\n1 0 0 nan 0 1\n0 1 0 0 0 1\n3 0 1 2\n",
     SSS_ERROR_PARSE},
    {"ascii text with binary format header",
     "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
     "element face 1\nproperty list uchar int vertex_indices\nend_header\n" TRI "3 0 1 2\n",
     SSS_OK /* any error: the bytes decode to some floats and then a bad face */},
};

static const text_case obj_cases[] = {
    {"empty", "", SSS_ERROR_PARSE},
    {"only comments", "# nothing\n\n", SSS_ERROR_PARSE},
    {"no faces", "v 0 0 0\nv 1 0 0\nv 0 1 0\n", SSS_ERROR_PARSE},
    {"index past the end", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", SSS_ERROR_PARSE},
    {"index zero", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", SSS_ERROR_PARSE},
    {"negative index too far back", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n", SSS_ERROR_PARSE},
    {"face before its vertices", "f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n", SSS_ERROR_PARSE},
    {"vt out of range", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/2 3/1\n", SSS_ERROR_PARSE},
    {"vn out of range", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//2\n", SSS_ERROR_PARSE},
    {"malformed corner 1/2/3/4", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1/1/1 2 3\n", SSS_ERROR_PARSE},
    {"malformed corner 1/", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/ 2 3\n", SSS_ERROR_PARSE},
    {"malformed corner /1", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf /1 2 3\n", SSS_ERROR_PARSE},
    {"malformed corner 1/2/", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1/ 2/1/ 3/1/\n", SSS_ERROR_PARSE},
    {"non-numeric index", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 two 3\n", SSS_ERROR_PARSE},
    {"two-vertex face", "v 0 0 0\nv 1 0 0\nf 1 2\n", SSS_ERROR_PARSE},
    {"malformed number", "v 0 0 0\nv 1 0 x\nv 0 1 0\nf 1 2 3\n", SSS_ERROR_PARSE},
    {"NaN coordinate", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", SSS_ERROR_PARSE},
    {"Inf normal", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn inf 0 0\nf 1//1 2//1 3//1\n", SSS_ERROR_PARSE},
    {"coordinate beyond float", "v 0 0 0\nv 1e40 0 0\nv 0 1 0\nf 1 2 3\n", SSS_ERROR_PARSE},
    {"too few numbers", "v 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", SSS_ERROR_PARSE},
    {"too many numbers", "v 0 0 0 1 2 3 4 5\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", SSS_ERROR_PARSE},
    {"garbage text", "this is not a mesh\njust some text\n", SSS_ERROR_PARSE},
    {"huge index", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999999\n", SSS_ERROR_PARSE},
};

/* Checks the error contract: code, a message naming the input, and a zeroed mesh. */
static void expect_failure(sss_result r, sss_result code, const sss_error *err, const sss_mesh *m, const char *name,
                           const char *label)
{
    CHECK_MSG(r != SSS_OK, "%s: accepted", label);
    if (code != SSS_OK) CHECK_MSG(r == code, "%s: code %d, expected %d (%s)", label, r, code, err->message);
    CHECK_MSG(strstr(err->message, name) == err->message, "%s: message '%s' does not start with the name", label,
              err->message);
    CHECK_MSG(m->positions == NULL && m->normals == NULL && m->indices == NULL && m->uvs == NULL &&
                  m->vertex_count == 0 && m->triangle_count == 0,
              "%s: mesh not zeroed after an error", label);
}

static void test_text_cases(void)
{
    for (size_t i = 0; i < sizeof ply_cases / sizeof ply_cases[0]; i++) {
        sss_mesh m;
        sss_error err = {0};
        sss_result r = sss_mesh_parse_ply(ply_cases[i].text, strlen(ply_cases[i].text), "case.ply", &m, &err);
        expect_failure(r, ply_cases[i].code, &err, &m, "case.ply", ply_cases[i].label);
        if (r == SSS_OK) sss_mesh_free(&m);
    }
    for (size_t i = 0; i < sizeof obj_cases / sizeof obj_cases[0]; i++) {
        sss_mesh m;
        sss_error err = {0};
        sss_result r = sss_mesh_parse_obj(obj_cases[i].text, strlen(obj_cases[i].text), "case.obj", &m, &err);
        expect_failure(r, obj_cases[i].code, &err, &m, "case.obj", obj_cases[i].label);
        if (r == SSS_OK) sss_mesh_free(&m);
    }
    /* ascii errors carry the line number: 9 header lines, 3 vertex lines: the bad face is line 13 */
    sss_mesh m;
    sss_error err = {0};
    const char *t = HDR3 TRI "3 0 1 3\n";
    sss_mesh_parse_ply(t, strlen(t), "x.ply", &m, &err);
    CHECK_MSG(strstr(err.message, "x.ply: line 13:") == err.message, "%s", err.message);
    t = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n";
    sss_mesh_parse_obj(t, strlen(t), "x.obj", &m, &err);
    CHECK_MSG(strstr(err.message, "x.obj: line 4:") == err.message, "%s", err.message);
}

/* A valid binary triangle: 3 float vertices, one uchar/int face. */
static void build_binary(bytes *b, int be, const char *vertex_count, int nan_at, int bad_index, int face_count)
{
    b->size = 0;
    put_text(b, be ? "ply\nformat binary_big_endian 1.0\n" : "ply\nformat binary_little_endian 1.0\n");
    put_text(b, "element vertex ");
    put_text(b, vertex_count);
    put_text(b, "\nproperty float x\nproperty float y\nproperty float z\nelement face 1\n"
                "property list uchar int vertex_indices\nend_header\n");
    for (int v = 0; v < 3; v++)
        for (int k = 0; k < 3; k++) put_f32(b, v * 3 + k == nan_at ? NAN : (float)(v == k + 1), be);
    put_uint(b, (uint64_t)face_count, 1, be);
    for (int k = 0; k < face_count; k++) put_uint(b, (uint64_t)(k == 2 ? bad_index : k), 4, be);
}

static void test_binary_cases(void)
{
    for (int be = 0; be < 2; be++) {
        bytes b;
        sss_mesh m;
        sss_error err = {0};
        build_binary(&b, be, "3", -1, 2, 3);
        sss_result r = sss_mesh_parse_ply(b.data, b.size, "ok.ply", &m, &err);
        CHECK_MSG(r == SSS_OK, "valid binary (be=%d): %s", be, err.message);
        sss_mesh_free(&m);

        /* every truncation of the valid file fails cleanly */
        int all_fail = 1;
        for (size_t cut = 0; cut < b.size; cut++) {
            r = sss_mesh_parse_ply(b.data, cut, "cut.ply", &m, &err);
            all_fail &= r != SSS_OK && strstr(err.message, "cut.ply") == err.message && m.positions == NULL;
            if (r == SSS_OK) sss_mesh_free(&m);
        }
        CHECK_MSG(all_fail, "every truncated binary file is rejected (be=%d)", be);

        build_binary(&b, be, "3", -1, 2, 3);
        b.data[b.size++] = 0; /* trailing byte */
        r = sss_mesh_parse_ply(b.data, b.size, "trail.ply", &m, &err);
        expect_failure(r, SSS_ERROR_PARSE, &err, &m, "trail.ply", "binary trailing data");

        build_binary(&b, be, "3", 4, 2, 3);
        r = sss_mesh_parse_ply(b.data, b.size, "nan.ply", &m, &err);
        expect_failure(r, SSS_ERROR_PARSE, &err, &m, "nan.ply", "binary NaN");
        CHECK_MSG(strstr(err.message, "nan.ply: vertex 1:") == err.message, "%s", err.message);

        build_binary(&b, be, "3", -1, 3, 3);
        r = sss_mesh_parse_ply(b.data, b.size, "idx.ply", &m, &err);
        expect_failure(r, SSS_ERROR_PARSE, &err, &m, "idx.ply", "binary index out of range");
        CHECK_MSG(strstr(err.message, "idx.ply: face 0:") == err.message, "%s", err.message);

        build_binary(&b, be, "3", -1, -5, 3); /* int index -5 */
        r = sss_mesh_parse_ply(b.data, b.size, "neg.ply", &m, &err);
        expect_failure(r, SSS_ERROR_PARSE, &err, &m, "neg.ply", "binary negative index");

        build_binary(&b, be, "3", -1, 2, 2);
        put_uint(&b, 0, 4, be); /* as many bytes as a valid file, so the face itself is read */
        r = sss_mesh_parse_ply(b.data, b.size, "two.ply", &m, &err);
        expect_failure(r, SSS_ERROR_PARSE, &err, &m, "two.ply", "binary two-vertex face");

        /* the count byte claims 255 indices in a file that holds 3 */
        build_binary(&b, be, "3", -1, 2, 3);
        b.data[b.size - 13] = 255;
        r = sss_mesh_parse_ply(b.data, b.size, "list.ply", &m, &err);
        expect_failure(r, SSS_ERROR_PARSE, &err, &m, "list.ply", "binary list count beyond the data");

        build_binary(&b, be, "2147483648", -1, 2, 3);
        r = sss_mesh_parse_ply(b.data, b.size, "huge.ply", &m, &err);
        expect_failure(r, SSS_ERROR_LIMIT, &err, &m, "huge.ply", "binary claims 2^31 vertices");

        build_binary(&b, be, "4000000", -1, 2, 3); /* under the limit, but the file is tiny */
        r = sss_mesh_parse_ply(b.data, b.size, "big.ply", &m, &err);
        expect_failure(r, SSS_ERROR_PARSE, &err, &m, "big.ply", "binary claims more data than present");
    }
    /* a skipped list element whose count runs past the end of the file */
    bytes b = {{0}, 0};
    put_text(&b, "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                 "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                 "element extra 1\nproperty list uint int payload\nend_header\n");
    for (int i = 0; i < 9; i++) put_f32(&b, (float)(i % 4 == 1), 0);
    put_uint(&b, 3, 1, 0);
    for (int k = 0; k < 3; k++) put_uint(&b, (uint64_t)k, 4, 0);
    put_uint(&b, 0x40000000u, 4, 0);
    sss_mesh m;
    sss_error err = {0};
    sss_result r = sss_mesh_parse_ply(b.data, b.size, "skip.ply", &m, &err);
    expect_failure(r, SSS_ERROR_PARSE, &err, &m, "skip.ply", "skipped list past the end");
}

/* Robustness: every prefix and every single-byte corruption of valid files parses into a sane mesh
 * or fails with a message; nothing crashes (the point of running this under ASan). */
static void test_corruptions(void)
{
    static const char *const texts[] = {
        HDR3 TRI "3 0 1 2\n",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nf 1/1/1 2/1/1 3/1/1\nf -3//-1 -2//-1 -1//-1\n",
    };
    static const unsigned char flips[] = {0, '\n', ' ', '-', '9', '/', 0xff, 'e', '.'};
    int sane = 1, named = 1, runs = 0;
    for (int f = 0; f < 2; f++) {
        const char *name = f == 0 ? "c.ply" : "c.obj";
        size_t n = strlen(texts[f]);
        unsigned char buf[512];
        /* runs 0..n: the prefix of that length; then n * flips: the whole text with one byte changed */
        for (size_t run = 0; run <= n + n * sizeof flips; run++) {
            size_t len = run <= n ? run : n;
            memcpy(buf, texts[f], len);
            if (run > n) buf[(run - n - 1) / sizeof flips] = flips[(run - n - 1) % sizeof flips];
            sss_mesh m;
            sss_error err = {0};
            sss_result r = f == 0 ? sss_mesh_parse_ply(buf, len, name, &m, &err) : sss_mesh_parse_obj(buf, len, name, &m, &err);
            runs++;
            if (r == SSS_OK) {
                sane &= mesh_is_sane(&m);
                sss_mesh_free(&m);
            } else {
                named &= strstr(err.message, name) == err.message;
            }
        }
    }
    CHECK_MSG(sane, "accepted corruptions give sane meshes");
    CHECK_MSG(named, "rejected corruptions name the input");
    CHECK(runs > 1000);
}

int main(void)
{
    test_text_cases();
    test_binary_cases();
    test_corruptions();
    return CHECK_DONE();
}
