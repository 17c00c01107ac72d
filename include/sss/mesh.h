/* sss/mesh.h — triangle meshes: PLY/OBJ readers, a binary PLY writer, normals, adjacency, areas,
 * the procedural shapes of SCENE.md and simplification (meshoptimizer).
 *
 * Does: indexed triangles with per-vertex positions, normals (always present after loading: area-
 * weighted when the file has none) and optional UVs; faces with more than three vertices are
 * fan-triangulated. Does not: materials, transforms of scenes, GL.
 * Memory: functions that produce a mesh allocate inside the sss_mesh; release with sss_mesh_free.
 * Limits: at most SSS_MESH_MAX_VERTICES vertices and SSS_MESH_MAX_TRIANGLES triangles; a file whose
 * header claims more data than it holds is rejected before anything is allocated.
 */
#ifndef SSS_MESH_H
#define SSS_MESH_H

#include <stdint.h>

#include "sss/common.h"

#ifdef __cplusplus
extern "C" {
#endif

#define SSS_MESH_MAX_VERTICES (1u << 26)
#define SSS_MESH_MAX_TRIANGLES (1u << 27)

typedef struct sss_mesh {
    uint32_t vertex_count, triangle_count;
    float *positions;  /* 3 * vertex_count */
    float *normals;    /* 3 * vertex_count, unit length */
    float *uvs;        /* 2 * vertex_count, or NULL when the file has none */
    uint32_t *indices; /* 3 * triangle_count, counter-clockwise seen from outside */
} sss_mesh;

void sss_mesh_free(sss_mesh *mesh);

/* Reads .ply (ascii, binary_little_endian, binary_big_endian) or .obj by extension. Rejects: NaN/Inf
 * coordinates, indices out of range, wrong element counts, truncated data, empty meshes. */
sss_result sss_mesh_read(const char *path, sss_mesh *out, sss_error *err);
/* The same from memory (for fuzzing and embedded data); name is used in messages. */
sss_result sss_mesh_parse_ply(const void *data, size_t size, const char *name, sss_mesh *out,
                              sss_error *err);
sss_result sss_mesh_parse_obj(const void *data, size_t size, const char *name, sss_mesh *out,
                              sss_error *err);
/* Binary little-endian PLY with positions, normals and (if present) UVs; written atomically. */
sss_result sss_mesh_write_ply(const char *path, const sss_mesh *mesh, sss_error *err);

/* Area-weighted vertex normals (replaces mesh->normals, allocating them if NULL). */
sss_result sss_mesh_compute_normals(sss_mesh *mesh, sss_error *err);
/* Per-vertex area: one third of each incident triangle's area. areas holds vertex_count floats. */
void sss_mesh_vertex_areas(const sss_mesh *mesh, float *areas);
double sss_mesh_surface_area(const sss_mesh *mesh);
void sss_mesh_bounds(const sss_mesh *mesh, float min[3], float max[3]);

/* Vertex adjacency in compressed rows: the neighbours of v are
 * neighbors[offsets[v] .. offsets[v + 1]), sorted, without duplicates or v itself. */
typedef struct sss_mesh_adjacency {
    uint32_t vertex_count;
    uint32_t *offsets;   /* vertex_count + 1 */
    uint32_t *neighbors; /* offsets[vertex_count] */
} sss_mesh_adjacency;

sss_result sss_mesh_adjacency_build(const sss_mesh *mesh, sss_mesh_adjacency *out, sss_error *err);
void sss_mesh_adjacency_free(sss_mesh_adjacency *adj);

/* Procedural shapes of SCENE.md, centred at the origin. */
sss_result sss_mesh_sphere(double radius, int subdivisions, sss_mesh *out, sss_error *err);
sss_result sss_mesh_torus(double major, double minor, int segments, sss_mesh *out, sss_error *err);
sss_result sss_mesh_trefoil(double radius, double tube, int segments, sss_mesh *out, sss_error *err);
sss_result sss_mesh_plane(double size, sss_mesh *out, sss_error *err); /* xz square facing +y */
sss_result sss_mesh_box(const double size[3], sss_mesh *out, sss_error *err);

/* Simplifies to at most target_triangles (meshoptimizer; falls back to sloppy simplification when the
 * topology-preserving one cannot reach the target). Normals are recomputed, UVs kept. */
sss_result sss_mesh_simplify(const sss_mesh *mesh, uint32_t target_triangles, sss_mesh *out,
                             sss_error *err);

#ifdef __cplusplus
}
#endif
#endif
