/* reference/ref_bounce.c — interreflection (sss/reference.h, "Bounces"): the light that leaves the
 * surfaces after bounce k - 1 gathered at every surface sample as bounce k.
 *
 * The image is linear in T at the samples (and in E for diffuse objects), so the bounces only need
 * T_k at the samples: they iterate there, the subsurface trees are rebuilt once with T_1 + ... + T_N,
 * and the (expensive) pixel pass runs once. The gather rays depend on the geometry only, so they are
 * traced once: each becomes a link (hit sample, weight) and a bounce is a sparse product
 * T_k(x_i) = sum over its links of weight * M_{k-1}(hit) (radiosity's form factors, sampled); the
 * exitance M_{k-1} is evaluated only at the samples some link reaches. */
#include <omp.h>
#include <stdatomic.h>
#include <stdlib.h>

#include "reference/ref_internal.h"

#define TRANSPORT_BUDGET (1ull << 18)
/* The tolerance of the trees that evaluate M_{k-1} at the samples, relative to the lit level: the
 * gathers average many of those values, so the pixels' 1e-6 would be wasted here. */
#define BOUNCE_TREE_ABS 1e-3
#define BOUNCE_TREE_ANGLE 1.0f
#define NO_LINK UINT32_MAX
#define LINKS_PER_RAY 2 /* the first hit and one point of its mirror chain */

static double luminance(const float v[3]) { return 0.2126 * v[0] + 0.7152 * v[1] + 0.0722 * v[2]; }

double ref_object_diagonal(const ref_object *ro)
{
    double d[3] = {ro->bounds_max[0] - ro->bounds_min[0], ro->bounds_max[1] - ro->bounds_min[1],
                   ro->bounds_max[2] - ro->bounds_min[2]};
    double l = v3_len(d);
    return isfinite(l) ? l : 0.0;
}

/* The objects the pixel density rule leaves without samples: diffuse ones, and subsurface ones
 * without a footprint; they get samples at their transport spacing. */
static int needs_transport_spacing(const ref_object *ro)
{
    return !ro->subsurface || !(ro->footprint > 0.0);
}

void ref_transport_spacing(ref_ctx *ctx)
{
    double f = ctx->desc.quality == SSS_REFERENCE_DRAFT ? 4.0 : 2.0;
    double g = 1.0, prev_total = INFINITY;
    for (int it = 0; it < 200; it++) {
        double total = 0.0;
        for (size_t o = 0; o < ctx->object_count; o++) {
            ref_object *ro = &ctx->objects[o];
            /* Subsurface: clusters of diameter R0 = 4 h (wider ones would take their own area whole at
             * S_r(R0) in the exitance, too much where S_r falls inside them). Diffuse: f footprints,
             * at most what REF_TRANSPORT_DIVISIONS gives a subsurface object of the same size. */
            double base = ro->subsurface && ro->spacing > 0.0 ? 4.0 * ro->spacing
                          : ro->footprint > 0.0 ? fmin(f * ro->footprint, 4.0 * ref_transport_cap(ctx, ro))
                                                : ref_object_diagonal(ro) / 64.0;
            ro->tspacing = base > 0.0 ? base * g : 0.0;
            if (needs_transport_spacing(ro)) ro->spacing = ro->tspacing;
            ro->tspacing = fmax(ro->tspacing, ro->spacing);
            if (ro->tspacing > 0.0) total += (double)ref_points_count(ro->src->mesh, ro->tspacing);
        }
        if (total <= (double)TRANSPORT_BUDGET || total >= prev_total * 0.999) break;
        prev_total = total;
        g *= 1.2;
    }
}

double ref_transport_cap(const ref_ctx *ctx, const ref_object *ro)
{
    double q = ctx->desc.quality == SSS_REFERENCE_DRAFT ? 1.0 : 0.5;
    return ctx->transport ? q * ref_object_diagonal(ro) / REF_TRANSPORT_DIVISIONS : INFINITY;
}

/* The sample of object o whose sub-triangle holds the point (u, v) of triangle prim (the cells of
 * ref_points.c: row i holds 2 (m - i) - 1 of them, up and down cells alternating); -1 if none. */
static int64_t sample_index(const ref_object *o, unsigned prim, double u, double v)
{
    if (!o->tri_offset || prim >= o->src->mesh->triangle_count) return -1;
    uint64_t b = o->tri_offset[prim], e = o->tri_offset[prim + 1];
    if (e == b) return -1;
    int64_t m = (int64_t)sqrt((double)(e - b) + 0.5);
    double x = u * (double)m, y = v * (double)m;
    int64_t i = (int64_t)floor(x), j = (int64_t)floor(y);
    if (i < 0) i = 0;
    if (i > m - 1) i = m - 1;
    if (j < 0) j = 0;
    if (j > m - 1 - i) j = m - 1 - i;
    int down = (x - (double)i) + (y - (double)j) > 1.0 && i + j + 2 <= m;
    return (int64_t)b + 2 * m * i - i * i + 2 * j + down;
}

