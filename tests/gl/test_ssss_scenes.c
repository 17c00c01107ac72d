/* ssss, ssss-gauss6, ssss-svd and screen against the CPU ground truth on the two committed test scenes
 * of issue 5 (cached references of test_gl_scenes: tests/data/gl/ref_backlit.exr, ref_shadow_edge.exr),
 * default parameters: no NaN/Inf, DSSIM printed and bounded.
 *
 * Bounds: the DSSIM measured when the test was written (llvmpipe, Mesa 22.3) plus about a third for
 * drift (kernel construction, driver rounding), as test_gl_scenes does. Techniques that model the
 * effect must also beat `local` (no transport between points; 0.19 back-lit, 0.040 shadow edge).
 *   technique     back-lit dragon   shadow edge (head, Skin1)
 *   maisch2020    0.052             0.018        (test_gl_scenes)
 *   screen        0.17  -> 0.23     0.018 -> 0.024
 *   ssss          0.041 -> 0.055    0.017 -> 0.023
 *   ssss-gauss6   0.18  -> 0.23     0.026 -> 0.034
 *   ssss-svd      0.037 -> 0.05     0.017 -> 0.023
 * screen and ssss-gauss6 miss the back-lit dragon's light: the screen-space pass sees only the visible
 * surface (Maisch & Ropinski 2020, section 8.1), and the six-Gaussian fit is skin's (variances in mm at 1000 mm per
 * unit: its transmittance T(s) vanishes beyond ~3 mm of Skimmilk), so they are bounded from above only.
 * ssss and ssss-svd get the back-lit light from the transmittance through thin parts (Jimenez et al.
 * 2010, from the shadow map); without it ssss measures 0.186, which is what Maisch & Ropinski 2020 compare against
 * (its SSSS [JZJ*15] is the screen-space filter; Fig. 9 adds translucency only in a separate variant).
 * Here maisch2020 must beat screen and ssss without transmittance. With the transmittance (the default,
 * as the SSSS reference code) ssss measures 0.041 at this size, below maisch2020's 0.052, whose
 * quarter-resolution translucency is only 32 x 32 pixels at 128 px: Maisch & Ropinski 2020's full ordering (against
 * ssss with transmittance too) is asserted at 256 x 256 by test_ordering.c. */
#include "gl_test_util.h"

typedef struct row {
    const char *technique;
    double bound_backlit, bound_edge;
    int beats_local_backlit;
} row;

static const row rows[] = {
    {"screen", 0.23, 0.024, 0},
    {"ssss", 0.055, 0.023, 1},
    {"ssss-gauss6", 0.23, 0.034, 0},
    {"ssss-svd", 0.05, 0.023, 1},
};
#define ROWS ((int)(sizeof rows / sizeof rows[0]))

int main(void)
{
    const char *files[2] = {"gl_backlit.json", "gl_shadow_edge.json"};
    const char *refs[2] = {"ref_backlit.exr", "ref_shadow_edge.exr"};
    double measured[2][ROWS];
    for (int s = 0; s < 2; s++) {
        sss_scene scene;
        sss_image ref;
        if (!gt_load(files[s], &scene)) {
            CHECK(0);
            continue;
        }
        CHECK(gt_read_ref(refs[s], &ref));
        double d_local = gt_technique_dssim(&scene, &ref, "local", NULL, 0);
        double d_maisch = gt_technique_dssim(&scene, &ref, "maisch2020", NULL, 0);
        printf("%s: maisch2020 %.4f, local %.4f\n", files[s], d_maisch, d_local);
        for (int i = 0; i < ROWS; i++) {
            double d = measured[s][i] = gt_technique_dssim(&scene, &ref, rows[i].technique, NULL, 0);
            double bound = s == 0 ? rows[i].bound_backlit : rows[i].bound_edge;
            printf("%s: %-12s DSSIM %.4f (bound %.3f)\n", files[s], rows[i].technique, d, bound);
            CHECK_MSG(d < bound, "%s on %s: DSSIM %g >= %g", rows[i].technique, files[s], d, bound);
            if (s == 1 || rows[i].beats_local_backlit) CHECK_MSG(d < d_local, "%s does not beat local", rows[i].technique);
        }
        if (s == 0) {
            sss_gl_param_value off = {"transmittance", 0};
            double d_plain = gt_technique_dssim(&scene, &ref, "ssss", &off, 1);
            printf("%s: ssss without transmittance %.4f\n", files[s], d_plain);
            /* Maisch & Ropinski 2020, section 8.1 and Fig. 10: the splatting translucency wins where light comes from
             * surfaces the screen does not see */
            CHECK(d_maisch < measured[0][0]);
            CHECK(d_maisch < d_plain);
        }
        sss_image_free(&ref);
        sss_scene_free(&scene);
    }
    return CHECK_DONE();
}
