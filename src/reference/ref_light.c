/* reference/ref_light.c — the lights of docs/scene-format.md: preprocessing, irradiance with shadow rays (the
 * T(x) of docs/physics.md §1 when a Fresnel index is given), and the radiance that camera rays see. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "reference/ref_internal.h"

void sss_reference_env_direction(double u, double v, double rotate_y_degrees, double dir[3])
{
    double phi = 2.0 * REF_PI * (u - 0.5) - rotate_y_degrees * (REF_PI / 180.0);
    double theta = REF_PI * v;
    double st = sin(theta);
    dir[0] = st * sin(phi);
    dir[1] = cos(theta);
    dir[2] = -st * cos(phi);
}

void sss_reference_env_uv(const double dir[3], double rotate_y_degrees, double *u, double *v)
{
    double len = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    double y = len > 0.0 ? dir[1] / len : 1.0;
    y = y < -1.0 ? -1.0 : (y > 1.0 ? 1.0 : y);
    double phi = atan2(dir[0], -dir[2]) + rotate_y_degrees * (REF_PI / 180.0);
    double uu = phi / (2.0 * REF_PI) + 0.5;
    uu -= floor(uu);
    if (!(uu < 1.0)) uu = 0.0;
    *u = uu;
    *v = acos(y) / REF_PI;
}

double sss_reference_spot_falloff(double cone_angle_degrees, double cone_delta_degrees, double cos_theta)
{
    double cos_total = cos(cone_angle_degrees * (REF_PI / 180.0));
    double cos_start = cos((cone_angle_degrees - cone_delta_degrees) * (REF_PI / 180.0));
    if (cos_theta < cos_total) return 0.0;
    if (cos_theta >= cos_start) return 1.0;
    double delta = (cos_theta - cos_total) / (cos_start - cos_total);
    return (delta * delta) * (delta * delta);
}

static int finite3(const double v[3]) { return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]); }
static int nonneg3(const double v[3]) { return finite3(v) && v[0] >= 0.0 && v[1] >= 0.0 && v[2] >= 0.0; }

static int is_delta_light(const sss_light *s)
{
    return s->type == SSS_LIGHT_POINT || s->type == SSS_LIGHT_SPOT || s->type == SSS_LIGHT_DIRECTIONAL;
}

static double luminance(const float *p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

/* Piecewise-constant 2D distribution over the map's pixels, weights luminance x sin(theta) (the
 * solid angle of a pixel), as PBRT's InfiniteAreaLight. */
static sss_result env_build(ref_env *e, size_t index, sss_error *err)
{
    int w = e->map->width, h = e->map->height;
    if (w < 1 || h < 1 || !e->map->pixels)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "lights[%zu]: empty environment map", index);
    e->width = w, e->height = h;
    e->marginal_cdf = malloc(sizeof(double) * (size_t)(h + 1));
    e->conditional_cdf = malloc(sizeof(double) * (size_t)h * (size_t)(w + 1));
    e->row_weight = malloc(sizeof(double) * (size_t)h);
    if (!e->marginal_cdf || !e->conditional_cdf || !e->row_weight)
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "lights[%zu]: out of memory (environment map)", index);
    double sl = 0.2126 * e->scale[0] + 0.7152 * e->scale[1] + 0.0722 * e->scale[2];
    e->marginal_cdf[0] = 0.0;
    for (int y = 0; y < h; y++) {
        double st = sin(REF_PI * (y + 0.5) / h);
        double *cdf = e->conditional_cdf + (size_t)y * (size_t)(w + 1);
        cdf[0] = 0.0;
        for (int x = 0; x < w; x++) {
            const float *p = e->map->pixels + 3 * ((size_t)y * (size_t)w + (size_t)x);
            double l = fmax(luminance(p), 0.0) * sl * st;
            cdf[x + 1] = cdf[x] + l;
        }
        e->row_weight[y] = cdf[w];
        e->marginal_cdf[y + 1] = e->marginal_cdf[y] + cdf[w];
    }
    e->total = e->marginal_cdf[h];
    return SSS_OK;
}

