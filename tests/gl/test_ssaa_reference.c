/* Supersampling antialiasing brings the techniques closer to the ground truth: the CPU reference
 * (single-event copies of scenes/references/ in tests/data/gl/, `sss reference --bounces 1`) integrates every pixel's
 * footprint with stratified camera samples, so its silhouettes are antialiased, and at k = 1 every
 * technique's DSSIM against it includes the aliasing of its silhouettes, which has nothing to do with
 * subsurface scattering. With k = 2 the box filter integrates the same footprint with 4 samples: the
 * DSSIM must drop, by at least 10% (measured: local on the head of eval_front 0.0261 -> 0.0216, -17%;
 * maisch2020 on the thin tube of eval_trefoil_low, all silhouette, 0.0150 -> 0.0104, -30%). */
#include "gl_test_util.h"

static void check_scene(const char *file, const char *ref_file, const char *technique)
{
    sss_scene scene;
    sss_image ref;
    char path[1024];
    snprintf(path, sizeof path, "%s/gl/ref_%s", SSS_TEST_DATA, ref_file);
    sss_error err = {0};
    if (!gt_load(file, &scene)) {
        CHECK(0);
        return;
    }
    if (sss_image_read(path, &ref, &err) != SSS_OK) {
        fprintf(stderr, "%s\n", err.message);
        CHECK(0);
        sss_scene_free(&scene);
        return;
    }
    sss_image a, b;
    if (gt_render_k(&scene, technique, 0.0, NULL, 0, 1, &a) && gt_render_k(&scene, technique, 0.0, NULL, 0, 2, &b)) {
        CHECK(sss_image_count_nonfinite(&b) == 0);
        double d1 = gt_dssim(&a, &ref), d2 = gt_dssim(&b, &ref);
        printf("%s, %s: DSSIM k = 1 %.4f, k = 2 %.4f (%+.0f%%)\n", file, technique, d1, d2, 100.0 * (d2 / d1 - 1.0));
        CHECK_MSG(d2 < 0.9 * d1, "%s %s: supersampling does not bring it closer to the reference (%.4f vs %.4f)",
                  file, technique, d2, d1);
        sss_image_free(&a);
        sss_image_free(&b);
    } else {
        CHECK_MSG(0, "%s %s failed to render", file, technique);
    }
    sss_image_free(&ref);
    sss_scene_free(&scene);
}

int main(void)
{
    check_scene("eval_front.json", "eval_front_384x384.exr", "local");
    check_scene("eval_trefoil_low.json", "eval_trefoil_low_384x384.exr", "maisch2020");
    return CHECK_DONE();
}
