/* sss/mesh.h — triangle meshes: PLY/OBJ readers, a binary PLY writer, normals, adjacency, areas,
 * the procedural shapes of docs/scene-format.md and simplification (meshoptimizer).
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
/* Largest size parameter (radius, edge length, ...) of a procedural shape: its coordinates and areas
 * must stay finite in float (areas reach size^2). */
#define SSS_MESH_MAX_SHAPE_SIZE 1e18

typedef struct sss_mesh {
    uint32_t vertex_count, triangle_count;
    float *positions;  /* 3 * vertex_count */
    float *normals;    /* 3 * vertex_count, unit length */
    float *uvs;        /* 2 * vertex_count, or NULL when the file has none */
    uint32_t *indices; /* 3 * triangle_count, counter-clockwise seen from outside */
    uint32_t source_flags; /* SSS_MESH_FROM_FILE_*: what the file itself provided (set by readers) */
} sss_mesh;

/* Bits of sss_mesh.source_flags. Normals are always present after loading; this tells whether they
 * came from the file (normalised) or were computed (area-weighted). */
#define SSS_MESH_FROM_FILE_NORMALS 1u
#define SSS_MESH_FROM_FILE_UVS 2u

SSS_API void sss_mesh_free(sss_mesh *mesh);

/* Reads .ply (ascii, binary_little_endian, binary_big_endian) or .obj by extension. Rejects: NaN/Inf
 * coordinates, indices out of range, wrong element counts, truncated data, empty meshes.
 * PLY: vertex x y z (any scalar type), optional nx ny nz and UVs (u v, s t, texture_u texture_v),
 * face list vertex_indices or vertex_index (any count/index types); other properties and elements
 * are skipped. OBJ: v, vt, vn, f (v, v/vt, v//vn, v/vt/vn, negative indices; an index must refer to
 * data defined before it); every distinct (v, vt, vn) corner becomes one vertex; o g s usemtl mtllib
 * l and other non-geometry statements are ignored, unknown ones rejected. File normals are normalised;
 * missing or zero ones are replaced by area-weighted normals. On error *out is zeroed. Messages:
 * "<file>: line N: ..." (ascii, OBJ, headers), "<file>: face K: ..." / "vertex K" (binary). */
SSS_API sss_result sss_mesh_read(const char *path, sss_mesh *out, sss_error *err);
/* The same from memory (for fuzzing and embedded data); name is used in messages. */
SSS_API sss_result sss_mesh_parse_ply(const void *data, size_t size, const char *name, sss_mesh *out,
                                      sss_error *err);
SSS_API sss_result sss_mesh_parse_obj(const void *data, size_t size, const char *name, sss_mesh *out,
                                      sss_error *err);
/* Binary little-endian PLY with positions, normals and (if present) UVs; written atomically. */
SSS_API sss_result sss_mesh_write_ply(const char *path, const sss_mesh *mesh, sss_error *err);

/* Area-weighted vertex normals (replaces mesh->normals, allocating them if NULL); a vertex without a
 * non-degenerate incident triangle gets +y. */
SSS_API sss_result sss_mesh_compute_normals(sss_mesh *mesh, sss_error *err);
/* Per-vertex area: one third of each incident triangle's area. areas holds vertex_count floats. */
SSS_API void sss_mesh_vertex_areas(const sss_mesh *mesh, float *areas);
SSS_API double sss_mesh_surface_area(const sss_mesh *mesh);
SSS_API void sss_mesh_bounds(const sss_mesh *mesh, float min[3], float max[3]);
/* Signed volume by the divergence theorem (sum of det(a, b, c) / 6): positive for a closed mesh
 * wound counter-clockwise seen from outside; only an approximation when the mesh has holes. */
SSS_API double sss_mesh_signed_volume(const sss_mesh *mesh);

/* Edge statistics of the index mesh. A mesh is closed when every edge has exactly two triangles. */
typedef struct sss_mesh_topology {
    uint64_t edge_count;        /* distinct undirected edges (between distinct vertices) */
    uint64_t boundary_edges;    /* edges with one incident triangle */
    uint64_t nonmanifold_edges; /* edges with more than two incident triangles */
    uint64_t degenerate_triangles; /* repeated index or zero area */
} sss_mesh_topology;

SSS_API sss_result sss_mesh_topology_compute(const sss_mesh *mesh, sss_mesh_topology *out, sss_error *err);

/* Vertex adjacency in compressed rows: the neighbours of v are
 * neighbors[offsets[v] .. offsets[v + 1]), sorted, without duplicates or v itself. */
typedef struct sss_mesh_adjacency {
    uint32_t vertex_count;
    uint32_t *offsets;   /* vertex_count + 1 */
    uint32_t *neighbors; /* offsets[vertex_count] */
} sss_mesh_adjacency;

SSS_API sss_result sss_mesh_adjacency_build(const sss_mesh *mesh, sss_mesh_adjacency *out, sss_error *err);
SSS_API void sss_mesh_adjacency_free(sss_mesh_adjacency *adj);

/* Procedural shapes of docs/scene-format.md, centred at the origin, with exact normals, CCW outward winding.
 * sphere: icosahedron subdivided `subdivisions` (0..8) times, 20 * 4^s triangles, closed, no UVs.
 * torus: in the xz-plane around +y, `segments` (3..2048) around both circles, closed, no UVs
 *   (UVs would need duplicated seam vertices, which would open the index mesh); minor < major.
 * trefoil: a tube of radius `tube` along the knot (sin t + 2 sin 2t, cos t - 2 cos 2t, -sin 3t) *
 *   radius / 3 (so `radius` is its extent in the xy-plane), `segments` (3..4096) along the knot and
 *   max(3, segments / 8) around the tube, closed, no UVs; 0 < tube <= radius / 6.
 * plane: two triangles, UVs (u along +x, v along -z). box: 24 vertices (flat faces), UVs per face. */
SSS_API sss_result sss_mesh_sphere(double radius, int subdivisions, sss_mesh *out, sss_error *err);
SSS_API sss_result sss_mesh_torus(double major, double minor, int segments, sss_mesh *out, sss_error *err);
SSS_API sss_result sss_mesh_trefoil(double radius, double tube, int segments, sss_mesh *out, sss_error *err);
SSS_API sss_result sss_mesh_plane(double size, sss_mesh *out, sss_error *err); /* xz square facing +y */
SSS_API sss_result sss_mesh_box(const double size[3], sss_mesh *out, sss_error *err);

/* Simplifies to at most target_triangles (meshoptimizer; falls back to sloppy simplification when the
 * topology-preserving one cannot reach the target). Degenerate triangles and unused vertices are
 * dropped, normals recomputed (area-weighted), UVs kept. A target at or above the count copies the
 * mesh. SSS_ERROR_NUMERIC when no non-empty result within the target exists (tiny targets). */
SSS_API sss_result sss_mesh_simplify(const sss_mesh *mesh, uint32_t target_triangles, sss_mesh *out,
                                     sss_error *err);

#ifdef __cplusplus
}
#endif
#endif
