/* reference/ref_internal.h — internals of the CPU ground truth (see sss/reference.h for the model). */
#ifndef SSS_REF_INTERNAL_H
#define SSS_REF_INTERNAL_H

#include <embree3/rtcore.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "core/vecmath.h"
#include "sss/reference.h"

#define REF_PI 3.14159265358979323846

/* ---- random numbers: PCG32 streams seeded by a splitmix64 hash of (seed, stream ids) ---------- */

typedef struct ref_rng {
    uint64_t state, inc;
} ref_rng;

static inline uint64_t ref_hash64(uint64_t x)
{
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

static inline uint32_t ref_rng_u32(ref_rng *r)
{
    uint64_t old = r->state;
    r->state = old * 6364136223846793005ull + r->inc;
    uint32_t xorshifted = (uint32_t)(((old >> 18u) ^ old) >> 27u);
    uint32_t rot = (uint32_t)(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
}

/* One independent stream per (seed, a, b): a = purpose/object, b = pixel or sample index. */
static inline void ref_rng_seed(ref_rng *r, uint64_t seed, uint64_t a, uint64_t b)
{
    uint64_t h = ref_hash64(seed ^ ref_hash64(a ^ ref_hash64(b)));
    r->state = 0;
    r->inc = (ref_hash64(h + 1) << 1) | 1u;
    ref_rng_u32(r);
    r->state += h;
    ref_rng_u32(r);
}

/* Uniform in [0, 1). */
static inline double ref_rng_uniform(ref_rng *r) { return ref_rng_u32(r) * (1.0 / 4294967296.0); }

/* ---- selection -------------------------------------------------------------------------------- */

/* Reorders items [0, n) (n >= 1) so that item k holds the k-th smallest key, smaller keys before it and
 * larger ones after (Hoare quickselect with a median-of-three pivot: deterministic). key reads item
 * i's key, swap exchanges two items; inline, so that the callers' key and swap inline too. */
static inline void ref_select_kth(void *items, size_t n, size_t k, const void *ctx,
                                  float (*key)(const void *items, size_t i, const void *ctx),
                                  void (*swap)(void *items, size_t i, size_t j))
{
    size_t lo = 0, hi = n - 1;
    while (hi > lo) {
        size_t mid = lo + (hi - lo) / 2;
        if (key(items, mid, ctx) < key(items, lo, ctx)) swap(items, mid, lo);
        if (key(items, hi, ctx) < key(items, lo, ctx)) swap(items, hi, lo);
        if (key(items, hi, ctx) < key(items, mid, ctx)) swap(items, hi, mid);
        float pivot = key(items, mid, ctx);
        size_t i = lo, j = hi;
        for (;;) {
            while (key(items, i, ctx) < pivot) i++;
            while (key(items, j, ctx) > pivot) j--;
            if (i >= j) break;
            swap(items, i, j);
            i++;
            j--;
        }
        /* Now [lo, j] <= pivot <= [j + 1, hi]. */
        if (k <= j)
            hi = j;
        else
            lo = j + 1;
    }
}

/* ---- tabulated profile (ref_profile.c) -------------------------------------------------------- */

/* The far part S_far(r) = S_r(max(r, R0)) per channel, on a grid uniform in r within each octave
 * [R0 2^k, R0 2^(k+1)) with REF_PROFILE_STEPS steps: entry i is at r = R0 2^(i >> 8) (1 + (i & 255)/256),
 * exactly the bits of the float r / R0 (exponent and top 8 mantissa bits), so a lookup is a bit shift. */
#define REF_PROFILE_STEPS 256
#define REF_NEAR_BINS 256

typedef struct ref_profile {
    float r0, inv_r0;  /* split radius R0 */
    float r_cut;       /* support: S_far = 0 beyond */
    uint32_t n;        /* grid entries (the last one is zero) */
    float *table;      /* 4 n floats: S_far of R, G, B and the criterion length l(r) at entry i */
    double s0[3];      /* S_r(R0) */
    double near[3];    /* int_0^R0 (S_r(r) - S_r(R0)) 2 pi r dr */
    double total[3];   /* plane integral of S_r */
    /* The near kernel S_near = S_r - S_r(R0) on [0, R0] in REF_NEAR_BINS bins (edges 0 and
     * R0 2^(-(REF_NEAR_BINS - j) / 8), j >= 1): per bin and channel its mass int S_near 2 pi r dr,
     * and the cumulative distribution of the bins' masses summed over channels (|.|), for sampling. */
    double near_edge[REF_NEAR_BINS + 1];
    double near_mass[REF_NEAR_BINS][3];
    double near_cdf[REF_NEAR_BINS + 1];
} ref_profile;

/* A radial profile to tabulate: the physics module's (PBD or dipole) or the artist mixture. */
typedef struct ref_profile_source {
    sss_scene_profile kind;
    sss_profile profile;      /* PBD, DIPOLE */
    sss_artist_params artist; /* ARTIST */
    double albedo[3];         /* ARTIST */
} ref_profile_source;

sss_result ref_profile_source_init(ref_profile_source *src, const sss_reference_object *obj, sss_error *err);
double ref_profile_source_eval(const ref_profile_source *src, int channel, double r);
/* Largest radius worth tabulating (PBD: the table's end for the widest channel). */
double ref_profile_source_support(const ref_profile_source *src);
/* The profile's plane integral per channel (closed forms, or the table's rho_eff). */
double ref_profile_source_total(const ref_profile_source *src, int channel);

/* Builds the table for split radius r0 > 0 and maximum distance max_r (the object's diameter). */
sss_result ref_profile_build(ref_profile *p, const ref_profile_source *src, double r0, double max_r,
                             sss_error *err);
void ref_profile_free(ref_profile *p);

/* S_far at r for the three channels (zero beyond r_cut); *len (may be NULL) receives l(r). */
static inline void ref_profile_lookup(const ref_profile *p, float r, float out[3], float *len)
{
    float x = r * p->inv_r0;
    if (!(x > 1.0f)) x = 1.0f;
    uint32_t bits;
    memcpy(&bits, &x, sizeof bits);
    uint32_t i = (bits >> 15) - (127u << 8);
    if (i + 1 >= p->n) {
        out[0] = out[1] = out[2] = 0.0f;
        if (len) *len = p->table[4 * (p->n - 1) + 3];
        return;
    }
    float t = (float)(bits & 0x7fffu) * (1.0f / 32768.0f);
    const float *a = p->table + 4 * i, *b = a + 4;
    out[0] = a[0] + t * (b[0] - a[0]);
    out[1] = a[1] + t * (b[1] - a[1]);
    out[2] = a[2] + t * (b[2] - a[2]);
    if (len) *len = a[3];
}

/* ---- surface samples and their tree (ref_tree.c) --------------------------------------------- */

typedef struct ref_point {
    float p[3];
    float ta[3]; /* T(x_i) A_i per channel */
} ref_point;

typedef struct ref_node {
    float center[3], radius; /* bounding sphere of the node's points (bbox centre, half diagonal) */
    float centroid[3];       /* T A-weighted centroid (area-weighted when T A is zero) */
    float ta[3];             /* sum of T A */
    uint32_t first;          /* leaf: first point; inner: index of the first of two children */
    uint32_t count;          /* leaf: number of points (> 0); inner: 0 */
} ref_node;

#define REF_LEAF_SIZE 8
#define REF_TREE_MAX_DEPTH 96

typedef struct ref_tree {
    ref_point *points; /* reordered by the build */
    size_t point_count;
    ref_node *nodes;
    size_t node_count, leaf_count;
    uint32_t depth;
} ref_tree;

/* Builds the tree over tree->points (point_count of them, already filled; points get reordered). */
sss_result ref_tree_build(ref_tree *tree, sss_error *err);
void ref_tree_free(ref_tree *tree);
/* sum over samples of T A S_far(|x - x_o|), hierarchical or brute force; *visits += nodes+points.
 * abs_tol (may be NULL): per channel, a node is also accepted when its estimated monopole error
 * T A S (s / l)^2 / 40 is below it (see ref_abs_tolerance). */
void ref_tree_sum(const ref_tree *tree, const ref_profile *prof, const float xo[3], const float abs_tol[3],
                  double out[3], uint64_t *visits);
/* The same with the angle criterion size <= angle d_min in place of REF_TREE_ANGLE. */
void ref_tree_sum_angle(const ref_tree *tree, const ref_profile *prof, const float xo[3], const float abs_tol[3],
                        float angle, double out[3], uint64_t *visits);
void ref_brute_sum(const ref_tree *tree, const ref_profile *prof, const float xo[3], double out[3],
                   uint64_t *visits);

/* Absolute tolerance of a node's error, relative to the object's lit level: the mean irradiance T of
 * its lit samples times the profile's plane integral (what a uniformly lit flat part would show). */
#define REF_TREE_ABS 1e-6

/* Tree criterion (see sss/reference.h); overridable at compile time for experiments. */
#ifndef REF_TREE_ANGLE
#define REF_TREE_ANGLE 0.5f
#endif
#ifndef REF_TREE_PROFILE
#define REF_TREE_PROFILE 0.6f
#endif

/* ---- lights (ref_light.c) -------------------------------------------------------------------- */

typedef struct ref_env {
    const sss_image *map; /* borrowed or owned_map */
    sss_image owned_map;
    double scale[3], rotate_y;
    int width, height;
    double *marginal_cdf;     /* height + 1 */
    double *conditional_cdf;  /* height * (width + 1) */
    double *row_weight;       /* height: the row's total (for pdfs) */
    double total;             /* sum of all weights */
} ref_env;

typedef struct ref_light {
    sss_light src;
    /* spot */
    double axis[3], cos_total, cos_start;
    /* directional: unit direction towards the light */
    double to_light[3];
    /* area */
    double normal[3], area;
    /* environment */
    ref_env env;
} ref_light;

/* ---- many point lights (ref_light_tree.c) ------------------------------------------------------
 * Up to REF_EXACT_POINT_LIGHTS point and spot lights, every one gets a shadow ray at every surface point.
 * Beyond that (a scene may hold thousands), a bounding-volume hierarchy over their positions chooses
 * REF_TREE_LIGHT_SAMPLES of them per point: each node's children are weighted by power over squared
 * distance (zero where the whole box lies below the surface), after Conty Estevez & Kulla 2018
 * ("Importance Sampling of Many Lights with Adaptive Tree Splitting"), and the samples descend together,
 * stratified (one offset per point), so the cost grows with log(lights), not with lights. */
#define REF_EXACT_POINT_LIGHTS 64
#define REF_TREE_LIGHT_SAMPLES 64

typedef struct ref_light_node {
    float lo[3], hi[3];
    double power;     /* sum of the intensities' channels below this node */
    uint32_t child;   /* internal: first child (the second is child + 1); leaf: the light's index */
    uint32_t is_leaf;
} ref_light_node;

typedef struct ref_light_tree {
    ref_light_node *nodes; /* NULL: no tree (few point lights) */
    size_t node_count;
} ref_light_tree;

struct ref_ctx;
sss_result ref_light_tree_build(struct ref_ctx *ctx, sss_error *err);
void ref_light_tree_free(ref_light_tree *t);
/* Calls add(light, weight) for the lights drawn at po (geometric normal ng) with offset u in [0, 1):
 * the sum of weight times each light's contribution is an unbiased estimate of all point and spot
 * lights' contribution. */
typedef void (*ref_light_visit)(void *user, const struct ref_light *light, double weight);
void ref_light_tree_sample(const struct ref_ctx *ctx, const double po[3], const double ng[3], double u,
                           ref_light_visit add, void *user);

/* ---- the render context ---------------------------------------------------------------------- */

typedef struct ref_object {
    const sss_reference_object *src;
    RTCScene probe_scene; /* the object alone, for the near-part probe rays */
    int subsurface;
    double eta, c_norm;  /* c = 1 - 2 FM1(1/eta) */
    ref_profile_source psrc;
    ref_profile prof;
    ref_tree tree;
    double spacing, footprint;
    float abs_tol[3];    /* REF_TREE_ABS times the lit level, per channel */
    double bounds_min[3], bounds_max[3];
    int visible;         /* seen by a pixel centre */
    uint64_t visible_pixels;
    /* Interreflection (ctx->transport): the samples in generation order (triangle t holds
     * [tri_offset[t], tri_offset[t + 1]), m^2 of them as ref_points.c enumerates them). */
    uint64_t *tri_offset;
    uint32_t *cluster_of;  /* NULL, or per sample of tri_offset its transport sample (cluster) in bs */
    struct ref_bsample *bs;
    size_t bs_count;
    double tspacing;       /* spacing of the transport samples (>= spacing) */
    float (*indirect)[3];  /* T (subsurface) or E (diffuse) of bounces 2..N */
    ref_tree itree;        /* subsurface: the transport samples with their indirect T A, for the pixels */
    float iabs_tol[3];
    uint64_t *nb_offset;   /* subsurface: transport sample i's neighbours within R0 are nb_index[nb_offset[i] ..] */
    uint32_t *nb_index;
    ref_tree stree;        /* subsurface: the transport samples with T A of bounces 1..N-1 (final gathers) */
    float stol[3];
    _Atomic unsigned char *sent_state; /* per sample: 2 once its exit_sum is computed (ref_bounce.c) */
    uint64_t base;         /* index of its first sample among all objects' */
    int gather;            /* gather rays (links) per sample */
    uint32_t *link_target; /* gather links: bs_count x gather, the hit sample (all objects') or UINT32_MAX */
    float *link_weight;    /* what the hit's exitance (M or E) contributes to T (E) here */
} ref_object;

/* One surface sample as the bounces use it. */
typedef struct ref_bsample {
    float p[3], ng[3]; /* position, unit geometric normal of its triangle */
    float area;
    float direct[3];   /* T (E) of bounce 1 */
    float t[3];        /* T (E) of the current bounce */
    float exit[3];     /* M (E) of the previous bounce */
    float t_before[3]; /* T (E) of bounces 1..N-1 summed */
    float exit_sum[3]; /* their M (E): what the pixels' final gathers see leave here */
} ref_bsample;

typedef struct ref_camera {
    double origin[3], right[3], up[3], forward[3];
    double tan_half[2];
    int width, height;
} ref_camera;

/* ---- sources by where the camera sees them (ref_sources.c) --------------------------------------
 * A diagnostic, not part of the public model: the single-event image with only some of the surface's
 * light sources, to split a real-time technique's light by where its sources lie and compare each part
 * with the ground truth's from the same surface (docs/maisch2020.md). A source point is in exactly one
 * class, so the images of a partition of the classes add up to the unmasked one (tests/reference/
 * test_ref_sources.c). Masked sources keep their place in the random streams: only their T becomes 0. */
typedef enum ref_source_class {
    REF_SOURCE_VISIBLE = 1u, /* on the image, seen by the camera, |n_s . v| >= grazing */
    REF_SOURCE_GRAZING = 2u, /* on the image, seen by the camera, |n_s . v| < grazing */
    REF_SOURCE_HIDDEN = 4u,  /* on the image, facing the camera (n_g . v >= 0), behind nearer surface */
    REF_SOURCE_BACK = 8u,    /* on the image, facing away (n_g . v < 0) */
    REF_SOURCE_OFF = 16u,    /* outside the image, or behind the camera */
    REF_SOURCE_ALL = 31u
} ref_source_class;

typedef struct ref_source_mask {
    unsigned keep;  /* the classes kept (ref_source_class bits); 0 or REF_SOURCE_ALL: every source */
    double grazing; /* |n_s . v| below which a seen source is GRAZING (e.g. a technique's cut-off) */
} ref_source_mask;

struct ref_ctx;
/* The class of a surface point p with unit geometric normal ng and shading normal ns. */
ref_source_class ref_source_classify(const struct ref_ctx *ctx, const double p[3], const double ng[3],
                                     const double ns[3], double grazing);
/* SSS_OK when mask can be used with desc (bounces 1, known classes, grazing in 0..1). */
sss_result ref_source_mask_check(const ref_source_mask *mask, const sss_reference_desc *desc, sss_error *err);
/* Whether ctx's mask keeps the source at p (always without a mask). */
int ref_source_kept(const struct ref_ctx *ctx, const double p[3], const double ng[3], const double ns[3]);
/* sss_reference_render_world with a source mask (NULL: none, the renderer); a mask needs desc->bounces = 1
 * (the single-event integral: T of the kept sources only). */
sss_result ref_render_world(const sss_reference_world *world, const sss_reference_desc *desc,
                            const ref_source_mask *mask, sss_image *out, sss_reference_progress_fn progress,
                            void *user, sss_reference_stats *stats, sss_error *err);
/* sss_reference_render with a source mask (NULL: none). */
sss_result ref_render_scene(const sss_scene *scene, const sss_reference_desc *desc, const ref_source_mask *mask,
                            sss_image *out, sss_reference_progress_fn progress, void *user,
                            sss_reference_stats *stats, sss_error *err);

typedef struct ref_ctx {
    const sss_reference_world *world;
    sss_reference_desc desc;
    ref_source_mask mask;      /* keep 0: every source (the renderer); else a diagnostic (above) */
    RTCDevice device;
    RTCScene scene;
    ref_camera cam;
    ref_object *objects;
    size_t object_count;
    ref_light *lights;
    size_t light_count;
    ref_light_tree light_tree; /* over the point and spot lights when there are many (ref_light_tree.c) */
    int has_env;
    unsigned light_geom_base; /* geomID of the first area light rectangle; lights get one each */
    unsigned *light_of_geom;  /* geomID - light_geom_base -> light index */
    unsigned light_geom_count;
    double eps;               /* ray offset scale (scene units) */
    int area_samples_point, area_samples_camera, env_samples_point, env_samples_camera;
    int near_probes;          /* probe rays per camera sample for the near part */
    int transport;            /* bounces > 1 (ref_bounce.c) */
    int gather_subsurface, gather_diffuse; /* gather rays per surface sample */
    int gather_pixel;         /* final-gather rays per pixel (its base samples; as many again where refined) */
    int gather_refine;        /* final-gather rays per subsurface transport sample after the bounces */
    /* progress: a phase maps its own fraction [0, 1] to [phase_lo, phase_hi] of the whole */
    sss_reference_progress_fn progress;
    void *user;
    double last_progress_time;
    double phase_lo, phase_hi;
    const char *stage;
    /* Embree's first error message (set by its error callback) */
    int embree_failed;
    char embree_message[256];
    /* statistics of the preparation */
    sss_reference_stats stats;
} ref_ctx;

/* ref_setup.c: everything before the pixels. */
sss_result ref_camera_init(const sss_camera *c, ref_camera *cam, sss_error *err);
void ref_camera_ray(const ref_camera *cam, double px, double py, double dir[3]);
/* Validates the world, builds the Embree scene and the lights, finds the sample spacing of every
 * subsurface object, generates its samples (with irradiance) and builds its tree. */
sss_result ref_prepare(ref_ctx *ctx, sss_error *err);
void ref_ctx_free(ref_ctx *ctx);
void ref_set_phase(ref_ctx *ctx, double lo, double hi, const char *stage);

/* ref_camera.c-free helpers live in ref_render.c; these are shared: */
sss_result ref_lights_init(ref_ctx *ctx, sss_error *err);
void ref_lights_free(ref_ctx *ctx);
/* T(x) (or E(x) when eta <= 0: diffuse, no Fresnel) at a surface point p with unit geometric normal
 * ng (the side the light must be on) and unit shading normal ns, with (about) the given numbers of
 * stratified samples of each area and environment light; stratum/strata (a square) interleave the
 * light samples of a pixel's camera samples (0, 1: on its own). Point and spot lights get a shadow ray
 * each up to REF_EXACT_POINT_LIGHTS of them; more are drawn from the light tree. */
void ref_irradiance(const ref_ctx *ctx, const double p[3], const double ng[3], const double ns[3],
                    double eta, int area_samples, int env_samples, int stratum, int strata, ref_rng *rng,
                    double out[3]);
/* Radiance of environment lights seen along unit direction dir (0 without one). */
void ref_env_radiance(const ref_ctx *ctx, const double dir[3], double out[3]);
/* Radiance of area light `light` seen from direction dir (unit, travelling towards the light). */
void ref_area_radiance(const ref_ctx *ctx, unsigned light, const double dir[3], double out[3]);

/* Closest hit of a ray from org along unit dir (ref_render.c); returns 0 on a miss. */
int ref_intersect(const ref_ctx *ctx, const double org[3], const double dir[3], struct RTCRayHit *rh);
/* True when the segment from p (already offset) along unit dir up to t_max is blocked. */
int ref_occluded(const ref_ctx *ctx, const double p[3], const double dir[3], double t_max);

/* Offsets a surface point along its normal for a ray leaving it (scene-scale and precision aware). */
static inline void ref_offset(const ref_ctx *ctx, const double p[3], const double n[3], double out[3])
{
    double m = fmax(fabs(p[0]), fmax(fabs(p[1]), fabs(p[2])));
    double e = ctx->eps + 4e-6 * m;
    out[0] = p[0] + e * n[0], out[1] = p[1] + e * n[1], out[2] = p[2] + e * n[2];
}

/* Surface samples of one object and their irradiance (ref_points.c). */
sss_result ref_points_generate(ref_ctx *ctx, size_t object, double spacing, sss_error *err);
/* Number of samples ref_points_generate makes for spacing h. */
uint64_t ref_points_count(const sss_mesh *mesh, double h);

/* Interreflection (ref_bounce.c). */
/* With bounces, the surface samples are spaced as if the object's bounding-box diagonal spanned at
 * least REF_TRANSPORT_DIVISIONS pixel footprints: the interreflected light must not depend on the
 * image size (it did: the bust's red at 96 px was 7% under that at 384 px, docs/reference.md). */
#define REF_TRANSPORT_DIVISIONS 384
/* The largest sample spacing h of object ro that rule allows (INFINITY without bounces). */
double ref_transport_cap(const ref_ctx *ctx, const ref_object *ro);
double ref_object_diagonal(const ref_object *ro);
/* Transport spacing of every object (and the sample spacing of those the density rule leaves
 * without samples). */
void ref_transport_spacing(ref_ctx *ctx);
/* Replaces object o's samples (ref_points_generate's, in generation order) by clusters of them of
 * diameter <= ro->tspacing (on one side of thin parts), T the area-weighted mean; ro->cluster_of
 * maps the samples to them. */
sss_result ref_transport_cluster(ref_ctx *ctx, size_t o, sss_error *err);
/* The transport samples within radius of each one of subsurface object ro, on its side of thin parts
 * (normals within 60 degrees), itself included (ref_neighbours.c). */
sss_result ref_neighbours_build(ref_object *ro, double radius, sss_error *err);
/* Sum over the transport samples of T_ind A S_far(|x - x_o|) (zero without them). */
void ref_indirect_sum(const ref_ctx *ctx, size_t o, const float xo[3], double out[3], uint64_t *visits);
/* Bounces 2..N at the samples of every object (after their direct T, E and trees exist); rebuilds
 * the subsurface trees with T_1 + T_2 + ... */
sss_result ref_bounces_run(ref_ctx *ctx, sss_error *err);
/* The share of bounces 2..N in the light (luminance) at the point (u, v) of triangle prim of object o,
 * from its transport sample: T_ind / (T_ind + T_direct) there, with `direct` (may be NULL) in place of
 * the sample's direct T (E); 1 without a sample or direct light. For the final gather's budget. */
double ref_indirect_share(const ref_ctx *ctx, size_t o, unsigned prim, double u, double v, const double direct[3]);
/* Bounces 2..N at surface point p by a final gather (the last bounce at the point itself, so that the
 * image does not show the transport samples' cells): stratified rays cosine-distributed about the unit
 * shading normal ns (smooth across the facets; rays below the unit geometric normal ng, the side the
 * light arrives on, see nothing), each adding what the surface it reaches sends back after bounces
 * 1..N-1 (exit_sum, with the mirror chain at subsurface hits). The camera samples of a pixel, stratum
 * of strata (a square), take interleaved subsets of one stratified set of at least pixel_rays rays
 * (as ref_irradiance's light samples). eta > 0: a subsurface point, the light enters with 1 - F_r
 * (T); else E. Returns the number of rays of this sample. */
int ref_final_gather(const ref_ctx *ctx, const double p[3], const double ng[3], const double ns[3], double eta,
                     int pixel_rays, int stratum, int strata, ref_rng *rng, double out[3]);

/* Reports the current phase's fraction (stage NULL: the phase's own); thread-safe, throttled to
 * ~10 calls per second unless force. */
void ref_report_progress(ref_ctx *ctx, double fraction, const char *stage, int force);

#endif
