/* mertens2003 (Mertens et al. 2003, src/gl/techniques/mertens2003/tech_mertens2003.c):
 *  - unbiasedness: a large flat plane under a directional light at normal incidence, seen head-on,
 *    has B(x_o) = rho_eff E everywhere, so the pixels show c_o F_t E rho_eff (docs/physics.md §1; rho_eff the
 *    material's PBD albedo, F_t and c from the physics module). On the plane the sample p' is the
 *    surface point, r = r', the Jacobian is 1 and every sample finds the object, so the estimator is
 *    unbiased for the integral of the tabulated R_d (the LUT's row A = 0; the importance tables and
 *    the uniform disc cover all but 1e-5 of it). Checked twice against c_o F_t E rho_eff:
 *    (a) without interleaving (pattern 1, no blur) every pixel is an independent, unbiased estimate
 *        (its own random strata offsets): the mean of the central 32 x 32 pixels lies within 3
 *        standard errors (pixel sd / sqrt(n)) plus 0.1% for the LUT's tabulation of R_d (measured
 *        -0.014% with 360 samples per pixel, 0.07 standard errors);
 *    (b) with the default 4 x 4 interleaving, a 4 x 4 block covers every stratum once, so the block
 *        means (blur off) are the independent unbiased estimates: same test with their standard error;
 *        the blur (on by default) keeps the mean on the plane;
 *  - back lighting (section 7.1): on the back-lit dragon the camera's irradiance image alone (no light
 *    views) misses most of the light: its mean is below 40% of the reference's per channel (measured
 *    2-9%); with the light-view image the mean is within 20% (measured -8% .. -12%: samples reach
 *    only as far as the tangent-plane disc, and the Jacobian is off for the camera image, as in the
 *    paper), and the DSSIM less than half of the camera-only one;
 *  - the committed test scenes against their cached references (DSSIM, printed; bounds below), no
 *    NaN/Inf in any output. */
#include "gl_test_util.h"
#include "sss/material.h"

static int plane_scene(sss_scene *scene)
{
    const char *json =
        "{\"camera\": {\"position\": [0, 1, 0], \"look_at\": [0, 0, 0], \"up\": [0, 0, -1], \"fov\": 30,"
        " \"width\": 64, \"height\": 64},"
        " \"objects\": [{\"procedural\": {\"shape\": \"plane\", \"size\": 2.0},"
        " \"material\": {\"type\": \"subsurface\", \"medium\": \"Skin1\", \"scale\": 200.0, \"eta\": 1.33}}],"
        " \"lights\": [{\"type\": \"directional\", \"direction\": [0, -1, 0], \"radiance\": [1, 1, 1]}]}";
    sss_error err = {0};
    if (sss_scene_parse(json, strlen(json), ".", "plane", NULL, scene, &err) != SSS_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 0;
    }
    return 1;
}

/* Mean and standard error over the central 32 x 32 pixels of averages over block x block cells. */
static void block_stats(const sss_image *im, int block, double mean[3], double se[3])
{
    int x0 = im->width / 4, y0 = im->height / 4, n = im->width / 2 / block;
    double s[3] = {0, 0, 0}, s2[3] = {0, 0, 0};
    for (int by = 0; by < n; by++)
        for (int bx = 0; bx < n; bx++) {
            double b[3] = {0, 0, 0};
            for (int y = 0; y < block; y++)
                for (int x = 0; x < block; x++)
                    for (int c = 0; c < 3; c++)
                        b[c] += im->pixels[3 * ((size_t)(y0 + by * block + y) * im->width + x0 + bx * block + x) + c];
            for (int c = 0; c < 3; c++) {
                b[c] /= block * block;
                s[c] += b[c];
                s2[c] += b[c] * b[c];
            }
        }
    int m = n * n;
    for (int c = 0; c < 3; c++) {
        mean[c] = s[c] / m;
        double var = (s2[c] - m * mean[c] * mean[c]) / (m - 1);
        se[c] = sqrt(var > 0.0 ? var / m : 0.0);
    }
}

