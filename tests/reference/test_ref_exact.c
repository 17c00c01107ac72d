/* Reference renderer: the hierarchical sum against the brute-force sum (--exact) over the same surface
 * samples, on a sphere lit from the side, a thin slab (box) and a torus lit from behind: relative
 * difference under 0.5% per pixel where the exact value is above 1% of the image maximum. */
#include "ref_test_util.h"

static void compare_modes(const char *label, sss_reference_world *w)
{
    sss_reference_desc d;
    memset(&d, 0, sizeof d);
    d.bounces = 1; /* the direct sums that the tree and brute force both evaluate */
    d.quality = SSS_REFERENCE_FINAL;
    d.spp = 1;
    d.no_adaptive = 1;
    d.seed = 11;
    sss_image hier, exact;
    sss_reference_stats sh, se;
    CHECK(render_or_die(w, &d, &hier, &sh));
    d.exact = 1;
    CHECK(render_or_die(w, &d, &exact, &se));
    if (!hier.pixels || !exact.pixels) return;
    CHECK(sh.surface_samples == se.surface_samples && sh.surface_samples > 1000);
    /* The tree must actually prune (otherwise this test proves nothing about it). */
    CHECK_MSG(sh.nodes_per_lookup < 0.5 * se.nodes_per_lookup, "%s: %g vs %g visits per sum", label,
              sh.nodes_per_lookup, se.nodes_per_lookup);
    double mx = img_max(&exact), worst = 0.0;
    size_t counted = 0;
    for (int y = 0; y < exact.height; y++)
        for (int x = 0; x < exact.width; x++)
            for (int c = 0; c < 3; c++) {
                double e = img_at(&exact, x, y, c), h = img_at(&hier, x, y, c);
                if (e <= 0.01 * mx) continue;
                counted++;
                worst = fmax(worst, fabs(h - e) / e);
            }
    CHECK_MSG(counted > 300, "%s: only %zu pixels above 1%% of the maximum", label, counted);
    CHECK_MSG(worst < 0.005, "%s: worst relative difference %.4g", label, worst);
    printf("%s: %llu samples, %.0f vs %.0f visits per sum, worst relative difference %.3g over %zu values\n",
           label, (unsigned long long)sh.surface_samples, sh.nodes_per_lookup, se.nodes_per_lookup, worst, counted);
    sss_image_free(&hier);
    sss_image_free(&exact);
}

int main(void)
{
    sss_error err;
    sss_material marble;
    CHECK(sss_material_from_medium("Marble", 2.0, 1.33, &marble, &err) == SSS_OK); /* mfp ~ 0.2 */
    sss_pbd_table *table;
    sss_reference_world w;

    /* A sphere lit from the side (a terminator through the middle). */
    tmesh sphere = {0};
    double c0[3] = {0, 0, 0};
    tmesh_sphere(&sphere, c0, 1.0, 40);
    sss_reference_object o = object_subsurface(&sphere.m, &marble, &table);
    sss_light l1 = light_directional(-1, -0.2, -0.3, 2.0);
    memset(&w, 0, sizeof w);
    camera_set(&w.camera, 0, 0, 4, 0, 0, 0, 40, 40, 40);
    w.objects = &o, w.object_count = 1, w.lights = &l1, w.light_count = 1;
    compare_modes("sphere, side light", &w);

    /* A thin slab (box 2 x 2 x 0.15) lit from behind by a point light. */
    tmesh slab = {0};
    double lo[3] = {-1, -1, -0.075}, hi[3] = {1, 1, 0.075};
    tmesh_box(&slab, lo, hi, 8);
    o.mesh = &slab.m;
    sss_light l2 = light_point(0.4, 0.3, -1.5, 6.0);
    w.lights = &l2;
    camera_set(&w.camera, 0.3, 0.2, 4, 0, 0, 0, 40, 40, 40);
    compare_modes("slab, back light", &w);

    /* A torus lit from behind. */
    tmesh torus = {0};
    tmesh_torus(&torus, c0, 1.0, 0.35, 48);
    o.mesh = &torus.m;
    sss_light l3 = light_point(0.2, 1.5, -2.5, 10.0);
    w.lights = &l3;
    camera_set(&w.camera, 0, 2.0, 3.5, 0, 0, 0, 40, 40, 40);
    compare_modes("torus, back light", &w);

    tmesh_free(&sphere);
    tmesh_free(&slab);
    tmesh_free(&torus);
    free(table);
    return CHECK_DONE();
}
