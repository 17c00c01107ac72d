/* reference/ref_setup.c — validation, camera, the Embree scene, and the surface samples of every
 * visible subsurface object with the density rule of sss/reference.h. */
#include <ctype.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>

#include "reference/ref_internal.h"

#define FINAL_BUDGET (16ull << 20)
#define DRAFT_BUDGET (2ull << 20)
#define MAX_VISIBILITY_RAYS (1u << 20)

void ref_report_progress(ref_ctx *ctx, double fraction, const char *stage, int force)
{
    if (!ctx->progress) return;
    double now = sss_time_seconds();
#pragma omp critical(ref_progress)
    {
        if (force || now - ctx->last_progress_time >= 0.1) {
            ctx->last_progress_time = now;
            double f = fraction < 0.0 ? 0.0 : (fraction > 1.0 ? 1.0 : fraction);
            ctx->progress(ctx->user, ctx->phase_lo + (ctx->phase_hi - ctx->phase_lo) * f,
                          stage ? stage : ctx->stage);
        }
    }
}

void ref_set_phase(ref_ctx *ctx, double lo, double hi, const char *stage)
{
    ctx->phase_lo = lo, ctx->phase_hi = hi, ctx->stage = stage;
    ref_report_progress(ctx, 0.0, NULL, 1);
}

static int finite3(const double v[3]) { return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]); }

/* The camera frame of sss/scene.h (sss_camera_basis): PBRT-v3's perspective camera, fov along the
 * shorter image axis, looking down its -z, y up. */
sss_result ref_camera_init(const sss_camera *c, ref_camera *cam, sss_error *err)
{
    memset(cam, 0, sizeof *cam);
    if (!finite3(c->position)) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "camera.position: not finite");
    if (!finite3(c->look_at)) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "camera.look_at: not finite");
    if (!finite3(c->up)) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "camera.up: not finite");
    if (!(c->fov >= SSS_SCENE_FOV_MIN && c->fov < 180.0))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "camera.fov: must be in [%g, 180) degrees, got %g",
                             SSS_SCENE_FOV_MIN, c->fov);
    if (c->width < 1 || c->height < 1 || c->width > SSS_IMAGE_MAX_DIM || c->height > SSS_IMAGE_MAX_DIM)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "camera.width, camera.height: must be in 1..%d, got %d x %d",
                             SSS_IMAGE_MAX_DIM, c->width, c->height);
    double f[3] = {c->look_at[0] - c->position[0], c->look_at[1] - c->position[1], c->look_at[2] - c->position[2]};
    if (!(v3_normalize(f) > 0.0))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "camera.look_at: must differ from camera.position");
    double r[3], u[3];
    v3_cross(f, c->up, r);
    if (!(v3_normalize(r) > 1e-12))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "camera.up: must not be parallel to the view direction");
    v3_cross(r, f, u);
    memcpy(cam->origin, c->position, sizeof cam->origin);
    memcpy(cam->forward, f, sizeof f);
    memcpy(cam->right, r, sizeof r);
    memcpy(cam->up, u, sizeof u);
    double t = tan(0.5 * c->fov * REF_PI / 180.0);
    cam->width = c->width, cam->height = c->height;
    if (c->width >= c->height) {
        cam->tan_half[0] = t * c->width / c->height;
        cam->tan_half[1] = t;
    } else {
        cam->tan_half[0] = t;
        cam->tan_half[1] = t * c->height / c->width;
    }
    return SSS_OK;
}

void ref_camera_ray(const ref_camera *cam, double px, double py, double dir[3])
{
    double x = (2.0 * px / cam->width - 1.0) * cam->tan_half[0];
    double y = (1.0 - 2.0 * py / cam->height) * cam->tan_half[1];
    for (int c = 0; c < 3; c++) dir[c] = cam->forward[c] + x * cam->right[c] + y * cam->up[c];
    v3_normalize(dir);
}

