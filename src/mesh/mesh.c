/* mesh/mesh.c — the sss_mesh container: allocation, normals, areas, bounds, volume, topology, and
 * sss_mesh_read (dispatch by extension). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/file_util.h"
#include "mesh/mesh_internal.h"

/* Largest mesh file we read into memory (the vertex/triangle limits bind well before this). */
#define MESH_MAX_FILE_BYTES \
    ((unsigned long long)(SIZE_MAX / 2) < (1ULL << 32) ? (size_t)(SIZE_MAX / 2) : (size_t)(1ULL << 32))

void sss_mesh_free(sss_mesh *mesh)
{
    if (!mesh) return;
    free(mesh->positions);
    free(mesh->normals);
    free(mesh->uvs);
    free(mesh->indices);
    memset(mesh, 0, sizeof *mesh);
}

int mesh_grow(void **p, size_t *cap, size_t need, size_t elem)
{
    if (need <= *cap) return 1;
    size_t n = *cap ? *cap : 16;
    while (n < need) {
        if (n > SIZE_MAX / 2) return 0;
        n *= 2;
    }
    if (n > SIZE_MAX / elem) return 0;
    void *q = realloc(*p, n * elem);
    if (!q) return 0;
    *p = q;
    *cap = n;
    return 1;
}

sss_result mesh_alloc(sss_mesh *m, uint32_t vertex_count, uint32_t triangle_count, int with_normals,
                      int with_uvs, const char *name, sss_error *err)
{
    memset(m, 0, sizeof *m);
    m->vertex_count = vertex_count;
    m->triangle_count = triangle_count;
    m->positions = calloc((size_t)vertex_count * 3 + 1, sizeof(float));
    m->indices = calloc((size_t)triangle_count * 3 + 1, sizeof(uint32_t));
    if (with_normals) m->normals = calloc((size_t)vertex_count * 3 + 1, sizeof(float));
    if (with_uvs) m->uvs = calloc((size_t)vertex_count * 2 + 1, sizeof(float));
    if (!m->positions || !m->indices || (with_normals && !m->normals) || (with_uvs && !m->uvs)) {
        sss_mesh_free(m);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory for %u vertices, %u triangles",
                             name, vertex_count, triangle_count);
    }
    return SSS_OK;
}

static void tri_cross(const sss_mesh *m, uint32_t t, double c[3])
{
    const uint32_t *tri = m->indices + 3 * (size_t)t;
    const float *a = m->positions + 3 * (size_t)tri[0];
    const float *b = m->positions + 3 * (size_t)tri[1];
    const float *d = m->positions + 3 * (size_t)tri[2];
    double e1[3] = {(double)b[0] - a[0], (double)b[1] - a[1], (double)b[2] - a[2]};
    double e2[3] = {(double)d[0] - a[0], (double)d[1] - a[1], (double)d[2] - a[2]};
    c[0] = e1[1] * e2[2] - e1[2] * e2[1];
    c[1] = e1[2] * e2[0] - e1[0] * e2[2];
    c[2] = e1[0] * e2[1] - e1[1] * e2[0];
}

int mesh_area_weighted_normals(const sss_mesh *m, float *out)
{
    double *acc = calloc((size_t)m->vertex_count * 3 + 1, sizeof(double));
    if (!acc) return 0;
    /* The cross product of two edges has length 2 * area: summing it weights each face normal by
     * its area without a square root per triangle. */
    for (uint32_t t = 0; t < m->triangle_count; t++) {
        double c[3];
        tri_cross(m, t, c);
        for (int k = 0; k < 3; k++) {
            double *n = acc + 3 * (size_t)m->indices[3 * (size_t)t + k];
            n[0] += c[0];
            n[1] += c[1];
            n[2] += c[2];
        }
    }
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        double *n = acc + 3 * (size_t)v;
        double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        float *o = out + 3 * (size_t)v;
        if (len > 0 && isfinite(len)) {
            o[0] = (float)(n[0] / len);
            o[1] = (float)(n[1] / len);
            o[2] = (float)(n[2] / len);
        } else { /* isolated vertex or only degenerate triangles: any unit vector will do */
            o[0] = 0.0f;
            o[1] = 1.0f;
            o[2] = 0.0f;
        }
    }
    free(acc);
    return 1;
}

sss_result sss_mesh_compute_normals(sss_mesh *mesh, sss_error *err)
{
    if (!mesh || !mesh->positions || !mesh->indices)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "mesh: no positions or indices");
    if (!mesh->normals) {
        mesh->normals = malloc(((size_t)mesh->vertex_count * 3 + 1) * sizeof(float));
        if (!mesh->normals) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "mesh: out of memory for normals");
    }
    if (!mesh_area_weighted_normals(mesh, mesh->normals))
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "mesh: out of memory computing normals");
    return SSS_OK;
}

