/* reference/ref_render.c — the pixel loop: camera samples, shading (docs/physics.md §1), adaptive
 * supersampling of edges, and the library entry point for a scene-independent world. */
#include <omp.h>
#include <stdlib.h>

#include "reference/ref_internal.h"

/* Extra per-thread counters. */
typedef struct shade_counters {
    uint64_t visits, lookups;
} shade_counters;

/* Closest hit of a ray; returns 0 on a miss. */
int ref_intersect(const ref_ctx *ctx, const double org[3], const double dir[3], struct RTCRayHit *rh)
{
    struct RTCIntersectContext ic;
    rtcInitIntersectContext(&ic);
    memset(rh, 0, sizeof *rh);
    rh->ray.org_x = (float)org[0], rh->ray.org_y = (float)org[1], rh->ray.org_z = (float)org[2];
    rh->ray.dir_x = (float)dir[0], rh->ray.dir_y = (float)dir[1], rh->ray.dir_z = (float)dir[2];
    rh->ray.tnear = 0.0f;
    rh->ray.tfar = INFINITY;
    rh->ray.mask = 0xffffffffu;
    rh->hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh->hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(ctx->scene, &ic, rh);
    return rh->hit.geomID != RTC_INVALID_GEOMETRY_ID;
}

/* A camera ray's hit on an object: position, geometric and shading normals facing the camera. */
typedef struct surface_hit {
    unsigned geom, prim;
    double u, v; /* barycentrics of the triangle's 2nd and 3rd vertices */
    double p[3], ng[3], ns[3];
    int back; /* seen from behind its triangles' winding (normals flipped) */
} surface_hit;

/* One camera sample: what the refinement of its pixel needs. */
typedef struct sample_info {
    int64_t geom;     /* -1: miss */
    double n[3];      /* geometric normal facing the camera */
    /* its final gather (gather rays, 0: none): the radiance holds coef * t_ind */
    int gather;
    double eta, coef[3], t_ind[3];
    surface_hit hit;
} sample_info;

/* Position and normals of a hit on object g; normals face `facing` (the side the ray came from). */
static void decode_hit(const ref_ctx *ctx, unsigned g, const struct RTCRayHit *rh, const double facing[3],
                       surface_hit *hit)
{
    const double *wo = facing;
    hit->geom = g;
    hit->prim = rh->hit.primID;
    hit->u = rh->hit.u, hit->v = rh->hit.v;
    const sss_mesh *m = ctx->objects[g].src->mesh;
    const uint32_t *idx = m->indices + 3 * (size_t)rh->hit.primID;
    const float *fa = m->positions + 3 * (size_t)idx[0], *fb = m->positions + 3 * (size_t)idx[1],
                *fc = m->positions + 3 * (size_t)idx[2];
    double u = rh->hit.u, v = rh->hit.v, w0 = 1.0 - u - v;
    double e1[3], e2[3];
    for (int c = 0; c < 3; c++) {
        /* Barycentric position: more precise than org + t dir far from the camera. */
        hit->p[c] = w0 * fa[c] + u * fb[c] + v * fc[c];
        e1[c] = (double)fb[c] - fa[c];
        e2[c] = (double)fc[c] - fa[c];
    }
    v3_cross(e1, e2, hit->ng);
    if (!(v3_normalize(hit->ng) > 0.0)) memcpy(hit->ng, wo, sizeof hit->ng);
    if (m->normals) {
        const float *na = m->normals + 3 * (size_t)idx[0], *nb = m->normals + 3 * (size_t)idx[1],
                    *nc = m->normals + 3 * (size_t)idx[2];
        for (int c = 0; c < 3; c++) hit->ns[c] = w0 * na[c] + u * nb[c] + v * nc[c];
        if (!(v3_normalize(hit->ns) > 0.0)) memcpy(hit->ns, hit->ng, sizeof hit->ns);
    } else {
        memcpy(hit->ns, hit->ng, sizeof hit->ns);
    }
    hit->back = v3_dot(hit->ng, wo) < 0.0;
    if (hit->back) {
        /* Seen from behind (open meshes): shade that side. */
        for (int c = 0; c < 3; c++) hit->ng[c] = -hit->ng[c], hit->ns[c] = -hit->ns[c];
    }
}

/* Traces a camera ray (or its mirror image): 0 miss, 1 object (hit filled), 2 area light (hit->geom
 * set). */
