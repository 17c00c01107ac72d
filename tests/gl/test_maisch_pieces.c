/* maisch2020 under zoom with a coarse splat mesh (issue 32): a splat-mesh triangle larger than the view.
 *
 * The procedural plane is two triangles; here 100 x 100 units of Marble (4 mm per unit: red
 * 1 / sigma_tr ~ 2 units), seen head-on from 30 units at fov 40, 13 and 6.5 (the image spans 21.8, 6.8
 * and 3.4 units), under a directional light along the normal. A uniformly lit plane is translation
 * invariant: every pixel shows c_o F_t E rho_eff (docs/physics.md §1: the plane integral of R_d is
 * rho_eff; c_o at the pixel's view angle), the plane's edges lying 39 units (20 red mean free paths)
 * or more beyond the image. The screen-space part holds the plane on the image, the splats
 * (offscreen_splats) the rest, so the image's mean must be the closed form's, within 1.5%.
 *
 * Each triangle is larger than the view: with one splat per triangle (offscreen_pieces=0, as before
 * issue 32) its off-image part became one splat at the mean of its off-image sub-triangles' centroids,
 * of their summed area (a disc wider than the kernel's reach), with F_t E lifted half its size off the
 * plane: measured -3.2/-2.2/-1.6% at fov 40, -10/-8/-6% at 13, -19/-15/-13% at 6.5 (printed). The defaults cut a
 * triangle not wholly in the view into pieces of at most a translucency pixel at the view's edge, or
 * half their distance from the view farther out: -0.7/-0.5/-0.4%, -0.3/-0.1/-0.1%, -0.1/+0.3/+0.3%. */
#include "gl_test_util.h"
#include "sss/material.h"

#define SIZE 64
#define DIST 30.0

static int plane_scene(double fov, sss_scene *scene)
{
    char json[1024];
    snprintf(json, sizeof json,
             "{\"camera\": {\"position\": [0, 0, %g], \"look_at\": [0, 0, 0], \"up\": [0, 1, 0], \"fov\": %g,"
             " \"width\": %d, \"height\": %d},"
             " \"objects\": [{\"procedural\": {\"shape\": \"plane\", \"size\": 100}, \"transform\": {\"rotate\": [1, 0, 0, 90]},"
             " \"material\": {\"type\": \"subsurface\", \"medium\": \"Marble\", \"scale\": 4.0, \"eta\": 1.33}}],"
             " \"lights\": [{\"type\": \"directional\", \"direction\": [0, 0, -1], \"radiance\": [1, 1, 1]}]}",
             DIST, fov, SIZE, SIZE);
    sss_error err = {0};
    if (sss_scene_parse(json, strlen(json), ".", "plane", NULL, scene, &err) != SSS_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 0;
    }
    return 1;
}

/* The image's mean over the closed form's, per channel: c_o(view angle) F_t(1) E rho_eff at every pixel. */
static void mean_over_closed_form(const sss_image *img, const sss_scene *scene, double ratio[3])
{
    const sss_scene_material *m = &scene->objects[0].material;
    double eta = m->optical.eta, c = sss_bssrdf_normalization(eta);
    double ft_in = 1.0 - sss_fresnel_dielectric(1.0, 1.0, eta);
    double t = tan(0.5 * scene->camera.fov * M_PI / 180.0), got[3] = {0, 0, 0}, want = 0.0;
    for (int y = 0; y < SIZE; y++)
        for (int x = 0; x < SIZE; x++) {
            double sx = (2.0 * (x + 0.5) / SIZE - 1.0) * t, sy = (2.0 * (y + 0.5) / SIZE - 1.0) * t;
            double cos_o = 1.0 / sqrt(1.0 + sx * sx + sy * sy);
            want += (1.0 - sss_fresnel_dielectric(cos_o, 1.0, eta)) / (M_PI * c) * ft_in;
            for (int k = 0; k < 3; k++) got[k] += img->pixels[3 * ((size_t)y * SIZE + x) + k];
        }
    for (int k = 0; k < 3; k++) ratio[k] = got[k] / (want * m->albedo[k]);
}

int main(void)
{
    static const double fovs[3] = {40.0, 13.0, 6.5};
    for (int f = 0; f < 3; f++) {
        sss_scene scene;
        if (!plane_scene(fovs[f], &scene)) {
            CHECK(0);
            continue;
        }
        for (int pieces = 1; pieces >= 0; pieces--) {
            sss_gl_param_value p = {"offscreen_pieces", 0};
            sss_image img;
            if (!gt_render(&scene, "maisch2020", 0.0, &p, pieces ? 0 : 1, &img)) {
                CHECK(0);
                continue;
            }
            CHECK(sss_image_count_nonfinite(&img) == 0);
            double r[3];
            mean_over_closed_form(&img, &scene, r);
            printf("fov %4.1f %-20s mean / c_o F_t E rho_eff: %.4f %.4f %.4f\n", fovs[f],
                   pieces ? "default" : "offscreen_pieces=0", r[0], r[1], r[2]);
            for (int k = 0; pieces && k < 3; k++)
                CHECK_MSG(fabs(r[k] - 1.0) < 0.015, "fov %g channel %d: mean %.4f of the closed form's", fovs[f], k,
                          r[k]);
            sss_image_free(&img);
        }
        sss_scene_free(&scene);
    }
    return CHECK_DONE();
}