/* Clusters of an object's samples (ids[0, n), reordered in place): split at the median of the box's
 * longest axis until a cluster fits in a sphere of diameter `size`, or, where the normals of its
 * samples disagree (thin parts: both sides), of the normals' widest component, so that a cluster
 * stays on one side. Writes the cluster index of every sample to cluster_of; returns the count. */
typedef struct cluster_job {
    uint32_t begin, end;
} cluster_job;

static int normal_axis(const ref_bsample *bs, const uint32_t *ids, uint32_t n, float *spread)
{
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (uint32_t i = 0; i < n; i++)
        for (int c = 0; c < 3; c++) lo[c] = fminf(lo[c], bs[ids[i]].ng[c]), hi[c] = fmaxf(hi[c], bs[ids[i]].ng[c]);
    int axis = 0;
    for (int c = 1; c < 3; c++)
        if (hi[c] - lo[c] > hi[axis] - lo[axis]) axis = c;
    *spread = hi[axis] - lo[axis];
    return axis;
}

/* Sample ids ordered by one coordinate of their position or (normal) geometric normal. */
typedef struct cluster_order {
    const ref_bsample *bs;
    int axis, normal;
} cluster_order;

static float cluster_key(const void *ids, size_t i, const void *order)
{
    const cluster_order *o = order;
    const ref_bsample *s = &o->bs[((const uint32_t *)ids)[i]];
    return o->normal ? s->ng[o->axis] : s->p[o->axis];
}

static void swap_ids(void *ids, size_t i, size_t j)
{
    uint32_t *d = ids, t = d[i];
    d[i] = d[j];
    d[j] = t;
}

static uint32_t make_clusters(const ref_bsample *bs, uint32_t *ids, uint32_t n, double size, uint32_t *cluster_of,
                              cluster_job *stack)
{
    uint32_t count = 0;
    size_t top = 0;
    stack[top++] = (cluster_job){0, n};
    while (top > 0) {
        cluster_job j = stack[--top];
        uint32_t m = j.end - j.begin;
        float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
        for (uint32_t i = j.begin; i < j.end; i++)
            for (int c = 0; c < 3; c++) lo[c] = fminf(lo[c], bs[ids[i]].p[c]), hi[c] = fmaxf(hi[c], bs[ids[i]].p[c]);
        int axis = 0;
        for (int c = 1; c < 3; c++)
            if (hi[c] - lo[c] > hi[axis] - lo[axis]) axis = c;
        double d2 = 0.0;
        for (int c = 0; c < 3; c++) d2 += (double)(hi[c] - lo[c]) * (hi[c] - lo[c]);
        float spread;
        int naxis = normal_axis(bs, ids + j.begin, m, &spread);
        int by_normal = spread > 0.5f; /* normals more than ~30 degrees apart */
        if (m <= 1 || (d2 <= size * size && !by_normal)) {
            for (uint32_t i = j.begin; i < j.end; i++) cluster_of[ids[i]] = count;
            count++;
            continue;
        }
        uint32_t mid = j.begin + m / 2;
        cluster_order order = {bs, by_normal ? naxis : axis, by_normal};
        ref_select_kth(ids + j.begin, m, mid - j.begin, &order, cluster_key, swap_ids);
        stack[top++] = (cluster_job){mid, j.end};
        stack[top++] = (cluster_job){j.begin, mid};
    }
    return count;
}

sss_result ref_transport_cluster(ref_ctx *ctx, size_t o, sss_error *err)
{
    ref_object *ro = &ctx->objects[o];
    if (!ro->bs || !(ro->tspacing > ro->spacing) || ro->bs_count >= UINT32_MAX) return SSS_OK;
    uint32_t n = (uint32_t)ro->bs_count;
    uint32_t *ids = malloc(sizeof(uint32_t) * n), *cluster_of = malloc(sizeof(uint32_t) * n);
    cluster_job *stack = malloc(sizeof(cluster_job) * 2 * 66);
    if (!ids || !cluster_of || !stack) {
        free(ids), free(cluster_of), free(stack);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "reference: out of memory (transport clusters)");
    }
    for (uint32_t i = 0; i < n; i++) ids[i] = i;
    uint32_t count = make_clusters(ro->bs, ids, n, ro->tspacing, cluster_of, stack);
    free(stack);
    ref_bsample *cs = calloc(count ? count : 1, sizeof *cs);
    double *acc = calloc(4 * (size_t)(count ? count : 1), sizeof(double)); /* area, T A per channel */
    if (!cs || !acc) {
        free(ids), free(cluster_of), free(cs), free(acc);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "reference: out of memory (transport clusters)");
    }
    for (uint32_t i = 0; i < n; i++) {
        const ref_bsample *f = &ro->bs[i];
        double *a = acc + 4 * (size_t)cluster_of[i];
        a[0] += f->area;
        for (int c = 0; c < 3; c++) a[1 + c] += (double)f->area * f->direct[c];
    }
    /* Each cluster sits at its first sample in generation order (on the surface, with its normal): the
     * gathers start there and the exitance is evaluated there. */
    for (uint32_t i = n; i-- > 0;) {
        ref_bsample *c = &cs[cluster_of[i]];
        memcpy(c->p, ro->bs[i].p, sizeof c->p);
        memcpy(c->ng, ro->bs[i].ng, sizeof c->ng);
    }
    for (uint32_t k = 0; k < count; k++) {
        const double *a = acc + 4 * (size_t)k;
        cs[k].area = (float)a[0];
        for (int c = 0; c < 3; c++) cs[k].direct[c] = cs[k].t[c] = a[0] > 0.0 ? (float)(a[1 + c] / a[0]) : 0.0f;
    }
    free(acc);
    free(ids);
    free(ro->bs);
    ro->bs = cs;
    ro->bs_count = count;
    ro->cluster_of = cluster_of;
    (void)ctx;
    return SSS_OK;
}

