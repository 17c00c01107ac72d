/* Reference renderer, lights: a Lambertian plane (radiance reflectance / pi * E) under each light type
 * against closed forms: point (I cos / d^2), spot (PBRT-v3 falloff), directional (E cos), a rectangle
 * parallel to the plane (the corner form factor), a constant environment (E = pi L) and a non-uniform
 * one (quadrature over its pixels); the environment seen by rays that miss; the --specular mirror term of an environment and of a lit
 * ceiling. */
#include "ref_test_util.h"

#define W 32
#define FOV 40.0
#define RHO 0.6

/* Camera height above the plane (below the area light's rectangle for that test). */
static double H_CAM = 4.0;
/* A black object between the lights and the plane (NULL: none). */
static const sss_mesh *OCCLUDER = NULL;

/* The plane point seen through raster point (px, py) of the downward camera at height H_CAM. */
static void plane_point(double px, double py, double *x, double *z)
{
    double t = tan(0.5 * FOV * T_PI / 180.0);
    double sx = (2.0 * px / W - 1.0) * t, sy = (1.0 - 2.0 * py / W) * t;
    /* camera_set with a vertical view: right = +x, up = -z. */
    *x = H_CAM * sx;
    *z = -H_CAM * sy;
}

typedef double (*irr_fn)(const void *ctx, double x, double z);

/* Renders the plane under `lights` and compares every pixel with reflectance/pi times the pixel
 * average (6 x 6 points) of the closed-form irradiance. Returns the worst deviation relative to the
 * image maximum. */
static double check_plane(const sss_light *lights, size_t nl, irr_fn f, const void *fctx, const sss_image *const *env)
{
    tmesh plane = {0};
    tmesh_plane(&plane, 60.0, 0, 0, 0, 4, 0);
    sss_reference_object o[2] = {object_diffuse(&plane.m, RHO)};
    if (OCCLUDER) o[1] = object_diffuse(OCCLUDER, 0.0);
    sss_reference_world w;
    memset(&w, 0, sizeof w);
    camera_set(&w.camera, 0, H_CAM, 0, 0, 0, 0, FOV, W, W);
    w.objects = o, w.object_count = OCCLUDER ? 2 : 1, w.lights = lights, w.light_count = nl;
    w.environment_maps = env;
    sss_reference_desc d;
    memset(&d, 0, sizeof d);
    d.bounces = 1; /* the single-event integral the closed forms describe */
    d.seed = 9;
    sss_image img;
    double worst = INFINITY;
    if (render_or_die(&w, &d, &img, NULL)) {
        double mx = 0.0, dev = 0.0;
        double *expect = malloc(sizeof(double) * W * W);
        for (int y = 0; y < W; y++)
            for (int x = 0; x < W; x++) {
                double e = 0.0;
                for (int j = 0; j < 6; j++)
                    for (int i = 0; i < 6; i++) {
                        double px, pz;
                        plane_point(x + (i + 0.5) / 6.0, y + (j + 0.5) / 6.0, &px, &pz);
                        e += f(fctx, px, pz) / 36.0;
                    }
                expect[y * W + x] = RHO / T_PI * e;
                mx = fmax(mx, expect[y * W + x]);
            }
        for (int y = 0; y < W; y++)
            for (int x = 0; x < W; x++)
                for (int c = 0; c < 3; c++) dev = fmax(dev, fabs(img_at(&img, x, y, c) - expect[y * W + x]));
        worst = mx > 0.0 ? dev / mx : dev;
        free(expect);
        sss_image_free(&img);
    }
    tmesh_free(&plane);
    return worst;
}

static double irr_point(const void *ctx, double x, double z)
{
    const sss_light *l = ctx;
    double dx = l->position[0] - x, dy = l->position[1], dz = l->position[2] - z;
    double d = sqrt(dx * dx + dy * dy + dz * dz);
    return l->intensity[0] * dy / (d * d * d);
}

