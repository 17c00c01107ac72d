/* Reference renderer: a large flat plane under a directional light at normal incidence. Far from the
 * edges the radiance is c_o F_t E rho_eff (docs/physics.md §1): c_o = F_t(cos theta_o) / (pi c), F_t of the
 * light at normal incidence, E the irradiance, rho_eff the plane integral of the profile from the
 * physics module. Within 0.5% per pixel. Also: scaling the light scales the image. */
#include "ref_test_util.h"

static void check_plane(const char *label, const sss_reference_object *obj, double plane_size, int energy)
{
    tmesh plane = {0};
    tmesh_plane(&plane, plane_size, 0, 0, 0, 8, 0);
    sss_reference_object o = *obj;
    o.mesh = &plane.m;
    const double E = 2.0, H = 10.0;
    sss_light l = light_directional(0, -1, 0, E);
    sss_reference_world w;
    memset(&w, 0, sizeof w);
    camera_set(&w.camera, 0, H, 0, 0, 0, 0, 20, 32, 32);
    w.objects = &o, w.object_count = 1, w.lights = &l, w.light_count = 1;
    sss_reference_desc d;
    memset(&d, 0, sizeof d);
    d.seed = 3;
    sss_image img;
    sss_reference_stats st;
    if (!render_or_die(&w, &d, &img, &st)) {
        CHECK(0);
        tmesh_free(&plane);
        return;
    }
    sss_profile phys;
    sss_error err;
    sss_profile_model model = o.profile == SSS_SCENE_PROFILE_DIPOLE ? SSS_PROFILE_DIPOLE : SSS_PROFILE_PBD;
    CHECK(sss_profile_init(&phys, model, &o.optical, o.table, &err) == SSS_OK);
    double eta = o.optical.eta;
    double c = 1.0 - 2.0 * sss_fresnel_moment1(1.0 / eta);
    double ft_light = 1.0 - sss_fresnel_dielectric(1.0, 1.0, eta);
    double tan_half = tan(10.0 * T_PI / 180.0), worst = 0.0;
    for (int y = 0; y < img.height; y++)
        for (int x = 0; x < img.width; x++) {
            /* Camera looking down -y with up = -z: the pixel centre's ray and its cosine. */
            double sx = (2.0 * (x + 0.5) / img.width - 1.0) * tan_half, sy = (1.0 - 2.0 * (y + 0.5) / img.height) * tan_half;
            double cos_o = 1.0 / sqrt(1.0 + sx * sx + sy * sy);
            double co = (1.0 - sss_fresnel_dielectric(cos_o, 1.0, eta)) / (T_PI * c);
            for (int ch = 0; ch < 3; ch++) {
                double expect = co * ft_light * E * sss_profile_total(&phys, ch);
                worst = fmax(worst, fabs(img_at(&img, x, y, ch) - expect) / expect);
            }
        }
    CHECK_MSG(worst < 0.005, "%s: worst relative deviation from c_o F_t E rho_eff: %.4g", label, worst);
    printf("%s: %llu samples (h %.3g, R0 %.3g), worst relative deviation %.3g\n", label,
           (unsigned long long)st.surface_samples, st.spacing_min, st.split_radius_min, worst);

    /* Energy: k times the light gives k times the image (same samples, same seed). */
    l.radiance[0] = l.radiance[1] = l.radiance[2] = 3.0 * E;
    sss_image img3;
    if (energy && render_or_die(&w, &d, &img3, NULL)) {
        double dev = 0.0;
        for (size_t i = 0; i < 3 * (size_t)img.width * img.height; i++)
            dev = fmax(dev, fabs(img3.pixels[i] - 3.0 * img.pixels[i]) / (3.0 * img.pixels[i]));
        CHECK_MSG(dev < 1e-5, "%s: light x3 changes the image by a factor off by %g", label, dev);
        sss_image_free(&img3);
    }
    sss_image_free(&img);
    tmesh_free(&plane);
}

int main(void)
{
    sss_error err;
    sss_pbd_table *t1, *t2;
    /* Explicit coefficients (per scene unit), a different albedo per channel. */
    sss_material m1 = material_coeffs(0.5, 1.0, 2.0, 1.0, 1.5, 3.0, 1.33);
    sss_reference_object o1 = object_subsurface(NULL, &m1, &t1);
    check_plane("coefficients, pbd", &o1, 24.0, 1);
    /* Marble with 10 mm per unit: high albedo, diffusion length about one unit. */
    sss_material marble;
    CHECK(sss_material_from_medium("Marble", 10.0, 1.5, &marble, &err) == SSS_OK);
    sss_reference_object o2 = object_subsurface(NULL, &marble, &t2);
    check_plane("marble x10, pbd", &o2, 32.0, 0);
    o2.profile = SSS_SCENE_PROFILE_DIPOLE;
    check_plane("marble x10, dipole", &o2, 32.0, 0);
    free(t1);
    free(t2);
    return CHECK_DONE();
}
