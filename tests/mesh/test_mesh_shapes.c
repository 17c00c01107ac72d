/* Procedural shapes and derived geometry against closed forms: sphere 4 pi r^2 and 4/3 pi r^3, torus
 * 4 pi^2 R r and 2 pi^2 R r^2, a tube's area 2 pi a L and volume pi a^2 L, exact box and plane;
 * outward normals; area-weighted normals at a box corner; per-vertex areas summing to the total. */
#include <stdio.h>

#include "check.h"
#include "mesh_test_util.h"
#include "sss/mesh.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* Every normal agrees with the area-weighted normal of the triangles around it: the winding and the
 * given normals face the same side. Returns the smallest dot product. */
static double min_dot_with_computed(const sss_mesh *m)
{
    sss_mesh copy = *m;
    copy.normals = malloc((size_t)m->vertex_count * 3 * sizeof(float));
    if (!copy.normals) return -2.0;
    sss_mesh_compute_normals(&copy, NULL);
    double worst = 1.0;
    for (size_t v = 0; v < m->vertex_count; v++) {
        const float *a = m->normals + 3 * v, *b = copy.normals + 3 * v;
        double d = (double)a[0] * b[0] + (double)a[1] * b[1] + (double)a[2] * b[2];
        if (d < worst) worst = d;
    }
    free(copy.normals);
    return worst;
}

static double vertex_area_sum(const sss_mesh *m)
{
    float *a = malloc((size_t)m->vertex_count * sizeof(float));
    if (!a) return -1.0;
    sss_mesh_vertex_areas(m, a);
    double s = 0.0;
    for (size_t v = 0; v < m->vertex_count; v++) s += a[v];
    free(a);
    return s;
}

static void test_sphere(void)
{
    const double r = 0.7;
    double prev_area_err = 1e9, prev_vol_err = 1e9;
    for (int s = 0; s <= 6; s++) {
        sss_mesh m;
        sss_error err = {0};
        sss_result res = sss_mesh_sphere(r, s, &m, &err);
        CHECK_MSG(res == SSS_OK, "%s", err.message);
        if (res != SSS_OK) continue;
        CHECK(m.triangle_count == 20u << (2 * s));
        CHECK(mesh_is_sane(&m));
        /* outward: n . p > 0, and n = p / |p| for a sphere */
        double min_dot = 1.0, max_dev = 0.0, max_radius_err = 0.0;
        for (size_t v = 0; v < m.vertex_count; v++) {
            const float *p = m.positions + 3 * v, *n = m.normals + 3 * v;
            double len = sqrt((double)p[0] * p[0] + (double)p[1] * p[1] + (double)p[2] * p[2]);
            double dot = (n[0] * p[0] + n[1] * p[1] + n[2] * p[2]) / len;
            if (dot < min_dot) min_dot = dot;
            for (int k = 0; k < 3; k++) max_dev = fmax(max_dev, fabs(n[k] - p[k] / len));
            max_radius_err = fmax(max_radius_err, fabs(len - r));
        }
        CHECK(min_dot > 0.999999);
        CHECK(max_dev < 1e-6);
        CHECK(max_radius_err < 1e-6);
        CHECK(min_dot_with_computed(&m) > 0.79); /* coarse s = 0 still within ~37 degrees */
        /* inscribed polyhedra: area and volume approach the sphere's from below, monotonically */
        double area = sss_mesh_surface_area(&m), vol = sss_mesh_signed_volume(&m);
        double area_err = 4.0 * M_PI * r * r - area, vol_err = 4.0 / 3.0 * M_PI * r * r * r - vol;
        CHECK(vol > 0);
        CHECK(area_err > 0 && area_err < prev_area_err / 3.0); /* error ~ h^2 shrinks ~4x per level */
        CHECK(vol_err > 0 && vol_err < prev_vol_err / 3.0);
        prev_area_err = area_err;
        prev_vol_err = vol_err;
        CHECK_REL(vertex_area_sum(&m), area, 1e-5);
        if (s == 6) {
            CHECK_REL(area, 4.0 * M_PI * r * r, 2e-4);
            CHECK_REL(vol, 4.0 / 3.0 * M_PI * r * r * r, 4e-4);
        }
        sss_mesh_free(&m);
    }
}

