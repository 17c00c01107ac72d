/* sam/sam_internal.h — shared internals of the SAM module: the reduced-fan sampler, the Kronecker
 * sequence and the vertex-to-triangle incidence. */
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

#endif