/* Index i with cdf[i] <= x < cdf[i + 1] among n intervals (cdf non-decreasing, x < cdf[n]). */
static int find_interval(const double *cdf, int n, double x)
{
    int lo = 0, hi = n - 1;
    while (lo < hi) {
        int mid = (lo + hi + 1) / 2;
        if (cdf[mid] <= x)
            lo = mid;
        else
            hi = mid - 1;
    }
    /* Skip empty intervals (zero weight) that share the same cdf value. */
    while (lo < n - 1 && cdf[lo + 1] <= x) lo++;
    return lo;
}

/* Samples a direction; returns its solid-angle pdf (0: nothing to sample). */
static double env_sample(const ref_env *e, double u1, double u2, double dir[3], int *px, int *py)
{
    if (!(e->total > 0.0)) return 0.0;
    int h = e->height, w = e->width;
    double xr = u1 * e->total;
    int y = find_interval(e->marginal_cdf, h, xr);
    double rw = e->row_weight[y];
    if (!(rw > 0.0)) return 0.0;
    double fy = (xr - e->marginal_cdf[y]) / rw;
    const double *cdf = e->conditional_cdf + (size_t)y * (size_t)(w + 1);
    double xc = u2 * rw;
    int x = find_interval(cdf, w, xc);
    double wx = cdf[x + 1] - cdf[x];
    if (!(wx > 0.0)) return 0.0;
    double fx = (xc - cdf[x]) / wx;
    fy = fy < 0.0 ? 0.0 : (fy > 1.0 ? 1.0 : fy);
    fx = fx < 0.0 ? 0.0 : (fx > 1.0 ? 1.0 : fx);
    /* Given the row, fy is uniform in [0, 1): the density is constant over the row's height, so it
     * is the position within the row (reusing it keeps the stratification of u1). */
    double u = (x + fx) / w, v = (y + fy) / h;
    sss_reference_env_direction(u, v, e->rotate_y, dir);
    double st = sin(REF_PI * v);
    if (!(st > 1e-8)) return 0.0;
    /* Density over the unit square: weight / total * w * h; per solid angle / (2 pi^2 sin theta). */
    double p_uv = wx / e->total * (double)w * (double)h;
    *px = x, *py = y;
    return p_uv / (2.0 * REF_PI * REF_PI * st);
}

/* Radiance of pixel (x, y) times scale (the piecewise-constant map that the sampling follows). */
static void env_pixel(const ref_env *e, int x, int y, double out[3])
{
    const float *p = e->map->pixels + 3 * ((size_t)y * (size_t)e->width + (size_t)x);
    for (int c = 0; c < 3; c++) out[c] = fmax((double)p[c], 0.0) * e->scale[c];
}

/* Bilinear lookup (what camera rays and mirror reflections see), wrapping in u. */
static void env_lookup(const ref_env *e, const double dir[3], double out[3])
{
    double u, v;
    sss_reference_env_uv(dir, e->rotate_y, &u, &v);
    int w = e->width, h = e->height;
    double fx = u * w - 0.5, fy = v * h - 0.5;
    int x0 = (int)floor(fx), y0 = (int)floor(fy);
    double tx = fx - x0, ty = fy - y0;
    out[0] = out[1] = out[2] = 0.0;
    for (int j = 0; j < 2; j++) {
        int y = y0 + j;
        y = y < 0 ? 0 : (y >= h ? h - 1 : y);
        for (int i = 0; i < 2; i++) {
            int x = ((x0 + i) % w + w) % w;
            double wgt = (i ? tx : 1.0 - tx) * (j ? ty : 1.0 - ty);
            double px[3];
            env_pixel(e, x, y, px);
            for (int c = 0; c < 3; c++) out[c] += wgt * px[c];
        }
    }
}

