/* sss/reference.h — the CPU ground truth: the subsurface integral of docs/physics.md §1, ray traced with
 * Embree 3, as PBRT-v3's `subsurface` material converges to it under direct lighting.
 *
 * What an image shows (per camera sample; rays, shadows and lights as docs/scene-format.md):
 *  - subsurface object hit at x_o, seen from w_o:
 *        L = F_t(x_o, w_o) / (pi c) * sum over surface samples x_i of the SAME object of
 *            T(x_i) A_i S_r(|x_i - x_o|),
 *    c = 1 - 2 FM1(1/eta), F_t = 1 - FrDielectric(cos theta_o, 1, eta), and
 *    T(x) = sum over lights of (1 - F_r(cos theta_light)) times that light's irradiance at x
 *    (shadow rays against every object; area and environment lights integrate F_t over their samples).
 *    S_r is the material's profile: the PBD table (PBRT-v3, default), the classical dipole, or for
 *    an artist profile its radially symmetric counterpart albedo * (w G2(r, near s) + (1 - w)
 *    G2(r, far s)) with normalised 2D Gaussians G2 (the separable product a(x) a(y) of Jimenez et al. 2019 is not
 *    radial, so it has no meaning on a curved surface).
 *  - diffuse object: reflectance / pi * E (Lambertian, two-sided, direct light only).
 *  - area-light rectangles are visible (radiance on their emitting side, black behind) and cast
 *    shadows; camera rays that miss see the environment map (black without one).
 *  - interreflection (desc.bounces, default: until converged): the light that leaves a surface lights
 *    every other surface point it reaches, bounce after bounce. Bounce 1 is the single-event integral
 *    above (T and E from the lights only; desc.bounces = 1 renders exactly that, bit for bit as before
 *    interreflection existed). Bounce k >= 2 adds T_k (E_k) at every surface sample, gathered from the
 *    radiance that bounce k - 1 leaves the surfaces with:
 *        subsurface surface y, seen along -w:  F_t(cos theta_y) / (pi c) * M_{k-1}(y),
 *            M_{k-1}(y) = sum_i T_{k-1}(x_i) A_i S_r(|x_i - y|)  (the exitance through the lobe S_w),
 *        diffuse surface y (its normal's side):  reflectance / pi * E_{k-1}(y);
 *    the light enters a subsurface sample with the factor 1 - F_r(cos theta) as direct light does.
 *    The image then shows T = T_1 + T_2 + ... in the sums above (linear in T, so the pixel pass runs
 *    once); the last bounce is gathered at each camera sample's own point (below), so that
 *    diffuse objects show reflectance / pi * (E_1 + a final gather of bounces 1..N-1).
 *  - no specular interface reflection of the camera ray unless desc.specular (then a smooth
 *    dielectric mirror F_r(cos theta_o) * L is added, L shaded along the reflected ray as along a
 *    camera ray: environment, area lights and the lit surfaces, up to 4 reflections deep; PBRT-v3's
 *    path tracer always includes it). Between bounces the interface's reflection always takes part
 *    (the gathers' mirror chain).
 *
 * How (the density rule and the tree criterion are documented at sss_reference_desc):
 *  - surface samples: every triangle of a visible subsurface object is cut into m^2 congruent
 *    sub-triangles (sides at most ~2 h, area at most h^2) with one sample at each centroid (the
 *    midpoint rule), weighted by its exact area; T is computed once per sample and shared by all
 *    pixels.
 *  - the profile is split at R0 = 4 h: S_r = S_far + S_near, S_far(r) = S_r(max(r, R0)) (continuous,
 *    flat inside R0) is summed over the samples, and S_near = S_r - S_far (the sharp peak at r -> 0,
 *    where a sample sum would be noise) is integrated over the surface within R0 of x_o by probe rays
 *    as PBRT samples its BSSRDF: radii drawn from S_near (binned, stratified), tangent-plane points
 *    projected onto the same object along -n, T evaluated at each probe hit with shadow rays, the
 *    estimate self-normalised so that a constant T gives exactly T int_0^R0 S_near 2 pi r dr.
 *    (Shadow edges at the pixel scale come from here.)
 *  - the sample sum is hierarchical (Jensen & Buhler 2002): a BVH over the samples stores per node
 *    the sum of T A (per channel) and the T A-weighted centroid; desc.exact sums all samples instead.
 *
 * Bounces (ref_bounce.c), when desc.bounces != 1:
 *  - resolution: the interreflected light must not depend on the image size, so with bounces the
 *    surface-sample spacing h of the density rule below is also at most (diagonal of the object's
 *    bounding box) / 384 / 2 (draft / 384): the samples of an image in which the object spans 384
 *    footprints, whatever the image's size (ref_internal.h, REF_TRANSPORT_DIVISIONS; eval_front's
 *    interreflected red grew by two thirds from 96 to 384 px when h followed the footprint alone).
 *  - transport samples: every object with a surface takes part. Transport spacing H = 4 h = R0 for
 *    subsurface objects (a wider cluster would take its own area whole at S_r(R0) in the exitance);
 *    diffuse objects 2 pixel footprints (draft 4), at most 4 times the cap above (objects without a
 *    footprint, behind the camera: bounding box diagonal / 64); all grown until all objects together
 *    have at most 256 k transport samples. Diffuse objects (and
 *    subsurface objects without a footprint) get the cells of ref_points.c at spacing H, with their
 *    own direct E (T). A subsurface object's pixel-density samples are grouped into clusters of
 *    diameter <= H (median splits; split by normal where normals differ by more than ~30 degrees, so
 *    that a cluster stays on one side of a thin part), each with the area-weighted mean direct T of its
 *    samples, placed at its first sample (position and normal on the surface).
 *  - links: from every transport sample, g x g gather rays (16 final, 4 draft; diffuse samples 64 and
 *    16), cosine-distributed about the triangle's geometric normal, stratified, seeded per (seed,
 *    object, sample), are traced once; a ray that hits an object links to the hit triangle's transport
 *    sample (cell, or the cluster of the pixel-density cell) holding the hit (the value there is
 *    piecewise constant), with weight pi / g^2 times the
 *    entry factor 1 - F_r(cos theta) (subsurface) times the exit factor F_t(cos theta_hit) / (pi c)
 *    (subsurface hit) or 1 / pi (diffuse hit on its normal's side; from behind: no link). Rays that
 *    miss or reach a light link nowhere (that light is bounce 1). Geometric normals throughout.
 *  - bounce k: T_k(x_i) = sum over x_i's links of weight * X_{k-1}(hit), with X = M_{k-1} (subsurface,
 *    evaluated with the tree over the transport samples, tolerance 1e-3 of the lit level and angle
 *    criterion s <= d_min, plus the near part as S_near's integral times the area-weighted mean
 *    T_{k-1} of the transport samples within R0 on the same side, normals within 60 degrees)
 *    or reflectance * E_{k-1} (diffuse); M is evaluated only at samples some link reaches. The same
 *    links serve every bounce (radiosity's form factors, sampled once).
 *  - pixels (issue 27: pixel by pixel, not per transport sample): bounces 2..N by a final gather at
 *    the camera sample's own surface point: stratified rays cosine-distributed about the shading
 *    normal (256 per pixel, draft 64, spread over its camera samples; as many again over the extra
 *    samples of a refined pixel; rays below the geometric surface see nothing), each adding what the
 *    surface it reaches sends back after bounces 1..N-1 (the exit factors of the links above, with
 *    the mirror chain, applied to M or reflectance * E of T_1 + ... + T_{N-1} at the hit's transport
 *    sample). Diffuse pixels (their normal's side) add it as E; subsurface pixels take it as the T of
 *    bounces 2..N in the near part (within R0 of x_o), and their far sums add the transport
 *    samples' T_2 + ... + T_N (their own tree, the same tolerances) to the direct sums above.
 *  - stopping: desc.bounces = N computes bounces 1..N; 0 stops after the first bounce k whose light
 *    entering the surfaces (sum over the transport samples of T_k A, or E_k A, luminance) is below
 *    SSS_REFERENCE_BOUNCE_STOP of that of bounce 2 (or of STOP x bounce 1, if that is more) on every
 *    object a pixel centre sees, or at SSS_REFERENCE_MAX_BOUNCES. stats.bounce_fraction holds that
 *    fraction per bounce (bounce 1 against itself: 1).
 *  - error bounds (tests/reference/test_ref_bounce.c): inside a closed sphere of diffuse walls
 *    (reflectance rho) or subsurface walls lit by a point light at its centre, N bounces give
 *    single (1 - q^N) / (1 - q) with q = rho, or rho_eff 2 / c int_0^1 F_t(mu)^2 mu dmu: within 1%
 *    (diffuse) and 2% (subsurface) on the image mean, 3% and 6% per pixel; bounce k + 1 adds q
 *    times what bounce k adds (within 1%).
 *
 * Determinism: for a given seed the image is bit-identical for any thread count (per-pixel and per-
 * sample random streams are seeded by their index). The library never prints; progress goes through
 * the callback.
 */
