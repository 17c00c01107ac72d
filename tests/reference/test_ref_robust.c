/* Reference renderer, robustness: no NaN/Inf for every measured medium and eta in [1, 2] (Spectralon
 * has sigma_a = 0), with degenerate (zero-area) triangles in the mesh; bad worlds give errors naming
 * the field and no image; the same seed gives the identical image with 1 and 2 threads. */
#include "ref_test_util.h"

/* A sphere plus a few degenerate triangles (repeated index, collinear vertices, a tiny sliver). */
static void degenerate_sphere(tmesh *b)
{
    double c0[3] = {0, 0, 0};
    tmesh_sphere(b, c0, 1.0, 12);
    double p0[3] = {0, 1.2, 0}, p1[3] = {0.5, 1.2, 0}, p2[3] = {1.0, 1.2, 0}, n[3] = {0, 1, 0};
    uint32_t a = tmesh_vertex(b, p0, n), bb = tmesh_vertex(b, p1, n), c = tmesh_vertex(b, p2, n);
    tmesh_reserve(b, 0, 3);
    uint32_t *t = b->m.indices + 3 * b->m.triangle_count;
    t[0] = a, t[1] = a, t[2] = bb;     /* repeated index */
    t[3] = a, t[4] = bb, t[5] = c;     /* collinear */
    t[6] = 0, t[7] = 0, t[8] = 0;      /* a point */
    b->m.triangle_count += 3;
}

static void test_media(void)
{
    tmesh sphere = {0};
    degenerate_sphere(&sphere);
    tmesh ground = {0};
    tmesh_plane(&ground, 6.0, 0, -1.0, 0, 1, 0);
    const double etas[3] = {1.0, 1.33, 2.0};
    int renders = 0, clean = 0;
    for (size_t i = 0; i < sss_measured_medium_count(); i++) {
        const char *name = sss_measured_medium_at(i)->name;
        for (int e = 0; e < 3; e++) {
            sss_material m;
            sss_error err;
            CHECK(sss_material_from_medium(name, 1.0 + 3.0 * e, etas[e], &m, &err) == SSS_OK);
            sss_pbd_table *table;
            sss_reference_object objs[2] = {object_subsurface(&sphere.m, &m, &table), object_diffuse(&ground.m, 0.5)};
            if (i % 2) objs[0].profile = SSS_SCENE_PROFILE_DIPOLE;
            sss_light l[2] = {light_point(1.5, 2, -2, 10.0), light_directional(0.2, -1, -0.3, 0.5)};
            sss_reference_world w;
            memset(&w, 0, sizeof w);
            camera_set(&w.camera, 0, 0.5, 4, 0, 0, 0, 40, 16, 16);
            w.objects = objs, w.object_count = 2, w.lights = l, w.light_count = 2;
            sss_reference_desc d;
            memset(&d, 0, sizeof d);
            d.quality = SSS_REFERENCE_DRAFT;
            d.density = 1.0 / 16.0; /* finite, lit images at any density; the bounces' sample cap costs 16x less */
            sss_image img;
            sss_reference_stats st;
            renders++;
            if (render_or_die(&w, &d, &img, &st)) {
                int ok = sss_image_count_nonfinite(&img) == 0 && st.nonfinite_samples == 0 && img_max(&img) > 0.0;
                if (ok) clean++;
                else fprintf(stderr, "%s eta %g: non-finite or black image\n", name, etas[e]);
                sss_image_free(&img);
            }
            free(table);
        }
    }
    CHECK_MSG(clean == renders, "%d of %d renders clean", clean, renders);
    tmesh_free(&sphere);
    tmesh_free(&ground);
}

static void expect_error(const sss_reference_world *w, const char *needle)
{
    sss_image img;
    sss_error err;
    memset(&err, 0, sizeof err);
    img.pixels = (float *)&img; /* must be cleared on failure */
    sss_reference_desc d;
    memset(&d, 0, sizeof d);
    d.quality = SSS_REFERENCE_DRAFT;
    sss_result r = sss_reference_render_world(w, &d, &img, NULL, NULL, NULL, &err);
    CHECK_MSG(r != SSS_OK && strstr(err.message, needle) != NULL, "expected an error naming '%s', got %d: %s",
              needle, (int)r, err.message);
    CHECK(img.pixels == NULL && img.width == 0);
}