static void test_torus(void)
{
    const double R = 1.5, rr = 0.4;
    double prev = 1e9;
    for (int n = 8; n <= 256; n *= 2) {
        sss_mesh m;
        sss_error err = {0};
        sss_result res = sss_mesh_torus(R, rr, n, &m, &err);
        CHECK_MSG(res == SSS_OK, "%s", err.message);
        if (res != SSS_OK) continue;
        CHECK(mesh_is_sane(&m));
        CHECK(min_dot_with_computed(&m) > 0.9);
        double area = sss_mesh_surface_area(&m), vol = sss_mesh_signed_volume(&m);
        double err_a = fabs(area - 4.0 * M_PI * M_PI * R * rr);
        CHECK(err_a < prev / 3.0);
        prev = err_a;
        CHECK(vol > 0);
        CHECK_REL(vertex_area_sum(&m), area, 1e-5);
        if (n == 256) {
            CHECK_REL(area, 4.0 * M_PI * M_PI * R * rr, 2e-4);
            CHECK_REL(vol, 2.0 * M_PI * M_PI * R * rr * rr, 4e-4);
        }
        /* outward from the core circle of radius R in the xz-plane */
        int outward = 1;
        for (size_t v = 0; v < m.vertex_count; v++) {
            const float *p = m.positions + 3 * v, *nn = m.normals + 3 * v;
            double rho = hypot(p[0], p[2]);
            double c[3] = {p[0] - R * p[0] / rho, p[1], p[2] - R * p[2] / rho};
            outward &= c[0] * nn[0] + c[1] * nn[1] + c[2] * nn[2] > 0.99 * rr;
        }
        CHECK_MSG(outward, "torus normals point away from the core circle (n=%d)", n);
        float lo[3], hi[3];
        sss_mesh_bounds(&m, lo, hi);
        CHECK(hi[1] <= rr + 1e-6 && lo[1] >= -rr - 1e-6 && hi[0] <= R + rr + 1e-6);
        sss_mesh_free(&m);
    }
}

/* Length of the documented trefoil core, (sin t + 2 sin 2t, cos t - 2 cos 2t, -sin 3t) * radius/3,
 * by Simpson's rule on |c'(t)|. */
static double trefoil_length(double radius)
{
    const int n = 20000;
    double sum = 0.0;
    for (int i = 0; i <= n; i++) {
        double t = 2.0 * M_PI * i / n;
        double dx = cos(t) + 4.0 * cos(2.0 * t), dy = -sin(t) + 4.0 * sin(2.0 * t), dz = -3.0 * cos(3.0 * t);
        double w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
        sum += w * sqrt(dx * dx + dy * dy + dz * dz);
    }
    return sum * (2.0 * M_PI / n) / 3.0 * radius / 3.0;
}

static void test_trefoil(void)
{
    const double radius = 1.2, tube = 0.15;
    double L = trefoil_length(radius);
    double prev = 1e9;
    for (int n = 64; n <= 2048; n *= 2) {
        sss_mesh m;
        sss_error err = {0};
        sss_result res = sss_mesh_trefoil(radius, tube, n, &m, &err);
        CHECK_MSG(res == SSS_OK, "%s", err.message);
        if (res != SSS_OK) continue;
        CHECK(mesh_is_sane(&m));
        CHECK(min_dot_with_computed(&m) > 0.9);
        double area = sss_mesh_surface_area(&m), vol = sss_mesh_signed_volume(&m);
        CHECK(vol > 0);
        /* A tube of radius a around a curve (a below the curvature radius) has area 2 pi a L and
         * volume pi a^2 L exactly, so volume / area = a / 2 whatever the curve. */
        double e = fabs(area / (2.0 * M_PI * tube * L) - 1.0);
        CHECK(e < prev);
        prev = e;
        if (n == 2048) {
            CHECK_REL(area, 2.0 * M_PI * tube * L, 2e-3);
            CHECK_REL(vol, M_PI * tube * tube * L, 4e-3);
            CHECK_REL(vol / area, tube / 2.0, 3e-3);
        }
        float lo[3], hi[3];
        sss_mesh_bounds(&m, lo, hi);
        CHECK(hi[0] <= radius + tube + 1e-5 && lo[1] >= -radius - tube - 1e-5);
        sss_mesh_free(&m);
    }
}