sss_result mesh_finish(sss_mesh *m, int file_normals, int file_uvs, const char *name, sss_error *err)
{
    if (m->vertex_count == 0) return sss_error_set(err, SSS_ERROR_PARSE, "%s: mesh has no vertices", name);
    if (m->triangle_count == 0) return sss_error_set(err, SSS_ERROR_PARSE, "%s: mesh has no triangles", name);
    m->source_flags = (file_normals ? SSS_MESH_FROM_FILE_NORMALS : 0u) | (file_uvs ? SSS_MESH_FROM_FILE_UVS : 0u);
    if (!file_normals || !m->normals) {
        m->source_flags &= ~SSS_MESH_FROM_FILE_NORMALS;
        return sss_mesh_compute_normals(m, err);
    }
    /* Normalise what the file gave; a zero normal carries no direction, so those vertices get the
     * area-weighted normal instead. */
    uint32_t zero = 0;
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        float *n = m->normals + 3 * (size_t)v;
        double len = sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
        if (len > 0 && isfinite(len)) {
            n[0] = (float)(n[0] / len);
            n[1] = (float)(n[1] / len);
            n[2] = (float)(n[2] / len);
        } else {
            n[0] = n[1] = n[2] = 0.0f;
            zero++;
        }
    }
    if (zero) {
        float *computed = malloc(((size_t)m->vertex_count * 3 + 1) * sizeof(float));
        if (!computed || !mesh_area_weighted_normals(m, computed)) {
            free(computed);
            return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory computing normals", name);
        }
        for (uint32_t v = 0; v < m->vertex_count; v++) {
            float *n = m->normals + 3 * (size_t)v;
            if (n[0] == 0.0f && n[1] == 0.0f && n[2] == 0.0f) memcpy(n, computed + 3 * (size_t)v, 3 * sizeof(float));
        }
        free(computed);
    }
    return SSS_OK;
}

void sss_mesh_vertex_areas(const sss_mesh *mesh, float *areas)
{
    for (uint32_t v = 0; v < mesh->vertex_count; v++) areas[v] = 0.0f;
    for (uint32_t t = 0; t < mesh->triangle_count; t++) {
        double c[3];
        tri_cross(mesh, t, c);
        float third = (float)(sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) / 6.0); /* area / 3 */
        for (int k = 0; k < 3; k++) areas[mesh->indices[3 * (size_t)t + k]] += third;
    }
}

double sss_mesh_surface_area(const sss_mesh *mesh)
{
    double sum = 0.0;
    for (uint32_t t = 0; t < mesh->triangle_count; t++) {
        double c[3];
        tri_cross(mesh, t, c);
        sum += 0.5 * sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    }
    return sum;
}

void sss_mesh_bounds(const sss_mesh *mesh, float min[3], float max[3])
{
    for (int k = 0; k < 3; k++) {
        min[k] = mesh->vertex_count ? INFINITY : 0.0f;
        max[k] = mesh->vertex_count ? -INFINITY : 0.0f;
    }
    for (uint32_t v = 0; v < mesh->vertex_count; v++)
        for (int k = 0; k < 3; k++) {
            float x = mesh->positions[3 * (size_t)v + k];
            if (x < min[k]) min[k] = x;
            if (x > max[k]) max[k] = x;
        }
}

double sss_mesh_signed_volume(const sss_mesh *mesh)
{
    /* Divergence theorem: each triangle with the origin spans a tetrahedron of volume det/6. The
     * first vertex is subtracted to keep the determinant's terms small (better rounding). */
    double sum = 0.0;
    const float *o = mesh->vertex_count ? mesh->positions : NULL;
    for (uint32_t t = 0; t < mesh->triangle_count; t++) {
        const uint32_t *tri = mesh->indices + 3 * (size_t)t;
        double p[3][3];
        for (int k = 0; k < 3; k++)
            for (int j = 0; j < 3; j++) p[k][j] = (double)mesh->positions[3 * (size_t)tri[k] + j] - o[j];
        sum += p[0][0] * (p[1][1] * p[2][2] - p[1][2] * p[2][1]) - p[0][1] * (p[1][0] * p[2][2] - p[1][2] * p[2][0]) +
               p[0][2] * (p[1][0] * p[2][1] - p[1][1] * p[2][0]);
    }
    return sum / 6.0;
}

int mesh_triangle_degenerate(const float *positions, uint32_t a, uint32_t b, uint32_t c)
{
    if (a == b || b == c || a == c) return 1;
    const float *p[3] = {positions + 3 * (size_t)a, positions + 3 * (size_t)b, positions + 3 * (size_t)c};
    double e[3][3], longest = 0.0;
    for (int k = 0; k < 3; k++) {
        double d2 = 0.0;
        for (int j = 0; j < 3; j++) {
            e[k][j] = (double)p[(k + 1) % 3][j] - p[k][j];
            d2 += e[k][j] * e[k][j];
        }
        if (d2 > longest) longest = d2;
    }
    double cx = e[0][1] * e[2][2] - e[0][2] * e[2][1], cy = e[0][2] * e[2][0] - e[0][0] * e[2][2],
           cz = e[0][0] * e[2][1] - e[0][1] * e[2][0];
    /* Zero area up to float rounding: the cross product is tiny against the longest edge squared. */
    return sqrt(cx * cx + cy * cy + cz * cz) <= 1e-10 * longest;
}