#ifndef SSS_REFERENCE_H
#define SSS_REFERENCE_H

#include <stdint.h>

#include "sss/common.h"
#include "sss/image.h"
#include "sss/material.h"
#include "sss/mesh.h"
#include "sss/profile.h"
#include "sss/scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Interreflection: the cap of desc.bounces and the stopping fraction of the default (see above). */
#define SSS_REFERENCE_MAX_BOUNCES 16
#define SSS_REFERENCE_BOUNCE_STOP 0.01
/* The version of what the interreflection computes (bounces != 1): raised whenever the same scene and
 * options give a different image, so that images cached with an older one are known to be stale
 * (sss eval's sidecars record it). 1: the first interreflection; 2: bounce gathers follow the mirror
 * reflection at subsurface interfaces, and the default stops relative to bounce 2; 3: the samples no
 * longer coarsen with the image size (the resolution cap), clusters of diameter R0; 4: the last
 * bounce gathered at the pixels' own points, the exitance's near part averaged over R0 (issue 27).
 * --bounces 1 has not changed since before interreflection. */
#define SSS_REFERENCE_TRANSPORT_VERSION 4

typedef enum sss_reference_quality {
    SSS_REFERENCE_FINAL = 0, /* default */
    SSS_REFERENCE_DRAFT
} sss_reference_quality;

