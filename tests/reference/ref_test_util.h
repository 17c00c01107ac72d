/* tests/reference/ref_test_util.h — small world-space meshes and scenes built in code for the
 * reference renderer's tests (independent of the mesh and scene modules). */
#ifndef SSS_REF_TEST_UTIL_H
#define SSS_REF_TEST_UTIL_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "sss/reference.h"

#define T_PI 3.14159265358979323846

/* ---- a growable mesh ---------------------------------------------------------------------- */

typedef struct tmesh {
    sss_mesh m;
    uint32_t vcap, tcap;
} tmesh;

static inline void tmesh_reserve(tmesh *b, uint32_t nv, uint32_t nt)
{
    if (b->m.vertex_count + nv > b->vcap) {
        b->vcap = 2 * (b->m.vertex_count + nv);
        b->m.positions = realloc(b->m.positions, sizeof(float) * 3 * b->vcap);
        b->m.normals = realloc(b->m.normals, sizeof(float) * 3 * b->vcap);
        if (!b->m.positions || !b->m.normals) exit(2);
    }
    if (b->m.triangle_count + nt > b->tcap) {
        b->tcap = 2 * (b->m.triangle_count + nt);
        b->m.indices = realloc(b->m.indices, sizeof(uint32_t) * 3 * b->tcap);
        if (!b->m.indices) exit(2);
    }
}

static inline uint32_t tmesh_vertex(tmesh *b, const double p[3], const double n[3])
{
    tmesh_reserve(b, 1, 0);
    uint32_t i = b->m.vertex_count++;
    for (int c = 0; c < 3; c++) {
        b->m.positions[3 * i + c] = (float)p[c];
        b->m.normals[3 * i + c] = (float)n[c];
    }
    return i;
}

/* Adds a triangle, wound counter-clockwise around the mean of its vertex normals. */
static inline void tmesh_triangle(tmesh *b, uint32_t i0, uint32_t i1, uint32_t i2)
{
    tmesh_reserve(b, 0, 1);
    const float *p = b->m.positions, *n = b->m.normals;
    double e1[3], e2[3], g[3], nn = 0.0;
    for (int c = 0; c < 3; c++) {
        e1[c] = (double)p[3 * i1 + c] - p[3 * i0 + c];
        e2[c] = (double)p[3 * i2 + c] - p[3 * i0 + c];
    }
    g[0] = e1[1] * e2[2] - e1[2] * e2[1];
    g[1] = e1[2] * e2[0] - e1[0] * e2[2];
    g[2] = e1[0] * e2[1] - e1[1] * e2[0];
    for (int c = 0; c < 3; c++) nn += g[c] * ((double)n[3 * i0 + c] + n[3 * i1 + c] + n[3 * i2 + c]);
    uint32_t *t = b->m.indices + 3 * b->m.triangle_count++;
    t[0] = i0;
    t[1] = nn >= 0.0 ? i1 : i2;
    t[2] = nn >= 0.0 ? i2 : i1;
}

/* A parametric surface patch f(s, t), s, t in [0, 1], as an ns x nt grid of quads. */
typedef void (*tsurf_fn)(const double *prm, double s, double t, double p[3], double n[3]);

static inline void tmesh_grid(tmesh *b, tsurf_fn f, const double *prm, int ns, int nt)
{
    uint32_t base = b->m.vertex_count;
    for (int j = 0; j <= nt; j++)
        for (int i = 0; i <= ns; i++) {
            double p[3], n[3];
            f(prm, (double)i / ns, (double)j / nt, p, n);
            tmesh_vertex(b, p, n);
        }
    for (int j = 0; j < nt; j++)
        for (int i = 0; i < ns; i++) {
            uint32_t a = base + (uint32_t)(j * (ns + 1) + i), bb = a + 1, c = a + (uint32_t)(ns + 1), d = c + 1;
            tmesh_triangle(b, a, bb, d);
            tmesh_triangle(b, a, d, c);
        }
}