/* The transport sample holding the point (u, v) of triangle prim of object o, or -1. */
static int64_t transport_index(const ref_object *o, unsigned prim, double u, double v)
{
    int64_t k = sample_index(o, prim, u, v);
    return k >= 0 && o->cluster_of ? (int64_t)o->cluster_of[k] : k;
}

double ref_indirect_share(const ref_ctx *ctx, size_t o, unsigned prim, double u, double v, const double direct[3])
{
    const ref_object *ro = &ctx->objects[o];
    int64_t k = ro->indirect ? transport_index(ro, prim, u, v) : -1;
    if (k < 0) return 1.0;
    const float *ti = ro->indirect[k], *td = ro->bs[k].direct;
    double ind = 0.2126 * ti[0] + 0.7152 * ti[1] + 0.0722 * ti[2];
    double dir = direct ? 0.2126 * direct[0] + 0.7152 * direct[1] + 0.0722 * direct[2]
                        : 0.2126 * td[0] + 0.7152 * td[1] + 0.0722 * td[2];
    return dir > 0.0 ? ind / (ind + dir) : 1.0;
}

/* What one ray sees at its first hit: the link (the sample there, and the factor from that sample's
 * exitance M (subsurface: the lobe F_t(cos theta) / (pi c)) or irradiance E (diffuse, its normal's
 * side: 1 / pi; the reflectance is applied per channel in the bounces) to the radiance towards the
 * ray's origin; target NO_LINK on a miss, a light, or the back of a diffuse triangle), and on a
 * subsurface object what its smooth interface reflects: F_r and the mirrored ray. */
typedef struct ray_hit {
    uint32_t target;
    double factor, fresnel;
    double org[3], dir[3]; /* the reflected ray (fresnel > 0) */
} ray_hit;

static void trace_link(const ref_ctx *ctx, const double org[3], const double dir[3], ray_hit *h)
{
    struct RTCRayHit rh;
    h->target = NO_LINK, h->factor = h->fresnel = 0.0;
    if (!ref_intersect(ctx, org, dir, &rh) || rh.hit.geomID >= ctx->light_geom_base) return;
    const ref_object *ro = &ctx->objects[rh.hit.geomID];
    int64_t k = transport_index(ro, rh.hit.primID, rh.hit.u, rh.hit.v);
    if (k < 0) return;
    const float *n = ro->bs[k].ng;
    double cos_out = -(dir[0] * n[0] + dir[1] * n[1] + dir[2] * n[2]);
    if (ro->subsurface) {
        h->fresnel = sss_fresnel_dielectric(fabs(cos_out), 1.0, ro->eta);
        h->factor = (1.0 - h->fresnel) / (REF_PI * ro->c_norm);
        /* mirrored about the hit triangle's plane, leaving on the side the ray came from */
        double ng[3] = {rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z}, hp[3];
        v3_normalize(ng);
        double d_n = dir[0] * ng[0] + dir[1] * ng[1] + dir[2] * ng[2];
        if (d_n > 0.0)
            for (int c = 0; c < 3; c++) ng[c] = -ng[c];
        d_n = -fabs(d_n);
        for (int c = 0; c < 3; c++) {
            hp[c] = org[c] + (double)rh.ray.tfar * dir[c];
            h->dir[c] = dir[c] - 2.0 * d_n * ng[c];
        }
        ref_offset(ctx, hp, ng, h->org);
    } else if (cos_out > 0.0) {
        h->factor = 1.0 / REF_PI;
    } else {
        return;
    }
    h->target = (uint32_t)(ro->base + (uint64_t)k);
}

/* The second link of a gather ray whose first hit is subsurface: the light its smooth interface
 * reflects towards the ray's origin (PBRT's path tracer follows it; without it a closed subsurface
 * enclosure loses 1 - 2/c int F_t^2 mu dmu = 5.5% per bounce at eta 1.33, test_ref_bounce.c). One
 * point of the mirror chain behind the hit stands for all of it: at each further subsurface hit
 * the chain stops with probability 1 - F_r and goes on with F_r, so the weight F_r(first) times the
 * stop point's factor / (1 - F_r) is unbiased (it reduces to F_r(first) / (pi c)). Returns NO_LINK
 * when the chain leaves the scene. */