/* Zero-initialised = defaults (final quality, all cores, t = 0, random seed = 0).
 *
 * Density rule. For each visible subsurface object, fp = the world-space size of one pixel at the
 * object's nearest visible points (the 1st percentile of the pixel footprints depth * 2 tan(fov/2) /
 * min(width, height) over the pixel centres that see the object; objects no centre sees use their
 * bounding box centre). Spacing h = fp / 2 (final: 4 samples per pixel^2 there) or h = fp (draft),
 * divided by sqrt(density); with bounces at most the resolution cap ("Bounces" above) divided by
 * sqrt(density). The total over all objects is capped at 16 M samples (final; draft 2 M;
 * both times density) by growing h, and every triangle gets at least one sample. The mean free path
 * does not enter: below R0 = 4 h = 2 fp the profile is handled by the probes, and above it the sample
 * sum of a profile that is flat inside R0 is a smooth quadrature; on a uniformly lit plane the
 * result is within 0.06% of c_o F_t E rho_eff per pixel for both short (sigma_tr R0 ~ 0.3) and long
 * (Marble) profiles (tests/reference/test_ref_plane.c), and 4x the density changes the dragon
 * benchmark by a DSSIM below 1e-4.
 *
 * Tree criterion. A node (bounding sphere of diameter s around its points, distance d_min from x_o
 * to that sphere) is used as one sample at its T A-weighted centroid when s <= 0.5 d_min and either
 * s <= 0.6 l(d_min), l(r) = min over channels of sqrt(S / (|S''| + 2 |S'| / r)) for S = S_far (the
 * monopole's relative error is about (s / l)^2 / 40: the second moment of the node's points against
 * the Hessian of S(|x - x_o|), whose eigenvalues are S'' and S'/r twice; channels count where a ring
 * of width r still holds 1e-4 of their plane integral), or that error estimate, T A S (s / l)^2 / 40,
 * is below 1e-6 of the object's lit level (mean T of its lit samples times the plane integral) in
 * every channel. A node is skipped when d_min is beyond the profile's support (the tail beyond holds
 * less than 1e-6 of the plane integral) or its T A is zero, and taken whole with S_r(R0) when it lies
 * inside R0; leaves (<= 8 samples) are summed exactly. Measured against desc.exact: <= 0.12% per
 * pixel (tests/reference/test_ref_exact.c).
 *
 * Pixel samples: spp stratified jittered samples (final 16 = 4x4, draft 1); pixels whose samples see
 * different surfaces (object, or normals differing by more than ~25 degrees) or whose 8-bit tone-
 * mapped values differ by more than 2 get 4 x spp more (final 64). The sample sum (the far part) is
 * smooth on the scale of R0 >= 2 pixels, so it is evaluated once per pixel at the pixel centre's hit
 * and shared by the pixel's samples that land on the same surface within R0 of it (the midpoint rule
 * over the pixel); the near part, F_t and visibility stay per sample. desc.no_far_reuse evaluates it
 * at every sample.
 * Light samples: per surface sample, area lights 16 and environment maps 64 (draft 4 and 16); per
 * pixel, spread over its camera samples and interleaved so that the pixel's set is stratified as a
 * whole, area lights 256 and environment maps 1024 (draft 16 and 64); probes for the near part: 128
 * per pixel (draft 16), at least 4 per camera sample. Environment maps are importance-sampled by
 * luminance x sin(theta) (piecewise constant, as PBRT's infinite light).
 */