static int trace_camera(const ref_ctx *ctx, const double org[3], const double dir[3], surface_hit *hit)
{
    struct RTCRayHit rh;
    if (!ref_intersect(ctx, org, dir, &rh)) return 0;
    unsigned g = rh.hit.geomID;
    hit->geom = g;
    if (g >= ctx->light_geom_base) return 2;
    double wo[3] = {-dir[0], -dir[1], -dir[2]};
    decode_hit(ctx, g, &rh, wo, hit);
    return 1;
}

/* Irradiance T at one probe of the near part: the tangent-plane point at radius r, angle ph around
 * x_o projected onto the object along -n (only this object is hit), times the surface area per
 * tangent-plane area; returns 0 when the probe finds no surface. */
static int probe_irradiance(const ref_ctx *ctx, const ref_object *obj, const surface_hit *x, const double t1[3],
                            const double t2[3], double r, double ph, int area_n, int env_n, ref_rng *rng,
                            double val[3])
{
    const double *n = x->ns;
    double r0 = obj->prof.r0, cp = cos(ph), sp = sin(ph), org[3];
    for (int c = 0; c < 3; c++) org[c] = x->p[c] + r * (cp * t1[c] + sp * t2[c]) + r0 * n[c];
    struct RTCIntersectContext ic;
    rtcInitIntersectContext(&ic);
    struct RTCRayHit rh;
    memset(&rh, 0, sizeof rh);
    rh.ray.org_x = (float)org[0], rh.ray.org_y = (float)org[1], rh.ray.org_z = (float)org[2];
    rh.ray.dir_x = (float)-n[0], rh.ray.dir_y = (float)-n[1], rh.ray.dir_z = (float)-n[2];
    rh.ray.tfar = (float)(2.0 * r0);
    rh.ray.mask = 0xffffffffu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(obj->probe_scene, &ic, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return 0;
    surface_hit y;
    decode_hit(ctx, x->geom, &rh, n, &y);
    ref_irradiance(ctx, y.p, y.ng, y.ns, obj->eta, area_n, env_n, 0, 1, rng, val);
    if (!ref_source_kept(ctx, y.p, y.ng, y.ns)) val[0] = val[1] = val[2] = 0.0;
    double jac = 1.0 / fmax(fabs(v3_dot(y.ng, n)), 0.1);
    for (int c = 0; c < 3; c++) val[c] *= jac;
    return 1;
}

/* The direct T at x_o itself. */
static void irradiance_at_hit(const ref_ctx *ctx, const ref_object *obj, const surface_hit *x, ref_rng *rng,
                              double T[3])
{
    ref_irradiance(ctx, x->p, x->ng, x->ns, obj->eta, ctx->area_samples_camera, ctx->env_samples_camera, 0, 1,
                   rng, T);
    if (!ref_source_kept(ctx, x->p, x->ng, x->ns)) T[0] = T[1] = T[2] = 0.0;
}

/* Near part below R0 (docs/physics.md §1): int over the surface within R0 of S_near(|y - x_o|) T(y) dA, by
 * ctx->near_probes probe rays as PBRT samples its BSSRDF: radii from the binned S_near (stratified),
 * angles from a randomised Kronecker sequence. Self-normalised, so that a constant T gives exactly
 * near * T; a probe that finds no surface uses T(x_o). (A probe count that adapts to the first
 * probes' agreement would be biased: a small lit part missed by them would never be looked for.)
 * The probes see the direct T; bounces 2..N enter as t_ind, their final gather at x_o itself (smooth
 * on the scale of R0 but for contacts: interreflected light has no hard shadows). */
static void near_part(const ref_ctx *ctx, const ref_object *obj, const surface_hit *x, const double t_ind[3],
                      ref_rng *rng, double out[3])
{
    const ref_profile *pf = &obj->prof;
    double total = pf->near_cdf[REF_NEAR_BINS];
    out[0] = out[1] = out[2] = 0.0;
    if (!(total > 0.0)) return;
    const double *n = x->ns;
    double t1[3], t2[3], a[3] = {1, 0, 0};
    if (fabs(n[0]) > 0.7) a[0] = 0, a[1] = 1;
    v3_cross(n, a, t1);
    v3_normalize(t1);
    v3_cross(n, t1, t2);
    int K = ctx->near_probes;
    int area_n = (ctx->area_samples_camera + K - 1) / K, env_n = (ctx->env_samples_camera + K - 1) / K;
    double num[3] = {0, 0, 0}, den[3] = {0, 0, 0}, Tx[3] = {0, 0, 0};
    int have_tx = 0;
    double phase = ref_rng_uniform(rng);
    for (int k = 0; k < K; k++) {
        double u = (k + ref_rng_uniform(rng)) / K * total;
        int lo = 0, hi = REF_NEAR_BINS - 1;
        while (lo < hi) { /* the bin j with cdf[j] <= u < cdf[j + 1] */
            int mid = (lo + hi + 1) / 2;
            if (pf->near_cdf[mid] <= u)
                lo = mid;
            else
                hi = mid - 1;
        }
        int j = lo;
        double pj = (pf->near_cdf[j + 1] - pf->near_cdf[j]) / total;
        if (!(pj > 0.0)) continue;
        double ea = pf->near_edge[j], eb = pf->near_edge[j + 1];
        double r = sqrt(ea * ea + ref_rng_uniform(rng) * (eb * eb - ea * ea)); /* uniform in area */
        double ph = 2.0 * REF_PI * fmod(phase + k * 0.6180339887498949, 1.0);
        double val[3];
        if (!probe_irradiance(ctx, obj, x, t1, t2, r, ph, area_n, env_n, rng, val)) {
            if (!have_tx) {
                irradiance_at_hit(ctx, obj, x, rng, Tx);
                have_tx = 1;
            }
            memcpy(val, Tx, sizeof val);
        }
        for (int c = 0; c < 3; c++) {
            double w = pf->near_mass[j][c] / pj;
            num[c] += w * val[c];
            den[c] += w;
        }
    }
    for (int c = 0; c < 3; c++) {
        if (den[c] != 0.0 && fabs(den[c]) > 1e-9 * fabs(pf->near[c])) {
            out[c] = pf->near[c] * num[c] / den[c];
        } else {
            if (!have_tx) {
                irradiance_at_hit(ctx, obj, x, rng, Tx);
                have_tx = 1;
            }
            out[c] = pf->near[c] * Tx[c];
        }
        if (ctx->transport) out[c] += pf->near[c] * t_ind[c];
    }
}

/* The sample sum at the pixel centre's hit, shared by the pixel's samples that land on the same
 * surface within R0 / 2 of it. The sum is smooth on the scale of R0 >= 2 pixels (S_far is flat
 * inside R0), so this is the midpoint rule over the pixel for it; the near part, F_t and visibility
 * stay per sample. */
typedef struct far_cache {
    int valid, computed;
    surface_hit center;
    double far[3];
} far_cache;

static void far_sum(const ref_ctx *ctx, const ref_object *obj, const double p[3], double far[3],
                    shade_counters *cnt)
{
    float xo[3] = {(float)p[0], (float)p[1], (float)p[2]};
    if (ctx->desc.exact)
        ref_brute_sum(&obj->tree, &obj->prof, xo, far, &cnt->visits);
    else
        ref_tree_sum(&obj->tree, &obj->prof, xo, obj->abs_tol, far, &cnt->visits);
    if (ctx->transport) { /* bounces 2..N, from the transport samples */
        double ind[3];
        ref_indirect_sum(ctx, (size_t)(obj - ctx->objects), xo, ind, &cnt->visits);
        for (int c = 0; c < 3; c++) far[c] += ind[c];
    }
    cnt->lookups++;
}

/* Camera rays follow the smooth interface's mirror reflection (desc.specular) this many times: F_r^4
 * is below 1e-4 except at grazing angles. */
#define MIRROR_DEPTH 4

static void shade(const ref_ctx *ctx, const double org[3], const double dir[3], int depth, int stratum, int strata,
                  ref_rng *rng, double L[3], sample_info *info, shade_counters *cnt, far_cache *fc);

/* Adds F_r times the radiance along the reflection of dir at a subsurface hit, shaded as a camera ray
 * (the environment, an area light, or another surface: PBRT's path tracer follows the same
 * reflection). */
static void add_mirror(const ref_ctx *ctx, const surface_hit *hit, const double dir[3], double fr, int depth,
                       int stratum, int strata, ref_rng *rng, shade_counters *cnt, double L[3])
{
    const double *ng = hit->ng, *ns = hit->ns;
    double r[3], dd = v3_dot(dir, ns);
    for (int c = 0; c < 3; c++) r[c] = dir[c] - 2.0 * dd * ns[c];
    if (!(v3_dot(r, ng) > 0.0)) { /* about the shading normal it would enter the surface */
        dd = v3_dot(dir, ng);
        for (int c = 0; c < 3; c++) r[c] = dir[c] - 2.0 * dd * ng[c];
    }
    v3_normalize(r);
    double po[3], Lr[3];
    ref_offset(ctx, hit->p, ng, po);
    sample_info si;
    far_cache none;
    memset(&none, 0, sizeof none);
    shade(ctx, po, r, depth + 1, stratum, strata, rng, Lr, &si, cnt, &none);
    for (int c = 0; c < 3; c++) L[c] += fr * Lr[c];
}

/* The final gather's rays for a pixel whose light is `share` indirect: gather_pixel where it is all
 * indirect, and in proportion to share^2 elsewhere (the gather's noise relative to the pixel, share /
 * sqrt(rays), stays that of a wholly indirect pixel; lit parts need few: a lit floor is ~10% indirect),
 * at least a sixteenth. The share comes from the transport samples, so the count does not depend on
 * the gather itself and the estimate stays unbiased. */
static int gather_rays(const ref_ctx *ctx, double share)
{
    double n = ceil(ctx->gather_pixel * share * share), lo = ctx->gather_pixel / 16;
    return (int)fmin(ctx->gather_pixel, fmax(lo, isfinite(n) ? n : lo));
}

/* The near part's share of the profile's plane integral (luminance): what of a subsurface pixel's
 * indirect light its final gather carries. */
static double near_share(const ref_object *obj)
{
    const double *n = obj->prof.near, *t = obj->prof.total;
    double total = 0.2126 * t[0] + 0.7152 * t[1] + 0.0722 * t[2];
    return total > 0.0 ? fmin(1.0, fmax(0.0, (0.2126 * n[0] + 0.7152 * n[1] + 0.0722 * n[2]) / total)) : 1.0;
}

/* The subsurface radiance at a hit towards -dir, docs/physics.md §1:
 * L = F_t(x_o) / (pi c) * [near part + sum_i T_i A_i S_far(|x_i - x_o|)]; returns F_r(x_o). */
static double shade_subsurface(const ref_ctx *ctx, const surface_hit *hit, const double dir[3], int stratum,
                               int strata, ref_rng *rng, shade_counters *cnt, far_cache *fc, double L[3],
                               sample_info *info)
{
    const ref_object *obj = &ctx->objects[hit->geom];
    const double *p = hit->p;
    double near[3], far[3] = {0, 0, 0}, t_ind[3] = {0, 0, 0};
    if (ctx->transport) {
        double share = near_share(obj) * ref_indirect_share(ctx, hit->geom, hit->prim, hit->u, hit->v, NULL);
        info->gather = ref_final_gather(ctx, p, hit->ng, hit->ns, obj->eta, gather_rays(ctx, share), stratum, strata,
                                        rng, t_ind);
    }
    near_part(ctx, obj, hit, t_ind, rng, near);
    if (obj->tree.point_count > 0) {
        double d[3] = {p[0] - fc->center.p[0], p[1] - fc->center.p[1], p[2] - fc->center.p[2]};
        if (fc->valid && fc->center.geom == hit->geom && v3_len(d) <= obj->prof.r0 &&
            v3_dot(hit->ng, fc->center.ng) > 0.9) {
            if (!fc->computed) {
                far_sum(ctx, obj, fc->center.p, fc->far, cnt);
                fc->computed = 1;
            }
            memcpy(far, fc->far, sizeof far);
        } else {
            far_sum(ctx, obj, p, far, cnt);
        }
    }
    double cos_o = fabs(v3_dot(hit->ns, dir));
    double fr = sss_fresnel_dielectric(cos_o, 1.0, obj->eta);
    double k = (1.0 - fr) / (REF_PI * obj->c_norm);
    for (int c = 0; c < 3; c++) {
        L[c] = k * (near[c] + far[c]);
        info->coef[c] = k * obj->prof.near[c];
        info->t_ind[c] = t_ind[c];
    }
    info->eta = obj->eta;
    info->hit = *hit;
    return fr;
}

/* Radiance along one camera ray from org (depth: mirror reflections so far). */
static void shade(const ref_ctx *ctx, const double org[3], const double dir[3], int depth, int stratum, int strata,
                  ref_rng *rng, double L[3], sample_info *info, shade_counters *cnt, far_cache *fc)
{
    surface_hit hit;
    L[0] = L[1] = L[2] = 0.0;
    memset(info, 0, sizeof *info);
    info->geom = -1;
    int kind = trace_camera(ctx, org, dir, &hit);
    if (kind == 0) {
        if (ctx->has_env) ref_env_radiance(ctx, dir, L);
        return;
    }
    info->geom = hit.geom;
    if (kind == 2) {
        ref_area_radiance(ctx, ctx->light_of_geom[hit.geom - ctx->light_geom_base], dir, L);
        memset(info->n, 0, sizeof info->n);
        return;
    }
    memcpy(info->n, hit.ng, sizeof info->n);
    const ref_object *obj = &ctx->objects[hit.geom];
    if (!obj->subsurface) {
        double E[3];
        ref_irradiance(ctx, hit.p, hit.ng, hit.ns, 0.0, ctx->area_samples_camera, ctx->env_samples_camera, stratum,
                       strata, rng, E);
        if (ctx->transport && !hit.back) { /* the transport holds the light on the normal's side only */
            double share = ref_indirect_share(ctx, hit.geom, hit.prim, hit.u, hit.v, E);
            info->gather = ref_final_gather(ctx, hit.p, hit.ng, hit.ns, 0.0, gather_rays(ctx, share), stratum, strata,
                                            rng, info->t_ind);
            for (int c = 0; c < 3; c++) E[c] += info->t_ind[c], info->coef[c] = obj->src->reflectance[c] / REF_PI;
            info->hit = hit;
        }
        for (int c = 0; c < 3; c++) L[c] = obj->src->reflectance[c] / REF_PI * E[c];
        return;
    }
    double fr = shade_subsurface(ctx, &hit, dir, stratum, strata, rng, cnt, fc, L, info);
    if (ctx->desc.specular && depth < MIRROR_DEPTH) add_mirror(ctx, &hit, dir, fr, depth, stratum, strata, rng, cnt, L);
}

static int tone8(double x, double scale)
{
    double v = x * scale;
    v = v > 0.0 ? (v < 1.0 ? v : 1.0) : 0.0;
    return (int)lround(255.0 * sss_srgb_encode(v));
}

/* Whether a pixel's base samples agree (same surface, similar normals, 8-bit values within 2), with
 * (gathered) or without (the edges: geometry and direct light) their final gathers' light. */
static int samples_agree(const double (*L)[3], const sample_info *info, int n, double scale, int gathered)
{
    for (int s = 1; s < n; s++) {
        if (info[s].geom != info[0].geom) return 0;
        if (info[0].geom >= 0 && v3_dot(info[s].n, info[0].n) < 0.9) return 0;
        for (int c = 0; c < 3; c++) {
            double a = L[s][c], b = L[0][c];
            if (!gathered) a -= info[s].coef[c] * info[s].t_ind[c], b -= info[0].coef[c] * info[0].t_ind[c];
            if (abs(tone8(a, scale) - tone8(b, scale)) > 2) return 0;
        }
    }
    return 1;
}

/* A pixel whose base samples differ only by their final gathers' noise: each sample gathers again at
 * its own hit with REGATHER times its rays, and its gathered light becomes the mean of all its rays
 * (where a bright surface fills a small solid angle, as the lit side of an object seen from its
 * shadow, 256 rays a pixel leave single bright pixels; this spends more only there). */
#define REGATHER 3

static void regather(const ref_ctx *ctx, const sample_info *info, int n, ref_rng *rng, double sum[3])
{
    for (int s = 0; s < n; s++) {
        const sample_info *si = &info[s];
        if (!si->gather) continue;
        double t[3];
        int rays = ref_final_gather(ctx, si->hit.p, si->hit.ng, si->hit.ns, si->eta, REGATHER * si->gather * n, s, n,
                                    rng, t);
        for (int c = 0; c < 3; c++)
            sum[c] += si->coef[c] * (si->t_ind[c] * si->gather + t[c] * rays) / (si->gather + rays) -
                      si->coef[c] * si->t_ind[c];
    }
}

#define MAX_BASE_SIDE 64

sss_result ref_render_world(const sss_reference_world *world, const sss_reference_desc *desc,
                            const ref_source_mask *mask, sss_image *out, sss_reference_progress_fn progress,
                            void *user, sss_reference_stats *stats, sss_error *err)
{
    if (!out) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "reference: output image is NULL");
    memset(out, 0, sizeof *out);
    if (!world) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "reference: world is NULL");
    double t_start = sss_time_seconds();
    ref_ctx ctx;
    memset(&ctx, 0, sizeof ctx);
    ctx.world = world;
    if (desc) ctx.desc = *desc;
    if (mask) {
        sss_result mr = ref_source_mask_check(mask, desc, err);
        if (mr != SSS_OK) return mr;
        ctx.mask = *mask;
    }
    if (ctx.desc.spp < 0 || ctx.desc.threads < 0 || !(ctx.desc.density >= 0.0) || !isfinite(ctx.desc.density) ||
        ctx.desc.light_samples < 0 || !isfinite(ctx.desc.time))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                             "reference: spp, threads, density and light_samples must be >= 0");
    if (ctx.desc.bounces < 0 || ctx.desc.bounces > SSS_REFERENCE_MAX_BOUNCES)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "reference: bounces must be in 0..%d, got %d",
                             SSS_REFERENCE_MAX_BOUNCES, ctx.desc.bounces);
    ctx.progress = progress;
    ctx.user = user;
    ctx.last_progress_time = -1e30;
    int draft = ctx.desc.quality == SSS_REFERENCE_DRAFT;
    int ls = ctx.desc.light_samples > 0 ? ctx.desc.light_samples : 1;
    /* Per camera sample: the per-pixel budgets of the quality spread over the pixel's base samples. */
    int spp = ctx.desc.spp > 0 ? ctx.desc.spp : (draft ? 1 : 16);
    int kb = (int)ceil(sqrt((double)spp));
    if (kb > MAX_BASE_SIDE) kb = MAX_BASE_SIDE;
    int ka = 2 * kb; /* the extra samples: 4 x spp */
    int nb = kb * kb;
    ctx.area_samples_point = (draft ? 4 : 16) * ls;
    ctx.env_samples_point = (draft ? 16 : 64) * ls;
    ctx.area_samples_camera = ((draft ? 16 : 256) * ls + nb - 1) / nb;
    ctx.env_samples_camera = ((draft ? 64 : 1024) * ls + nb - 1) / nb;
    ctx.near_probes = ((draft ? 16 : 128) + nb - 1) / nb;
    if (ctx.near_probes < 4) ctx.near_probes = 4;
    ctx.transport = ctx.desc.bounces != 1;
    ctx.gather_subsurface = draft ? 4 : 16;
    ctx.gather_diffuse = draft ? 16 : 64;
    ctx.gather_pixel = draft ? 64 : 256;
    ctx.gather_refine = draft ? 12 : 48;
    int saved_threads = omp_get_max_threads();
    if (ctx.desc.threads > 0) omp_set_num_threads(ctx.desc.threads);

    sss_result r = ref_prepare(&ctx, err);
    if (r == SSS_OK) r = sss_image_create(out, ctx.cam.width, ctx.cam.height, err);
    if (r != SSS_OK) {
        ref_ctx_free(&ctx);
        sss_image_free(out);
        omp_set_num_threads(saved_threads);
        return r;
    }

    double t_pixels = sss_time_seconds();
    ref_set_phase(&ctx, 0.3, 1.0, "pixels");
    const int W = ctx.cam.width, H = ctx.cam.height;
    const double scale = exp2(isfinite(world->exposure) ? world->exposure : 0.0);
    uint64_t visits = 0, lookups = 0, camera_samples = 0, adaptive = 0, nonfinite = 0;
    int rows_done = 0, alloc_failed = 0;
