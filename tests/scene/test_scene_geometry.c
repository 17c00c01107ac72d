/* Scene geometry: object transforms (T R S, normal matrix, world meshes) and the camera (basis,
 * primary rays with fov on the shorter axis, projection, GL matrices). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "sss/scene.h"

static const double PI = 3.14159265358979323846;

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void mat3_vec(const double m[16], const double v[3], double out[3])
{
    for (int r = 0; r < 3; r++) out[r] = m[4 * r] * v[0] + m[4 * r + 1] * v[1] + m[4 * r + 2] * v[2];
}

/* ---- Transforms ------------------------------------------------------------------------------- */

static void make_transform(sss_transform *t, const double tr[3], const double rot[4], const double sc[3])
{
    memcpy(t->translate, tr, 3 * sizeof *tr);
    memcpy(t->rotate, rot, 4 * sizeof *rot);
    memcpy(t->scale, sc, 3 * sizeof *sc);
    CHECK(sss_transform_update(t, NULL) == SSS_OK);
}

static void test_transform_compose(void)
{
    sss_transform t;
    /* scale (2, 3, 4), then 90 degrees about +z ((x, y) -> (-y, x), right-handed), then translate. */
    make_transform(&t, (double[]){1, 2, 3}, (double[]){0, 0, 1, 90}, (double[]){2, 3, 4});
    double p[3] = {1, 1, 1}, q[3];
    sss_transform_point(t.matrix, p, q);
    CHECK_NEAR(q[0], -3 + 1, 1e-12);
    CHECK_NEAR(q[1], 2 + 2, 1e-12);
    CHECK_NEAR(q[2], 4 + 3, 1e-12);
    CHECK(t.matrix[12] == 0 && t.matrix[13] == 0 && t.matrix[14] == 0 && t.matrix[15] == 1);

    /* 120 degrees about (1, 1, 1) (unnormalised) cycles the axes x -> y -> z -> x. */
    make_transform(&t, (double[]){0, 0, 0}, (double[]){5, 5, 5, 120}, (double[]){1, 1, 1});
    double ex[3] = {1, 0, 0}, ey[3] = {0, 1, 0};
    sss_transform_point(t.matrix, ex, q);
    CHECK_NEAR(q[0], 0, 1e-12);
    CHECK_NEAR(q[1], 1, 1e-12);
    CHECK_NEAR(q[2], 0, 1e-12);
    sss_transform_point(t.matrix, ey, q);
    CHECK_NEAR(q[2], 1, 1e-12);

    /* Scale happens before rotation: a uniform-axis rotation of a scaled x point keeps |2 x|. */
    make_transform(&t, (double[]){0, 0, 0}, (double[]){0, 1, 0, 30}, (double[]){2, 1, 1});
    sss_transform_point(t.matrix, ex, q);
    CHECK_NEAR(q[0], 2 * cos(30 * PI / 180), 1e-12);
    CHECK_NEAR(q[2], -2 * sin(30 * PI / 180), 1e-12); /* right-handed about +y: x -> -z */

    /* Identity. */
    sss_transform_identity(&t);
    sss_transform_point(t.matrix, (double[]){3, -4, 5}, q);
    CHECK(q[0] == 3 && q[1] == -4 && q[2] == 5);

    /* Errors. */
    sss_error err = {0};
    sss_transform bad;
    sss_transform_identity(&bad);
    bad.rotate[1] = 0;
    CHECK(sss_transform_update(&bad, &err) == SSS_ERROR_INVALID_ARGUMENT);
    sss_transform_identity(&bad);
    bad.scale[2] = 0;
    CHECK(sss_transform_update(&bad, &err) == SSS_ERROR_INVALID_ARGUMENT);
    sss_transform_identity(&bad);
    bad.translate[0] = NAN;
    CHECK(sss_transform_update(&bad, &err) == SSS_ERROR_INVALID_ARGUMENT);
    /* A subnormal scale is finite and non-zero, but the normal matrix (1/scale) would be infinite. */
    sss_transform_identity(&bad);
    bad.scale[0] = 1e-320;
    CHECK(sss_transform_update(&bad, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(err.message, "out of range") != NULL);
    sss_transform_identity(&bad);
    bad.scale[1] = -2e18;
    CHECK(sss_transform_update(&bad, &err) == SSS_ERROR_INVALID_ARGUMENT);
    /* The limits themselves are accepted, and an axis near DBL_MAX is normalised (no overflow). */
    sss_transform lim;
    sss_transform_identity(&lim);
    lim.scale[0] = SSS_SCENE_SCALE_MIN;
    lim.scale[2] = -SSS_SCENE_SCALE_MAX;
    lim.rotate[0] = 1e308;
    lim.rotate[1] = 1e308;
    lim.rotate[3] = 90;
    CHECK(sss_transform_update(&lim, &err) == SSS_OK);
    double nq[3];
    sss_transform_normal(lim.normal_matrix, (double[]){1, 0, 0}, nq);
    CHECK(fabs(hypot(hypot(nq[0], nq[1]), nq[2]) - 1) < 1e-12);
}

/* The normal matrix keeps transformed normals perpendicular to transformed tangents under
 * non-uniform (and mirroring) scale. */
static void test_normal_matrix(void)
{
    sss_transform t;
    make_transform(&t, (double[]){0.3, -2, 7}, (double[]){0.2, -1, 0.7, 47}, (double[]){3, 0.25, -1.5});
    srand(7);
    for (int k = 0; k < 200; k++) {
        double n[3], a[3], tan1[3], tan2[3];
        for (int i = 0; i < 3; i++) {
            n[i] = rand() / (double)RAND_MAX - 0.5;
            a[i] = rand() / (double)RAND_MAX - 0.5;
        }
        /* Two tangents perpendicular to n. */
        tan1[0] = n[1] * a[2] - n[2] * a[1];
        tan1[1] = n[2] * a[0] - n[0] * a[2];
        tan1[2] = n[0] * a[1] - n[1] * a[0];
        tan2[0] = n[1] * tan1[2] - n[2] * tan1[1];
        tan2[1] = n[2] * tan1[0] - n[0] * tan1[2];
        tan2[2] = n[0] * tan1[1] - n[1] * tan1[0];
        double tn[3], tt1[3], tt2[3];
        sss_transform_normal(t.normal_matrix, n, tn);
        mat3_vec(t.matrix, tan1, tt1);
        mat3_vec(t.matrix, tan2, tt2);
        CHECK_NEAR(sqrt(dot3(tn, tn)), 1, 1e-12);
        CHECK_NEAR(dot3(tn, tt1) / sqrt(dot3(tt1, tt1)), 0, 1e-12);
        CHECK_NEAR(dot3(tn, tt2) / sqrt(dot3(tt2, tt2)), 0, 1e-12);
    }
    /* A plain matrix (instead of the inverse transpose) would fail the same test. */
    double n[3] = {1, 1, 0}, tan[3] = {1, -1, 0}, tn[3], tt[3];
    make_transform(&t, (double[]){0, 0, 0}, (double[]){0, 1, 0, 0}, (double[]){4, 1, 1});
    sss_transform_normal(t.normal_matrix, n, tn);
    mat3_vec(t.matrix, tan, tt);
    CHECK_NEAR(dot3(tn, tt), 0, 1e-12);
    mat3_vec(t.matrix, n, tn);
    CHECK(fabs(dot3(tn, tt)) > 1);
}

/* A closed tetrahedron, counter-clockwise from outside. */
static void make_tetra(sss_mesh *m)
{
    static const float pos[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    static const uint32_t idx[12] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
    memset(m, 0, sizeof *m);
    m->vertex_count = 4;
    m->triangle_count = 4;
    m->positions = malloc(sizeof pos);
    m->normals = malloc(sizeof pos);
    m->indices = malloc(sizeof idx);
    memcpy(m->positions, pos, sizeof pos);
    memcpy(m->indices, idx, sizeof idx);
    for (int v = 0; v < 4; v++) {
        double c[3] = {pos[3 * v] - 0.25, pos[3 * v + 1] - 0.25, pos[3 * v + 2] - 0.25};
        double l = sqrt(dot3(c, c));
        for (int i = 0; i < 3; i++) m->normals[3 * v + i] = (float)(c[i] / l);
    }
}

static double signed_volume(const sss_mesh *m)
{
    double v = 0;
    for (uint32_t f = 0; f < m->triangle_count; f++) {
        const float *a = &m->positions[3 * m->indices[3 * f]], *b = &m->positions[3 * m->indices[3 * f + 1]],
                    *c = &m->positions[3 * m->indices[3 * f + 2]];
        v += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
              a[2] * (b[0] * c[1] - b[1] * c[0])) / 6.0;
    }
    return v;
}

static void test_world_mesh(void)
{
    sss_scene_object obj;
    memset(&obj, 0, sizeof obj);
    make_tetra(&obj.mesh);
    CHECK_NEAR(signed_volume(&obj.mesh), 1.0 / 6, 1e-7);
    /* Mirror in x, stretch: volume scales by |det| = 2 * 3 * 1, sign kept by the winding flip. */
    make_transform(&obj.transform, (double[]){1, 2, 3}, (double[]){0, 1, 0, 90}, (double[]){-2, 3, 1});
    sss_mesh w;
    sss_error err = {0};
    CHECK(sss_scene_object_world_mesh(&obj, 0.0, &w, &err) == SSS_OK);
    CHECK_NEAR(signed_volume(&w), 6.0 / 6, 1e-5);
    /* Positions match sss_transform_point; normals stay unit and outward (away from the centroid). */
    double centroid[3] = {0, 0, 0};
    for (uint32_t v = 0; v < 4; v++)
        for (int i = 0; i < 3; i++) centroid[i] += w.positions[3 * v + i] / 4.0;
    for (uint32_t v = 0; v < 4; v++) {
        double p[3] = {obj.mesh.positions[3 * v], obj.mesh.positions[3 * v + 1], obj.mesh.positions[3 * v + 2]}, q[3];
        sss_transform_point(obj.transform.matrix, p, q);
        for (int i = 0; i < 3; i++) CHECK_NEAR(w.positions[3 * v + i], q[i], 1e-5);
        double n[3] = {w.normals[3 * v], w.normals[3 * v + 1], w.normals[3 * v + 2]};
        double out[3] = {q[0] - centroid[0], q[1] - centroid[1], q[2] - centroid[2]};
        CHECK_NEAR(dot3(n, n), 1, 1e-5);
        CHECK(dot3(n, out) > 0);
    }
    /* The source mesh is untouched. */
    CHECK(obj.mesh.positions[3] == 1.0f && obj.mesh.indices[1] == 2);
    sss_mesh_free(&w);
    /* Non-finite time is refused; a huge translation that overflows float is reported, not returned. */
    CHECK(sss_scene_object_world_mesh(&obj, NAN, &w, &err) == SSS_ERROR_INVALID_ARGUMENT);
    make_transform(&obj.transform, (double[]){1e300, 0, 0}, (double[]){0, 1, 0, 0}, (double[]){1, 1, 1});
    CHECK(sss_scene_object_world_mesh(&obj, 0.0, &w, &err) == SSS_ERROR_NUMERIC);
    sss_mesh_free(&obj.mesh);
}

/* ---- Camera ------------------------------------------------------------------------------------ */

static sss_camera camera(double fov, int w, int h)
{
    sss_camera c = {{1, 2, 3}, {1, 2, 0}, {0, 1, 0}, fov, w, h};
    return c;
}

/* Point at distance 1 along forward on the ray through raster (px, py), in camera (right, up). */
static void plane_point(const sss_camera_basis *b, double px, double py, double *x, double *y)
{
    double o[3], d[3];
    sss_camera_ray(b, px, py, o, d);
    double f = dot3(d, b->forward);
    *x = dot3(d, b->right) / f;
    *y = dot3(d, b->up) / f;
}

static void test_camera_rays(void)
{
    sss_camera_basis b;
    sss_error err = {0};
    sss_camera c = camera(40, 200, 100);
    CHECK(sss_camera_basis_init(&c, &b, &err) == SSS_OK);
    /* The centre of the image looks at look_at. */
    double o[3], d[3];
    sss_camera_ray(&b, 100, 50, o, d);
    CHECK(o[0] == 1 && o[1] == 2 && o[2] == 3);
    CHECK_NEAR(d[0], 0, 1e-15);
    CHECK_NEAR(d[1], 0, 1e-15);
    CHECK_NEAR(d[2], -1, 1e-15);
    /* fov along the shorter (vertical) axis: extent 2 tan(fov/2) at distance 1, horizontal twice. */
    double t = tan(20 * PI / 180), x0, y0, x1, y1;
    plane_point(&b, 100, 0, &x0, &y0);
    plane_point(&b, 100, 100, &x1, &y1);
    CHECK_NEAR(y0 - y1, 2 * t, 1e-12);
    plane_point(&b, 0, 50, &x0, &y0);
    plane_point(&b, 200, 50, &x1, &y1);
    CHECK_NEAR(x1 - x0, 4 * t, 1e-12);
    /* Orientation: camera at +z looking at -z, y up -> raster x grows towards +x (right-handed, OpenGL
     * convention) and raster y grows downwards. */
    sss_camera_ray(&b, 199.5, 50, o, d);
    CHECK(d[0] > 0.5);
    sss_camera_ray(&b, 100, 0.5, o, d);
    CHECK(d[1] > 0.3);
    /* Tall image: the shorter axis is now horizontal. */
    c = camera(40, 100, 200);
    CHECK(sss_camera_basis_init(&c, &b, &err) == SSS_OK);
    plane_point(&b, 0, 100, &x0, &y0);
    plane_point(&b, 100, 100, &x1, &y1);
    CHECK_NEAR(x1 - x0, 2 * t, 1e-12);
    plane_point(&b, 50, 0, &x0, &y0);
    plane_point(&b, 50, 200, &x1, &y1);
    CHECK_NEAR(y0 - y1, 4 * t, 1e-12);
    /* A tilted up vector is orthogonalised; the basis is orthonormal and right-handed. */
    sss_camera tilted = {{0, 0, 0}, {1, 1, 1}, {0.3, 1, 0}, 60, 64, 48};
    CHECK(sss_camera_basis_init(&tilted, &b, &err) == SSS_OK);
    CHECK_NEAR(dot3(b.right, b.up), 0, 1e-14);
    CHECK_NEAR(dot3(b.right, b.forward), 0, 1e-14);
    CHECK_NEAR(dot3(b.up, b.forward), 0, 1e-14);
    double cr[3] = {b.right[1] * b.up[2] - b.right[2] * b.up[1], b.right[2] * b.up[0] - b.right[0] * b.up[2],
                    b.right[0] * b.up[1] - b.right[1] * b.up[0]};
    CHECK_NEAR(dot3(cr, b.forward), -1, 1e-14); /* right x up = -forward = camera +z */
    /* Projection inverts the ray. */
    for (int k = 0; k < 50; k++) {
        double px = 64.0 * k / 49.0, py = 48.0 * ((k * 7) % 50) / 49.0, p[3], r[2], depth;
        sss_camera_ray(&b, px, py, o, d);
        for (int i = 0; i < 3; i++) p[i] = o[i] + 3.7 * d[i];
        CHECK(sss_camera_project(&b, p, r, &depth) == 1);
        CHECK_NEAR(r[0], px, 1e-9);
        CHECK_NEAR(r[1], py, 1e-9);
        CHECK_NEAR(depth, 3.7 * dot3(d, b.forward), 1e-12);
    }
    double behind[3] = {-1, -1, -1}, r[2];
    CHECK(sss_camera_project(&b, behind, r, NULL) == 0);
}

static void mat4_apply(const double m[16], const double p[4], double out[4])
{
    for (int r = 0; r < 4; r++) out[r] = m[4 * r] * p[0] + m[4 * r + 1] * p[1] + m[4 * r + 2] * p[2] + m[4 * r + 3] * p[3];
}

static void test_camera_matrices(void)
{
    sss_camera c = {{0.5, 1, 4}, {0, 0.2, 0}, {0, 1, 0}, 35, 320, 240};
    sss_camera_basis b;
    CHECK(sss_camera_basis_init(&c, &b, NULL) == SSS_OK);
    double V[16], P[16];
    sss_camera_view_matrix(&b, V);
    sss_camera_projection_matrix(&b, 0.1, 100, P);
    double pos[4] = {0.5, 1, 4, 1}, look[4] = {0, 0.2, 0, 1}, q[4], clip[4];
    mat4_apply(V, pos, q);
    CHECK_NEAR(q[0], 0, 1e-12);
    CHECK_NEAR(q[1], 0, 1e-12);
    CHECK_NEAR(q[2], 0, 1e-12);
    mat4_apply(V, look, q);
    double dist = sqrt(0.25 + 0.64 + 16);
    CHECK_NEAR(q[0], 0, 1e-12);
    CHECK_NEAR(q[1], 0, 1e-12);
    CHECK_NEAR(q[2], -dist, 1e-12);
    /* A point on the ray through raster (px, py) lands at NDC (2 px / w - 1, 1 - 2 py / h); the near
     * and far distances map to depth -1 and 1. */
    double o[3], d[3];
    sss_camera_ray(&b, 40, 200, o, d);
    double along = 10 / dot3(d, b.forward);
    double p[4] = {o[0] + along * d[0], o[1] + along * d[1], o[2] + along * d[2], 1};
    mat4_apply(V, p, q);
    mat4_apply(P, q, clip);
    CHECK_NEAR(clip[0] / clip[3], 2 * 40.0 / 320 - 1, 1e-12);
    CHECK_NEAR(clip[1] / clip[3], 1 - 2 * 200.0 / 240, 1e-12);
    double near_pt[4] = {0, 0, -0.1, 1}, far_pt[4] = {0, 0, -100, 1};
    mat4_apply(P, near_pt, clip);
    CHECK_NEAR(clip[2] / clip[3], -1, 1e-12);
    mat4_apply(P, far_pt, clip);
    CHECK_NEAR(clip[2] / clip[3], 1, 1e-12);
}

static void test_camera_errors(void)
{
    sss_camera_basis b;
    sss_error err = {0};
    sss_camera c = camera(0, 10, 10);
    CHECK(sss_camera_basis_init(&c, &b, &err) == SSS_ERROR_INVALID_ARGUMENT);
    c = camera(180, 10, 10);
    CHECK(sss_camera_basis_init(&c, &b, &err) == SSS_ERROR_INVALID_ARGUMENT);
    c = camera(30, 0, 10);
    CHECK(sss_camera_basis_init(&c, &b, &err) == SSS_ERROR_INVALID_ARGUMENT);
    c = camera(30, 10, SSS_SCENE_MAX_IMAGE_SIZE + 1);
    CHECK(sss_camera_basis_init(&c, &b, &err) == SSS_ERROR_INVALID_ARGUMENT);
    c = camera(30, 10, 10);
    c.look_at[2] = 3;
    CHECK(sss_camera_basis_init(&c, &b, &err) == SSS_ERROR_INVALID_ARGUMENT);
    c = camera(30, 10, 10);
    c.up[1] = 0;
    c.up[2] = 1;
    CHECK(sss_camera_basis_init(&c, &b, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(err.message, "parallel") != NULL);
    c = camera(30, 10, 10);
    c.position[0] = INFINITY;
    CHECK(sss_camera_basis_init(&c, &b, &err) == SSS_ERROR_INVALID_ARGUMENT);
}

int main(void)
{
    test_transform_compose();
    test_normal_matrix();
    test_world_mesh();
    test_camera_rays();
    test_camera_matrices();
    test_camera_errors();
    return CHECK_DONE();
}