typedef struct sss_reference_desc {
    sss_reference_quality quality;
    int threads;           /* OpenMP threads; 0 = all cores */
    double time;           /* animation time (seconds) for sss_reference_render */
    uint64_t seed;
    int exact;             /* brute-force sample sums instead of the tree (slow; for validation) */
    int specular;          /* add the camera ray's smooth dielectric reflection (of everything it sees) */
    int spp;               /* base samples per pixel (rounded up to a square); 0 = the quality's */
    int no_adaptive;       /* no extra samples at edges */
    double density;        /* multiplies the surface-sample density (samples per area); 0 = 1 */
    int light_samples;     /* multiplies the light sample counts above (not the probes); 0 = 1 */
    int no_far_reuse;      /* evaluate the sample sum at every camera sample (see below) */
    int bounces;           /* 0 = until converged (default), 1 = single event, N = exactly N (<= 16) */
} sss_reference_desc;

typedef struct sss_reference_stats {
    uint64_t surface_samples;       /* over all subsurface objects */
    uint64_t tree_nodes, tree_leaves;
    uint32_t tree_depth;            /* deepest tree */
    double spacing_min, spacing_max; /* h over subsurface objects (scene units) */
    double split_radius_min;        /* R0 */
    uint64_t camera_samples;        /* all primary rays */
    uint64_t adaptive_pixels;       /* pixels that got the extra samples */
    uint64_t lookups;               /* sample sums evaluated (camera samples on subsurface objects) */
    double nodes_per_lookup;        /* mean nodes + samples visited per sum */
    uint64_t nonfinite_samples;     /* camera samples that produced NaN/Inf and were replaced by 0 */
    double seconds_setup;           /* Embree scene, profiles, lights */
    double seconds_samples;         /* surface samples and their irradiance */
    double seconds_tree;
    double seconds_pixels;
    double seconds_total;
    /* Interreflection: bounces computed (1 = single event), the samples that carry them (all
     * objects), and per bounce k (index k - 1) its seconds and its light entering the surfaces
     * relative to bounce 1 (index 0: the direct samples, seconds_samples, 1.0; the last bounce's
     * seconds include the trees the pixels use, seconds_pixels the pixels' final gathers). */
    uint32_t bounces;
    uint64_t transport_samples;
    double seconds_bounce[SSS_REFERENCE_MAX_BOUNCES];
    double bounce_fraction[SSS_REFERENCE_MAX_BOUNCES];
} sss_reference_stats;