static inline void tmesh_free(tmesh *b)
{
    free(b->m.positions);
    free(b->m.normals);
    free(b->m.indices);
    memset(b, 0, sizeof *b);
}

/* prm: corner (3), edge s (3), edge t (3), normal (3). */
static inline void surf_quad(const double *prm, double s, double t, double p[3], double n[3])
{
    for (int c = 0; c < 3; c++) {
        p[c] = prm[c] + s * prm[3 + c] + t * prm[6 + c];
        n[c] = prm[9 + c];
    }
}

/* Horizontal square of edge `size` centred at (cx, y, cz), facing +y (or -y when down). */
static inline void tmesh_plane(tmesh *b, double size, double cx, double y, double cz, int n, int down)
{
    double prm[12] = {cx - size / 2, y, cz - size / 2, size, 0, 0, 0, 0, size, 0, down ? -1 : 1, 0};
    tmesh_grid(b, surf_quad, prm, n, n);
}

/* Axis-aligned box [lo, hi] with flat faces, each an n x n grid. */
static inline void tmesh_box(tmesh *b, const double lo[3], const double hi[3], int n)
{
    for (int axis = 0; axis < 3; axis++)
        for (int side = 0; side < 2; side++) {
            int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
            double prm[12] = {0};
            prm[axis] = side ? hi[axis] : lo[axis];
            prm[a1] = lo[a1];
            prm[a2] = lo[a2];
            prm[3 + a1] = hi[a1] - lo[a1];
            prm[6 + a2] = hi[a2] - lo[a2];
            prm[9 + axis] = side ? 1.0 : -1.0;
            tmesh_grid(b, surf_quad, prm, n, n);
        }
}

/* prm: centre (3), radius. */
static inline void surf_sphere(const double *prm, double s, double t, double p[3], double n[3])
{
    double th = T_PI * t, ph = 2.0 * T_PI * s;
    n[0] = sin(th) * cos(ph), n[1] = cos(th), n[2] = sin(th) * sin(ph);
    for (int c = 0; c < 3; c++) p[c] = prm[c] + prm[3] * n[c];
}

static inline void tmesh_sphere(tmesh *b, const double c[3], double radius, int n)
{
    double prm[4] = {c[0], c[1], c[2], radius};
    tmesh_grid(b, surf_sphere, prm, 2 * n, n);
}

/* prm: centre (3), major, minor; around +y. */
static inline void surf_torus(const double *prm, double s, double t, double p[3], double n[3])
{
    double u = 2.0 * T_PI * s, v = 2.0 * T_PI * t;
    n[0] = cos(v) * cos(u), n[1] = sin(v), n[2] = cos(v) * sin(u);
    double ring[3] = {prm[3] * cos(u), 0.0, prm[3] * sin(u)};
    for (int c = 0; c < 3; c++) p[c] = prm[c] + ring[c] + prm[4] * n[c];
}

static inline void tmesh_torus(tmesh *b, const double c[3], double major, double minor, int n)
{
    double prm[5] = {c[0], c[1], c[2], major, minor};
    tmesh_grid(b, surf_torus, prm, 2 * n, n);
}

/* ---- world helpers -------------------------------------------------------------------------- */

static inline void camera_set(sss_camera *cam, double px, double py, double pz, double lx, double ly, double lz,
                       double fov, int w, int h)
{
    memset(cam, 0, sizeof *cam);
    cam->position[0] = px, cam->position[1] = py, cam->position[2] = pz;
    cam->look_at[0] = lx, cam->look_at[1] = ly, cam->look_at[2] = lz;
    cam->up[0] = 0, cam->up[1] = 1, cam->up[2] = 0;
    if (fabs(px - lx) < 1e-12 && fabs(pz - lz) < 1e-12) cam->up[1] = 0, cam->up[2] = -1;
    cam->fov = fov;
    cam->width = w, cam->height = h;
}