#define CHAIN_MAX 8

static uint32_t trace_mirror_chain(const ref_ctx *ctx, const ray_hit *first, ref_rng *rng, double *weight)
{
    ray_hit cur = *first, next;
    *weight = 0.0;
    for (int i = 0; i < CHAIN_MAX; i++) {
        trace_link(ctx, cur.org, cur.dir, &next);
        if (next.target == NO_LINK) return NO_LINK;
        int last = i == CHAIN_MAX - 1 || !(next.fresnel > 0.0);
        if (last || ref_rng_uniform(rng) >= next.fresnel) {
            *weight = first->fresnel * next.factor / (last ? 1.0 : 1.0 - next.fresnel);
            return next.target;
        }
        cur = next;
    }
    return NO_LINK;
}

/* An orthonormal frame (t1, t2) about the unit normal n. */
static void tangent_frame(const double n[3], double t1[3], double t2[3])
{
    double a[3] = {1, 0, 0};
    if (fabs(n[0]) > 0.7) a[0] = 0, a[1] = 1;
    v3_cross(n, a, t1);
    v3_normalize(t1);
    v3_cross(n, t1, t2);
}

/* The cosine-distributed direction of (u1, u2) in [0, 1)^2 about n; returns its cosine. */
static double cosine_dir(const double n[3], const double t1[3], const double t2[3], double u1, double u2,
                         double dir[3])
{
    double r = sqrt(u1), ph = 2.0 * REF_PI * u2, cz = sqrt(fmax(0.0, 1.0 - u1));
    for (int c = 0; c < 3; c++) dir[c] = r * cos(ph) * t1[c] + r * sin(ph) * t2[c] + cz * n[c];
    v3_normalize(dir);
    return cz;
}

/* One gather ray from po along dir: its LINKS_PER_RAY links (the first hit, and one point of the mirror
 * chain when the hit is subsurface) with their factors. */
static void gather_ray(const ref_ctx *ctx, const double po[3], const double dir[3], ref_rng *chain_rng,
                       uint32_t target[LINKS_PER_RAY], double factor[LINKS_PER_RAY])
{
    ray_hit h;
    trace_link(ctx, po, dir, &h);
    target[0] = h.target;
    factor[0] = h.factor;
    factor[1] = 0.0;
    target[1] = h.target != NO_LINK && h.fresnel > 0.0 ? trace_mirror_chain(ctx, &h, chain_rng, &factor[1]) : NO_LINK;
}

/* The links of sample i of object o: k x k gather rays cosine-distributed about its geometric
 * normal (stratified), each weighted by pi / k^2 (the cosine-weighted estimate of int L cos dw) and,
 * for subsurface samples, by the entry factor 1 - F_r(cos theta); LINKS_PER_RAY per ray: the first
 * hit and its mirror chain. */
static void sample_links(const ref_ctx *ctx, size_t o, size_t i)
{
    const ref_object *ro = &ctx->objects[o];
    const ref_bsample *s = &ro->bs[i];
    int k = (int)lround(sqrt((double)ro->gather));
    ref_rng rng, chain_rng;
    ref_rng_seed(&rng, ctx->desc.seed, 0x424f554e00000000ull + (uint64_t)o, (uint64_t)i);
    ref_rng_seed(&chain_rng, ctx->desc.seed, 0x4d49525200000000ull + (uint64_t)o, (uint64_t)i);
    double ng[3] = {s->ng[0], s->ng[1], s->ng[2]}, p[3] = {s->p[0], s->p[1], s->p[2]};
    double t1[3], t2[3], po[3];
    tangent_frame(ng, t1, t2);
    ref_offset(ctx, p, ng, po);
    uint32_t *target = ro->link_target + i * (size_t)ro->gather * LINKS_PER_RAY;
    float *weight = ro->link_weight + i * (size_t)ro->gather * LINKS_PER_RAY;
    for (int a1 = 0; a1 < k; a1++)
        for (int a2 = 0; a2 < k; a2++) {
            double u1 = (a1 + ref_rng_uniform(&rng)) / k, u2 = (a2 + ref_rng_uniform(&rng)) / k, dir[3];
            double cz = cosine_dir(ng, t1, t2, u1, u2, dir), factor[LINKS_PER_RAY];
            size_t l = ((size_t)a1 * (size_t)k + (size_t)a2) * LINKS_PER_RAY;
            gather_ray(ctx, po, dir, &chain_rng, target + l, factor);
            double entry = ro->subsurface ? 1.0 - sss_fresnel_dielectric(cz, 1.0, ro->eta) : 1.0;
            for (int j = 0; j < LINKS_PER_RAY; j++) weight[l + j] = (float)(REF_PI / (k * k) * entry * factor[j]);
        }
}

