/* SAM building and files: back-side links of a sphere lie across it (Eq. 13-14) and are the nearest
 * back-side vertices; the tree search equals the brute-force search over all pairs while testing far
 * fewer; any n (up to 50); K' reproduces K at rest (Eq. 15); .sam round trip, a file for another mesh
 * or material is rejected, truncated and corrupted files are rejected. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "sam_test_util.h"
#include "sss/sam.h"


static void test_sphere(uint32_t n)
{
    sss_mesh m;
    sss_error err = {0};
    const double R = 1.0;
    CHECK(sss_mesh_sphere(R, 3, &m, &err) == SSS_OK);
    sss_profile p;
    sam_test_profile(10.0, &p); /* Marble: 1 / sigma_tr of red ~ 0.85 units, comparable to R */
    sss_sam_desc d;
    memset(&d, 0, sizeof d);
    d.n = n;
    sss_sam s;
    sss_sam_stats st;
    CHECK(sss_sam_build(&m, &p, &d, &s, &st, &err) == SSS_OK);
    printf("sphere n=%u: %u vertices, %.3f s, tested %.2f%% of pairs, %llu form factors\n", n, m.vertex_count,
           st.seconds, 100.0 * st.vertices_tested / ((double)m.vertex_count * m.vertex_count),
           (unsigned long long)st.form_factors);
    CHECK(st.linked_vertices == m.vertex_count);
    double edge = 0.0; /* longest edge */
    for (uint32_t t = 0; t < m.triangle_count; t++)
        for (int k = 0; k < 3; k++) {
            double e = sam_test_dist(m.positions + 3 * m.indices[3 * t + k], m.positions + 3 * m.indices[3 * t + (k + 1) % 3]);
            if (e > edge) edge = e;
        }
    int bad = 0, across = 0, nearest = 0, sorted = 0;
    for (uint32_t v = 0; v < m.vertex_count; v++) {
        const float *xo = m.positions + 3 * v, *no = m.normals + 3 * v;
        double dmin = INFINITY; /* nearest back-side vertex */
        for (uint32_t j = 0; j < m.vertex_count; j++)
            if (sss_sam_is_back(xo, no, m.positions + 3 * j, m.normals + 3 * j)) {
                double dd = sam_test_dist(xo, m.positions + 3 * j);
                if (dd < dmin) dmin = dd;
            }
        for (uint32_t k = 0; k < n; k++) {
            uint32_t b = s.links[v * n + k];
            if (b == SSS_SAM_NONE || b >= m.vertex_count) {
                bad++;
                continue;
            }
            const float *xi = m.positions + 3 * b, *ni = m.normals + 3 * b;
            double facing = no[0] * ni[0] + no[1] * ni[1] + no[2] * ni[2];
            double depth = (xi[0] - xo[0]) * no[0] + (xi[1] - xo[1]) * no[1] + (xi[2] - xo[2]) * no[2];
            /* on a sphere, n_i . n_o < 0 puts x_i more than R below the tangent plane at x_o */
            if (facing < 0.0 && depth < -R * (1.0 - 1e-5)) across++;
            if (k > 0) {
                double a = 0, b2 = 0;
                for (int c = 0; c < 3; c++) {
                    a += s.form_factor[3 * (v * n + k - 1) + c];
                    b2 += s.form_factor[3 * (v * n + k) + c];
                }
                sorted += a >= b2;
            }
        }
        /* the strongest link is among the nearest back-side vertices (R_d falls with distance) */
        uint32_t b0 = s.links[v * n];
        if (b0 != SSS_SAM_NONE && sam_test_dist(xo, m.positions + 3 * b0) <= dmin + 2.0 * edge) nearest++;
    }
    CHECK(bad == 0);
    CHECK(across == (int)(n * m.vertex_count));
    CHECK(nearest == (int)m.vertex_count);
    CHECK(sorted == (int)((n - 1) * m.vertex_count));
    /* K' reproduces K at rest (Eq. 15) */
    float *approx = malloc(sizeof(float) * 3 * n * m.vertex_count);
    sss_sam_profile_table t;
    CHECK(sss_sam_profile_table_build(&p, 0.0, 0, &t, &err) == SSS_OK);
    sss_sam_approximate(&s, &m, NULL, &t, approx);
    int same = 0;
    for (size_t i = 0; i < 3 * (size_t)n * m.vertex_count; i++)
        same += fabs(approx[i] - s.form_factor[i]) <= 1e-4 * s.form_factor[i] + 1e-30;
    CHECK(same == (int)(3 * n * m.vertex_count));
    sss_sam_profile_table_free(&t);
    free(approx);
    sss_sam_free(&s);
    sss_mesh_free(&m);
}