static double irr_spot(const void *ctx, double x, double z)
{
    const sss_light *l = ctx;
    double dx = x - l->position[0], dy = -l->position[1], dz = z - l->position[2];
    double d = sqrt(dx * dx + dy * dy + dz * dz);
    double ax = l->look_at[0] - l->position[0], ay = l->look_at[1] - l->position[1], az = l->look_at[2] - l->position[2];
    double al = sqrt(ax * ax + ay * ay + az * az);
    double ct = (dx * ax + dy * ay + dz * az) / (d * al);
    /* PBRT-v3 falloff, written out again here. */
    double cos_total = cos(l->cone_angle * T_PI / 180.0), cos_start = cos((l->cone_angle - l->cone_delta) * T_PI / 180.0);
    double f = ct < cos_total ? 0.0 : (ct >= cos_start ? 1.0 : pow((ct - cos_total) / (cos_start - cos_total), 4.0));
    return l->intensity[0] * f * (-dy) / (d * d * d);
}

static double irr_dir(const void *ctx, double x, double z)
{
    (void)x, (void)z;
    const sss_light *l = ctx;
    double len = sqrt(l->direction[0] * l->direction[0] + l->direction[1] * l->direction[1] + l->direction[2] * l->direction[2]);
    return l->radiance[0] * fmax(0.0, -l->direction[1] / len);
}

/* Form factor from a point to a parallel rectangle [0, a] x [0, b] at height c with a corner above it. */
static double corner_ff(double a, double b, double c)
{
    double X = a / c, Y = b / c, sx = sqrt(1.0 + X * X), sy = sqrt(1.0 + Y * Y);
    return (X / sx * atan(Y / sx) + Y / sy * atan(X / sy)) / (2.0 * T_PI);
}

/* Signed corner form factor, for rectangles on either side of the point. */
static double ff_signed(double a, double b, double c)
{
    double s = (a < 0 ? -1.0 : 1.0) * (b < 0 ? -1.0 : 1.0);
    return s * corner_ff(fabs(a), fabs(b), c);
}

static double irr_area(const void *ctx, double x, double z)
{
    /* Axis-aligned rectangle (u along x, v along z), emitting downwards, at height center[1]. */
    const sss_light *l = ctx;
    double x0 = l->center[0] - fabs(l->u[0]) - x, x1 = l->center[0] + fabs(l->u[0]) - x;
    double z0 = l->center[2] - fabs(l->v[2]) - z, z1 = l->center[2] + fabs(l->v[2]) - z;
    double c = l->center[1];
    double F = ff_signed(x1, z1, c) - ff_signed(x0, z1, c) - ff_signed(x1, z0, c) + ff_signed(x0, z0, c);
    return T_PI * l->radiance[0] * F;
}

/* E on an upward-facing, unoccluded plane: quadrature over the map's pixels (4 x 4 points each) of
 * L(pixel) cos(theta_up) d omega. */
static double env_irradiance(const sss_image *map, double rotate)
{
    double sum = 0.0;
    int w = map->width, h = map->height;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            for (int j = 0; j < 4; j++)
                for (int i = 0; i < 4; i++) {
                    double u = (x + (i + 0.5) / 4) / w, v = (y + (j + 0.5) / 4) / h, d[3];
                    sss_reference_env_direction(u, v, rotate, d);
                    if (d[1] <= 0.0) continue;
                    double dom = (2.0 * T_PI / w) * (T_PI / h) * sin(T_PI * v) / 16.0;
                    sum += map->pixels[3 * ((size_t)y * w + x) + 1] * d[1] * dom;
                }
    return sum;
}

static double irr_const(const void *ctx, double x, double z)
{
    (void)x, (void)z;
    return *(const double *)ctx;
}

/* Many point lights (more than REF_EXACT_POINT_LIGHTS: drawn from the light tree) on a 16 x 16 grid at
 * height 6, part of them hidden behind a black slab at height 5..5.1 over x >= 0.3: the closed form
 * sums I cos / d^2 over the lights that the segment to the plane point passes by the slab. */
#define GRID_LIGHTS 16
#define SLAB_LO 5.0
#define SLAB_HI 5.1
#define SLAB_X 0.3

typedef struct light_set {
    const sss_light *lights;
    size_t count;
    int slab;
} light_set;