/* Which T (E) of the samples a tree or an exitance is made of. */
enum { T_BOUNCE, T_INDIRECT, T_BEFORE_LAST };

static double t_value(const ref_object *ro, size_t i, int which, int c)
{
    return which == T_BOUNCE ? ro->bs[i].t[c] : which == T_INDIRECT ? ro->indirect[i][c] : ro->bs[i].t_before[c];
}

/* Tree points in generation order with T A from the samples (`which`). Sets abs_tol to `rel` times the
 * lit level (ref_points.c). */
static sss_result fill_tree(ref_object *ro, int which, double rel, ref_tree *tree, float abs_tol[3], sss_error *err)
{
    memset(tree, 0, sizeof *tree);
    tree->points = malloc(sizeof(ref_point) * (ro->bs_count ? ro->bs_count : 1));
    if (!tree->points) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "reference: out of memory (bounce tree)");
    tree->point_count = ro->bs_count;
    double ta_sum[3] = {0, 0, 0}, lit[3] = {0, 0, 0};
    for (size_t i = 0; i < ro->bs_count; i++) {
        const ref_bsample *s = &ro->bs[i];
        ref_point *pt = &tree->points[i];
        memcpy(pt->p, s->p, sizeof pt->p);
        for (int c = 0; c < 3; c++) {
            double ta = t_value(ro, i, which, c) * s->area;
            pt->ta[c] = isfinite(ta) && ta > 0.0 ? (float)ta : 0.0f;
            if (pt->ta[c] > 0.0f) ta_sum[c] += pt->ta[c], lit[c] += s->area;
        }
    }
    for (int c = 0; c < 3; c++)
        abs_tol[c] = lit[c] > 0.0 ? (float)(rel * ta_sum[c] / lit[c] * ro->prof.total[c]) : 0.0f;
    return ref_tree_build(tree, err);
}

/* M at sample i of a subsurface object from a tree over its samples' T (which): the tree sum of S_far
 * plus the near part, int_0^R0 S_near 2 pi r dr times the area-weighted mean T of the samples within
 * R0 (the near part's own support: the same second-order quadrature as T at the sample alone, but
 * each sample's T is a gather of few rays, and a sample's own noise would pass into its exitance
 * whole; for short mean free paths the near part is most of M). */
static void exitance_at(const ref_object *ro, const ref_tree *tree, const float tol[3], int which, size_t i,
                        float out[3])
{
    double far[3] = {0, 0, 0}, ta[3] = {0, 0, 0}, a = 0.0;
    ref_tree_sum_angle(tree, &ro->prof, ro->bs[i].p, tol, BOUNCE_TREE_ANGLE, far, NULL);
    for (uint64_t k = ro->nb_offset[i]; k < ro->nb_offset[i + 1]; k++) {
        const ref_bsample *s = &ro->bs[ro->nb_index[k]];
        a += s->area;
        for (int c = 0; c < 3; c++) ta[c] += (double)s->area * t_value(ro, ro->nb_index[k], which, c);
    }
    for (int c = 0; c < 3; c++)
        out[c] = (float)(far[c] + ro->prof.near[c] * (a > 0.0 ? ta[c] / a : t_value(ro, i, which, c)));
}

/* What the samples' T (E) of the current bounce send out into exit, at the samples a link reaches
 * (needed; zero elsewhere): subsurface the exitance M, diffuse reflectance * E; exit_sum adds it up. */
static sss_result bounce_exit(ref_object *ro, const uint8_t *needed, sss_error *err)
{
    const int64_t n = (int64_t)ro->bs_count;
    ref_tree tree;
    float tol[3];
    memset(&tree, 0, sizeof tree);
    sss_result r = ro->subsurface ? fill_tree(ro, T_BOUNCE, BOUNCE_TREE_ABS, &tree, tol, err) : SSS_OK;
    if (r == SSS_OK) {
#pragma omp parallel for schedule(dynamic, 256)
        for (int64_t i = 0; i < n; i++) {
            ref_bsample *s = &ro->bs[i];
            if (!needed[i])
                s->exit[0] = s->exit[1] = s->exit[2] = 0.0f;
            else if (ro->subsurface)
                exitance_at(ro, &tree, tol, T_BOUNCE, (size_t)i, s->exit);
            else
                for (int c = 0; c < 3; c++) s->exit[c] = (float)(ro->src->reflectance[c] * s->t[c]);
            for (int c = 0; c < 3; c++) s->exit_sum[c] += s->exit[c];
        }
    }
    ref_tree_free(&tree);
    return r;
}

/* What the final gathers see leave the samples: M (E) of T_1 + ... + T_{N-1}, the sum of the bounces'
 * exit where a link reaches (needed). Diffuse: reflectance * E everywhere. Subsurface: elsewhere M is
 * computed (M is linear in T: from the tree over T_1 + ... + T_{N-1}) when a final gather first
 * reaches the sample, which is rare: the links reach what the surfaces see. */
