/* dss (Deep Screen Space as seed 000 configures it, src/gl/tech_dss.c):
 *  - energy: a large flat plane lit at normal incidence by a directional light (E = 1) shows
 *    c_o F_t E rho_eff in the middle of the view (FACTS.md 1; rho_eff the plane integral of R_d, the
 *    scene material's PBD albedo; F_t and c from the physics module). The splats tile the plane and
 *    the disc-integrated kernel keeps each splat's integral A R'_d exact, so the spatial mean over many
 *    splats is exact up to the kernel's cut-off (splat_energy = 1: r_max, which holds at least
 *    lut_energy = 99.9%) and the LUT's tabulation: with half-pixel surfels within 0.75% (measured
 *    -0.05%, -0.08%, -0.14%). With the default 2-pixel surfels the blue kernel (mean free path 0.4
 *    pixel) is narrower than the surfel lattice, the image shows the lattice (pixel sd 10-15%) and a
 *    32 x 32 window's mean depends on where the lattice falls: measured -1.6% .. +2.5% for 1..8-pixel
 *    surfels (defaults, 4 pixels: -1.3%, -0.4%, -0.5%), bound 4% (the default splat_energy 0.99 also
 *    leaves out up to 1%);
 *  - linearity in the lights: two directional lights give the sum of the images of each alone;
 *  - the committed test scenes against their cached references (DSSIM, printed; bounds below), no
 *    NaN/Inf, and seed 000's ordering on the back-lit dragon (section 8.1, Fig. 6a): the splatting
 *    techniques beat the screen-space ones, here `ssss` and `screen`. */
#include <unistd.h>

#include "splat_plane_util.h"
#include "sss/material.h"

static void test_plane_energy(void)
{
    sss_scene scene;
    if (!plane_scene(0, 0, &scene)) {
        CHECK(0);
        return;
    }
    const sss_scene_material *m = &scene.objects[0].material;
    double eta = m->optical.eta;
    double ft = 1.0 - sss_fresnel_dielectric(1.0, 1.0, eta);
    double co = ft / (M_PI * sss_bssrdf_normalization(eta));
    sss_image fine, dflt;
    sss_gl_param_value p[2] = {{"splat_energy", 1.0}, {"surfel_pixels", 0.5}};
    CHECK(gt_render(&scene, "dss", 0.0, p, 2, &fine));
    CHECK(gt_render(&scene, "dss", 0.0, NULL, 0, &dflt));
    double mf[3], md[3];
    centre_mean(&fine, mf);
    centre_mean(&dflt, md);
    for (int c = 0; c < 3; c++) {
        double expect = co * ft * 1.0 * m->albedo[c];
        printf("plane channel %d: c_o F_t E rho_eff %.6f, dss (half-pixel surfels) %.6f (%+.2f%%), defaults %.6f "
               "(%+.2f%%)\n",
               c, expect, mf[c], 100.0 * (mf[c] / expect - 1.0), md[c], 100.0 * (md[c] / expect - 1.0));
        CHECK_REL(mf[c], expect, 0.0075);
        CHECK_REL(md[c], expect, 0.04);
    }
    CHECK(sss_image_count_nonfinite(&fine) == 0 && sss_image_count_nonfinite(&dflt) == 0);
    sss_image_free(&fine);
    sss_image_free(&dflt);
    sss_scene_free(&scene);
}

static void test_lights_add(void)
{
    sss_scene both, a, b;
    if (!plane_scene(1, 0, &both) || !plane_scene(0, 0, &a) || !plane_scene(0, 1, &b)) {
        CHECK(0);
        return;
    }
    sss_image ib, ia, ic;
    CHECK(gt_render(&both, "dss", 0.0, NULL, 0, &ib));
    CHECK(gt_render(&a, "dss", 0.0, NULL, 0, &ia));
    CHECK(gt_render(&b, "dss", 0.0, NULL, 0, &ic));
    double worst = 0.0;
    for (size_t i = 0; i < 3 * (size_t)ib.width * ib.height; i++) {
        double sum = ia.pixels[i] + ic.pixels[i];
        double d = fabs(ib.pixels[i] - sum) / (sum > 1e-6 ? sum : 1e-6);
        if (d > worst) worst = d;
    }
    printf("two lights vs the sum of each alone: largest relative difference %.2e\n", worst);
    CHECK(worst < 1e-3);
    sss_image_free(&ib);
    sss_image_free(&ia);
    sss_image_free(&ic);
    sss_scene_free(&both);
    sss_scene_free(&a);
    sss_scene_free(&b);
}

/* DSSIM against the cached reference below bound; returns it (1 on failure). */
static double scene_dssim(const char *file, const char *ref_name, const char *technique, double bound)
{
    sss_scene scene;
    if (!gt_load(file, &scene)) {
        CHECK(0);
        return 1.0;
    }
    sss_image ref, img;
    double d = 1.0;
    if (gt_read_ref(ref_name, &ref)) {
        if (gt_render(&scene, technique, 0.0, NULL, 0, &img)) {
            d = gt_dssim(&img, &ref);
            CHECK(sss_image_count_nonfinite(&img) == 0);
            sss_image_free(&img);
        }
        sss_image_free(&ref);
    }
    printf("%s, %s: DSSIM %.4f\n", file, technique, d);
    if (bound > 0.0) CHECK_MSG(d < bound, "%s %s: DSSIM %g >= %g", file, technique, d, bound);
    sss_scene_free(&scene);
    return d;
}

int main(void)
{
    (void)gt_mean;
    CHECK(write_grid("dss"));
    test_plane_energy();
    test_lights_add();
    /* Back-lit dragon: measured 0.026 (bound +1/3). The translucency dominates (seed 000, 8.1). */
    double d_bl = scene_dssim("gl_backlit.json", "ref_backlit.exr", "dss", 0.035);
    /* Front-lit head with a shadow edge: measured 0.061 — worse than `local` (0.040): the surfels of
     * the 4096-triangle splat mesh lie on its chords, a few pixels apart, and the Skin1 kernel is
     * narrower than that, so the tiling shows and the shadow edge blurs, as seed 000 reports for DSS
     * ("shadow edges are not preserved very well", section 8.1). The bound keeps it from getting worse. */
    scene_dssim("gl_shadow_edge.json", "ref_shadow_edge.exr", "dss", 0.07);
    /* seed 000's ordering on the back-lit scene */
    const char *others[] = {"ssss", "screen"};
    for (int i = 0; i < 2; i++) {
        if (!sss_gl_technique_find(others[i])) {
            printf("technique %s not registered: compared with local instead\n", others[i]);
            others[i] = "local";
        }
        double d = scene_dssim("gl_backlit.json", "ref_backlit.exr", others[i], 0.0);
        CHECK_MSG(d_bl < d, "dss %g does not beat %s %g on the back-lit scene", d_bl, others[i], d);
    }
    remove(grid_path);
    return CHECK_DONE();
}