static void test_bad_worlds(void)
{
    tmesh sphere = {0};
    double c0[3] = {0, 0, 0};
    tmesh_sphere(&sphere, c0, 1.0, 8);
    sss_material m = material_coeffs(0.1, 0.1, 0.1, 1, 1, 1, 1.33);
    sss_pbd_table *table;
    sss_reference_object o = object_subsurface(&sphere.m, &m, &table);
    sss_light l = light_point(0, 2, 2, 1.0);
    sss_reference_world w;
    memset(&w, 0, sizeof w);
    camera_set(&w.camera, 0, 0, 4, 0, 0, 0, 40, 8, 8);
    w.objects = &o, w.object_count = 1, w.lights = &l, w.light_count = 1;

    w.camera.width = 0;
    expect_error(&w, "camera.width");
    w.camera.width = 8;
    w.camera.fov = 180.0;
    expect_error(&w, "camera.fov");
    w.camera.fov = 40.0;
    w.camera.look_at[2] = 4.0;
    expect_error(&w, "camera.look_at");
    w.camera.look_at[2] = 0.0;
    o.optical.sigma_a[1] = -0.5;
    expect_error(&w, "objects[0].material");
    o.optical.sigma_a[1] = 0.1;
    o.table = NULL;
    expect_error(&w, "objects[0].material");
    o.table = table;
    sphere.m.indices[5] = sphere.m.vertex_count + 3;
    expect_error(&w, "objects[0].mesh");
    sphere.m.indices[5] = 0;
    l.intensity[0] = -1.0;
    expect_error(&w, "lights[0].intensity");
    l.intensity[0] = 1.0;
    sss_light env;
    memset(&env, 0, sizeof env);
    env.type = SSS_LIGHT_ENVIRONMENT;
    env.scale[0] = env.scale[1] = env.scale[2] = 1.0;
    env.file = (char *)"/nonexistent/sky.exr";
    w.lights = &env;
    expect_error(&w, "lights[0].file");
    free(table);
    tmesh_free(&sphere);
}

static void test_determinism(void)
{
    tmesh box = {0}, ground = {0};
    double lo[3] = {-1, 0, -0.3}, hi[3] = {1, 1.2, 0.3};
    tmesh_box(&box, lo, hi, 4);
    tmesh_plane(&ground, 8.0, 0, 0, 0, 2, 0);
    sss_material m;
    sss_error err;
    CHECK(sss_material_from_medium("Marble", 5.0, 1.33, &m, &err) == SSS_OK);
    sss_pbd_table *table;
    sss_reference_object objs[2] = {object_subsurface(&box.m, &m, &table), object_diffuse(&ground.m, 0.5)};
    sss_light lights[2];
    lights[0] = light_point(0.5, 2.5, -2, 12.0);
    memset(&lights[1], 0, sizeof lights[1]);
    lights[1].type = SSS_LIGHT_AREA;
    lights[1].center[0] = 1.5, lights[1].center[1] = 2.5, lights[1].center[2] = 1.5;
    lights[1].u[0] = 0.4, lights[1].v[2] = 0.4;
    lights[1].radiance[0] = lights[1].radiance[1] = lights[1].radiance[2] = 4.0;
    sss_reference_world w;
    memset(&w, 0, sizeof w);
    camera_set(&w.camera, 1, 2, 4, 0, 0.5, 0, 40, 32, 24);
    w.objects = objs, w.object_count = 2, w.lights = lights, w.light_count = 2;
    sss_reference_desc d;
    memset(&d, 0, sizeof d);
    d.spp = 4;
    d.seed = 1234;
    d.density = 0.25; /* determinism holds at any density */
    sss_image a, b, c;
    d.threads = 1;
    CHECK(render_or_die(&w, &d, &a, NULL));
    d.threads = 2;
    CHECK(render_or_die(&w, &d, &b, NULL));
    d.seed = 1235;
    CHECK(render_or_die(&w, &d, &c, NULL));
    size_t bytes = sizeof(float) * 3 * (size_t)a.width * a.height;
    CHECK_MSG(memcmp(a.pixels, b.pixels, bytes) == 0, "1 and 2 threads differ");
    /* The seed matters (area-light sampling), so the comparison above is not vacuous. */
    CHECK(memcmp(a.pixels, c.pixels, bytes) != 0);
    sss_image_free(&a);
    sss_image_free(&b);
    sss_image_free(&c);
    free(table);
    tmesh_free(&box);
    tmesh_free(&ground);
}

int main(void)
{
    test_media();
    test_bad_worlds();
    test_determinism();
    return CHECK_DONE();
}
