/* Maisch & Ropinski 2020's ordering on the back-lit scene (section 8.1, Fig. 6a; issue 5): the techniques with a
 * translucency part — maisch2020, dss, chen2012 — beat the screen-space ones — screen and ssss (with
 * its shadow-map transmittance, its default as in the SSSS reference code) — in DSSIM against the CPU
 * ground truth (tests/data/gl/ref_backlit256.exr).
 *
 * Why 256 x 256 and not the 128 x 128 of the other GL tests: maisch2020 splats its translucency at a
 * quarter of the resolution (section 5), which at 128 px is a 32 x 32 image — below the resolutions
 * the paper works at — and there its blur of the dragon's thin spikes cost it the comparison with
 * ssss (0.052 vs 0.041). At 256 px (64 x 64 translucency) the paper's claim is measurable. Measured
 * (llvmpipe, Mesa 22.3): maisch2020 0.024, dss 0.017, chen2012 0.015 vs ssss 0.034, screen 0.133. */
#include "gl_test_util.h"

int main(void)
{
    sss_scene scene;
    sss_image ref;
    if (!gt_load("gl_backlit256.json", &scene) || !gt_read_ref("ref_backlit256.exr", &ref)) {
        CHECK(0);
        return CHECK_DONE();
    }
    const char *winners[3] = {"maisch2020", "dss", "chen2012"};
    const char *losers[2] = {"screen", "ssss"};
    double dw[3], dl[2];
    for (int i = 0; i < 2; i++) {
        dl[i] = gt_technique_dssim(&scene, &ref, losers[i], NULL, 0);
        printf("back-lit 256: %-10s DSSIM %.4f\n", losers[i], dl[i]);
    }
    for (int i = 0; i < 3; i++) {
        dw[i] = gt_technique_dssim(&scene, &ref, winners[i], NULL, 0);
        printf("back-lit 256: %-10s DSSIM %.4f\n", winners[i], dw[i]);
        for (int j = 0; j < 2; j++)
            CHECK_MSG(dw[i] < dl[j], "%s (%.4f) does not beat %s (%.4f) on the back-lit scene", winners[i], dw[i],
                      losers[j], dl[j]);
    }
    sss_image_free(&ref);
    sss_scene_free(&scene);
    return CHECK_DONE();
}
