/* Reference renderer: the source mask (reference/ref_sources.c), the diagnostic that splits the single-event
 * image by where its sources lie (off the image, facing away, hidden, grazing, seen).
 *
 * A uniformly lit plane seen straight down (64 x 64, fov 40 from height 2: the image spans x in +-0.73)
 * with a kernel of 0.05-0.08 units (about 3 pixels). The sources off the image beyond its left edge
 * x_e form a half-plane, so at a pixel a = x - x_e from that edge their light is c_o T J(a) (J: the
 * profile's integral over a half-plane a away, ref_edge_J) and the seen sources' light c_o T (rho - J(a)),
 * averaged over the pixel's footprint; the image's other edges lie 24 pixels (seven kernel lengths) or
 * more from the rows checked. Both within 1% of the lit level in each of the 16 columns next to the
 * edge (their means over 16 rows), as test_ref_edge's closed form; the
 * plane has no source facing away, hidden or grazing (their image is zero); and the classes add up to
 * the unmasked image (within 1e-4 of the lit level: the tree's tolerance follows the kept sources).
 * Final quality without the adaptive samples (which follow each image's values, so the classes' images
 * would not share their camera samples): at draft quality (one sample per pixel, the near part's radius
 * four pixels, longer than this kernel) the two pixels next to the edge measured 5% of the lit level
 * off. A mask needs the single-event integral and known classes. */
#include "reference/ref_internal.h"
#include "ref_test_util.h"

#define SIZE 64
#define HEIGHT 2.0
#define FOV 40.0
#define E_LIGHT 1.5

static int render_masked(const sss_reference_world *w, unsigned keep, sss_image *img)
{
    sss_reference_desc d;
    memset(&d, 0, sizeof d);
    d.bounces = 1;
    d.no_adaptive = 1; /* the same camera samples in every image (the extra ones follow the image's values) */
    d.seed = 3;
    ref_source_mask m = {keep, 0.05};
    sss_error err;
    sss_result r = ref_render_world(w, &d, keep ? &m : NULL, img, NULL, NULL, NULL, &err);
    if (r != SSS_OK) fprintf(stderr, "render (classes 0x%x) failed: %s\n", keep, err.message);
    return r == SSS_OK;
}

/* The closed forms of the seen and the off-image sources' light next to the left edge. */
static void check_edge_light(const sss_image *seen, const sss_image *off, const sss_reference_object *obj)
{
    sss_profile phys;
    sss_error err;
    CHECK(sss_profile_init(&phys, SSS_PROFILE_PBD, &obj->optical, obj->table, &err) == SSS_OK);
    double eta = obj->optical.eta, c = 1.0 - 2.0 * sss_fresnel_moment1(1.0 / eta);
    double T0 = (1.0 - sss_fresnel_dielectric(1.0, 1.0, eta)) * E_LIGHT;
    double th = tan(0.5 * FOV * T_PI / 180.0), x_edge = -HEIGHT * th;
    double worst = 0.0;
    for (int x = 0; x < 16; x++) {
        double x0 = HEIGHT * (2.0 * x / SIZE - 1.0) * th, x1 = HEIGHT * (2.0 * (x + 1) / SIZE - 1.0) * th;
        for (int ch = 0; ch < 3; ch++) {
            double total = sss_profile_total(&phys, ch), J = 0.0;
            for (int k = 0; k < 16; k++) J += ref_edge_J(&phys, ch, x0 + (x1 - x0) * (k + 0.5) / 16 - x_edge) / 16;
            /* the column's mean over the middle rows (single pixels next to the edge carry 1-2% noise) */
            double d_off = 0.0, d_seen = 0.0, lit = 0.0;
            for (int y = 24; y < 40; y++) {
                double sx = 0.5 * (x0 + x1) / HEIGHT, sy = (1.0 - 2.0 * (y + 0.5) / SIZE) * th;
                double cos_o = 1.0 / sqrt(1.0 + sx * sx + sy * sy);
                double co = (1.0 - sss_fresnel_dielectric(cos_o, 1.0, eta)) / (T_PI * c);
                lit += co * T0 * total;
                d_off += img_at(off, x, y, ch) - co * T0 * J;
                d_seen += img_at(seen, x, y, ch) - co * T0 * (total - J);
            }
            worst = fmax(worst, fmax(fabs(d_off), fabs(d_seen)) / lit);
        }
    }
    printf("next to the image's left edge: seen and off-image sources within %.3g of the lit level\n", worst);
    CHECK_MSG(worst < 0.01, "masked light off the closed form by %.4g of the lit level", worst);
}