static sss_result validate_object(ref_ctx *ctx, size_t i, sss_error *err)
{
    const sss_reference_object *o = &ctx->world->objects[i];
    ref_object *ro = &ctx->objects[i];
    ro->src = o;
    const sss_mesh *m = o->mesh;
    if (!m) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "objects[%zu]: no mesh", i);
    if (m->triangle_count > 0 && (!m->positions || !m->indices))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "objects[%zu].mesh: missing positions or indices", i);
    for (size_t k = 0; k < 3 * (size_t)m->vertex_count; k++)
        if (!isfinite(m->positions[k]))
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "objects[%zu].mesh: vertex %zu is not finite", i, k / 3);
    if (m->normals)
        for (size_t k = 0; k < 3 * (size_t)m->vertex_count; k++)
            if (!isfinite(m->normals[k]))
                return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "objects[%zu].mesh: normal %zu is not finite", i, k / 3);
    for (size_t k = 0; k < 3 * (size_t)m->triangle_count; k++)
        if (m->indices[k] >= m->vertex_count)
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                                 "objects[%zu].mesh: vertex index %u out of range (%u vertices)", i, m->indices[k],
                                 m->vertex_count);
    for (int c = 0; c < 3; c++) ro->bounds_min[c] = INFINITY, ro->bounds_max[c] = -INFINITY;
    for (uint32_t v = 0; v < m->vertex_count; v++)
        for (int c = 0; c < 3; c++) {
            double x = m->positions[3 * (size_t)v + c];
            if (x < ro->bounds_min[c]) ro->bounds_min[c] = x;
            if (x > ro->bounds_max[c]) ro->bounds_max[c] = x;
        }
    if (o->type == SSS_REFERENCE_DIFFUSE) {
        for (int c = 0; c < 3; c++)
            if (!(o->reflectance[c] >= 0.0) || !isfinite(o->reflectance[c]))
                return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                                     "objects[%zu].material.reflectance: must be finite and >= 0", i);
        return SSS_OK;
    }
    if (o->type != SSS_REFERENCE_SUBSURFACE)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "objects[%zu].material.type: unknown (%d)", i, (int)o->type);
    char prefix[64];
    snprintf(prefix, sizeof prefix, "objects[%zu].material", i);
    sss_result r = sss_material_validate(&o->optical, err);
    if (r == SSS_OK) r = ref_profile_source_init(&ro->psrc, o, err);
    if (r != SSS_OK) {
        sss_error_prefix(err, prefix);
        return r;
    }
    ro->subsurface = 1;
    ro->eta = o->optical.eta;
    ro->c_norm = sss_bssrdf_normalization(ro->eta);
    if (!(ro->c_norm > 0.0))
        return sss_error_set(err, SSS_ERROR_NUMERIC, "%s.eta: normalisation 1 - 2 FM1(1/eta) is not positive", prefix);
    return SSS_OK;
}

static void embree_error(void *user, enum RTCError code, const char *str)
{
    ref_ctx *ctx = user;
    if (ctx->embree_failed) return;
    ctx->embree_failed = 1;
    snprintf(ctx->embree_message, sizeof ctx->embree_message, "Embree error %d: %s", (int)code, str ? str : "");
}

static sss_result embree_fail(ref_ctx *ctx, sss_error *err, const char *what)
{
    return sss_error_set(err, SSS_ERROR_UNSUPPORTED, "reference: %s failed (%s)", what,
                         ctx->embree_failed ? ctx->embree_message : "no message");
}

/* Embree's device configuration: one build thread (the BVH, and so every hit, is the same whatever the
 * render's thread count), then SSS_EMBREE_CONFIG appended (docs/reference.md: "Machine dependence"),
 * e.g. "isa=sse4.2" to hold Embree to another instruction set than the processor's best. */
static sss_result embree_config(char *config, size_t cap, sss_error *err)
{
    static const char base[] = "threads=1,set_affinity=0";
    const char *extra = getenv("SSS_EMBREE_CONFIG");
    if (!extra || !*extra) {
        snprintf(config, cap, "%s", base);
        return SSS_OK;
    }
    if (strlen(extra) + sizeof base + 1 > cap)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "SSS_EMBREE_CONFIG: longer than %zu characters",
                             cap - sizeof base - 1);
    for (const char *c = extra; *c; c++)
        if (!isalnum((unsigned char)*c) && !strchr("=,._-", *c))
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                                 "SSS_EMBREE_CONFIG: character 0x%02x is not allowed (letters, digits and =,._- only)",
                                 (unsigned char)*c);
    snprintf(config, cap, "%s,%s", base, extra);
    return SSS_OK;
}

