/* sss/sam.h — Spatial Adjacency Maps (Maisch & Ropinski 2017): per-vertex links to the n
 * back-side vertices that contribute most to a vertex's translucency, with their form factors.
 *
 * Does: reduced fan areas F'_i (Eq. 16: a third of each incident triangle, the part of it closer in
 * barycentric terms to the vertex than to the others), Monte Carlo form factors between reduced fans
 * (Eq. 11, a 4D Kronecker sequence with per-vertex random shifts), the back-side criteria (Eq. 13-14),
 * the search for the n back-side vertices with the largest form factors (best-first branch and bound
 * over a bounding-volume tree of the vertices: a node's upper bound is its largest fan area times the
 * profile's upper envelope at the node's smallest possible fan-to-fan distance; nodes wholly in front
 * of the tangent plane or whose normals all face the same way as n_o are skipped), the constants K'
 * of Eq. 15, the per-frame update of the links of a deforming mesh through vertex adjacency (section
 * 3.4), and the versioned .sam file (docs/sam_format.md). Optionally the links point to the vertices
 * of a lower-tessellation back-side mesh (section 4.4 and the paper's appendix; desc->backside,
 * desc->backside_triangles), which the map then carries (file version 2).
 * Does not: lighting, GL (the `sam` technique, src/gl/techniques/sam/tech_sam.c, evaluates Eq. 12 on the GPU).
 *
 * Units: positions in scene units; form factors K are dimensionless (an area times R_d): the
 * translucency of Eq. 12 is sum_k L_d(v_k) K_k with L_d = F_t E, so the exit radiance is
 * c_o (screen part + sum_k F_t E K_k) exactly as the subsurface integral of docs/physics.md §1.
 * Threads: sss_sam_build uses OpenMP (all cores unless desc->threads > 0); results do not depend on
 * the number of threads.
 */
#ifndef SSS_SAM_H
#define SSS_SAM_H

#include <stdint.h>

#include "sss/common.h"
#include "sss/material.h"
#include "sss/mesh.h"
#include "sss/profile.h"

