/* SAM geometry: region integrals against the closed-form view factor of parallel plates, reduced fans
 * and their areas (Eq. 16), and form factors of the build (Eq. 11) against an independent 4D
 * Gauss-Legendre quadrature of R_d over two reduced fans. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "sam_test_util.h"
#include "sss/sam.h"

static void square(double a, double b, double y, float *t)
{
    float q[4][3] = {{0, (float)y, 0}, {(float)a, (float)y, 0}, {(float)a, (float)y, (float)b}, {0, (float)y, (float)b}};
    int idx[6] = {0, 1, 2, 0, 2, 3};
    for (int i = 0; i < 6; i++) memcpy(t + 3 * i, q[idx[i]], sizeof q[0]);
}

static void test_plates(void)
{
    /* published value for unit squares one unit apart: 0.1998 */
    CHECK_NEAR(sam_test_plates(1, 1, 1), 0.1998, 1e-4);
    double cases[3][3] = {{1, 1, 1}, {2, 1, 1}, {1, 1, 0.5}};
    for (int k = 0; k < 3; k++) {
        float A[18], B[18];
        square(cases[k][0], cases[k][1], 0.0, A);
        square(cases[k][0], cases[k][1], cases[k][2], B);
        double out[3];
        sss_error err = {0};
        CHECK(sss_sam_region_integral(A, 2, B, 2, 1u << 17, 7, sam_test_view_kernel, &cases[k][2], out, &err) == SSS_OK);
        double exact = sam_test_plates(cases[k][0], cases[k][1], cases[k][2]);
        printf("plates %g x %g at %g: %.5f (closed form %.5f)\n", cases[k][0], cases[k][1], cases[k][2], out[0], exact);
        CHECK_REL(out[0], exact, 0.01);
    }
    /* errors */
    float A[18];
    square(1, 1, 0, A);
    double out[3];
    sss_error err = {0};
    CHECK(sss_sam_region_integral(A, 0, A, 2, 16, 0, sam_test_view_kernel, NULL, out, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(sss_sam_region_integral(A, 2, A, 2, 0, 0, sam_test_view_kernel, NULL, out, &err) == SSS_ERROR_INVALID_ARGUMENT);
}

static double tri_area(const float *t)
{
    double e1[3], e2[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = t[3 + k] - t[k];
        e2[k] = t[6 + k] - t[k];
    }
    double x = e1[1] * e2[2] - e1[2] * e2[1], y = e1[2] * e2[0] - e1[0] * e2[2], z = e1[0] * e2[1] - e1[1] * e2[0];
    return 0.5 * sqrt(x * x + y * y + z * z);
}

static void test_fans(void)
{
    sss_mesh m;
    sss_error err = {0};
    CHECK(sss_mesh_sphere(1.0, 2, &m, &err) == SSS_OK);
    float *area = malloc(sizeof(float) * m.vertex_count), *va = malloc(sizeof(float) * m.vertex_count);
    sss_sam_fan_areas(&m, area);
    sss_mesh_vertex_areas(&m, va);
    double sum = 0.0;
    for (uint32_t v = 0; v < m.vertex_count; v++) {
        sum += area[v];
        CHECK_REL(area[v], va[v], 1e-5);
    }
    CHECK_REL(sum, sss_mesh_surface_area(&m), 1e-6);
    /* the reduced fan's triangles cover exactly F' (the barycentric third of each triangle) */
    float tris[9 * 64];
    for (uint32_t v = 0; v < m.vertex_count; v += 37) {
        size_t nt = sss_sam_reduced_fan(&m, v, tris, 64);
        CHECK(nt >= 10 && nt <= 12); /* valence 5 or 6 */
        double a = 0.0;
        for (size_t i = 0; i < nt; i++) a += tri_area(tris + 9 * i);
        CHECK_REL(a, area[v], 1e-5);
    }
    /* criteria (Eq. 13-14) */
    float o[3] = {0, 0, 0}, n[3] = {0, 0, 1}, below[3] = {0, 0, -1}, above[3] = {0, 0, 1}, up[3] = {0, 0, 1},
          down[3] = {0, 0, -1};
    CHECK(sss_sam_is_back(o, n, below, down));
    CHECK(!sss_sam_is_back(o, n, below, up));
    CHECK(!sss_sam_is_back(o, n, above, down));
    free(area);
    free(va);
    sss_mesh_free(&m);
}

/* ---- form factors of the build vs an independent quadrature ---------------------------------- */

static const double GL_X[8] = {0.0198550717512319, 0.1016667612931866, 0.2372337950418355, 0.4082826787521751,
                               0.5917173212478249, 0.7627662049581645, 0.8983332387068134, 0.9801449282487681};
static const double GL_W[8] = {0.0506142681451881, 0.1111905172266872, 0.1568533229389436, 0.1813418916891810,
                               0.1813418916891810, 0.1568533229389436, 0.1111905172266872, 0.0506142681451881};

/* Nodes of a triangle by the collapsed map x = a + u (b - a) + u v (c - b), weight 2 A u. */
static int tri_nodes(const float *t, double *pts, double *w)
{
    double A = tri_area(t);
    int n = 0;
    for (int i = 0; i < 8; i++)
        for (int j = 0; j < 8; j++, n++) {
            double u = GL_X[i], v = GL_X[j];
            for (int k = 0; k < 3; k++) pts[3 * n + k] = t[k] + u * (t[3 + k] - t[k]) + u * v * (t[6 + k] - t[3 + k]);
            w[n] = GL_W[i] * GL_W[j] * 2.0 * A * u;
        }
    return n;
}

static void quad_form_factor(const sss_mesh *m, const sss_profile *p, uint32_t vo, uint32_t vi, double out[3])
{
    float A[9 * 64], B[9 * 64];
    size_t na = sss_sam_reduced_fan(m, vo, A, 64), nb = sss_sam_reduced_fan(m, vi, B, 64);
    double pa[3 * 64], wa[64], pb[3 * 64], wb[64], area_a = 0.0;
    out[0] = out[1] = out[2] = 0.0;
    for (size_t i = 0; i < na; i++) {
        area_a += tri_area(A + 9 * i);
        int nn = tri_nodes(A + 9 * i, pa, wa);
        for (size_t j = 0; j < nb; j++) {
            tri_nodes(B + 9 * j, pb, wb);
            for (int x = 0; x < nn; x++)
                for (int y = 0; y < nn; y++) {
                    double dx = pa[3 * x] - pb[3 * y], dy = pa[3 * x + 1] - pb[3 * y + 1], dz = pa[3 * x + 2] - pb[3 * y + 2];
                    double rd[3];
                    sss_profile_eval_rgb(p, sqrt(dx * dx + dy * dy + dz * dz), rd);
                    for (int c = 0; c < 3; c++) out[c] += wa[x] * wb[y] * rd[c];
                }
        }
    }
    for (int c = 0; c < 3; c++) out[c] /= area_a; /* Eq. 11 */
}

static void test_build_form_factors(void)
{
    sss_mesh m;
    sss_error err = {0};
    CHECK(sss_mesh_sphere(1.0, 2, &m, &err) == SSS_OK);
        CHECK(sss_pbd_table_build(1.33, 0.0, &sam_test_table, &err) == SSS_OK);
    sss_material mat;
    CHECK(sss_material_from_medium("Marble", 10.0, 1.33, &mat, &err) == SSS_OK);
    sss_profile p;
    CHECK(sss_profile_init(&p, SSS_PROFILE_PBD, &mat, &sam_test_table, &err) == SSS_OK);
    sss_sam_desc d;
    memset(&d, 0, sizeof d);
    d.n = 2;
    d.samples = 2048;
    sss_sam s;
    CHECK(sss_sam_build(&m, &p, &d, &s, NULL, &err) == SSS_OK);
    for (uint32_t v = 0; v < m.vertex_count; v += 53) {
        uint32_t vi = s.links[v * s.n];
        CHECK(vi != SSS_SAM_NONE);
        if (vi == SSS_SAM_NONE) continue;
        double q[3];
        quad_form_factor(&m, &p, v, vi, q);
        for (int c = 0; c < 3; c++) CHECK_REL(s.form_factor[3 * v * s.n + c], q[c], 0.02);
        if (v == 0) printf("K(0, %u) = %.5g %.5g %.5g, quadrature %.5g %.5g %.5g\n", vi, s.form_factor[0],
                           s.form_factor[1], s.form_factor[2], q[0], q[1], q[2]);
    }
    sss_sam_free(&s);
    sss_mesh_free(&m);
}

int main(void)
{
    test_plates();
    test_fans();
    test_build_form_factors();
    return CHECK_DONE();
}