static sss_result build_scene(ref_ctx *ctx, sss_error *err)
{
    char config[256];
    sss_result r = embree_config(config, sizeof config, err);
    if (r != SSS_OK) return r;
    ctx->device = rtcNewDevice(config);
    if (!ctx->device)
        return sss_error_set(err, SSS_ERROR_UNSUPPORTED, "reference: cannot create an Embree device with \"%s\"",
                             config);
    rtcSetDeviceErrorFunction(ctx->device, embree_error, ctx);
    ctx->scene = rtcNewScene(ctx->device);
    if (!ctx->scene) return embree_fail(ctx, err, "rtcNewScene");
    rtcSetSceneFlags(ctx->scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(ctx->scene, RTC_BUILD_QUALITY_HIGH);
    for (size_t i = 0; i < ctx->object_count; i++) {
        const sss_mesh *m = ctx->objects[i].src->mesh;
        if (m->triangle_count == 0) continue;
        RTCGeometry g = rtcNewGeometry(ctx->device, RTC_GEOMETRY_TYPE_TRIANGLE);
        if (!g) return embree_fail(ctx, err, "rtcNewGeometry");
        float *vb = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                            m->vertex_count);
        unsigned *ib = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned),
                                               m->triangle_count);
        if (!vb || !ib) {
            rtcReleaseGeometry(g);
            return embree_fail(ctx, err, "rtcSetNewGeometryBuffer");
        }
        memcpy(vb, m->positions, sizeof(float) * 3 * (size_t)m->vertex_count);
        memcpy(ib, m->indices, sizeof(unsigned) * 3 * (size_t)m->triangle_count);
        rtcCommitGeometry(g);
        rtcAttachGeometryByID(ctx->scene, g, (unsigned)i);
        rtcReleaseGeometry(g);
        if (!ctx->objects[i].subsurface) continue;
        /* The object alone, for the probe rays of its near part (they must not see other objects). */
        RTCScene ps = rtcNewScene(ctx->device);
        RTCGeometry pg = rtcNewGeometry(ctx->device, RTC_GEOMETRY_TYPE_TRIANGLE);
        if (!ps || !pg) {
            if (ps) rtcReleaseScene(ps);
            if (pg) rtcReleaseGeometry(pg);
            return embree_fail(ctx, err, "rtcNewScene");
        }
        ctx->objects[i].probe_scene = ps;
        rtcSetSceneFlags(ps, RTC_SCENE_FLAG_ROBUST);
        vb = rtcSetNewGeometryBuffer(pg, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), m->vertex_count);
        ib = rtcSetNewGeometryBuffer(pg, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), m->triangle_count);
        if (!vb || !ib) {
            rtcReleaseGeometry(pg);
            return embree_fail(ctx, err, "rtcSetNewGeometryBuffer");
        }
        memcpy(vb, m->positions, sizeof(float) * 3 * (size_t)m->vertex_count);
        memcpy(ib, m->indices, sizeof(unsigned) * 3 * (size_t)m->triangle_count);
        rtcCommitGeometry(pg);
        rtcAttachGeometryByID(ps, pg, 0);
        rtcReleaseGeometry(pg);
        rtcCommitScene(ps);
    }
    /* Area lights are rectangles in the scene: visible and casting shadows, as in PBRT. */
    ctx->light_geom_base = (unsigned)ctx->object_count;
    ctx->light_of_geom = calloc(ctx->light_count + 1, sizeof(unsigned));
    if (!ctx->light_of_geom) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "reference: out of memory");
    for (size_t i = 0; i < ctx->light_count; i++) {
        const sss_light *s = &ctx->lights[i].src;
        if (s->type != SSS_LIGHT_AREA) continue;
        RTCGeometry g = rtcNewGeometry(ctx->device, RTC_GEOMETRY_TYPE_TRIANGLE);
        if (!g) return embree_fail(ctx, err, "rtcNewGeometry");
        float *vb = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 4);
        unsigned *ib = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), 2);
        if (!vb || !ib) {
            rtcReleaseGeometry(g);
            return embree_fail(ctx, err, "rtcSetNewGeometryBuffer");
        }
        static const double su[4] = {-1, 1, 1, -1}, sv[4] = {-1, -1, 1, 1};
        for (int k = 0; k < 4; k++)
            for (int c = 0; c < 3; c++) vb[3 * k + c] = (float)(s->center[c] + su[k] * s->u[c] + sv[k] * s->v[c]);
        static const unsigned quad[6] = {0, 1, 2, 0, 2, 3};
        memcpy(ib, quad, sizeof quad);
        rtcCommitGeometry(g);
        unsigned id = ctx->light_geom_base + ctx->light_geom_count;
        rtcAttachGeometryByID(ctx->scene, g, id);
        rtcReleaseGeometry(g);
        ctx->light_of_geom[ctx->light_geom_count++] = (unsigned)i;
    }
    rtcCommitScene(ctx->scene);
    if (ctx->embree_failed) return embree_fail(ctx, err, "building the ray tracing scene");
    struct RTCBounds b;
    rtcGetSceneBounds(ctx->scene, &b);
    double d[3] = {b.upper_x - b.lower_x, b.upper_y - b.lower_y, b.upper_z - b.lower_z};
    double diag = finite3(d) ? v3_len(d) : 0.0;
    ctx->eps = diag > 0.0 ? 1e-5 * diag : 1e-5;
    return SSS_OK;
}