static void test_tree_equals_brute_force(void)
{
    sss_mesh m;
    sss_error err = {0};
    char path[1024];
    snprintf(path, sizeof path, "%s/assets/bunny.ply", SSS_SOURCE_DIR);
    CHECK(sss_mesh_read(path, &m, &err) == SSS_OK);
    double scales[2] = {2.5, 0.25}; /* short and long scattering distances against the 10-unit bunny */
    for (int c = 0; c < 2; c++) {
        sss_profile p;
        sam_test_profile(scales[c], &p);
        sss_sam_desc d;
        memset(&d, 0, sizeof d);
        d.n = 10;
        d.samples = 16;
        sss_sam a, b;
        sss_sam_stats sa, sb;
        CHECK(sss_sam_build(&m, &p, &d, &a, &sa, &err) == SSS_OK);
        d.brute_force = 1;
        CHECK(sss_sam_build(&m, &p, &d, &b, &sb, &err) == SSS_OK);
        size_t slots = (size_t)d.n * m.vertex_count;
        int same = memcmp(a.links, b.links, slots * sizeof(uint32_t)) == 0 &&
                   memcmp(a.form_factor, b.form_factor, 3 * slots * sizeof(float)) == 0;
        CHECK(same);
        double frac = (double)sa.vertices_tested / ((double)m.vertex_count * m.vertex_count);
        printf("bunny, scale %g: tree %.3f s (%.2f%% of pairs tested, %llu form factors), brute force %.3f s "
               "(%llu)\n",
               scales[c], sa.seconds, 100.0 * frac, (unsigned long long)sa.form_factors, sb.seconds,
               (unsigned long long)sb.form_factors);
        CHECK(frac < 0.5);
        CHECK(sa.form_factors <= sb.form_factors);
        sss_sam_free(&a);
        sss_sam_free(&b);
    }
    sss_mesh_free(&m);
}

static void copy_prefix(const char *from, const char *to, long bytes, long flip_at)
{
    FILE *f = fopen(from, "rb"), *g = fopen(to, "wb");
    for (long i = 0; f && g && i < bytes; i++) {
        int ch = fgetc(f);
        if (ch == EOF) break;
        if (i == flip_at) ch ^= 0x40;
        fputc(ch, g);
    }
    if (f) fclose(f);
    if (g) fclose(g);
}

