/* maisch2020: surface hidden behind another object still scatters light (occluded_margin).
 *
 * A uniformly lit Skin1 plane (200 mm per unit: red 1 / sigma_tr ~ 0.018 units) seen head-on, with a
 * thin opaque bar floating between it and the camera (0.3 units above the plane, 0.04 wide). The light
 * travels at 45 degrees along the bar's normal, so the bar's shadow falls 0.3 units away, more than
 * ten red mean free paths from the pixels measured: the irradiance is uniform over all of the plane
 * that matters, the strip under the bar included. A uniformly lit plane is translation invariant, so
 * the plane's radiance next to the bar equals that of the open plane, c_o F_t E rho_eff (docs/physics.md §1:
 * the plane integral of R_d is rho_eff), whatever hides the strip from the camera.
 *
 * The strip under the bar faces the camera but is not seen by it: the screen-space pass cannot gather
 * it, and the paper's splat cull (Eq. 2 and 8: behind the G-buffer AND back-facing or grazing) drops
 * it too. Measured at 128 x 128, brightening off (energy-conserving, docs/maisch2020.md), in the band
 * 0.03..0.09 units from the bar's axis (the hidden strip ends at 0.029): occluded_margin 0 (the paper)
 * R -7.1%, G -2.5%, B -0.6% in the mean, -35% in the row next to the bar; with the default (3) the
 * strip is splatted: R +2.7%, G +3.1%, B +3.3% in the mean, 13% in the worst row (the splat's disc,
 * of the hidden part's area, reaches a little past the bar's edge, and the quarter-resolution
 * splatting blurs the strip's peak). Bounds: 5% in the mean, 17% in any row. The CPU reference
 * (sss reference, final quality) renders every row of the band within 0.06% of the closed form.
 * With outer_divisor=2 (the outer layers once per 2 x 2 block, upsampled) the blocks next to the bar
 * hold only plane pixels (the bar is another object) and the same bounds hold. */
#include "splat_plane_util.h"
#include "sss/material.h"

#define SIZE 128
#define FOV_DEG 30.0

static int bar_scene(sss_scene *scene)
{
    char json[2048];
    snprintf(json, sizeof json,
             "{\"camera\": {\"position\": [0, 1, 0], \"look_at\": [0, 0, 0], \"up\": [0, 0, -1], \"fov\": %g,"
             " \"width\": %d, \"height\": %d},"
             " \"objects\": [{\"mesh\": \"%s\","
             " \"material\": {\"type\": \"subsurface\", \"medium\": \"Skin1\", \"scale\": 200.0, \"eta\": 1.33}},"
             " {\"procedural\": {\"shape\": \"box\", \"size\": [1.2, 0.02, 0.04]}, \"transform\": {\"translate\": [0, 0.3, 0]},"
             " \"material\": {\"type\": \"diffuse\", \"reflectance\": [0.5, 0.5, 0.5]}}],"
             " \"lights\": [{\"type\": \"directional\", \"direction\": [0, -1, 1], \"radiance\": [1, 1, 1]}]}",
             FOV_DEG, SIZE, SIZE, grid_path);
    sss_error err = {0};
    if (sss_scene_parse(json, strlen(json), ".", "bar", NULL, scene, &err) != SSS_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 0;
    }
    return 1;
}

/* The plane's z under image row y (pixel centre), seen head-on from height 1. */
static double row_z(int y)
{
    double half = tan(FOV_DEG * M_PI / 360.0);
    return ((y + 0.5) / (SIZE / 2.0) - 1.0) * half;
}

/* Relative deviation from expect[] of the band's mean (per channel) and of its worst row mean. The
 * band: rows whose plane point lies 0.03..0.09 units from the bar's axis (the strip it hides reaches
 * 0.02 / (1 - 0.31) = 0.029; 0.09 is five red mean free paths), the central half of the columns (the
 * bar spans the whole width). */
static void band_error(const sss_image *im, const double expect[3], double mean_dev[3], double *worst_row)
{
    double sum[3] = {0, 0, 0};
    int rows = 0;
    *worst_row = 0.0;
    for (int y = 0; y < SIZE; y++) {
        double z = fabs(row_z(y));
        if (z < 0.03 || z > 0.09) continue;
        double row[3] = {0, 0, 0};
        for (int x = SIZE / 4; x < 3 * SIZE / 4; x++)
            for (int c = 0; c < 3; c++) row[c] += im->pixels[3 * ((size_t)y * SIZE + x) + c] / (SIZE / 2);
        for (int c = 0; c < 3; c++) {
            sum[c] += row[c];
            double d = fabs(row[c] / expect[c] - 1.0);
            if (d > *worst_row) *worst_row = d;
        }
        rows++;
    }
    for (int c = 0; c < 3; c++) mean_dev[c] = rows ? sum[c] / rows / expect[c] - 1.0 : 1.0;
}

int main(void)
{
    if (!write_grid("maisch_occluded")) {
        CHECK(0);
        return CHECK_DONE();
    }
    sss_scene scene;
    if (!bar_scene(&scene)) {
        CHECK(0);
        unlink(grid_path);
        return CHECK_DONE();
    }
    /* c_o F_t E rho_eff: view along the normal (c_o at normal incidence), light at 45 degrees */
    const sss_scene_material *m = &scene.objects[0].material;
    double co;
    gt_normal_transmission(m, &co);
    double cos_l = 1.0 / sqrt(2.0);
    double ft_l = 1.0 - sss_fresnel_dielectric(cos_l, 1.0, m->optical.eta);
    double expect[3];
    for (int c = 0; c < 3; c++) expect[c] = co * ft_l * cos_l * m->albedo[c];

    for (int fixed = 0; fixed <= 2; fixed++) {
        /* fixed = 1: the default occluded_margin; 0: the paper's cull; 2: the default with outer_divisor=2 */
        sss_gl_param_value p[2] = {{"brightening", 0}, {"occluded_margin", 0}};
        if (fixed == 2) p[1] = (sss_gl_param_value){"outer_divisor", 2};
        sss_image im;
        if (!gt_render(&scene, "maisch2020", 0.0, p, fixed == 1 ? 1 : 2, &im)) {
            CHECK(0);
            continue;
        }
        CHECK(sss_image_count_nonfinite(&im) == 0);
        double dev[3], worst;
        band_error(&im, expect, dev, &worst);
        printf("occluded_margin %s: band next to the bar vs c_o F_t E rho_eff: mean R %+.1f%% G %+.1f%% B %+.1f%%, "
               "worst row %.1f%%\n",
 fixed == 2 ? "default, outer_divisor=2" : fixed ? "default" : "0 (paper)", 100 * dev[0], 100 * dev[1], 100 * dev[2], 100 * worst);
        if (fixed) {
            for (int c = 0; c < 3; c++)
                CHECK_MSG(fabs(dev[c]) < 0.05, "channel %d: band mean %+.3f off the closed form", c, dev[c]);
            CHECK_MSG(worst < 0.17, "a row next to the bar is %.3f off the closed form", worst);
        }
        sss_image_free(&im);
    }
    sss_scene_free(&scene);
    unlink(grid_path);
    return CHECK_DONE();
}