static void test_plane_box(void)
{
    sss_mesh m;
    sss_error err = {0};
    CHECK(sss_mesh_plane(2.5, &m, &err) == SSS_OK);
    CHECK(mesh_is_sane(&m));
    CHECK_NEAR(sss_mesh_surface_area(&m), 2.5 * 2.5, 1e-12);
    CHECK(min_dot_with_computed(&m) > 0.999999);
    int up = 1, uv_ok = m.uvs != NULL;
    for (size_t v = 0; v < m.vertex_count; v++) {
        up &= m.normals[3 * v + 1] == 1.0f && m.positions[3 * v + 1] == 0.0f;
        up &= fabs(m.positions[3 * v]) == 1.25f && fabs(m.positions[3 * v + 2]) == 1.25f;
        if (m.uvs) uv_ok &= m.uvs[2 * v] >= 0 && m.uvs[2 * v] <= 1 && m.uvs[2 * v + 1] >= 0 && m.uvs[2 * v + 1] <= 1;
    }
    CHECK_MSG(up, "plane corners at +-size/2 in xz with normal +y");
    CHECK(uv_ok);
    /* winding: the geometric normal of each triangle is +y */
    for (uint32_t t = 0; t < m.triangle_count; t++) {
        const float *a = m.positions + 3 * m.indices[3 * t], *b = m.positions + 3 * m.indices[3 * t + 1],
                    *c = m.positions + 3 * m.indices[3 * t + 2];
        double ny = (double)(c[0] - a[0]) * (b[2] - a[2]) - (double)(c[2] - a[2]) * (b[0] - a[0]);
        CHECK(ny > 0);
    }
    sss_mesh_free(&m);

    const double size[3] = {0.5, 2.0, 3.0};
    CHECK(sss_mesh_box(size, &m, &err) == SSS_OK);
    CHECK(mesh_is_sane(&m));
    CHECK(m.uvs != NULL);
    CHECK_NEAR(sss_mesh_surface_area(&m), 2.0 * (0.5 * 2.0 + 2.0 * 3.0 + 0.5 * 3.0), 1e-12);
    CHECK_NEAR(sss_mesh_signed_volume(&m), 3.0, 1e-12);
    CHECK(min_dot_with_computed(&m) > 0.999999); /* flat faces: given = computed */
    float lo[3], hi[3];
    sss_mesh_bounds(&m, lo, hi);
    for (int k = 0; k < 3; k++) CHECK(lo[k] == (float)(-size[k] / 2) && hi[k] == (float)(size[k] / 2));
    CHECK_NEAR(vertex_area_sum(&m), sss_mesh_surface_area(&m), 1e-6);
    sss_mesh_free(&m);
}

/* Area-weighted normals at the corners of the 1 x 2 x 3 box of box_ascii.ply: at each corner, the
 * sum over incident triangles of (triangle area) x (its face's axis normal), normalised. The face of
 * a triangle is found from which coordinate its corners share; each triangle is half its face. */
