/* mesh/mesh_internal.h — helpers shared by the mesh readers, shapes and simplifier (not public). */
#ifndef SSS_MESH_INTERNAL_H
#define SSS_MESH_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "sss/mesh.h"

/* Grows *p (elements of elem bytes, capacity *cap) to hold at least need elements (doubling).
 * Returns 0 on overflow or allocation failure, leaving *p untouched. */
int mesh_grow(void **p, size_t *cap, size_t need, size_t elem);

/* Allocates positions (and normals, uvs when asked) for vertex_count vertices and indices for
 * triangle_count triangles; zero-fills. Frees nothing on failure (call sss_mesh_free). */
sss_result mesh_alloc(sss_mesh *m, uint32_t vertex_count, uint32_t triangle_count, int with_normals,
                      int with_uvs, const char *name, sss_error *err);

/* Common last step of every reader: rejects empty meshes, normalises file normals (zero or missing
 * ones are replaced by area-weighted normals) and sets source_flags. Indices must already be valid
 * and positions finite. */
sss_result mesh_finish(sss_mesh *m, int file_normals, int file_uvs, const char *name, sss_error *err);

/* Area-weighted normal of every vertex into out (3 * vertex_count floats, unit length; vertices
 * without a non-degenerate incident triangle get +y). Returns 0 when out of memory. */
int mesh_area_weighted_normals(const sss_mesh *m, float *out);

/* 1 when triangle (a, b, c) repeats an index or has zero area up to float rounding:
 * |e1 x e2| <= 1e-10 * (longest edge)^2. */
int mesh_triangle_degenerate(const float *positions, uint32_t a, uint32_t b, uint32_t c);

/* Simple open-addressing hash from a 64-bit key to a uint32 value (keys must not be UINT64_MAX). */
typedef struct mesh_hash {
    uint64_t *keys;
    uint32_t *values;
    size_t cap, count; /* cap is a power of two */
} mesh_hash;

int mesh_hash_init(mesh_hash *h, size_t expected);
/* Returns a pointer to the value slot for key; *inserted = 1 when the key was new (value unset).
 * NULL when out of memory. */
uint32_t *mesh_hash_get(mesh_hash *h, uint64_t key, int *inserted);
void mesh_hash_free(mesh_hash *h);

#endif