static int cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

sss_result sss_mesh_topology_compute(const sss_mesh *mesh, sss_mesh_topology *out, sss_error *err)
{
    memset(out, 0, sizeof *out);
    for (size_t i = 0; i < (size_t)mesh->triangle_count * 3; i++)
        if (mesh->indices[i] >= mesh->vertex_count)
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "mesh: triangle %zu: index %u out of range", i / 3,
                                 mesh->indices[i]);
    size_t n = 0;
    uint64_t *edges = malloc(((size_t)mesh->triangle_count * 3 + 1) * sizeof(uint64_t));
    if (!edges) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "mesh: out of memory for edges");
    for (uint32_t t = 0; t < mesh->triangle_count; t++) {
        const uint32_t *tri = mesh->indices + 3 * (size_t)t;
        for (int k = 0; k < 3; k++) {
            uint32_t a = tri[k], b = tri[(k + 1) % 3];
            if (a != b) edges[n++] = a < b ? (uint64_t)a << 32 | b : (uint64_t)b << 32 | a;
        }
        if (mesh_triangle_degenerate(mesh->positions, tri[0], tri[1], tri[2])) out->degenerate_triangles++;
    }
    qsort(edges, n, sizeof *edges, cmp_u64);
    for (size_t i = 0; i < n;) {
        size_t j = i;
        while (j < n && edges[j] == edges[i]) j++;
        out->edge_count++;
        if (j - i == 1) out->boundary_edges++;
        else if (j - i > 2) out->nonmanifold_edges++;
        i = j;
    }
    free(edges);
    return SSS_OK;
}

sss_result sss_mesh_read(const char *path, sss_mesh *out, sss_error *err)
{
    memset(out, 0, sizeof *out);
    char ext[8];
    sss_path_extension(path, ext, sizeof ext);
    int is_ply = strcmp(ext, "ply") == 0, is_obj = strcmp(ext, "obj") == 0;
    if (!is_ply && !is_obj)
        return sss_error_set(err, SSS_ERROR_UNSUPPORTED, "%s: unknown mesh format (expected .ply or .obj)", path);
    char *data = NULL;
    size_t size = 0;
    sss_result r = sss_read_file(path, MESH_MAX_FILE_BYTES, &data, &size, err);
    if (r != SSS_OK) return r;
    r = is_ply ? sss_mesh_parse_ply(data, size, path, out, err) : sss_mesh_parse_obj(data, size, path, out, err);
    free(data);
    return r;
}

/* ---- hash map ---- */

int mesh_hash_init(mesh_hash *h, size_t expected)
{
    memset(h, 0, sizeof *h);
    size_t cap = 64;
    while (cap < expected * 2) {
        if (cap > SIZE_MAX / 4 / sizeof(uint64_t)) return 0;
        cap *= 2;
    }
    h->keys = malloc(cap * sizeof *h->keys);
    h->values = malloc(cap * sizeof *h->values);
    if (!h->keys || !h->values) {
        mesh_hash_free(h);
        return 0;
    }
    memset(h->keys, 0xff, cap * sizeof *h->keys);
    h->cap = cap;
    return 1;
}

static size_t hash_u64(uint64_t k)
{
    /* splitmix64 finaliser: spreads nearby keys over the table */
    k ^= k >> 30;
    k *= 0xbf58476d1ce4e5b9ULL;
    k ^= k >> 27;
    k *= 0x94d049bb133111ebULL;
    k ^= k >> 31;
    return (size_t)k;
}

static int hash_rehash(mesh_hash *h)
{
    mesh_hash bigger;
    if (h->cap > SIZE_MAX / 4 / sizeof(uint64_t) || !mesh_hash_init(&bigger, h->cap)) return 0;
    for (size_t i = 0; i < h->cap; i++) {
        if (h->keys[i] == UINT64_MAX) continue;
        size_t j = hash_u64(h->keys[i]) & (bigger.cap - 1);
        while (bigger.keys[j] != UINT64_MAX) j = (j + 1) & (bigger.cap - 1);
        bigger.keys[j] = h->keys[i];
        bigger.values[j] = h->values[i];
    }
    bigger.count = h->count;
    mesh_hash_free(h);
    *h = bigger;
    return 1;
}

uint32_t *mesh_hash_get(mesh_hash *h, uint64_t key, int *inserted)
{
    if ((h->count + 1) * 2 > h->cap && !hash_rehash(h)) return NULL;
    size_t j = hash_u64(key) & (h->cap - 1);
    while (h->keys[j] != UINT64_MAX) {
        if (h->keys[j] == key) {
            *inserted = 0;
            return &h->values[j];
        }
        j = (j + 1) & (h->cap - 1);
    }
    h->keys[j] = key;
    h->count++;
    *inserted = 1;
    return &h->values[j];
}

void mesh_hash_free(mesh_hash *h)
{
    free(h->keys);
    free(h->values);
    memset(h, 0, sizeof *h);
}