static sss_result sent_prepare(ref_object *ro, const uint8_t *needed, sss_error *err)
{
    if (!ro->subsurface) {
        for (size_t i = 0; i < ro->bs_count; i++)
            for (int c = 0; c < 3; c++) ro->bs[i].exit_sum[c] = (float)(ro->src->reflectance[c] * ro->bs[i].t_before[c]);
        return SSS_OK;
    }
    ro->sent_state = calloc(ro->bs_count, sizeof *ro->sent_state);
    if (!ro->sent_state) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "reference: out of memory (bounces)");
    for (size_t i = 0; i < ro->bs_count; i++)
        if (needed[i]) atomic_init(&ro->sent_state[i], 2);
    return fill_tree(ro, T_BEFORE_LAST, BOUNCE_TREE_ABS, &ro->stree, ro->stol, err);
}

/* The sample with global index g. */
static const ref_bsample *global_sample(const ref_ctx *ctx, uint32_t g, size_t *object)
{
    size_t lo = 0, hi = ctx->object_count - 1;
    while (lo < hi) { /* the last object whose base <= g (objects without samples share bases) */
        size_t mid = (lo + hi + 1) / 2;
        if (ctx->objects[mid].base <= g)
            lo = mid;
        else
            hi = mid - 1;
    }
    while (ctx->objects[lo].bs_count == 0 || g - ctx->objects[lo].base >= ctx->objects[lo].bs_count) lo--;
    if (object) *object = lo;
    return &ctx->objects[lo].bs[g - ctx->objects[lo].base];
}

/* exit_sum of the sample with global index g: cached, or computed now (into tmp) and published for
 * the other threads (the value depends only on the sample, so the race only duplicates work). */
static const float *sent_exitance(const ref_ctx *ctx, uint32_t g, float tmp[3])
{
    size_t o;
    const ref_bsample *s = global_sample(ctx, g, &o);
    ref_object *ro = &ctx->objects[o];
    if (!ro->sent_state) return s->exit_sum;
    size_t i = (size_t)(s - ro->bs);
    if (atomic_load_explicit(&ro->sent_state[i], memory_order_acquire) == 2) return s->exit_sum;
    exitance_at(ro, &ro->stree, ro->stol, T_BEFORE_LAST, i, tmp);
    unsigned char idle = 0;
    if (atomic_compare_exchange_strong(&ro->sent_state[i], &idle, 1)) {
        memcpy(ro->bs[i].exit_sum, tmp, sizeof ro->bs[i].exit_sum);
        atomic_store_explicit(&ro->sent_state[i], 2, memory_order_release);
    }
    return tmp;
}

/* T_k (E_k) at every sample of object o into next, through its links; returns its light sum
 * T A (luminance). */
static double bounce_gather(const ref_ctx *ctx, size_t o, float (*next)[3])
{
    const ref_object *ro = &ctx->objects[o];
    const int64_t n = (int64_t)ro->bs_count;
#pragma omp parallel for schedule(dynamic, 256)
    for (int64_t i = 0; i < n; i++) {
        double T[3] = {0, 0, 0};
        const size_t links = (size_t)ro->gather * LINKS_PER_RAY;
        const uint32_t *target = ro->link_target + (size_t)i * links;
        const float *weight = ro->link_weight + (size_t)i * links;
        for (size_t l = 0; l < links; l++) {
            if (target[l] == NO_LINK) continue;
            const float *e = global_sample(ctx, target[l], NULL)->exit;
            for (int c = 0; c < 3; c++) T[c] += (double)weight[l] * e[c];
        }
        for (int c = 0; c < 3; c++) next[i][c] = isfinite(T[c]) && T[c] > 0.0 ? (float)T[c] : 0.0f;
    }
    double sum = 0.0; /* sequentially: independent of the thread count */
    for (int64_t i = 0; i < n; i++) sum += luminance(next[i]) * ro->bs[i].area;
    return sum;
}

/* Traces every sample's gather rays once and marks the samples they reach (needed). */
static sss_result build_links(ref_ctx *ctx, uint8_t **needed, sss_error *err)
{
    uint64_t total = 0;
    for (size_t o = 0; o < ctx->object_count; o++) {
        ref_object *ro = &ctx->objects[o];
        ro->base = total;
        total += ro->bs_count;
        ro->gather = ro->subsurface ? ctx->gather_subsurface : ctx->gather_diffuse;
    }
    if (total >= NO_LINK) return sss_error_set(err, SSS_ERROR_LIMIT, "reference: too many samples for the bounces");
    *needed = calloc(total + 1, 1);
    if (!*needed) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "reference: out of memory (bounces)");
    for (size_t o = 0; o < ctx->object_count; o++) {
        ref_object *ro = &ctx->objects[o];
        if (!ro->bs_count) continue;
        size_t links = ro->bs_count * (size_t)ro->gather * LINKS_PER_RAY;
        ro->indirect = calloc(ro->bs_count, sizeof *ro->indirect);
        ro->link_target = malloc(sizeof(uint32_t) * links);
        ro->link_weight = malloc(sizeof(float) * links);
        if (!ro->indirect || !ro->link_target || !ro->link_weight)
            return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "reference: out of memory (%zu bounce links)", links);
        sss_result r = ro->subsurface ? ref_neighbours_build(ro, ro->prof.r0, err) : SSS_OK;
        if (r != SSS_OK) return r;
        const int64_t n = (int64_t)ro->bs_count;