static int slab_blocks(const sss_light *l, double x, double z)
{
    (void)z; /* the slab spans z = -50..50 */
    double x_lo = x + (l->position[0] - x) * SLAB_LO / l->position[1];
    double x_hi = x + (l->position[0] - x) * SLAB_HI / l->position[1];
    return (x_lo >= SLAB_X && x_lo <= 50.0) || (x_hi >= SLAB_X && x_hi <= 50.0);
}

static double irr_many(const void *ctx, double x, double z)
{
    const light_set *set = ctx;
    double e = 0.0;
    for (size_t i = 0; i < set->count; i++)
        if (!set->slab || !slab_blocks(&set->lights[i], x, z)) e += irr_point(&set->lights[i], x, z);
    return e;
}

/* The plane's mean over the image against the closed form's: unbiased draws average out. */
static void check_many_lights(void)
{
    sss_light lights[GRID_LIGHTS * GRID_LIGHTS];
    for (int i = 0; i < GRID_LIGHTS; i++)
        for (int j = 0; j < GRID_LIGHTS; j++)
            lights[i * GRID_LIGHTS + j] = light_point(-3.0 + 6.0 * i / (GRID_LIGHTS - 1), 6.0,
                                                      -3.0 + 6.0 * j / (GRID_LIGHTS - 1), 0.05);
    light_set open = {lights, GRID_LIGHTS * GRID_LIGHTS, 0};
    double dev = check_plane(lights, open.count, irr_many, &open, NULL);
    CHECK_MSG(dev < 0.02, "%zu point lights: worst deviation %.4g of the maximum", open.count, dev);
    printf("%zu point lights: %.3g\n", open.count, dev);
    tmesh slab = {0};
    const double lo[3] = {SLAB_X, SLAB_LO, -50.0}, hi[3] = {50.0, SLAB_HI, 50.0};
    tmesh_box(&slab, lo, hi, 2);
    OCCLUDER = &slab.m;
    light_set hidden = {lights, GRID_LIGHTS * GRID_LIGHTS, 1};
    dev = check_plane(lights, hidden.count, irr_many, &hidden, NULL);
    CHECK_MSG(dev < 0.05, "%zu point lights, part hidden: worst deviation %.4g of the maximum", hidden.count, dev);
    printf("%zu point lights, part hidden: %.3g\n", hidden.count, dev);
    OCCLUDER = NULL;
    tmesh_free(&slab);
}

/* Renders w as the single-event integral the closed forms describe (draft, no adaptive sampling),
 * without (a) and with (b) the camera ray's mirror reflection; 1 when both rendered. */
static int render_specular_pair(const sss_reference_world *w, sss_image *a, sss_image *b)
{
    sss_reference_desc d;
    memset(&d, 0, sizeof d);
    d.bounces = 1;
    d.quality = SSS_REFERENCE_DRAFT;
    d.no_adaptive = 1;
    if (!render_or_die(w, &d, a, NULL)) return 0;
    d.specular = 1;
    if (render_or_die(w, &d, b, NULL)) return 1;
    sss_image_free(a);
    return 0;
}

/* --specular reflects the lit scene too: a camera straight above a black subsurface floor (albedo
 * ~1e-4) sees in its mirror a Lambertian ceiling lit by a point light halfway up, so the centre pixel
 * is F_r(1) times the ceiling's radiance reflectance / pi * I / d^2 (d = 5); without it, ~0. */