static int cmp_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

/* Pixel footprint (world size of one pixel) at the nearest visible points of every object: the 1st
 * percentile over pixel centres (a sub-grid of at most 1 M of them). */
static sss_result find_footprints(ref_ctx *ctx, sss_error *err)
{
    const ref_camera *cam = &ctx->cam;
    int stride = 1;
    while ((uint64_t)((cam->width + stride - 1) / stride) * (uint64_t)((cam->height + stride - 1) / stride) >
           MAX_VISIBILITY_RAYS)
        stride++;
    int nx = (cam->width + stride - 1) / stride, ny = (cam->height + stride - 1) / stride;
    size_t n = (size_t)nx * (size_t)ny;
    int32_t *id = malloc(sizeof(int32_t) * n);
    float *fp = malloc(sizeof(float) * n);
    size_t *count = calloc(ctx->object_count + 1, sizeof(size_t));
    if (!id || !fp || !count) {
        free(id);
        free(fp);
        free(count);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "reference: out of memory (visibility)");
    }
    double pixel_angle = 2.0 * fmin(cam->tan_half[0], cam->tan_half[1]) / (cam->width < cam->height ? cam->width : cam->height);
#pragma omp parallel for schedule(dynamic, 4)
    for (int y = 0; y < ny; y++) {
        for (int x = 0; x < nx; x++) {
            double dir[3];
            ref_camera_ray(cam, x * stride + 0.5, y * stride + 0.5, dir);
            struct RTCIntersectContext ic;
            rtcInitIntersectContext(&ic);
            struct RTCRayHit rh;
            memset(&rh, 0, sizeof rh);
            rh.ray.org_x = (float)cam->origin[0], rh.ray.org_y = (float)cam->origin[1], rh.ray.org_z = (float)cam->origin[2];
            rh.ray.dir_x = (float)dir[0], rh.ray.dir_y = (float)dir[1], rh.ray.dir_z = (float)dir[2];
            rh.ray.tfar = INFINITY;
            rh.ray.mask = 0xffffffffu;
            rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
            rtcIntersect1(ctx->scene, &ic, &rh);
            size_t k = (size_t)y * (size_t)nx + (size_t)x;
            id[k] = -1;
            if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID && rh.hit.geomID < ctx->light_geom_base) {
                id[k] = (int32_t)rh.hit.geomID;
                fp[k] = (float)(rh.ray.tfar * v3_dot(dir, cam->forward) * pixel_angle);
            }
        }
    }
    for (size_t k = 0; k < n; k++)
        if (id[k] >= 0) count[id[k]]++;
    size_t *start = calloc(ctx->object_count + 1, sizeof(size_t));
    float *sorted = malloc(sizeof(float) * (n ? n : 1));
    if (!start || !sorted) {
        free(id), free(fp), free(count), free(start), free(sorted);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "reference: out of memory (visibility)");
    }
    for (size_t o = 0; o < ctx->object_count; o++) start[o + 1] = start[o] + count[o];
    memset(count, 0, sizeof(size_t) * (ctx->object_count + 1));
    for (size_t k = 0; k < n; k++)
        if (id[k] >= 0) sorted[start[id[k]] + count[id[k]]++] = fp[k];
    for (size_t o = 0; o < ctx->object_count; o++) {
        ref_object *ro = &ctx->objects[o];
        ro->visible_pixels = count[o];
        if (count[o] > 0) {
            qsort(sorted + start[o], count[o], sizeof(float), cmp_float);
            size_t k = count[o] / 100;
            while (k + 1 < count[o] && !(sorted[start[o] + k] > 0.0f)) k++; /* hits at the eye */
            ro->footprint = sorted[start[o] + k];
            ro->visible = 1;
        } else {
            /* Seen by no pixel centre (tiny on screen): the footprint at its bounding box centre. */
            double c[3];
            for (int k = 0; k < 3; k++) c[k] = 0.5 * (ro->bounds_min[k] + ro->bounds_max[k]) - cam->origin[k];
            double depth = v3_dot(c, cam->forward);
            ro->footprint = depth > 0.0 ? depth * pixel_angle : 0.0;
        }
    }
    free(id), free(fp), free(count), free(start), free(sorted);
    return SSS_OK;
}

