/* tests/mesh/mesh_test_util.h — small helpers shared by the mesh tests: a byte buffer for building
 * binary PLY files with explicit byte order, and mesh property checks. */
#ifndef SSS_TESTS_MESH_UTIL_H
#define SSS_TESTS_MESH_UTIL_H

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "sss/mesh.h"

typedef struct bytes {
    unsigned char data[8192];
    size_t size;
} bytes;

static inline void put_text(bytes *b, const char *s)
{
    size_t n = strlen(s);
    memcpy(b->data + b->size, s, n);
    b->size += n;
}

/* Writes the low `size` bytes of v in little (be = 0) or big (be = 1) endian order. */
static inline void put_uint(bytes *b, uint64_t v, int size, int be)
{
    for (int i = 0; i < size; i++) b->data[b->size + (size_t)(be ? size - 1 - i : i)] = (unsigned char)(v >> (8 * i));
    b->size += (size_t)size;
}

static inline void put_f32(bytes *b, float f, int be)
{
    uint32_t u;
    memcpy(&u, &f, 4);
    put_uint(b, u, 4, be);
}

static inline void put_f64(bytes *b, double d, int be)
{
    uint64_t u;
    memcpy(&u, &d, 8);
    put_uint(b, u, 8, be);
}

/* 1 when every index is in range, every position and normal finite, every normal unit length. */
static inline int mesh_is_sane(const sss_mesh *m)
{
    if (!m->positions || !m->normals || !m->indices || m->vertex_count == 0 || m->triangle_count == 0) return 0;
    for (size_t i = 0; i < (size_t)m->triangle_count * 3; i++)
        if (m->indices[i] >= m->vertex_count) return 0;
    for (size_t v = 0; v < m->vertex_count; v++) {
        const float *p = m->positions + 3 * v, *n = m->normals + 3 * v;
        if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) return 0;
        double len = sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
        if (fabs(len - 1.0) > 1e-5) return 0;
    }
    return 1;
}

#endif