sss_result ref_lights_init(ref_ctx *ctx, sss_error *err)
{
    const sss_reference_world *w = ctx->world;
    ctx->light_count = w->light_count;
    if (w->light_count == 0) return SSS_OK;
    if (!w->lights) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "lights: NULL array");
    ctx->lights = calloc(w->light_count, sizeof *ctx->lights);
    if (!ctx->lights) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "reference: out of memory (lights)");
    for (size_t i = 0; i < w->light_count; i++) {
        ref_light *l = &ctx->lights[i];
        l->src = w->lights[i];
        const sss_light *s = &l->src;
        switch (s->type) {
        case SSS_LIGHT_POINT:
        case SSS_LIGHT_SPOT:
            if (!finite3(s->position))
                return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "lights[%zu].position: not finite", i);
            if (!nonneg3(s->intensity))
                return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                                     "lights[%zu].intensity: must be finite and >= 0", i);
            if (s->type == SSS_LIGHT_SPOT) {
                double a[3] = {s->look_at[0] - s->position[0], s->look_at[1] - s->position[1],
                               s->look_at[2] - s->position[2]};
                if (!finite3(a) || !(v3_normalize(a) > 0.0))
                    return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                                         "lights[%zu].look_at: must differ from position", i);
                if (!(s->cone_angle > 0.0 && s->cone_angle <= 180.0) ||
                    !(s->cone_delta >= 0.0 && s->cone_delta <= s->cone_angle))
                    return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                                         "lights[%zu]: cone_angle must be in (0, 180] and cone_delta in "
                                         "[0, cone_angle]", i);
                memcpy(l->axis, a, sizeof a);
            }
            break;
        case SSS_LIGHT_DIRECTIONAL: {
            double d[3] = {-s->direction[0], -s->direction[1], -s->direction[2]};
            if (!finite3(d) || !(v3_normalize(d) > 0.0))
                return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "lights[%zu].direction: must be non-zero", i);
            if (!nonneg3(s->radiance))
                return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                                     "lights[%zu].radiance: must be finite and >= 0", i);
            memcpy(l->to_light, d, sizeof d);
            break;
        }
        case SSS_LIGHT_AREA: {
            double n[3];
            if (!finite3(s->center) || !finite3(s->u) || !finite3(s->v))
                return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "lights[%zu]: center, u, v must be finite", i);
            v3_cross(s->u, s->v, n);
            double len = v3_normalize(n);
            if (!(len > 0.0))
                return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                                     "lights[%zu]: u and v must be non-zero and not parallel", i);
            if (!nonneg3(s->radiance))
                return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                                     "lights[%zu].radiance: must be finite and >= 0", i);
            memcpy(l->normal, n, sizeof n);
            l->area = 4.0 * len; /* u, v are half extents */
            break;
        }
        case SSS_LIGHT_ENVIRONMENT: {
            ref_env *e = &l->env;
            if (!nonneg3(s->scale))
                return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "lights[%zu].scale: must be finite and >= 0", i);
            if (!isfinite(s->rotate_y))
                return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "lights[%zu].rotate_y: not finite", i);
            memcpy(e->scale, s->scale, sizeof e->scale);
            e->rotate_y = s->rotate_y;
            sss_result r = SSS_OK;
            if (w->environment_maps && w->environment_maps[i]) {
                e->map = w->environment_maps[i];
            } else {
                if (!s->file)
                    return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "lights[%zu].file: missing", i);
                r = sss_image_read(s->file, &e->owned_map, err);
                e->map = &e->owned_map;
            }
            if (r == SSS_OK) r = sss_image_require_finite(e->map, s->file ? s->file : "environment map", err);
            if (r != SSS_OK) {
                char prefix[64];
                snprintf(prefix, sizeof prefix, "lights[%zu].file", i);
                sss_error_prefix(err, prefix);
                return r;
            }
            if ((r = env_build(e, i, err)) != SSS_OK) return r;
            ctx->has_env = 1;
            break;
        }
        default:
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "lights[%zu]: unknown type %d", i, (int)s->type);
        }
    }
    return ref_light_tree_build(ctx, err);
}

void ref_lights_free(ref_ctx *ctx)
{
    for (size_t i = 0; ctx->lights && i < ctx->light_count; i++) {
        ref_env *e = &ctx->lights[i].env;
        sss_image_free(&e->owned_map);
        free(e->marginal_cdf);
        free(e->conditional_cdf);
        free(e->row_weight);
    }
    free(ctx->lights);
    ctx->lights = NULL;
    ctx->light_count = 0;
    ref_light_tree_free(&ctx->light_tree);
}

int ref_occluded(const ref_ctx *ctx, const double p[3], const double dir[3], double t_max)
{
    struct RTCIntersectContext ic;
    rtcInitIntersectContext(&ic);
    struct RTCRay ray;
    ray.org_x = (float)p[0], ray.org_y = (float)p[1], ray.org_z = (float)p[2];
    ray.dir_x = (float)dir[0], ray.dir_y = (float)dir[1], ray.dir_z = (float)dir[2];
    ray.tnear = 0.0f;
    ray.tfar = isfinite(t_max) ? (float)t_max : INFINITY;
    ray.time = 0.0f;
    ray.mask = 0xffffffffu;
    ray.id = 0;
    ray.flags = 0;
    rtcOccluded1(ctx->scene, &ic, &ray);
    return ray.tfar < 0.0f;
}