#ifdef __cplusplus
extern "C" {
#endif

#define SSS_SAM_MAX_N 256        /* links per vertex */
#define SSS_SAM_MAX_SAMPLES 4096 /* Monte Carlo pairs per form factor */
#define SSS_SAM_NONE UINT32_MAX  /* an unused link slot (fewer than n back-side vertices contribute) */
/* The newest .sam version this build reads and writes. Version 1: links index the mesh's own vertices;
 * version 2 adds a separate back-side mesh (Maisch & Ropinski 2017, section 4.4 and its appendix). A map without a
 * back-side mesh is still written as version 1, byte for byte as before. */
#define SSS_SAM_FORMAT_VERSION 2u

/* ---- The radial profile as a table (shared by the build, the update and the GPU) ------------- */

/* R_d(r) per channel at r_j = r_max (j / (size - 1))^2 (dense near 0), linear in between, 0 beyond
 * r_max; env_sum[j] = the largest channel sum R_r + R_g + R_b at any r >= r_j (an upper envelope:
 * the table is not monotone for every medium). r_max holds `energy` of every channel's plane
 * integral of R_d. */
typedef struct sss_sam_profile_table {
    int size;
    double r_max;
    float *rgb;     /* 3 * size */
    float *env_sum; /* size */
} sss_sam_profile_table;

/* energy in (0, 1): 0 -> 0.9999. size 0 -> 4096 (at least 16). */
SSS_API sss_result sss_sam_profile_table_build(const sss_profile *profile, double energy, int size,
                                               sss_sam_profile_table *out, sss_error *err);
SSS_API void sss_sam_profile_table_free(sss_sam_profile_table *t);
SSS_API void sss_sam_profile_table_eval(const sss_sam_profile_table *t, double r, double out[3]);
/* An upper bound of R_r + R_g + R_b over every distance >= r. */
SSS_API double sss_sam_profile_table_bound(const sss_sam_profile_table *t, double r);

/* ---- Geometry ---------------------------------------------------------------------------------- */

/* Eq. 16: F'_i = sum over the fan of |(v_ij-1 - v_i) x (v_ij - v_i)| / 6 (a third of each incident
 * triangle). areas holds vertex_count floats. */
SSS_API void sss_sam_fan_areas(const sss_mesh *mesh, float *areas);

/* Eq. 13 and 14: x_i lies behind the tangent plane at x_o and the normals face apart. */
SSS_API int sss_sam_is_back(const float xo[3], const float no[3], const float xi[3], const float ni[3]);

/* A kernel k(x_o, x_i) with three channels (R_d of each colour, or a test function). */
typedef void (*sss_sam_kernel_fn)(const double xo[3], const double xi[3], void *user, double out[3]);

/* (1 / |A|) int_A int_B k(x_o, x_i) dx_i dx_o over two regions given as triangle soups (9 floats per
 * triangle), by `samples` pairs of a 4D Kronecker sequence with a random shift from seed. This is
 * Eq. 11 when A and B are reduced fans. Errors: empty or zero-area region, samples out of range. */
SSS_API sss_result sss_sam_region_integral(const float *tris_a, size_t count_a, const float *tris_b, size_t count_b,
                                           uint32_t samples, uint64_t seed, sss_sam_kernel_fn kernel, void *user,
                                           double out[3], sss_error *err);

/* The reduced fan of vertex v (Fig. 2) as a triangle soup: two triangles (v, mid(v, b), centroid) and
 * (v, centroid, mid(v, c)) per incident triangle (v, b, c). tris receives 9 * 2 * (incident triangles)
 * floats, at most capacity triangles; returns the number of triangles of the fan. */
SSS_API size_t sss_sam_reduced_fan(const sss_mesh *mesh, uint32_t v, float *tris, size_t capacity);

/* ---- Building ---------------------------------------------------------------------------------- */

typedef struct sss_sam_desc {
    uint32_t n;         /* back-side links per vertex, 1..SSS_SAM_MAX_N (0 -> 3, the paper's choice) */
    uint32_t samples;   /* Monte Carlo pairs per form factor (0 -> 64) */
    uint64_t seed;      /* of the per-vertex random shifts */
    double energy;      /* profile table radius (0 -> 0.9999 of each channel's energy) */
    int threads;        /* 0: OpenMP's default */
    int brute_force;    /* 1: test every vertex pair (no tree), for tests of the search */
    const double *transform; /* row-major 4x4 recorded in the file (the mesh given is already in scene
                                units); NULL: identity */
    /* A lower-tessellation mesh for the back side (Maisch & Ropinski 2017, section 4.4: "a proof of concept that works
     * on a lower triangulation for back side information", described in its appendix): every vertex of
     * the mesh links to n vertices of this mesh, chosen by Eq. 13-14 against its vertices and normals,
     * with its reduced fans (Eq. 16) as the sources of Eq. 11 and in K' (Eq. 15). Its fans are larger,
     * so n links cover more of the back side. In the same space as the mesh given (scene units for
     * sss_sam_build, object space for sss_sam_build_object, which poses it like the object's mesh);
     * needs normals; the map keeps a copy. NULL: the mesh itself (no back-side mesh). */
    const sss_mesh *backside;
    /* > 0 (and backside NULL): the back-side mesh is the mesh simplified to at most this many
     * triangles (sss_mesh_simplify); at or above the mesh's count the map has no back-side mesh. */
    uint32_t backside_triangles;
} sss_sam_desc;

typedef struct sss_sam_stats {
    double seconds;
    uint64_t nodes_visited;      /* tree nodes taken from the queue */
    uint64_t vertices_tested;    /* leaf vertices checked against the criteria and the bound */
    uint64_t form_factors;       /* Monte Carlo form factors computed */
    uint32_t linked_vertices;    /* vertices with at least one link */
} sss_sam_stats;

typedef struct sss_sam {
    uint32_t vertex_count, triangle_count, n, samples;
    uint64_t mesh_hash, seed;
    sss_profile_model model;
    sss_material material;
    double energy;
    double transform[16];  /* row-major; identity for plain meshes */
    float *fan_area;       /* vertex_count: F'_i at rest (Eq. 16) */
    uint32_t *links;       /* vertex_count * n: b_ok sorted by decreasing K (sum of channels); NONE */
    float *form_factor;    /* vertex_count * n * 3: K_ok (Eq. 11), 0 for NONE */
    float *kprime;         /* vertex_count * n * 3: K'_ok = K_ok / (F'_k R_d(|v_k - v_o|)) (Eq. 15) */
    /* The back-side mesh (file version 2), at rest in the units of fan_area; back_vertex_count 0: none,
     * links index the mesh's own vertices (version 1). With one, links index its vertices and F'_k,
     * v_k in Eq. 15 are its fan areas and positions. */
    uint32_t back_vertex_count, back_triangle_count;
    uint64_t back_hash;       /* sss_sam_mesh_hash of the back-side mesh */
    float *back_positions;    /* 3 * back_vertex_count */
    float *back_normals;      /* 3 * back_vertex_count, unit length */
    float *back_uvs;          /* 2 * back_vertex_count, or NULL (the back-side mesh has no UVs) */
    float *back_fan_area;     /* back_vertex_count: F'_k at rest (Eq. 16 on the back-side mesh) */
    uint32_t *back_indices;   /* 3 * back_triangle_count (adjacency and fans for deformation, 3.4) */
} sss_sam;

/* Builds the map for a mesh in scene units (apply the object's transform first) and a profile whose
 * material is in the same units. The mesh needs normals. stats may be NULL. */
SSS_API sss_result sss_sam_build(const sss_mesh *mesh, const sss_profile *profile, const sss_sam_desc *desc,
                                 sss_sam *out, sss_sam_stats *stats, sss_error *err);
SSS_API void sss_sam_free(sss_sam *sam);

/* The mesh the links point to: a view (no copy; do not free) of the map's back-side mesh, or a zeroed
 * mesh when the map has none (the links then index the map's own mesh). Returns whether it has one. */
SSS_API int sss_sam_back_mesh(const sss_sam *sam, sss_mesh *view);

/* FNV-1a 64 over the vertex and triangle counts, positions and indices (little-endian bytes). */
SSS_API uint64_t sss_sam_mesh_hash(const sss_mesh *mesh);

/* ---- Deformation (section 3.4) ------------------------------------------------------------------ */

/* One update step for a deformed copy of the mesh (same topology, positions and normals changed):
 * each link moves to the one-ring neighbour (or stays) with the largest F'_j R_d(|v_j - v_o|) among
 * those that pass Eq. 13-14 and are not already linked from v_o; K' is kept. fan_area receives the
 * deformed F' (vertex_count floats; may be NULL). Returns the number of links that moved. */
SSS_API uint64_t sss_sam_update(sss_sam *sam, const sss_mesh *deformed, const sss_mesh_adjacency *adj,
                                const sss_sam_profile_table *table, float *fan_area);
/* The approximate form factors of Eq. 15 for the (deformed) mesh: K'_ok F'_k R_d(|v_k - v_o|) per
 * channel, 0 for unused slots and for links that fail Eq. 13-14; out holds vertex_count * n * 3. */
SSS_API void sss_sam_approximate(const sss_sam *sam, const sss_mesh *mesh, const float *fan_area,
                                 const sss_sam_profile_table *table, float *out);
/* The two above for a map with a back-side mesh (sss_sam_update and sss_sam_approximate do nothing
 * for such a map: they return 0 / write zeros): `back` is the deformed back-side mesh (same topology
 * as the map's), back_adj its adjacency, back_fan_area receives / holds its deformed F' (may be NULL:
 * the rest areas). With back NULL they are sss_sam_update and sss_sam_approximate. */
SSS_API uint64_t sss_sam_update_back(sss_sam *sam, const sss_mesh *deformed, const sss_mesh *back,
                                     const sss_mesh_adjacency *back_adj, const sss_sam_profile_table *table,
                                     float *back_fan_area);
SSS_API void sss_sam_approximate_back(const sss_sam *sam, const sss_mesh *mesh, const sss_mesh *back,
                                      const float *back_fan_area, const sss_sam_profile_table *table, float *out);

/* ---- Scene objects ------------------------------------------------------------------------------- */

struct sss_scene;
struct sss_scene_object;

/* The mesh a map of a scene object is built on: its mesh at rest (no animation) with its transform
 * applied, in scene units (sss_scene_object_world_mesh without the animation). */
SSS_API sss_result sss_sam_object_mesh(const struct sss_scene_object *obj, sss_mesh *out, sss_error *err);
/* The profile of a subsurface object's material (its model; artist profiles use PBD, as the GL LUT). */
SSS_API sss_result sss_sam_object_profile(const struct sss_scene_object *obj, sss_profile *out, sss_error *err);
/* Builds the map of scene object `index` (desc->transform is set to the object's). Errors name the
 * scene and the object: out of range, not subsurface. */
SSS_API sss_result sss_sam_build_object(const struct sss_scene *scene, size_t index, const sss_sam_desc *desc,
                                        sss_sam *out, sss_sam_stats *stats, sss_error *err);
/* Reads `path` and checks it against scene object `index` (mesh, material, model, transform). */
SSS_API sss_result sss_sam_read_object(const char *path, const struct sss_scene *scene, size_t index, sss_sam *out,
                                       sss_error *err);

/* ---- Files -------------------------------------------------------------------------------------- */

/* Binary little-endian: magic "SSSSAM1\n", version, vertex and triangle counts, mesh hash, n, samples,
 * seed, profile model, energy, material (sigma_a, sigma_s, eta, g), transform, then fan areas, links,
 * form factors, K', and an FNV-1a 64 checksum of everything before it. Written atomically. Version 2
 * (maps with a back-side mesh) adds to the header the back-side mesh's vertex and triangle counts,
 * hash and whether it has UVs, and before the checksum its positions, normals, UVs, fan areas and
 * indices (docs/sam_format.md). Maps without one are written as version 1. */
SSS_API sss_result sss_sam_write(const char *path, const sss_sam *sam, sss_error *err);
/* Reads versions 1 and 2. Checks magic, version, sizes (before allocating: the file size must equal
 * what the header implies), the checksum, link indices (against the back-side mesh in version 2), the
 * back-side mesh's indices and hash, and finite values. */
SSS_API sss_result sss_sam_read(const char *path, sss_sam *out, sss_error *err);
/* The same checks on a .sam file held in memory (size bytes); messages name `name` (NULL: "<memory>").
 * On failure *out is left empty. */
SSS_API sss_result sss_sam_decode(const void *data, size_t size, const char *name, sss_sam *out, sss_error *err);
/* Whether a map belongs to this mesh, material, profile model and transform (NULL: identity); the
 * message names `name` (the .sam file) and what differs. */
SSS_API sss_result sss_sam_check(const sss_sam *sam, const sss_mesh *mesh, const sss_material *material,
                                 sss_profile_model model, const double *transform, const char *name, sss_error *err);

#ifdef __cplusplus
}
#endif
#endif