static inline sss_reference_object object_diffuse(const sss_mesh *m, double r)
{
    sss_reference_object o;
    memset(&o, 0, sizeof o);
    o.mesh = m;
    o.type = SSS_REFERENCE_DIFFUSE;
    o.reflectance[0] = o.reflectance[1] = o.reflectance[2] = r;
    return o;
}

/* A PBD subsurface object; *table is built here (caller frees it). */
static inline sss_reference_object object_subsurface(const sss_mesh *m, const sss_material *mat, sss_pbd_table **table)
{
    sss_reference_object o;
    memset(&o, 0, sizeof o);
    o.mesh = m;
    o.type = SSS_REFERENCE_SUBSURFACE;
    o.optical = *mat;
    o.profile = SSS_SCENE_PROFILE_PBD;
    *table = malloc(sizeof **table);
    sss_error err;
    if (!*table || sss_pbd_table_build(mat->eta, mat->g, *table, &err) != SSS_OK) {
        fprintf(stderr, "table build failed\n");
        exit(2);
    }
    o.table = *table;
    return o;
}

static inline sss_material material_coeffs(double sa0, double sa1, double sa2, double ss0, double ss1, double ss2,
                                    double eta)
{
    sss_material m;
    memset(&m, 0, sizeof m);
    m.sigma_a[0] = sa0, m.sigma_a[1] = sa1, m.sigma_a[2] = sa2;
    m.sigma_s[0] = ss0, m.sigma_s[1] = ss1, m.sigma_s[2] = ss2;
    m.eta = eta;
    return m;
}

static inline sss_light light_directional(double dx, double dy, double dz, double e)
{
    sss_light l;
    memset(&l, 0, sizeof l);
    l.type = SSS_LIGHT_DIRECTIONAL;
    l.direction[0] = dx, l.direction[1] = dy, l.direction[2] = dz;
    l.radiance[0] = l.radiance[1] = l.radiance[2] = e;
    return l;
}

static inline sss_light light_point(double x, double y, double z, double i)
{
    sss_light l;
    memset(&l, 0, sizeof l);
    l.type = SSS_LIGHT_POINT;
    l.position[0] = x, l.position[1] = y, l.position[2] = z;
    l.intensity[0] = l.intensity[1] = l.intensity[2] = i;
    return l;
}

static inline double img_at(const sss_image *img, int x, int y, int c) { return img->pixels[3 * ((size_t)y * img->width + x) + c]; }

static inline double img_max(const sss_image *img)
{
    double m = 0.0;
    for (size_t i = 0; i < 3 * (size_t)img->width * img->height; i++)
        if (img->pixels[i] > m) m = img->pixels[i];
    return m;
}

/* J(a) = int_a^inf S(r) 2 r acos(a / r) dr: the plane integral of channel c of the profile over a
 * half-plane whose edge is a >= 0 away (the arc of the circle of radius r beyond the edge); midpoint rule
 * in v, r = a + e^v, from 1e-10 to 60 units beyond a. */
static inline double ref_edge_J(const sss_profile *p, int c, double a)
{
    double v0 = log(1e-10), v1 = log(60.0), sum = 0.0;
    int n = 6000;
    for (int i = 0; i < n; i++) {
        double v = v0 + (v1 - v0) * (i + 0.5) / n, e = exp(v), r = a + e;
        double ac = a > 0.0 ? acos(a / r) : 0.5 * T_PI;
        sum += sss_profile_eval(p, c, r) * 2.0 * r * ac * e * (v1 - v0) / n;
    }
    return sum;
}

static inline int render_or_die(const sss_reference_world *w, const sss_reference_desc *d, sss_image *out,
                         sss_reference_stats *st)
{
    sss_error err;
    memset(&err, 0, sizeof err);
    sss_result r = sss_reference_render_world(w, d, out, NULL, NULL, st, &err);
    if (r != SSS_OK) fprintf(stderr, "render failed: %s\n", err.message);
    return r == SSS_OK;
}

#endif