/* The unshadowed light a surface point receives at normal incidence from one direction, passed on to
 * the shadow ray and the interface (add_sample). */
typedef struct light_ray {
    double wi[3]; /* unit, towards the light */
    double t_max; /* the shadow ray stops short of the light */
    double li[3];
} light_ray;

/* Adds one light direction's contribution, li (irradiance at normal incidence or L / pdf) times weight,
 * if the light is above the surface and unoccluded. */
static void add_sample(const ref_ctx *ctx, const double po[3], const double ng[3], const double ns[3],
                       double eta, const light_ray *ray, double weight, double out[3])
{
    const double *wi = ray->wi, *li = ray->li;
    if (!(v3_dot(wi, ng) > 0.0)) return; /* light below the surface */
    double cs = v3_dot(wi, ns);
    if (!(cs > 0.0)) return;
    if (!(li[0] > 0.0 || li[1] > 0.0 || li[2] > 0.0)) return;
    if (ref_occluded(ctx, po, wi, ray->t_max)) return;
    /* docs/physics.md §1: the light enters through the interface with F_t = 1 - F_r(cos theta_i). */
    double ft = eta > 0.0 ? 1.0 - sss_fresnel_dielectric(cs, 1.0, eta) : 1.0;
    double k = cs * ft * weight;
    for (int c = 0; c < 3; c++) out[c] += li[c] * k;
}

/* The ray towards a point, spot or directional light from po; 0 where the light sends nothing there. */
static int delta_light_ray(const ref_light *l, const double po[3], light_ray *ray)
{
    const sss_light *s = &l->src;
    if (s->type == SSS_LIGHT_DIRECTIONAL) {
        memcpy(ray->wi, l->to_light, sizeof ray->wi);
        ray->t_max = INFINITY;
        memcpy(ray->li, s->radiance, sizeof ray->li);
        return 1;
    }
    for (int c = 0; c < 3; c++) ray->wi[c] = s->position[c] - po[c];
    double d = v3_normalize(ray->wi);
    if (!(d > 0.0)) return 0;
    double f = 1.0;
    if (s->type == SSS_LIGHT_SPOT) f = sss_reference_spot_falloff(s->cone_angle, s->cone_delta, -v3_dot(ray->wi, l->axis));
    if (!(f > 0.0)) return 0;
    ray->t_max = d * (1.0 - 1e-6);
    for (int c = 0; c < 3; c++) ray->li[c] = s->intensity[c] * f / (d * d);
    return 1;
}

/* The shading point of a light tree's draws (ref_light_tree_sample's visitor). */
typedef struct tree_draws {
    const ref_ctx *ctx;
    const double *po, *ng, *ns;
    double eta;
    double *out;
} tree_draws;

static void add_drawn_light(void *user, const ref_light *l, double weight)
{
    const tree_draws *t = user;
    light_ray ray;
    if (delta_light_ray(l, t->po, &ray)) add_sample(t->ctx, t->po, t->ng, t->ns, t->eta, &ray, weight, t->out);
}

static void add_area_light(const ref_ctx *ctx, const ref_light *l, const double po[3], const double ng[3],
                           const double ns[3], double eta, int samples, int si, int sj, int m, ref_rng *rng,
                           double out[3])
{
    const sss_light *s = &l->src;
    int k = (int)ceil(sqrt((double)(samples > 0 ? samples : 1)));
    double weight = l->area / (double)(k * k);
    for (int a = 0; a < k; a++)
        for (int b = 0; b < k; b++) {
            double su = 2.0 * (a + (si + ref_rng_uniform(rng)) / m) / k - 1.0;
            double sv = 2.0 * (b + (sj + ref_rng_uniform(rng)) / m) / k - 1.0;
            light_ray ray;
            double q[3];
            for (int c = 0; c < 3; c++) q[c] = s->center[c] + su * s->u[c] + sv * s->v[c];
            for (int c = 0; c < 3; c++) ray.wi[c] = q[c] - po[c];
            double d = v3_normalize(ray.wi);
            if (!(d > 0.0)) continue;
            double cl = -v3_dot(ray.wi, l->normal);
            if (s->two_sided) cl = fabs(cl);
            if (!(cl > 0.0)) continue;
            /* Area to solid angle: cos at the light / d^2. Stop short of the rectangle itself. */
            for (int c = 0; c < 3; c++) ray.li[c] = s->radiance[c] * cl / (d * d);
            ray.t_max = d * (1.0 - 1e-4);
            add_sample(ctx, po, ng, ns, eta, &ray, weight, out);
        }
}

