/* mesh/shapes.c — the procedural shapes of docs/scene-format.md (sphere, torus, trefoil, plane, box), centred at
 * the origin, counter-clockwise seen from outside, with exact (analytic) normals. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mesh/mesh_internal.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* A usable size: positive and small enough that positions and areas stay finite in float. */
static int positive(double x) { return isfinite(x) && x > 0.0 && x <= SSS_MESH_MAX_SHAPE_SIZE; }

static void set3(float *dst, double x, double y, double z)
{
    dst[0] = (float)x;
    dst[1] = (float)y;
    dst[2] = (float)z;
}

/* ---- sphere: a subdivided icosahedron ---- */

static uint32_t midpoint(mesh_hash *h, double *unit, uint32_t *count, uint32_t a, uint32_t b, int *oom)
{
    uint64_t key = a < b ? (uint64_t)a << 32 | b : (uint64_t)b << 32 | a;
    int inserted;
    uint32_t *slot = mesh_hash_get(h, key, &inserted);
    if (!slot) {
        *oom = 1;
        return 0;
    }
    if (!inserted) return *slot;
    double *pa = unit + 3 * (size_t)a, *pb = unit + 3 * (size_t)b, *pm = unit + 3 * (size_t)*count;
    double m[3] = {pa[0] + pb[0], pa[1] + pb[1], pa[2] + pb[2]};
    double len = sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
    for (int k = 0; k < 3; k++) pm[k] = m[k] / len; /* projected back onto the sphere */
    *slot = (*count)++;
    return *slot;
}

sss_result sss_mesh_sphere(double radius, int subdivisions, sss_mesh *out, sss_error *err)
{
    memset(out, 0, sizeof *out);
    if (!positive(radius)) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sphere: radius must be in (0, %g] (got %g)", SSS_MESH_MAX_SHAPE_SIZE, radius);
    if (subdivisions < 0 || subdivisions > 8)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sphere: subdivisions must be in 0..8 (got %d)", subdivisions);
    /* A regular icosahedron: cyclic permutations of (+-1, +-g, 0), g the golden ratio. */
#define G 1.6180339887498948482
    static const double ico_v[12][3] = {{-1, G, 0}, {1, G, 0},  {-1, -G, 0}, {1, -G, 0}, {0, -1, G},  {0, 1, G},
                                        {0, -1, -G}, {0, 1, -G}, {G, 0, -1},  {G, 0, 1},  {-G, 0, -1}, {-G, 0, 1}};
#undef G
    static const uint32_t ico_f[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                          {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                          {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                          {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    uint32_t nv = 10u * (1u << (2 * subdivisions)) + 2u, nt = 20u * (1u << (2 * subdivisions));
    double *unit = malloc((size_t)nv * 3 * sizeof *unit);
    uint32_t *tri = malloc((size_t)nt * 3 * sizeof *tri), *next = malloc((size_t)nt * 3 * sizeof *next);
    mesh_hash h;
    int hash_ok = mesh_hash_init(&h, (size_t)nv);
    sss_result r = SSS_OK;
    if (!unit || !tri || !next || !hash_ok) r = sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "sphere: out of memory");
    uint32_t count = 12, tris = 20;
    if (r == SSS_OK) {
        for (int i = 0; i < 12; i++) {
            double len = sqrt(ico_v[i][0] * ico_v[i][0] + ico_v[i][1] * ico_v[i][1] + ico_v[i][2] * ico_v[i][2]);
            for (int k = 0; k < 3; k++) unit[3 * i + k] = ico_v[i][k] / len;
        }
        memcpy(tri, ico_f, sizeof ico_f);
    }
    for (int s = 0; s < subdivisions && r == SSS_OK; s++) {
        int oom = 0;
        h.count = 0;
        memset(h.keys, 0xff, h.cap * sizeof *h.keys);
        for (uint32_t t = 0; t < tris; t++) {
            uint32_t a = tri[3 * t], b = tri[3 * t + 1], c = tri[3 * t + 2];
            uint32_t ab = midpoint(&h, unit, &count, a, b, &oom);
            uint32_t bc = midpoint(&h, unit, &count, b, c, &oom);
            uint32_t ca = midpoint(&h, unit, &count, c, a, &oom);
            uint32_t quad[12] = {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca}; /* same winding as the parent */
            memcpy(next + 12 * (size_t)t, quad, sizeof quad);
        }
        if (oom) r = sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "sphere: out of memory");
        uint32_t *swap = tri;
        tri = next;
        next = swap;
        tris *= 4;
    }
    if (r == SSS_OK) r = mesh_alloc(out, nv, nt, 1, 0, "sphere", err);
    if (r == SSS_OK) {
        for (size_t i = 0; i < (size_t)nv * 3; i++) {
            out->positions[i] = (float)(radius * unit[i]);
            out->normals[i] = (float)unit[i];
        }
        memcpy(out->indices, tri, (size_t)nt * 3 * sizeof *tri);
    }
    free(unit);
    free(tri);
    free(next);
    mesh_hash_free(&h);
    return r;
}

/* ---- tubes: torus and trefoil share the grid of quads ---- */

/* Indices of an n x m grid that wraps in both directions; vertex (i, j) is i * m + j with i along
 * the tube's core and j around it. Each quad is split as (i,j) (i,j+1) (i+1,j+1) and (i,j) (i+1,j+1)
 * (i+1,j): its normal is d/dj x d/di, which the callers make point outward. */
static void wrapped_grid(uint32_t *idx, uint32_t n, uint32_t m)
{
    for (uint32_t i = 0; i < n; i++)
        for (uint32_t j = 0; j < m; j++) {
            uint32_t i1 = (i + 1) % n, j1 = (j + 1) % m;
            uint32_t a = i * m + j, b = i * m + j1, c = i1 * m + j1, d = i1 * m + j;
            uint32_t *t = idx + 6 * ((size_t)i * m + j);
            t[0] = a, t[1] = b, t[2] = c;
            t[3] = a, t[4] = c, t[5] = d;
        }
}

sss_result sss_mesh_torus(double major, double minor, int segments, sss_mesh *out, sss_error *err)
{
    memset(out, 0, sizeof *out);
    if (!positive(major) || !positive(minor) || !(minor < major))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "torus: need 0 < minor < major (got major %g, minor %g)",
                             major, minor);
    if (segments < 3 || segments > 2048)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "torus: segments must be in 3..2048 (got %d)", segments);
    uint32_t n = (uint32_t)segments;
    sss_result r = mesh_alloc(out, n * n, 2 * n * n, 1, 0, "torus", err);
    if (r != SSS_OK) return r;
    for (uint32_t i = 0; i < n; i++) {
        double u = 2.0 * M_PI * i / n, cu = cos(u), su = sin(u);
        for (uint32_t j = 0; j < n; j++) {
            double v = 2.0 * M_PI * j / n, cv = cos(v), sv = sin(v);
            size_t k = 3 * ((size_t)i * n + j);
            /* around +y in the xz-plane; d/dv x d/du points outward, hence the grid's (j, then i) order */
            set3(out->positions + k, (major + minor * cv) * cu, minor * sv, (major + minor * cv) * su);
            set3(out->normals + k, cv * cu, sv, cv * su);
        }
    }
    wrapped_grid(out->indices, n, n);
    return SSS_OK;
}