static void check_mirror_of_scene(void)
{
    tmesh floor = {0}, ceiling = {0};
    tmesh_plane(&floor, 60.0, 0, 0, 0, 4, 0);
    tmesh_plane(&ceiling, 60.0, 0, 10.0, 0, 4, 1);
    sss_material m = material_coeffs(100.0, 100.0, 100.0, 0.01, 0.01, 0.01, 1.5);
    sss_pbd_table *table;
    sss_reference_object o[2] = {object_subsurface(&floor.m, &m, &table), object_diffuse(&ceiling.m, RHO)};
    sss_light l = light_point(0.0, 5.0, 0.0, 2.0);
    sss_reference_world w;
    memset(&w, 0, sizeof w);
    camera_set(&w.camera, 0, 1.0, 0, 0, 0, 0, 40, 17, 17);
    w.objects = o, w.object_count = 2, w.lights = &l, w.light_count = 1;
    sss_image a, b; /* the ceiling's radiance is its direct light: no interreflection */
    if (render_specular_pair(&w, &a, &b)) {
        double fr = pow((1.5 - 1.0) / (1.5 + 1.0), 2.0), ceiling_l = RHO / T_PI * 2.0 / 25.0;
        CHECK_MSG(img_at(&a, 8, 8, 1) < 1e-3 * fr * ceiling_l, "black floor without --specular: %g",
                  img_at(&a, 8, 8, 1));
        CHECK_NEAR(img_at(&b, 8, 8, 1), fr * ceiling_l, 0.01 * fr * ceiling_l);
        printf("mirror of the scene: %.5g (closed form %.5g)\n", img_at(&b, 8, 8, 1), fr * ceiling_l);
        sss_image_free(&a);
        sss_image_free(&b);
    }
    free(table);
    tmesh_free(&floor);
    tmesh_free(&ceiling);
}