static void add_environment_light(const ref_ctx *ctx, const ref_light *l, const double po[3], const double ng[3],
                                  const double ns[3], double eta, int samples, int si, int sj, int m,
                                  ref_rng *rng, double out[3])
{
    int k = (int)ceil(sqrt((double)(samples > 0 ? samples : 1)));
    for (int a = 0; a < k; a++)
        for (int b = 0; b < k; b++) {
            double u1 = (a + (si + ref_rng_uniform(rng)) / m) / k;
            double u2 = (b + (sj + ref_rng_uniform(rng)) / m) / k;
            light_ray ray;
            int px, py;
            double pdf = env_sample(&l->env, u1, u2, ray.wi, &px, &py);
            if (!(pdf > 0.0)) continue;
            env_pixel(&l->env, px, py, ray.li);
            for (int c = 0; c < 3; c++) ray.li[c] /= pdf;
            ray.t_max = INFINITY;
            add_sample(ctx, po, ng, ns, eta, &ray, 1.0 / (k * k), out);
        }
}

void ref_irradiance(const ref_ctx *ctx, const double p[3], const double ng[3], const double ns[3],
                    double eta, int area_samples, int env_samples, int stratum, int strata, ref_rng *rng,
                    double out[3])
{
    /* The light samples of the pixel's camera samples interleave: sample `stratum` of `strata` takes
     * sub-cell (stratum % m, stratum / m) of every cell of its k x k grid, m = sqrt(strata), so that
     * the pixel as a whole gets a (k m) x (k m) stratified set. */
    int m = strata > 1 ? (int)lround(sqrt((double)strata)) : 1;
    if (m < 1) m = 1;
    int si = stratum % m, sj = (stratum / m) % m;
    out[0] = out[1] = out[2] = 0.0;
    double po[3];
    ref_offset(ctx, p, ng, po);
    int from_tree = ctx->light_tree.nodes != NULL;
    for (size_t i = 0; i < ctx->light_count; i++) {
        const ref_light *l = &ctx->lights[i];
        light_ray ray;
        if (is_delta_light(&l->src)) {
            int drawn = from_tree && l->src.type != SSS_LIGHT_DIRECTIONAL;
            if (!drawn && delta_light_ray(l, po, &ray)) add_sample(ctx, po, ng, ns, eta, &ray, 1.0, out);
        } else if (l->src.type == SSS_LIGHT_AREA) {
            add_area_light(ctx, l, po, ng, ns, eta, area_samples, si, sj, m, rng, out);
        } else if (l->src.type == SSS_LIGHT_ENVIRONMENT) {
            add_environment_light(ctx, l, po, ng, ns, eta, env_samples, si, sj, m, rng, out);
        }
    }
    if (from_tree) {
        /* The camera samples of a pixel take strata of the tree's offset too. */
        int n = strata > 1 ? strata : 1;
        tree_draws t = {ctx, po, ng, ns, eta, out};
        ref_light_tree_sample(ctx, po, ng, (stratum % n + ref_rng_uniform(rng)) / n, add_drawn_light, &t);
    }
}

void ref_env_radiance(const ref_ctx *ctx, const double dir[3], double out[3])
{
    out[0] = out[1] = out[2] = 0.0;
    for (size_t i = 0; i < ctx->light_count; i++) {
        if (ctx->lights[i].src.type != SSS_LIGHT_ENVIRONMENT) continue;
        double v[3];
        env_lookup(&ctx->lights[i].env, dir, v);
        for (int c = 0; c < 3; c++) out[c] += v[c];
    }
}

void ref_area_radiance(const ref_ctx *ctx, unsigned light, const double dir[3], double out[3])
{
    const ref_light *l = &ctx->lights[light];
    double facing = -v3_dot(dir, l->normal);
    int lit = l->src.two_sided ? facing != 0.0 : facing > 0.0;
    for (int c = 0; c < 3; c++) out[c] = lit ? l->src.radiance[c] : 0.0;
}