/* The trefoil's core curve scaled so its extent in the xy-plane is `radius`, and its derivative. */
static void trefoil_curve(double t, double s, double c[3], double d[3])
{
    c[0] = s * (sin(t) + 2.0 * sin(2.0 * t));
    c[1] = s * (cos(t) - 2.0 * cos(2.0 * t));
    c[2] = -s * sin(3.0 * t);
    d[0] = s * (cos(t) + 4.0 * cos(2.0 * t));
    d[1] = s * (-sin(t) + 4.0 * sin(2.0 * t));
    d[2] = -3.0 * s * cos(3.0 * t);
}

sss_result sss_mesh_trefoil(double radius, double tube, int segments, sss_mesh *out, sss_error *err)
{
    memset(out, 0, sizeof *out);
    /* The core's closest approach to itself is 0.40 radius and its smallest radius of curvature
     * 0.43 radius, so a tube up to radius / 6 never intersects itself. */
    if (!positive(radius) || !positive(tube) || tube > radius / 6.0)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "trefoil: need 0 < tube <= radius / 6 (got radius %g, tube %g)",
                             radius, tube);
    if (segments < 3 || segments > 4096)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "trefoil: segments must be in 3..4096 (got %d)", segments);
    uint32_t n = (uint32_t)segments, m = n / 8 < 3 ? 3 : n / 8;
    sss_result r = mesh_alloc(out, n * m, 2 * n * m, 1, 0, "trefoil", err);
    if (r != SSS_OK) return r;
    for (uint32_t i = 0; i < n; i++) {
        double c[3], d[3];
        trefoil_curve(2.0 * M_PI * i / n, radius / 3.0, c, d);
        /* Frame: T along the curve, N the z axis made orthogonal to T (T is never parallel to z: its
         * xy part has length >= 3 s), B = T x N. It is periodic, so the tube closes without a twist. */
        double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        double T[3] = {d[0] / len, d[1] / len, d[2] / len};
        double N[3] = {-T[2] * T[0], -T[2] * T[1], 1.0 - T[2] * T[2]};
        double nl = sqrt(N[0] * N[0] + N[1] * N[1] + N[2] * N[2]);
        for (int k = 0; k < 3; k++) N[k] /= nl;
        double B[3] = {T[1] * N[2] - T[2] * N[1], T[2] * N[0] - T[0] * N[2], T[0] * N[1] - T[1] * N[0]};
        for (uint32_t j = 0; j < m; j++) {
            double th = 2.0 * M_PI * j / m, ct = cos(th), st = sin(th);
            double nrm[3] = {ct * N[0] + st * B[0], ct * N[1] + st * B[1], ct * N[2] + st * B[2]};
            size_t k = 3 * ((size_t)i * m + j);
            /* d/dtheta x T = nrm (T x N = B, T x B = -N), so (j, then i) is outward as for the torus */
            set3(out->positions + k, c[0] + tube * nrm[0], c[1] + tube * nrm[1], c[2] + tube * nrm[2]);
            set3(out->normals + k, nrm[0], nrm[1], nrm[2]);
        }
    }
    wrapped_grid(out->indices, n, m);
    return SSS_OK;
}