static void test_files(void)
{
    sss_mesh m, other;
    sss_error err = {0};
    CHECK(sss_mesh_sphere(1.0, 2, &m, &err) == SSS_OK);
    CHECK(sss_mesh_sphere(1.0, 1, &other, &err) == SSS_OK);
    sss_profile p;
    sam_test_profile(10.0, &p);
    sss_sam_desc d;
    memset(&d, 0, sizeof d);
    d.n = 4;
    sss_sam s, r;
    CHECK(sss_sam_build(&m, &p, &d, &s, NULL, &err) == SSS_OK);
    char dir[] = "/tmp/sss_sam_testXXXXXX", path[256], bad[256];
    CHECK(mkdtemp(dir) != NULL);
    snprintf(path, sizeof path, "%s/sphere.sam", dir);
    snprintf(bad, sizeof bad, "%s/bad.sam", dir);
    CHECK(sss_sam_write(path, &s, &err) == SSS_OK);
    CHECK(sss_sam_read(path, &r, &err) == SSS_OK);
    size_t slots = (size_t)s.n * s.vertex_count;
    CHECK(r.vertex_count == s.vertex_count && r.triangle_count == s.triangle_count && r.n == s.n &&
          r.mesh_hash == s.mesh_hash && r.samples == s.samples && r.model == s.model);
    CHECK(memcmp(&r.material, &s.material, sizeof r.material) == 0);
    CHECK(memcmp(r.links, s.links, slots * 4) == 0 && memcmp(r.fan_area, s.fan_area, 4 * (size_t)s.vertex_count) == 0 &&
          memcmp(r.form_factor, s.form_factor, 12 * slots) == 0 && memcmp(r.kprime, s.kprime, 12 * slots) == 0);
    CHECK(sss_sam_check(&r, &m, &p.material, SSS_PROFILE_PBD, NULL, path, &err) == SSS_OK);
    /* another mesh */
    CHECK(sss_sam_check(&r, &other, NULL, SSS_PROFILE_PBD, NULL, path, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(err.message, "different mesh") != NULL && strstr(err.message, "sphere.sam") != NULL);
    printf("%s\n", err.message);
    /* same counts, moved vertex: the hash tells */
    m.positions[7] += 1e-3f;
    CHECK(sss_sam_check(&r, &m, NULL, SSS_PROFILE_PBD, NULL, path, &err) == SSS_ERROR_INVALID_ARGUMENT);
    m.positions[7] -= 1e-3f;
    /* another material, another model, another transform */
    sss_material mat2 = p.material;
    mat2.sigma_a[1] *= 2.0;
    CHECK(sss_sam_check(&r, &m, &mat2, SSS_PROFILE_PBD, NULL, path, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(err.message, "material") != NULL);
    CHECK(sss_sam_check(&r, &m, &p.material, SSS_PROFILE_DIPOLE, NULL, path, &err) == SSS_ERROR_INVALID_ARGUMENT);
    double tr[16] = {2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1};
    CHECK(sss_sam_check(&r, &m, NULL, SSS_PROFILE_PBD, tr, path, &err) == SSS_ERROR_INVALID_ARGUMENT);
    sss_sam_free(&r);
    /* truncated: every prefix length class is rejected (header, payload, checksum) */
    long size = sam_test_file_size(path);
    long cuts[5] = {0, 10, 200, size / 2, size - 1};
    for (int i = 0; i < 5; i++) {
        copy_prefix(path, bad, cuts[i], -1);
        sss_sam t;
        CHECK(sss_sam_read(bad, &t, &err) != SSS_OK);
        CHECK(t.links == NULL);
        if (i == 3) {
            printf("%s\n", err.message);
            CHECK(strstr(err.message, "truncated") != NULL);
        }
    }
    /* one flipped bit in the payload: checksum */
    copy_prefix(path, bad, size, size / 2);
    CHECK(sss_sam_read(bad, &r, &err) == SSS_ERROR_PARSE);
    /* header promising more than the file holds is refused before allocating (vertex count patched) */
    copy_prefix(path, bad, size, 17);
    CHECK(sss_sam_read(bad, &r, &err) != SSS_OK);
    CHECK(sss_sam_read("/nonexistent/x.sam", &r, &err) == SSS_ERROR_IO);
    unlink(path);
    unlink(bad);
    rmdir(dir);
    sss_sam_free(&s);
    sss_mesh_free(&m);
    sss_mesh_free(&other);
}

static void test_errors(void)
{
    sss_mesh m;
    sss_error err = {0};
    CHECK(sss_mesh_sphere(1.0, 1, &m, &err) == SSS_OK);
    sss_profile p;
    sam_test_profile(10.0, &p);
    sss_sam_desc d;
    memset(&d, 0, sizeof d);
    sss_sam s;
    d.n = SSS_SAM_MAX_N + 1;
    CHECK(sss_sam_build(&m, &p, &d, &s, NULL, &err) == SSS_ERROR_INVALID_ARGUMENT);
    d.n = 3;
    m.positions[4] = NAN;
    CHECK(sss_sam_build(&m, &p, &d, &s, NULL, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(s.links == NULL);
    sss_mesh_free(&m);
}

int main(void)
{
    sss_error err = {0};
    if (sss_pbd_table_build(1.33, 0.0, &sam_test_table, &err) != SSS_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
    test_sphere(3);
    test_sphere(50);
    test_tree_equals_brute_force();
    test_files();
    test_errors();
    return CHECK_DONE();
}