int main(void)
{
    check_many_lights();
    double dev;
    sss_light l = light_point(0.7, 3.0, -0.4, 5.0);
    dev = check_plane(&l, 1, irr_point, &l, NULL);
    CHECK_MSG(dev < 0.005, "point light: worst deviation %.4g of the maximum", dev);
    printf("point: %.3g\n", dev);

    memset(&l, 0, sizeof l);
    l.type = SSS_LIGHT_SPOT;
    l.position[0] = 0.2, l.position[1] = 3.0, l.position[2] = 0.1;
    l.look_at[0] = -0.3, l.look_at[1] = 0.0, l.look_at[2] = 0.2;
    l.cone_angle = 20.0, l.cone_delta = 8.0;
    l.intensity[0] = l.intensity[1] = l.intensity[2] = 6.0;
    dev = check_plane(&l, 1, irr_spot, &l, NULL);
    CHECK_MSG(dev < 0.01, "spot light: worst deviation %.4g of the maximum", dev);
    printf("spot: %.3g\n", dev);

    l = light_directional(0.3, -1.0, 0.5, 1.7);
    dev = check_plane(&l, 1, irr_dir, &l, NULL);
    CHECK_MSG(dev < 1e-4, "directional light: worst deviation %.4g of the maximum", dev);
    printf("directional: %.3g\n", dev);

    /* A rectangle facing down (u x v = -y): one-sided, and the same rectangle facing up with two_sided. */
    memset(&l, 0, sizeof l);
    l.type = SSS_LIGHT_AREA;
    l.center[0] = 0.4, l.center[1] = 1.5, l.center[2] = -0.2;
    l.u[0] = 0.8, l.v[2] = 0.5; /* (0.8,0,0) x (0,0,0.5) = (0, -0.4, 0): faces down */
    l.radiance[0] = l.radiance[1] = l.radiance[2] = 2.0;
    H_CAM = 1.0; /* below the rectangle, which would hide part of the plane */
    dev = check_plane(&l, 1, irr_area, &l, NULL);
    CHECK_MSG(dev < 0.01, "area light: worst deviation %.4g of the maximum", dev);
    printf("area: %.3g\n", dev);
    l.v[2] = -0.5; /* now facing up, away from the plane */
    l.two_sided = 1;
    dev = check_plane(&l, 1, irr_area, &l, NULL);
    CHECK_MSG(dev < 0.01, "two-sided area light: worst deviation %.4g of the maximum", dev);
    l.two_sided = 0;
    H_CAM = 4.0;
    {
        /* One-sided and facing away: the plane stays black. */
        tmesh plane = {0};
        tmesh_plane(&plane, 60.0, 0, 0, 0, 4, 0);
        sss_reference_object o = object_diffuse(&plane.m, RHO);
        sss_reference_world w;
        memset(&w, 0, sizeof w);
        camera_set(&w.camera, 0, H_CAM, 0, 0, 0, 0, FOV, 16, 16);
        w.objects = &o, w.object_count = 1, w.lights = &l, w.light_count = 1;
        sss_reference_desc d;
        memset(&d, 0, sizeof d);
        d.bounces = 1; /* the single-event integral the closed forms describe */
        d.quality = SSS_REFERENCE_DRAFT;
        sss_image img;
        if (render_or_die(&w, &d, &img, NULL)) {
            /* The plane is black; the camera above sees the rectangle's emitting side. */
            CHECK(img_at(&img, 0, 0, 0) == 0.0 && img_at(&img, 15, 15, 1) == 0.0);
            CHECK_NEAR(img_at(&img, 11, 6, 2), 2.0, 1e-6);
            sss_image_free(&img);
        }
        tmesh_free(&plane);
    }

    /* Environment: constant radiance L over the sphere gives E = pi L on an open plane. */
    sss_image env;
    sss_error err;
    CHECK(sss_image_create(&env, 64, 32, &err) == SSS_OK);
    for (size_t i = 0; i < 3 * 64 * 32; i++) env.pixels[i] = 0.8f;
    memset(&l, 0, sizeof l);
    l.type = SSS_LIGHT_ENVIRONMENT;
    l.scale[0] = l.scale[1] = l.scale[2] = 1.0;
    const sss_image *maps[1] = {&env};
    double e_const = env_irradiance(&env, 0.0);
    CHECK_REL(e_const, T_PI * 0.8, 1e-3); /* the quadrature itself */
    dev = check_plane(&l, 1, irr_const, &e_const, maps);
    CHECK_MSG(dev < 0.01, "constant environment: worst deviation %.4g of the maximum", dev);
    printf("constant environment: %.3g\n", dev);
    /* A non-uniform map: a bright spot and a gradient, rotated. */
    for (int y = 0; y < 32; y++)
        for (int x = 0; x < 64; x++) {
            float v = (float)(0.1 + 0.5 * (double)y / 32.0);
            if (x >= 20 && x < 24 && y >= 6 && y < 9) v = 40.0f;
            for (int c = 0; c < 3; c++) env.pixels[3 * (y * 64 + x) + c] = v;
        }
    l.rotate_y = 30.0;
    double e_spot = env_irradiance(&env, 30.0);
    dev = check_plane(&l, 1, irr_const, &e_spot, maps);
    CHECK_MSG(dev < 0.02, "bright-spot environment: worst deviation %.4g of the maximum", dev);
    printf("bright-spot environment: %.3g\n", dev);

    /* Rays that miss see the map; with --specular a subsurface sphere adds F_r(cos) L of the mirror
     * direction: in a constant environment L, the centre pixel gains F_r(1) L. */
    for (size_t i = 0; i < 3 * 64 * 32; i++) env.pixels[i] = 0.5f;
    l.rotate_y = 0.0;
    {
        tmesh sphere = {0};
        double c0[3] = {0, 0, 0};
        tmesh_sphere(&sphere, c0, 1.0, 32);
        sss_material m = material_coeffs(0.1, 0.1, 0.1, 1.0, 1.0, 1.0, 1.5);
        sss_pbd_table *table;
        sss_reference_object o = object_subsurface(&sphere.m, &m, &table);
        sss_reference_world w;
        memset(&w, 0, sizeof w);
        camera_set(&w.camera, 0, 0, 5, 0, 0, 0, 40, 17, 17);
        w.objects = &o, w.object_count = 1, w.lights = &l, w.light_count = 1, w.environment_maps = maps;
        sss_image a, b;
        if (render_specular_pair(&w, &a, &b)) {
            double fr = pow((1.5 - 1.0) / (1.5 + 1.0), 2.0);
            CHECK_NEAR(img_at(&b, 8, 8, 1) - img_at(&a, 8, 8, 1), fr * 0.5, 0.02 * fr * 0.5);
            CHECK_NEAR(img_at(&a, 0, 0, 0), 0.5, 1e-6); /* a corner misses the sphere */
            sss_image_free(&a);
            sss_image_free(&b);
        }
        free(table);
        tmesh_free(&sphere);
    }
    sss_image_free(&env);
    check_mirror_of_scene();
    return CHECK_DONE();
}