#pragma omp parallel for schedule(dynamic, 64)
        for (int64_t i = 0; i < n; i++) sample_links(ctx, o, (size_t)i);
        for (size_t l = 0; l < links; l++)
            if (ro->link_target[l] != NO_LINK) (*needed)[ro->link_target[l]] = 1;
    }
    return SSS_OK;
}

/* The indirect trees the pixels use: T_2 + ... + T_N at the transport samples. */
/* The pixels' far sums add the transport samples' T_2 + ... + T_N: the links' gather of exit_sum, 16
 * rays a sample. Through a wide profile its noise showed as blotches of the profile's size where a
 * floor lights the object (the Marble bunny of default.json); a final gather of gather_refine more
 * rays per sample joins it, weighted by ray count (the same estimate: T_k is the links' sum of
 * exit_{k-1}, so T_2 + ... + T_N theirs of exit_sum). */
static void refine_indirect(const ref_ctx *ctx, ref_object *ro, size_t o)
{
    const int64_t n = (int64_t)ro->bs_count;
#pragma omp parallel for schedule(dynamic, 64)
    for (int64_t i = 0; i < n; i++) {
        const ref_bsample *s = &ro->bs[i];
        ref_rng rng;
        ref_rng_seed(&rng, ctx->desc.seed, 0x46494e4c00000000ull + (uint64_t)o, (uint64_t)i);
        double p[3] = {s->p[0], s->p[1], s->p[2]}, ng[3] = {s->ng[0], s->ng[1], s->ng[2]}, t[3];
        int rays = ref_final_gather(ctx, p, ng, ng, ro->eta, ctx->gather_refine, 0, 1, &rng, t);
        for (int c = 0; c < 3; c++)
            ro->indirect[i][c] = (float)((ro->indirect[i][c] * (double)ro->gather + t[c] * rays) / (ro->gather + rays));
    }
}

static sss_result build_indirect_trees(ref_ctx *ctx, sss_error *err)
{
    for (size_t o = 0; o < ctx->object_count; o++) {
        ref_object *ro = &ctx->objects[o];
        if (!ro->subsurface || !ro->bs_count) continue;
        if (ctx->gather_refine > 0) refine_indirect(ctx, ro, o);
        sss_result r = fill_tree(ro, T_INDIRECT, BOUNCE_TREE_ABS, &ro->itree, ro->iabs_tol, err);
        if (r != SSS_OK) return r;
    }
    return SSS_OK;
}

void ref_indirect_sum(const ref_ctx *ctx, size_t o, const float xo[3], double out[3], uint64_t *visits)
{
    const ref_object *ro = &ctx->objects[o];
    out[0] = out[1] = out[2] = 0.0;
    if (ro->itree.point_count)
        ref_tree_sum_angle(&ro->itree, &ro->prof, xo, ro->iabs_tol, BOUNCE_TREE_ANGLE, out, visits);
}

int ref_final_gather(const ref_ctx *ctx, const double p[3], const double ng[3], const double ns[3], double eta,
                     int pixel_rays, int stratum, int strata, ref_rng *rng, double out[3])
{
    int m = strata > 1 ? (int)lround(sqrt((double)strata)) : 1;
    if (m < 1) m = 1;
    int k = ((int)ceil(sqrt((double)(pixel_rays > 1 ? pixel_rays : 1))) + m - 1) / m; /* (k m)^2 >= pixel_rays */
    int si = stratum % m, sj = (stratum / m) % m;
    double t1[3], t2[3], po[3], acc[3] = {0, 0, 0};
    tangent_frame(ns, t1, t2);
    ref_offset(ctx, p, ng, po);
    for (int a1 = 0; a1 < k; a1++)
        for (int a2 = 0; a2 < k; a2++) {
            double u1 = (a1 + (si + ref_rng_uniform(rng)) / m) / k, u2 = (a2 + (sj + ref_rng_uniform(rng)) / m) / k;
            double dir[3], factor[LINKS_PER_RAY], cz = cosine_dir(ns, t1, t2, u1, u2, dir);
            uint32_t target[LINKS_PER_RAY];
            if (!(v3_dot(dir, ng) > 0.0)) continue; /* below the surface itself: no light (as PBRT-v3's BSDFs) */
            gather_ray(ctx, po, dir, rng, target, factor);
            double w = REF_PI / (k * k) * (eta > 0.0 ? 1.0 - sss_fresnel_dielectric(cz, 1.0, eta) : 1.0);
            for (int j = 0; j < LINKS_PER_RAY; j++) {
                if (target[j] == NO_LINK) continue;
                float tmp[3];
                const float *e = sent_exitance(ctx, target[j], tmp);
                for (int c = 0; c < 3; c++) acc[c] += w * factor[j] * e[c];
            }
        }
    for (int c = 0; c < 3; c++) out[c] = isfinite(acc[c]) && acc[c] > 0.0 ? acc[c] : 0.0;
    return k * k;
}