/* OFF + VISIBLE = the unmasked image (relative to its largest value, the lit level); no other source. */
static void check_partition(const sss_image *all, const sss_image *seen, const sss_image *off, const sss_image *rest)
{
    double lit = img_max(all), worst = 0.0, rest_max = img_max(rest);
    for (size_t i = 0; i < 3 * (size_t)all->width * all->height; i++)
        worst = fmax(worst, fabs(seen->pixels[i] + off->pixels[i] - all->pixels[i]) / lit);
    printf("classes: seen + off-image - unmasked within %.3g of the lit level; hidden, back, grazing max %g\n", worst,
           rest_max);
    CHECK_MSG(worst < 1e-4, "the classes do not add up to the unmasked image: %.4g of the lit level", worst);
    CHECK_MSG(rest_max == 0.0, "a plane seen head-on has no hidden, back-facing or grazing source (max %g)", rest_max);
}

static void check_refusals(const sss_reference_world *w)
{
    sss_reference_desc d;
    memset(&d, 0, sizeof d);
    d.quality = SSS_REFERENCE_DRAFT;
    ref_source_mask m = {REF_SOURCE_OFF, 0.05};
    sss_image img;
    sss_error err;
    CHECK(ref_render_world(w, &d, &m, &img, NULL, NULL, NULL, &err) == SSS_ERROR_INVALID_ARGUMENT); /* bounces 0 */
    CHECK(strstr(err.message, "bounces = 1") != NULL);
    CHECK(img.pixels == NULL);
    d.bounces = 1;
    m.keep = 0x40;
    CHECK(ref_render_world(w, &d, &m, &img, NULL, NULL, NULL, &err) == SSS_ERROR_INVALID_ARGUMENT);
    m.keep = REF_SOURCE_OFF, m.grazing = NAN;
    CHECK(ref_render_world(w, &d, &m, &img, NULL, NULL, NULL, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(err.message, "grazing") != NULL);
}

int main(void)
{
    tmesh plane = {0};
    tmesh_plane(&plane, 6.0, 0, 0, 0, 12, 0);
    sss_pbd_table *table;
    sss_material mat = material_coeffs(4.0, 6.0, 8.0, 10.0, 10.0, 10.0, 1.33);
    sss_reference_object obj = object_subsurface(&plane.m, &mat, &table);
    sss_light l = light_directional(0, -1, 0, E_LIGHT);
    sss_reference_world w;
    memset(&w, 0, sizeof w);
    camera_set(&w.camera, 0, HEIGHT, 0, 0, 0, 0, FOV, SIZE, SIZE);
    w.objects = &obj, w.object_count = 1, w.lights = &l, w.light_count = 1;
    sss_image all, seen, off, rest;
    if (render_masked(&w, 0, &all) && render_masked(&w, REF_SOURCE_VISIBLE, &seen) &&
        render_masked(&w, REF_SOURCE_OFF, &off) &&
        render_masked(&w, REF_SOURCE_HIDDEN | REF_SOURCE_BACK | REF_SOURCE_GRAZING, &rest)) {
        check_partition(&all, &seen, &off, &rest);
        check_edge_light(&seen, &off, &obj);
        sss_image_free(&all), sss_image_free(&seen), sss_image_free(&off), sss_image_free(&rest);
    } else {
        CHECK(0);
    }
    check_refusals(&w);
    free(table);
    tmesh_free(&plane);
    return CHECK_DONE();
}