/* ---- plane and box ---- */

sss_result sss_mesh_plane(double size, sss_mesh *out, sss_error *err)
{
    memset(out, 0, sizeof *out);
    if (!positive(size)) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "plane: size must be in (0, %g] (got %g)", SSS_MESH_MAX_SHAPE_SIZE, size);
    sss_result r = mesh_alloc(out, 4, 2, 1, 1, "plane", err);
    if (r != SSS_OK) return r;
    double h = size / 2.0;
    static const double corner[4][2] = {{-1, -1}, {-1, 1}, {1, 1}, {1, -1}}; /* (x, z): CCW seen from +y */
    for (int i = 0; i < 4; i++) {
        set3(out->positions + 3 * i, h * corner[i][0], 0.0, h * corner[i][1]);
        set3(out->normals + 3 * i, 0.0, 1.0, 0.0);
        out->uvs[2 * i] = (float)(0.5 + 0.5 * corner[i][0]);
        out->uvs[2 * i + 1] = (float)(0.5 - 0.5 * corner[i][1]); /* v grows towards -z */
    }
    static const uint32_t idx[6] = {0, 1, 2, 0, 2, 3};
    memcpy(out->indices, idx, sizeof idx);
    return SSS_OK;
}

sss_result sss_mesh_box(const double size[3], sss_mesh *out, sss_error *err)
{
    memset(out, 0, sizeof *out);
    if (!size || !positive(size[0]) || !positive(size[1]) || !positive(size[2]))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "box: size must be three numbers in (0, %g]", SSS_MESH_MAX_SHAPE_SIZE);
    sss_result r = mesh_alloc(out, 24, 12, 1, 1, "box", err);
    if (r != SSS_OK) return r;
    /* Per face: outward axis n and in-face axes s, t with s x t = n, so the corners (-,-), (+,-),
     * (+,+), (-,+) in (s, t) run counter-clockwise seen from outside. */
    static const int face[3][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}}; /* n, s, t for +x, +y, +z */
    static const double uv[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (int f = 0; f < 6; f++) {
        int axis = f % 3, n = face[axis][0], s = face[axis][1], t = face[axis][2];
        double sign = f < 3 ? 1.0 : -1.0;
        if (sign < 0) { /* mirrored face: swapping s and t keeps s x t = -n */
            int tmp = s;
            s = t;
            t = tmp;
        }
        for (int c = 0; c < 4; c++) {
            double p[3] = {0, 0, 0}, nrm[3] = {0, 0, 0};
            p[n] = sign * size[n] / 2.0;
            p[s] = uv[c][0] * size[s] / 2.0;
            p[t] = uv[c][1] * size[t] / 2.0;
            nrm[n] = sign;
            int v = 4 * f + c;
            set3(out->positions + 3 * v, p[0], p[1], p[2]);
            set3(out->normals + 3 * v, nrm[0], nrm[1], nrm[2]);
            out->uvs[2 * v] = (float)(0.5 + 0.5 * uv[c][0]);
            out->uvs[2 * v + 1] = (float)(0.5 + 0.5 * uv[c][1]);
        }
        uint32_t *tri = out->indices + 6 * f, b = 4u * (uint32_t)f;
        tri[0] = b, tri[1] = b + 1, tri[2] = b + 2;
        tri[3] = b, tri[4] = b + 2, tri[5] = b + 3;
    }
    return SSS_OK;
}