/* Light of bounce k relative to bounce 2, the first interreflected one (or to STOP x bounce 1 when
 * that is more), the largest over the objects a pixel centre sees. Not relative to bounce 1: on a
 * back-lit object bounce 1 is mostly on the lit side, which radiates into the void, while the side
 * the camera sees is lit by bounces 2.. (stopping at 1% of bounce 1 left 4% of the back-lit eval
 * dragon's light out). */
static double bounce_fraction(const ref_ctx *ctx, const double *first, const double *second, const double *now)
{
    double f = 0.0;
    for (size_t o = 0; o < ctx->object_count; o++) {
        double ref = fmax(second[o], SSS_REFERENCE_BOUNCE_STOP * first[o]);
        if (ctx->objects[o].visible && ref > 0.0) f = fmax(f, now[o] / ref);
    }
    return f;
}

sss_result ref_bounces_run(ref_ctx *ctx, sss_error *err)
{
    ref_set_phase(ctx, 0.3, 0.3, "bounces");
    double t0 = sss_time_seconds();
    uint8_t *needed = NULL;
    size_t n_obj = ctx->object_count;
    float(**next)[3] = calloc(n_obj + 1, sizeof *next);
    double *light = calloc(3 * (n_obj + 1), sizeof(double)); /* per object: bounce 1, 2, now */
    sss_result r = next && light ? build_links(ctx, &needed, err)
                                 : sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "reference: out of memory (bounces)");
    double *first = light, *second = light + n_obj + 1, *now = light + 2 * (n_obj + 1);
    for (size_t o = 0; r == SSS_OK && o < n_obj; o++) {
        const ref_object *ro = &ctx->objects[o];
        ctx->stats.transport_samples += ro->bs_count;
        for (size_t i = 0; i < ro->bs_count; i++) first[o] += luminance(ro->bs[i].t) * ro->bs[i].area;
        if (ro->bs_count && !(next[o] = calloc(ro->bs_count, sizeof *next[o])))
            r = sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "reference: out of memory (bounces)");
    }
    double links_seconds = sss_time_seconds() - t0;
    int cap = ctx->desc.bounces > 0 ? ctx->desc.bounces : SSS_REFERENCE_MAX_BOUNCES;
    for (int k = 2; r == SSS_OK && k <= cap; k++) {
        double t1 = sss_time_seconds();
        for (size_t o = 0; r == SSS_OK && o < n_obj; o++)
            if (ctx->objects[o].bs_count)
                r = bounce_exit(&ctx->objects[o], needed + ctx->objects[o].base, err);
        if (r != SSS_OK) break;
        for (size_t o = 0; o < n_obj; o++) now[o] = ctx->objects[o].bs_count ? bounce_gather(ctx, o, next[o]) : 0.0;
        for (size_t o = 0; o < n_obj; o++) {
            ref_object *ro = &ctx->objects[o];
            for (size_t i = 0; i < ro->bs_count; i++)
                for (int c = 0; c < 3; c++) {
                    ro->bs[i].t_before[c] += ro->bs[i].t[c];
                    ro->bs[i].t[c] = next[o][i][c];
                    ro->indirect[i][c] += next[o][i][c];
                }
            if (k == 2) second[o] = now[o];
        }
        double fraction = bounce_fraction(ctx, first, second, now);
        ctx->stats.bounces = (uint32_t)k;
        /* the links' ray tracing counts towards bounce 2 */
        ctx->stats.seconds_bounce[k - 1] = sss_time_seconds() - t1 + (k == 2 ? links_seconds : 0.0);
        ctx->stats.bounce_fraction[k - 1] = fraction;
        ref_report_progress(ctx, 1.0, NULL, 1);
        if (ctx->desc.bounces == 0 && !(fraction >= SSS_REFERENCE_BOUNCE_STOP)) break;
    }
    for (size_t o = 0; next && o < n_obj; o++) free(next[o]);
    double t2 = sss_time_seconds(); /* the trees the pixels use count towards the last bounce */
    for (size_t o = 0; r == SSS_OK && o < n_obj; o++)
        if (ctx->objects[o].bs_count) r = sent_prepare(&ctx->objects[o], needed + ctx->objects[o].base, err);
    free(next);
    free(light);
    free(needed);
    if (r == SSS_OK) r = build_indirect_trees(ctx, err);
    ctx->stats.seconds_bounce[ctx->stats.bounces - 1] += sss_time_seconds() - t2;
    return r;
}
