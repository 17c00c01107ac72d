/* dss (Deep Screen Space as Maisch & Ropinski 2020 configure it, src/gl/techniques/dss/tech_dss.c):
 *  - energy: a large flat plane lit at normal incidence by a directional light (E = 1) shows
 *    c_o F_t E rho_eff in the middle of the view (docs/physics.md §1; rho_eff the plane integral of R_d, the
 *    scene material's PBD albedo; F_t and c from the physics module). The splats tile the plane and
 *    the disc-integrated kernel keeps each splat's integral A R'_d exact, so the spatial mean over many
 *    splats is exact up to the kernel's cut-off (splat_energy = 1: r_max, which holds at least
 *    lut_energy = 99.9%) and the LUT's tabulation: with half-pixel surfels within 0.75% (measured
 *    -0.02%, -0.02%, -0.03%). With the default 4-pixel surfels the blue kernel (mean free path 0.4
 *    pixel) is narrower than the surfel lattice: with one disc of each surfel's area (footprint = 0)
 *    the image showed the lattice (pixel sd 10-15%) and a 32 x 32 window's mean depended on where the
 *    lattice fell (-1.6% .. +2.5% for 1..8-pixel surfels); the default footprint smooths it
 *    (test_dss_lattice; defaults measured -1.45%, -0.11%, -0.19%), bound 4% (the default splat_energy
 *    0.99 leaves out up to 1% of the red);
 *  - linearity in the lights: two directional lights give the sum of the images of each alone;
 *  - the committed test scenes against their cached references (DSSIM, printed; bounds below), no
 *    NaN/Inf, and Maisch & Ropinski 2020's ordering on the back-lit dragon (section 8.1, Fig. 6a): the splatting
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
    double co, ft = gt_normal_transmission(m, &co);
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

int main(void)
{
    CHECK(write_grid("dss"));
    test_plane_energy();
    plane_lights_add("dss", NULL, 0);
    /* Back-lit dragon: measured 0.030 (0.026 with footprint = 0; bound 0.035). The translucency
     * dominates (Maisch & Ropinski 2020, 8.1). */
    double d_bl = gt_scene_dssim("gl_backlit.json", "ref_backlit.exr", "dss", 0.035);
    /* Front-lit head with a shadow edge: measured 0.029, better than `local` (0.040). The surfels are
     * a few pixels apart and the Skin1 kernel is narrower than that: with one disc of each surfel's own
     * area (footprint = 0) their lattice showed, 0.045 (0.061 with the surfels on the splat mesh's
     * chords too, surface_snap = 0; test_dss_chords); the shadow edge still blurs, as Maisch & Ropinski 2020 report
     * for DSS ("shadow edges are not preserved very well", section 8.1). Bound +1/3: 0.039. */
    gt_scene_dssim("gl_shadow_edge.json", "ref_shadow_edge.exr", "dss", 0.039);
    /* Maisch & Ropinski 2020's ordering on the back-lit scene */
    const char *others[] = {"ssss", "screen"};
    for (int i = 0; i < 2; i++) {
        if (!sss_gl_technique_find(others[i])) {
            printf("technique %s not registered: compared with local instead\n", others[i]);
            others[i] = "local";
        }
        double d = gt_scene_dssim("gl_backlit.json", "ref_backlit.exr", others[i], 0.0);
        CHECK_MSG(d_bl < d, "dss %g does not beat %s %g on the back-lit scene", d_bl, others[i], d);
    }
    remove(grid_path);
    return CHECK_DONE();
}