/* Progress: fraction in [0, 1] over the whole render, stage a static string ("setup", "surface
 * samples", "pixels"). Called from worker threads, one call at a time, at most every ~0.1 s. */
typedef void (*sss_reference_progress_fn)(void *user, double fraction, const char *stage);

/* Renders a loaded scene (objects posed at desc->time with the scene module's shared deformation).
 * out is allocated (camera width x height) and must be freed with sss_image_free; on failure it is
 * left empty. stats and progress may be NULL. Environment maps are read with sss_image_read. */
SSS_API sss_result sss_reference_render(const sss_scene *scene, const sss_reference_desc *desc, sss_image *out,
                                        sss_reference_progress_fn progress, void *user,
                                        sss_reference_stats *stats, sss_error *err);

/* ---- The scene-independent description the renderer works on -------------------------------- */

typedef enum sss_reference_material {
    SSS_REFERENCE_DIFFUSE = 0,
    SSS_REFERENCE_SUBSURFACE
} sss_reference_material;

typedef struct sss_reference_object {
    const sss_mesh *mesh;           /* WORLD space; its normals (if any) are the shading normals */
    sss_reference_material type;
    double reflectance[3];          /* DIFFUSE, [0, 1] */
    sss_material optical;           /* SUBSURFACE: per scene unit, eta, g */
    sss_scene_profile profile;      /* SUBSURFACE: PBD (default), DIPOLE or ARTIST */
    const sss_pbd_table *table;     /* PBD: built for optical.eta and optical.g */
    sss_artist_params artist;       /* ARTIST: s in scene units */
    double albedo[3];               /* ARTIST: plane integral of the profile per channel */
} sss_reference_object;

typedef struct sss_reference_world {
    sss_camera camera;
    const sss_reference_object *objects;
    size_t object_count;
    const sss_light *lights;        /* as sss/scene.h (directional direction need not be unit) */
    size_t light_count;
    /* Optional, light_count entries: the map of each ENVIRONMENT light (NULL entries and a NULL
     * array: read lights[i].file with sss_image_read). */
    const sss_image *const *environment_maps;
    double exposure;                /* display exposure: the adaptive-sampling threshold uses it */
} sss_reference_world;

SSS_API sss_result sss_reference_render_world(const sss_reference_world *world, const sss_reference_desc *desc,
                                              sss_image *out, sss_reference_progress_fn progress, void *user,
                                              sss_reference_stats *stats, sss_error *err);

/* ---- Conventions shared with the other renderers ---------------------------------------------- */

/* Equirectangular environment maps (docs/scene-format.md: +y up, u = 0.5 at -z), not mirrored: standing inside
 * and facing -z, image right is world right (+x). The map's own direction of (u, v), v = 0 the top
 * row, is  m = (sin theta sin phi, cos theta, -sin theta cos phi),  phi = 2 pi (u - 0.5), theta = pi v;
 * the world direction is R_y(rotate_y) m, a right-handed rotation about +y (positive angles move the
 * map's -z towards -x), i.e. the same formula with phi = 2 pi (u - 0.5) - rad(rotate_y). */
SSS_API void sss_reference_env_direction(double u, double v, double rotate_y_degrees, double dir[3]);
/* Its inverse: dir need not be unit; u in [0, 1), v in [0, 1]. */
SSS_API void sss_reference_env_uv(const double dir[3], double rotate_y_degrees, double *u, double *v);

/* Spot light falloff of PBRT-v3 (lights/spot.cpp): with cos_total = cos(cone_angle), cos_start =
 * cos(cone_angle - cone_delta) and cos_theta the cosine between the spot's axis and the direction
 * from the light to the lit point: 0 below cos_total, 1 above cos_start, delta^4 in between with
 * delta = (cos_theta - cos_total) / (cos_start - cos_total). (PBRT-v4 uses smoothstep instead.) */
SSS_API double sss_reference_spot_falloff(double cone_angle_degrees, double cone_delta_degrees, double cos_theta);

#ifdef __cplusplus
}
#endif
#endif