/* Spacing of every subsurface object: h = f * footprint / sqrt(density), all grown by one factor
 * until the total fits the budget. */
static void choose_spacing(ref_ctx *ctx)
{
    int draft = ctx->desc.quality == SSS_REFERENCE_DRAFT;
    double density = ctx->desc.density > 0.0 ? ctx->desc.density : 1.0;
    double f = (draft ? 1.0 : 0.5) / sqrt(density);
    double budget = (double)(draft ? DRAFT_BUDGET : FINAL_BUDGET) * density;
    double g = 1.0, prev_total = INFINITY;
    for (int it = 0; it < 200; it++) {
        double total = 0.0;
        for (size_t o = 0; o < ctx->object_count; o++) {
            ref_object *ro = &ctx->objects[o];
            ro->spacing = 0.0;
            if (!ro->subsurface || !(ro->footprint > 0.0)) continue;
            ro->spacing = fmin(ro->footprint * f, ref_transport_cap(ctx, ro) / sqrt(density)) * g;
            total += (double)ref_points_count(ro->src->mesh, ro->spacing);
        }
        /* Stop when within the budget, or when growing h no longer helps (one per triangle). */
        if (total <= budget || total >= prev_total * 0.999) break;
        prev_total = total;
        g *= 1.2;
    }
}

