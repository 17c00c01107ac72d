/* Reference renderer, energy and translucency: a 10-unit sphere lit from behind shows light on its
 * front for a medium whose mean free path is comparable to the object (Marble, scale 0.03 mm per unit)
 * and almost none for Ketchup at scale 1 (where green and blue die within a few units); scaling every
 * light (point, area, environment) by k scales the image by k. */
#include "ref_test_util.h"

/* Front-centre radiance of a sphere of radius 5 lit from behind, relative to the radiance of its lit
 * back seen from the light's side, per channel. */
static void backlit_ratio(const char *medium, double scale, double ratio[3])
{
    tmesh sphere = {0};
    double c0[3] = {0, 0, 0};
    tmesh_sphere(&sphere, c0, 5.0, 40);
    sss_material m;
    sss_error err;
    CHECK(sss_material_from_medium(medium, scale, 1.33, &m, &err) == SSS_OK);
    sss_pbd_table *table;
    sss_reference_object o = object_subsurface(&sphere.m, &m, &table);
    sss_light l = light_point(0, 0, -30, 900.0);
    sss_reference_world w;
    memset(&w, 0, sizeof w);
    w.objects = &o, w.object_count = 1, w.lights = &l, w.light_count = 1;
    sss_reference_desc d;
    memset(&d, 0, sizeof d);
    d.bounces = 1; /* the single-event integral the closed forms describe */
    d.quality = SSS_REFERENCE_DRAFT;
    sss_image front, back;
    camera_set(&w.camera, 0, 0, 30, 0, 0, 0, 25, 24, 24);
    int ok = render_or_die(&w, &d, &front, NULL);
    camera_set(&w.camera, 0, 0, -30, 0, 0, 0, 25, 24, 24);
    ok = ok && render_or_die(&w, &d, &back, NULL);
    CHECK(ok);
    for (int c = 0; c < 3; c++) {
        double f = 0.0, b = 0.0;
        for (int y = 10; y < 14; y++)
            for (int x = 10; x < 14; x++) f += img_at(&front, x, y, c), b += img_at(&back, x, y, c);
        ratio[c] = ok && b > 0.0 ? f / b : -1.0;
    }
    if (ok) {
        sss_image_free(&front);
        sss_image_free(&back);
    }
    free(table);
    tmesh_free(&sphere);
}

static void test_backlit(void)
{
    double rm[3], rk[3];
    /* Marble x 0.03: sigma_t' = 0.066 .. 0.09 per unit, a mean free path of 11 .. 15 units. */
    backlit_ratio("Marble", 0.03, rm);
    /* Ketchup x 1: green and blue sigma_tr = sqrt(3 sigma_a sigma_t') = 1.7 and 2.5 per unit. */
    backlit_ratio("Ketchup", 1.0, rk);
    printf("front/back: marble %.3g %.3g %.3g, ketchup %.3g %.3g %.3g\n", rm[0], rm[1], rm[2], rk[0], rk[1], rk[2]);
    for (int c = 0; c < 3; c++) CHECK_MSG(rm[c] > 0.05, "marble channel %d: front/back %g", c, rm[c]);
    /* Diffusion through 10 units: e^(-17) and less for green and blue. */
    CHECK_MSG(rk[1] >= 0.0 && rk[1] < 1e-4 && rk[2] >= 0.0 && rk[2] < 1e-4, "ketchup: front/back %g %g", rk[1], rk[2]);
    /* Red (sigma_tr = 0.21 per unit) still glows a little, far less than marble. */
    CHECK_MSG(rk[0] >= 0.0 && rk[0] < 0.5 * rm[0], "ketchup red: %g vs marble %g", rk[0], rm[0]);
}

/* Every light x k gives the image x k (no adaptive refinement: its decisions see tone-mapped values). */
static void test_linearity(void)
{
    tmesh box = {0}, ground = {0};
    double lo[3] = {-1, 0, -1}, hi[3] = {1, 1.5, 1};
    tmesh_box(&box, lo, hi, 6);
    tmesh_plane(&ground, 12.0, 0, 0, 0, 2, 0);
    sss_material m;
    sss_error err;
    CHECK(sss_material_from_medium("Skin1", 10.0, 1.4, &m, &err) == SSS_OK);
    sss_pbd_table *table;
    sss_reference_object objs[2] = {object_subsurface(&box.m, &m, &table), object_diffuse(&ground.m, 0.4)};
    sss_image env;
    CHECK(sss_image_create(&env, 16, 8, &err) == SSS_OK);
    for (int i = 0; i < 16 * 8 * 3; i++) env.pixels[i] = (float)(0.05 + 0.01 * (i % 7));
    sss_light lights[3];
    lights[0] = light_point(2, 3, -2, 20.0);
    memset(&lights[1], 0, sizeof lights[1]);
    lights[1].type = SSS_LIGHT_AREA;
    lights[1].center[0] = -2, lights[1].center[1] = 3, lights[1].center[2] = 1;
    lights[1].u[0] = 0.5, lights[1].v[2] = 0.5;
    lights[1].radiance[0] = 3, lights[1].radiance[1] = 2, lights[1].radiance[2] = 1;
    memset(&lights[2], 0, sizeof lights[2]);
    lights[2].type = SSS_LIGHT_ENVIRONMENT;
    lights[2].scale[0] = lights[2].scale[1] = lights[2].scale[2] = 1.0;
    const sss_image *maps[3] = {NULL, NULL, &env};
    sss_reference_world w;
    memset(&w, 0, sizeof w);
    camera_set(&w.camera, 3, 3, 5, 0, 0.5, 0, 35, 32, 24);
    w.objects = objs, w.object_count = 2, w.lights = lights, w.light_count = 3, w.environment_maps = maps;
    sss_reference_desc d;
    memset(&d, 0, sizeof d);
    d.bounces = 1; /* the single-event integral the closed forms describe */
    d.quality = SSS_REFERENCE_DRAFT;
    d.no_adaptive = 1;
    d.seed = 42;
    sss_image a, b;
    CHECK(render_or_die(&w, &d, &a, NULL));
    const double k = 2.5;
    lights[0].intensity[0] *= k, lights[0].intensity[1] *= k, lights[0].intensity[2] *= k;
    for (int c = 0; c < 3; c++) lights[1].radiance[c] *= k, lights[2].scale[c] *= k;
    CHECK(render_or_die(&w, &d, &b, NULL));
    double dev = 0.0, mx = img_max(&a);
    for (size_t i = 0; i < 3 * (size_t)a.width * a.height; i++) dev = fmax(dev, fabs(b.pixels[i] - k * a.pixels[i]));
    CHECK_MSG(mx > 0.0 && dev <= 1e-5 * k * mx, "lights x %g: image off by %g (max %g)", k, dev, k * mx);
    sss_image_free(&a);
    sss_image_free(&b);
    sss_image_free(&env);
    free(table);
    tmesh_free(&box);
    tmesh_free(&ground);
}

int main(void)
{
    test_backlit();
    test_linearity();
    return CHECK_DONE();
}