static void test_unbiased(void)
{
    sss_scene scene;
    if (!plane_scene(&scene)) {
        CHECK(0);
        return;
    }
    const sss_scene_material *m = &scene.objects[0].material;
    double co, ft = gt_normal_transmission(m, &co);
    /* the block of the pattern is the left-bottom aligned 4 x 4: the window starts at 16, a multiple */
    sss_gl_param_value plain[2] = {{"pattern", 1}, {"blur", 0}}, noblur = {"blur", 0};
    sss_image a, b, c;
    CHECK(gt_render(&scene, "mertens2003", 0.0, plain, 2, &a));
    CHECK(gt_render(&scene, "mertens2003", 0.0, &noblur, 1, &b));
    CHECK(gt_render(&scene, "mertens2003", 0.0, NULL, 0, &c));
    double ma[3], sa[3], mb[3], sb[3], mc[3], sc[3];
    block_stats(&a, 1, ma, sa);
    block_stats(&b, 4, mb, sb);
    block_stats(&c, 4, mc, sc);
    for (int ch = 0; ch < 3; ch++) {
        double expect = co * ft * 1.0 * m->albedo[ch];
        printf("channel %d: c_o F_t E rho_eff %.6f; pixels %.6f (%+.2f SE, SE %.2f%%), 4x4 blocks %.6f (%+.2f SE, "
               "SE %.2f%%), blurred %.6f\n",
               ch, expect, ma[ch], (ma[ch] - expect) / sa[ch], 100.0 * sa[ch] / expect, mb[ch],
               (mb[ch] - expect) / sb[ch], 100.0 * sb[ch] / expect, mc[ch]);
        CHECK(fabs(ma[ch] - expect) <= 3.0 * sa[ch] + 1e-3 * expect);
        CHECK(fabs(mb[ch] - expect) <= 3.0 * sb[ch] + 1e-3 * expect);
        CHECK(fabs(mc[ch] - expect) <= 3.0 * sb[ch] + 1e-3 * expect);
        CHECK(sa[ch] > 0.0 && sb[ch] > 0.0);
    }
    CHECK(sss_image_count_nonfinite(&a) == 0 && sss_image_count_nonfinite(&b) == 0 &&
          sss_image_count_nonfinite(&c) == 0);
    sss_image_free(&a);
    sss_image_free(&b);
    sss_image_free(&c);
    sss_scene_free(&scene);
}

static void test_backlit(void)
{
    sss_scene scene;
    if (!gt_load("gl_backlit.json", &scene)) {
        CHECK(0);
        return;
    }
    sss_image ref, img, cam;
    CHECK(gt_read_ref("ref_backlit.exr", &ref));
    sss_gl_param_value no_views = {"light_views", 0};
    CHECK(gt_render(&scene, "mertens2003", 0.0, NULL, 0, &img));
    CHECK(gt_render(&scene, "mertens2003", 0.0, &no_views, 1, &cam));
    double d = gt_dssim(&img, &ref), dc = gt_dssim(&cam, &ref);
    double mi[3], mc[3], mr[3];
    gt_mean(&img, mi);
    gt_mean(&cam, mc);
    gt_mean(&ref, mr);
    printf("backlit: DSSIM %.4f (camera image only %.4f); mean / reference: with light views (%.3f %.3f %.3f), "
           "camera only (%.3f %.3f %.3f)\n",
           d, dc, mi[0] / mr[0], mi[1] / mr[1], mi[2] / mr[2], mc[0] / mr[0], mc[1] / mr[1], mc[2] / mr[2]);
    /* measured 0.032 (bound +1/3); `local` measures 0.19 here */
    CHECK(d < 0.042);
    CHECK(dc > 2.0 * d);
    for (int c = 0; c < 3; c++) {
        CHECK(mc[c] < 0.4 * mr[c]);
        CHECK_REL(mi[c], mr[c], 0.2);
    }
    CHECK(sss_image_count_nonfinite(&img) == 0);
    sss_image_free(&ref);
    sss_image_free(&img);
    sss_image_free(&cam);
    sss_scene_free(&scene);
}

static void test_shadow_edge(void)
{
    sss_scene scene;
    if (!gt_load("gl_shadow_edge.json", &scene)) {
        CHECK(0);
        return;
    }
    sss_image ref, img;
    CHECK(gt_read_ref("ref_shadow_edge.exr", &ref));
    CHECK(gt_render(&scene, "mertens2003", 0.0, NULL, 0, &img));
    double d = gt_dssim(&img, &ref);
    printf("shadow edge: DSSIM %.4f\n", d);
    /* measured 0.037 (bound +1/3): the local response is right, but samples of the wide red kernel that
     * land on nearby folds (glasses, ear) weigh R_d(r) / R_d(r') >> 1 and leave red specks, the
     * undersampling artefacts Mertens et al. 2003 describe (section 7.1); `local` measures 0.040 */
    CHECK(d < 0.049);
    CHECK(sss_image_count_nonfinite(&img) == 0);
    sss_image_free(&ref);
    sss_image_free(&img);
    sss_scene_free(&scene);
}

int main(void)
{
    test_unbiased();
    test_backlit();
    test_shadow_edge();
    return CHECK_DONE();
}
