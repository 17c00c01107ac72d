/* dss's surfel lattice must not print into the image (footprint, shell_splat.frag.glsl; docs/dss.md).
 *
 * A uniformly lit plane scatters light uniformly: the reference image of its middle is flat (docs/physics.md
 * 1: c_o F_t E rho_eff at every pixel, whatever R_d's width). dss tessellates the splat mesh's
 * triangles into surfels a few pixels apart, and Skin1's blue kernel (1/sigma_tr 0.4 pixel here) is
 * far narrower than that, so the image shows what the surfels' footprints add up to. With one disc of
 * each surfel's own area (footprint = 0, the code before) the discs do not tile the plane: the
 * lattice printed into the image, and on thin triangles, whose area is small against the lattice's
 * spacing h, stripes across them. The default footprint (three discs of radii 0.5, 0.75, 1 times h)
 * must keep each channel's pixels within a few percent of their mean, and that mean, the plane's
 * energy, at c_o F_t E rho_eff (splat_energy 1: the kernel's whole reach).
 *
 *  - The plane of test_dss (32 x 32 grid cells of 7.5 pixels: sub-triangles of ~3.5-pixel edges) at
 *    the default surfel_pixels 4, lit head-on (E = 1), 64 x 64 pixels, the central 32 x 32: relative
 *    standard deviation per channel below 5% (measured 1.1%, 2.3%, 3.7%; footprint = 0: 11%, 22%,
 *    34%), mean within 1% of c_o F_t E rho_eff (measured -0.1%, -0.1%, -0.2%).
 *  - The same plane from 4 x 32 cells of 8:1 (sub-triangles 3.8 x 0.47 pixels): the same bounds
 *    (measured 0.2%, 0.5%, 0.9%, means -0.1..-0.3%; footprint = 0: stripes, 30%, 56%, 78%, means
 *    +0.3..+1.2%).
 *  - footprint = 0's deviation must exceed the default's (the test sees the lattice). */
#include "splat_plane_util.h"

/* Mean and relative standard deviation per channel of the central half of the image. */
static void centre_stats(const sss_image *im, double mean[3], double rsd[3])
{
    double s[3] = {0, 0, 0}, s2[3] = {0, 0, 0};
    int n = 0;
    for (int y = im->height / 4; y < 3 * im->height / 4; y++)
        for (int x = im->width / 4; x < 3 * im->width / 4; x++, n++)
            for (int c = 0; c < 3; c++) {
                double v = im->pixels[3 * ((size_t)y * im->width + x) + c];
                s[c] += v;
                s2[c] += v * v;
            }
    for (int c = 0; c < 3; c++) {
        mean[c] = s[c] / n;
        double var = s2[c] / n - mean[c] * mean[c];
        rsd[c] = sqrt(var > 0.0 ? var : 0.0) / mean[c];
    }
}

static void check_plane(const char *label, int nx, int nz)
{
    sss_scene scene;
    if (!write_grid_cells("dss_lattice", nx, nz) || !plane_scene(0, 0, &scene)) {
        CHECK(0);
        return;
    }
    const sss_scene_material *m = &scene.objects[0].material;
    double co, ft = gt_normal_transmission(m, &co);
    /* splat_energy 1: the kernel's whole reach (the default 0.99 leaves out up to 1% of the red) */
    sss_gl_param_value p[2] = {{"splat_energy", 1.0}, {"footprint", 0.0}};
    sss_image now, before;
    CHECK(gt_render(&scene, "dss", 0.0, p, 1, &now));
    CHECK(gt_render(&scene, "dss", 0.0, p, 2, &before));
    double mn[3], rn[3], mb[3], rb[3];
    centre_stats(&now, mn, rn);
    centre_stats(&before, mb, rb);
    for (int c = 0; c < 3; c++) {
        double expect = co * ft * m->albedo[c];
        printf("%s channel %d: c_o F_t E rho_eff %.6f; footprint %.6f (%+.2f%%), pixel sd %.2f%%; footprint = 0 "
               "%.6f (%+.2f%%), pixel sd %.2f%%\n",
               label, c, expect, mn[c], 100.0 * (mn[c] / expect - 1.0), 100.0 * rn[c], mb[c],
               100.0 * (mb[c] / expect - 1.0), 100.0 * rb[c]);
        CHECK_MSG(rn[c] < 0.05, "%s channel %d: the surfel lattice shows (pixel sd %.2f%%)", label, c, 100.0 * rn[c]);
        CHECK_REL(mn[c], expect, 0.01);
        CHECK_MSG(rb[c] > rn[c], "%s channel %d: footprint = 0 is not the coarser lattice", label, c);
    }
    CHECK(sss_image_count_nonfinite(&now) == 0);
    sss_image_free(&now);
    sss_image_free(&before);
    sss_scene_free(&scene);
}

int main(void)
{
    check_plane("grid plane", 32, 32);
    check_plane("thin-cell plane", 4, 32);
    remove(grid_path);
    return CHECK_DONE();
}
