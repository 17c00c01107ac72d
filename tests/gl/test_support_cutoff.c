/* tests/gl/test_support_cutoff.c — maisch2020's and screen's support_cutoff skips outer layers that lie
 * wholly beyond the kernel's support r_max at the pixel's depth. It must be exact: their samples add
 * nothing (R'_d is 0 past r_max), so the image equals the one that reads every layer, up to float
 * rounding of the shader compiler, at every zoom — near (no layer skipped), far (most skipped).
 * maisch2020 renders without its splatted translucency, which the cutoff does not touch and whose
 * additive blending sums in an order that varies between frames (up to 1.2e-4 of the image). */
#include "gl_test_util.h"

static int load_view(double distance, sss_scene *scene)
{
    char text[1024];
    int n = snprintf(text, sizeof text,
                     "{\"camera\": {\"position\": [0, 0.3, %g], \"look_at\": [0, 0, 0], \"fov\": 30, \"width\": 96,"
                     " \"height\": 64},"
                     " \"objects\": [{\"procedural\": {\"shape\": \"sphere\", \"radius\": 1, \"subdivisions\": 3},"
                     " \"material\": {\"type\": \"subsurface\", \"medium\": \"Marble\", \"scale\": 10}},"
                     " {\"procedural\": {\"shape\": \"torus\", \"major\": 1.6, \"minor\": 0.3},"
                     " \"material\": {\"type\": \"subsurface\", \"medium\": \"Skin1\", \"scale\": 20}}],"
                     " \"lights\": [{\"type\": \"point\", \"position\": [2, 3, -2], \"intensity\": [20, 20, 20]},"
                     " {\"type\": \"directional\", \"direction\": [-0.3, -1, -0.5], \"radiance\": [1, 1, 1]}]}",
                     distance);
    sss_error err = {0};
    if (sss_scene_parse(text, (size_t)n, ".", "support_cutoff", NULL, scene, &err) != SSS_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 0;
    }
    return 1;
}

int main(void)
{
    const char *techs[] = {"maisch2020", "screen"};
    const double distances[] = {2.5, 6, 25};
    for (size_t d = 0; d < sizeof distances / sizeof *distances; d++) {
        sss_scene scene;
        if (!load_view(distances[d], &scene)) {
            CHECK(0);
            continue;
        }
        for (int t = 0; t < 2; t++) {
            sss_gl_param_value all[] = {{"support_cutoff", 0}, {"translucency", 0}},
                               cut[] = {{"support_cutoff", 1}, {"translucency", 0}};
            sss_image a, b;
            if (!gt_render_k(&scene, techs[t], 0.0, all, t == 0 ? 2 : 1, 0, &a)) {
                CHECK(0);
                continue;
            }
            if (gt_render_k(&scene, techs[t], 0.0, cut, t == 0 ? 2 : 1, 0, &b)) {
                double max = 0.0, diff = 0.0;
                for (size_t i = 0; i < (size_t)a.width * a.height * 3; i++) {
                    max = fmax(max, a.pixels[i]);
                    diff = fmax(diff, fabs((double)a.pixels[i] - b.pixels[i]));
                }
                CHECK_MSG(max > 0.0 && diff <= 1e-4 * max, "%s at distance %g: differs by %g (max %g)", techs[t],
                          distances[d], diff, max);
                printf("%s at distance %g: max difference %.3g of %.3g\n", techs[t], distances[d], diff, max);
                sss_image_free(&b);
            } else {
                CHECK(0);
            }
            sss_image_free(&a);
        }
        sss_scene_free(&scene);
    }
    return CHECK_DONE();
}