#pragma omp parallel reduction(+ : visits, lookups, camera_samples, adaptive, nonfinite)
    {
        double (*L)[3] = malloc(sizeof(double[3]) * (size_t)kb * kb);
        sample_info *info = malloc(sizeof(sample_info) * (size_t)kb * kb);
        int ok = L && info;
#pragma omp for schedule(dynamic, 1)
        for (int y = 0; y < H; y++) {
            if (!ok) continue;
            shade_counters cnt = {0, 0};
            for (int x = 0; x < W; x++) {
                ref_rng rng;
                ref_rng_seed(&rng, ctx.desc.seed, 0x50495845ull, (uint64_t)y * (uint64_t)W + (uint64_t)x);
                far_cache fc;
                fc.valid = fc.computed = 0;
                if (!ctx.desc.no_far_reuse) {
                    double dir[3];
                    ref_camera_ray(&ctx.cam, x + 0.5, y + 0.5, dir);
                    fc.valid = trace_camera(&ctx, ctx.cam.origin, dir, &fc.center) == 1 &&
                               ctx.objects[fc.center.geom].tree.point_count > 0;
                }
                double sum[3] = {0, 0, 0};
                int n = kb * kb;
                for (int s = 0; s < n; s++) {
                    double dir[3];
                    ref_camera_ray(&ctx.cam, x + (s % kb + ref_rng_uniform(&rng)) / kb,
                                   y + (s / kb + ref_rng_uniform(&rng)) / kb, dir);
                    shade(&ctx, ctx.cam.origin, dir, 0, s, n, &rng, L[s], &info[s], &cnt, &fc);
                    for (int c = 0; c < 3; c++) {
                        if (!isfinite(L[s][c])) {
                            nonfinite++;
                            L[s][c] = 0.0;
                        }
                        sum[c] += L[s][c];
                    }
                }
                int total = n, refine = !ctx.desc.no_adaptive && n > 1;
                if (refine && samples_agree((const double(*)[3])L, info, n, scale, 0) &&
                    !samples_agree((const double(*)[3])L, info, n, scale, 1)) {
                    regather(&ctx, info, n, &rng, sum);
                } else if (refine && !samples_agree((const double(*)[3])L, info, n, scale, 0)) {
                    adaptive++;
                    for (int s = 0; s < ka * ka; s++) {
                        double dir[3], Ls[3];
                        sample_info si;
                        ref_camera_ray(&ctx.cam, x + (s % ka + ref_rng_uniform(&rng)) / ka,
                                       y + (s / ka + ref_rng_uniform(&rng)) / ka, dir);
                        shade(&ctx, ctx.cam.origin, dir, 0, s, ka * ka, &rng, Ls, &si, &cnt, &fc);
                        for (int c = 0; c < 3; c++) {
                            if (!isfinite(Ls[c])) {
                                nonfinite++;
                                Ls[c] = 0.0;
                            }
                            sum[c] += Ls[c];
                        }
                    }
                    total += ka * ka;
                }
                camera_samples += (uint64_t)total;
                float *px = out->pixels + 3 * ((size_t)y * (size_t)W + (size_t)x);
                for (int c = 0; c < 3; c++) {
                    double val = sum[c] / total;
                    px[c] = isfinite(val) && val > 0.0 ? (float)val : 0.0f;
                }
            }
            visits += cnt.visits;
            lookups += cnt.lookups;
            int d;
#pragma omp atomic capture
            d = ++rows_done;
            ref_report_progress(&ctx, (double)d / H, NULL, 0);
        }
        free(L);
        free(info);
        if (!ok) {
#pragma omp atomic write
            alloc_failed = 1;
        }
    }
    omp_set_num_threads(saved_threads);
    if (alloc_failed) {
        ref_ctx_free(&ctx);
        sss_image_free(out);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "reference: out of memory (pixel samples)");
    }
    ref_report_progress(&ctx, 1.0, NULL, 1);
    ctx.stats.seconds_pixels = sss_time_seconds() - t_pixels;
    ctx.stats.camera_samples = camera_samples;
    ctx.stats.adaptive_pixels = adaptive;
    ctx.stats.lookups = lookups;
    ctx.stats.nodes_per_lookup = lookups ? (double)visits / (double)lookups : 0.0;
    ctx.stats.nonfinite_samples = nonfinite;
    ctx.stats.seconds_total = sss_time_seconds() - t_start;
    if (stats) *stats = ctx.stats;
    ref_ctx_free(&ctx);
    if (sss_image_count_nonfinite(out) != 0) {
        sss_image_free(out);
        return sss_error_set(err, SSS_ERROR_NUMERIC, "reference: the image has non-finite values");
    }
    return SSS_OK;
}

sss_result sss_reference_render_world(const sss_reference_world *world, const sss_reference_desc *desc,
                                      sss_image *out, sss_reference_progress_fn progress, void *user,
                                      sss_reference_stats *stats, sss_error *err)
{
    return ref_render_world(world, desc, NULL, out, progress, user, stats, err);
}