static void test_box_corner_normals(void)
{
    sss_mesh m;
    sss_error err = {0};
    if (sss_mesh_read(SSS_TEST_DATA "/meshes/box_ascii.ply", &m, &err) != SSS_OK) {
        CHECK_MSG(0, "%s", err.message);
        return;
    }
    const double dim[3] = {1.0, 2.0, 3.0};
    double expect[8][3] = {{0}};
    for (uint32_t t = 0; t < m.triangle_count; t++) {
        const uint32_t *tri = m.indices + 3 * t;
        for (int axis = 0; axis < 3; axis++) {
            float c = m.positions[3 * tri[0] + (uint32_t)axis];
            if (m.positions[3 * tri[1] + (uint32_t)axis] != c || m.positions[3 * tri[2] + (uint32_t)axis] != c) continue;
            double area = 0.5 * dim[(axis + 1) % 3] * dim[(axis + 2) % 3];
            double sign = c > 0 ? 1.0 : -1.0;
            for (int k = 0; k < 3; k++) expect[tri[k]][axis] += sign * area;
        }
    }
    double worst = 0.0;
    for (int v = 0; v < 8; v++) {
        double len = sqrt(expect[v][0] * expect[v][0] + expect[v][1] * expect[v][1] + expect[v][2] * expect[v][2]);
        for (int k = 0; k < 3; k++) worst = fmax(worst, fabs(m.normals[3 * v + k] - expect[v][k] / len));
    }
    CHECK_MSG(worst < 1e-6, "corner normals differ from the area-weighted sum by %g", worst);
    /* and the weighting matters here: the unweighted mean of the three face normals differs */
    CHECK(fabs(m.normals[6 * 3 + 0] - 1.0 / sqrt(3.0)) > 0.1);
    /* per-vertex areas: one third of each incident triangle, summing to the total 22 */
    float areas[8];
    sss_mesh_vertex_areas(&m, areas);
    double sum = 0.0;
    for (int v = 0; v < 8; v++) sum += areas[v];
    CHECK_NEAR(sum, 22.0, 1e-5);
    sss_mesh_free(&m);
}

static void test_invalid_parameters(void)
{
    sss_mesh m;
    sss_error err = {0};
    const double zero_box[3] = {1, 0, 1}, nan_box[3] = {1, NAN, 1};
    CHECK(sss_mesh_sphere(0.0, 2, &m, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(sss_mesh_sphere(-1.0, 2, &m, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(sss_mesh_sphere(NAN, 2, &m, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(sss_mesh_sphere(INFINITY, 2, &m, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(sss_mesh_sphere(1.0, -1, &m, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(sss_mesh_sphere(1.0, 9, &m, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(err.message, "sphere") != NULL);
    CHECK(sss_mesh_torus(1.0, 1.0, 16, &m, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(sss_mesh_torus(1.0, 0.0, 16, &m, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(sss_mesh_torus(1.0, 0.3, 2, &m, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(sss_mesh_torus(1.0, 0.3, 100000, &m, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(sss_mesh_trefoil(1.0, 0.5, 64, &m, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(sss_mesh_trefoil(1.0, -0.1, 64, &m, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(sss_mesh_trefoil(1.0, 0.1, 2, &m, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(sss_mesh_plane(0.0, &m, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(sss_mesh_plane(-2.0, &m, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(sss_mesh_box(zero_box, &m, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(sss_mesh_box(nan_box, &m, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(sss_mesh_box(NULL, &m, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(m.positions == NULL && m.vertex_count == 0);
    /* the limits themselves are accepted */
    CHECK(sss_mesh_sphere(1.0, 0, &m, &err) == SSS_OK && m.vertex_count == 12 && m.triangle_count == 20);
    sss_mesh_free(&m);
    CHECK(sss_mesh_torus(1.0, 0.3, 3, &m, &err) == SSS_OK && m.triangle_count == 18);
    sss_mesh_free(&m);
    CHECK(sss_mesh_trefoil(1.0, 1.0 / 6.0, 3, &m, &err) == SSS_OK && mesh_is_sane(&m));
    sss_mesh_free(&m);
}

int main(void)
{
    test_sphere();
    test_torus();
    test_trefoil();
    test_plane_box();
    test_box_corner_normals();
    test_invalid_parameters();
    return CHECK_DONE();
}
