/* sam/sam_internal.h — shared internals of the SAM module: the reduced-fan sampler, the Kronecker
 * sequence, the vertex-to-triangle incidence, the search (sam_search.c) and the back-side mesh
 * (sam_back.c). */
#ifndef SSS_SAM_INTERNAL_H
#define SSS_SAM_INTERNAL_H

#include <stdint.h>

#include "sss/sam.h"

/* 4D Kronecker sequence: alpha_k = phi^-k, phi the real root of x^5 = x + 1 (the "generalised golden
 * ratio" of dimension 4); point s is frac(shift + s alpha). Pairs of coordinates (0, 1) place the
 * receiver sample, (2, 3) the source sample of Eq. 11. */
void sam_kronecker(uint32_t s, const double shift[4], double u[4]);
/* SplitMix64: a per-vertex stream of shifts. */
uint64_t sam_splitmix(uint64_t *state);
double sam_unit(uint64_t *state);

/* A region as a list of triangles with a cumulative-area table for sampling. */
typedef struct sam_region {
    const float *tris; /* 9 floats per triangle */
    size_t count;
    double *cdf;       /* count: running area */
    double area;
} sam_region;

/* cdf must hold count doubles. */
void sam_region_init(sam_region *r, const float *tris, size_t count, double *cdf);
/* Uniform point of the region for u in [0, 1)^2 (u[0] picks the triangle and is reused). */
void sam_region_sample(const sam_region *r, double u0, double u1, double out[3]);

/* Incident triangles per vertex in compressed rows. */
typedef struct sam_incidence {
    uint32_t *offsets; /* vertex_count + 1 */
    uint32_t *tris;    /* offsets[vertex_count] */
} sam_incidence;

sss_result sam_incidence_build(const sss_mesh *mesh, sam_incidence *out, sss_error *err);
void sam_incidence_free(sam_incidence *inc);
/* Reduced fan of v as triangles (2 per incident triangle) into tris (capacity triangles). */
size_t sam_reduced_fan_inc(const sss_mesh *mesh, const sam_incidence *inc, uint32_t v, float *tris, size_t capacity);

/* ---- Search (sam_search.c) ------------------------------------------------------------------------ */

typedef struct sam_node {
    float lo[3], hi[3];   /* positions */
    float nlo[3], nhi[3]; /* normal components */
    float max_area, max_rad;
    uint32_t first, count; /* leaf: range of the ordered vertices; inner: count = 0, first = left child */
    uint32_t right;
} sam_node;

typedef struct sam_tree {
    sam_node *nodes;       /* room for 2 * (source vertices) + 1 */
    uint32_t node_count;
    uint32_t *order;       /* source vertex ids in leaf order (those with a non-zero fan area) */
} sam_tree;

/* What the search reads: receivers v_o of `recv`, sources v_i of `src` (recv itself, or the back-side
 * mesh). */
typedef struct sam_build_ctx {
    const sss_mesh *recv, *src;
    int same;                      /* src == recv: a vertex is never linked to itself */
    const sss_sam_profile_table *table;
    const float *area, *rad;       /* per source vertex: F' (Eq. 16) and the fan's radius */
    const float *rad_recv;         /* per receiver: the fan's radius */
    const float *src_samples;      /* `samples` points of each source fan (3 floats each) */
    uint32_t samples, n;
    sam_tree t;
} sam_build_ctx;

typedef struct sam_cand {
    double ks; /* channel sum */
    double k[3];
    uint32_t v;
} sam_cand;

typedef struct sam_qitem {
    double bound;
    uint32_t node;
} sam_qitem;

/* Per-thread search state; recv holds the receiver's `samples` points (set by the caller). */
typedef struct sam_search {
    sam_cand *best; /* min-heap by ks, size <= n */
    uint32_t count;
    sam_qitem *queue; /* max-heap by bound */
    size_t qcount, qcap;
    float *recv;
    uint64_t nodes, tested, ffs;
} sam_search;

/* Builds the tree over t.order[first .. first + count); returns the node id. */
uint32_t sam_tree_build(sam_build_ctx *b, uint32_t first, uint32_t count);
/* The n best sources of v_o into s->best (s->count of them, unsorted). 0 on out of memory. */
int sam_search_vertex(const sam_build_ctx *b, sam_search *s, uint32_t vo, int brute);
/* qsort order: decreasing ks, then increasing vertex id. */
int sam_cmp_cand_desc(const void *a, const void *b);

/* ---- Back-side mesh (sam_back.c) --------------------------------------------------------------------- */

/* The back-side mesh that desc asks for (a copy of desc->backside, or the mesh simplified to
 * desc->backside_triangles), checked; *out zeroed and SSS_OK when there is none. */
sss_result sam_back_prepare(const sss_mesh *mesh, const sss_sam_desc *desc, sss_mesh *out, sss_error *err);
/* Copies the back-side mesh and its fan areas into the map (back_* fields). */
sss_result sam_back_store(sss_sam *sam, const sss_mesh *back, const float *fan_area, sss_error *err);

#endif