sss_result ref_prepare(ref_ctx *ctx, sss_error *err)
{
    const sss_reference_world *w = ctx->world;
    ref_set_phase(ctx, 0.0, 0.02, "setup");
    double t0 = sss_time_seconds();
    sss_result r = ref_camera_init(&w->camera, &ctx->cam, err);
    if (r != SSS_OK) return r;
    if (w->object_count > 0 && !w->objects) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "objects: NULL array");
    if (w->object_count >= 0x7fffffffu) return sss_error_set(err, SSS_ERROR_LIMIT, "objects: too many");
    ctx->object_count = w->object_count;
    ctx->objects = calloc(w->object_count + 1, sizeof *ctx->objects);
    if (!ctx->objects) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "reference: out of memory");
    for (size_t i = 0; i < w->object_count; i++)
        if ((r = validate_object(ctx, i, err)) != SSS_OK) return r;
    if ((r = ref_lights_init(ctx, err)) != SSS_OK) return r;
    if ((r = build_scene(ctx, err)) != SSS_OK) return r;
    if ((r = find_footprints(ctx, err)) != SSS_OK) return r;
    choose_spacing(ctx);
    if (ctx->transport) ref_transport_spacing(ctx);
    ctx->stats.seconds_setup = sss_time_seconds() - t0;

    /* Surface samples: progress in proportion to each object's sample count. */
    double total = 0.0, done = 0.0;
    for (size_t o = 0; o < ctx->object_count; o++)
        if (ctx->objects[o].spacing > 0.0)
            total += (double)ref_points_count(ctx->objects[o].src->mesh, ctx->objects[o].spacing);
    ctx->stats.spacing_min = INFINITY;
    ctx->stats.split_radius_min = INFINITY;
    for (size_t o = 0; o < ctx->object_count; o++) {
        ref_object *ro = &ctx->objects[o];
        if (!(ro->spacing > 0.0)) continue;
        if (!ro->subsurface) {
            /* Diffuse (ctx->transport only): E at the samples; the bounces keep their copy. */
            double t1 = sss_time_seconds();
            if ((r = ref_points_generate(ctx, o, ro->spacing, err)) != SSS_OK) return r;
            ref_tree_free(&ro->tree);
            ctx->stats.seconds_samples += sss_time_seconds() - t1;
            continue;
        }
        double h = ro->spacing, r0 = 4.0 * h;
        double d[3] = {ro->bounds_max[0] - ro->bounds_min[0], ro->bounds_max[1] - ro->bounds_min[1],
                       ro->bounds_max[2] - ro->bounds_min[2]};
        char prefix[64];
        snprintf(prefix, sizeof prefix, "objects[%zu]", o);
        double t1 = sss_time_seconds();
        if ((r = ref_profile_build(&ro->prof, &ro->psrc, r0, 1.001 * v3_len(d) + r0, err)) != SSS_OK) {
            sss_error_prefix(err, prefix);
            return r;
        }
        double n = (double)ref_points_count(ro->src->mesh, h);
        double lo = 0.02 + 0.28 * (total > 0.0 ? done / total : 0.0);
        double hi = 0.02 + 0.28 * (total > 0.0 ? (done + n) / total : 1.0);
        ref_set_phase(ctx, lo, hi, "surface samples");
        if ((r = ref_points_generate(ctx, o, h, err)) != SSS_OK) return r;
        if (ctx->transport && (r = ref_transport_cluster(ctx, o, err)) != SSS_OK) return r;
        done += n;
        double t2 = sss_time_seconds();
        if ((r = ref_tree_build(&ro->tree, err)) != SSS_OK) return r;
        double t3 = sss_time_seconds();
        ctx->stats.seconds_samples += t2 - t1;
        ctx->stats.seconds_tree += t3 - t2;
        ctx->stats.surface_samples += ro->tree.point_count;
        ctx->stats.tree_nodes += ro->tree.node_count;
        ctx->stats.tree_leaves += ro->tree.leaf_count;
        if (ro->tree.depth > ctx->stats.tree_depth) ctx->stats.tree_depth = ro->tree.depth;
        if (h < ctx->stats.spacing_min) ctx->stats.spacing_min = h;
        if (h > ctx->stats.spacing_max) ctx->stats.spacing_max = h;
        if (r0 < ctx->stats.split_radius_min) ctx->stats.split_radius_min = r0;
    }
    if (!isfinite(ctx->stats.spacing_min)) ctx->stats.spacing_min = 0.0;
    if (!isfinite(ctx->stats.split_radius_min)) ctx->stats.split_radius_min = 0.0;
    ctx->stats.bounces = 1;
    ctx->stats.seconds_bounce[0] = ctx->stats.seconds_samples;
    ctx->stats.bounce_fraction[0] = 1.0;
    if (ctx->transport) return ref_bounces_run(ctx, err);
    return SSS_OK;
}

void ref_ctx_free(ref_ctx *ctx)
{
    for (size_t o = 0; ctx->objects && o < ctx->object_count; o++) {
        ref_profile_free(&ctx->objects[o].prof);
        ref_tree_free(&ctx->objects[o].tree);
        ref_tree_free(&ctx->objects[o].itree);
        ref_tree_free(&ctx->objects[o].stree);
        free((void *)ctx->objects[o].sent_state);
        free(ctx->objects[o].nb_offset);
        free(ctx->objects[o].nb_index);
        free(ctx->objects[o].tri_offset);
        free(ctx->objects[o].cluster_of);
        free(ctx->objects[o].bs);
        free(ctx->objects[o].indirect);
        free(ctx->objects[o].link_target);
        free(ctx->objects[o].link_weight);
        if (ctx->objects[o].probe_scene) rtcReleaseScene(ctx->objects[o].probe_scene);
    }
    free(ctx->objects);
    ctx->objects = NULL;
    ref_lights_free(ctx);
    free(ctx->light_of_geom);
    ctx->light_of_geom = NULL;
    if (ctx->scene) rtcReleaseScene(ctx->scene);
    if (ctx->device) rtcReleaseDevice(ctx->device);
    ctx->scene = NULL;
    ctx->device = NULL;
}
