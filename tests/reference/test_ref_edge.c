/* Reference renderer: a straight shadow edge on a plane. An occluder above the half-space x < 0 casts
 * a shadow half-plane under a directional light at normal incidence; the radiance across the edge
 * must match the independent 1D integral of S_r over the lit half-plane:
 *   I(a) = rho - J(a) on the lit side at distance a, J(a) in the shadow, J(a) = int_a^inf S(r) 2 r acos(a/r) dr
 * (the arc of the circle of radius r that lies beyond the edge), averaged over each pixel's footprint,
 * within 1%. */
#include "ref_test_util.h"

/* Plane integral over the lit half-plane {x > 0} seen from (x, 0). */
static double edge_I(const sss_profile *p, int c, double x, double total)
{
    return x >= 0.0 ? total - ref_edge_J(p, c, x) : ref_edge_J(p, c, -x);
}

static void check_edge(const char *label, const sss_reference_object *obj)
{
    tmesh plane = {0}, occ = {0};
    tmesh_plane(&plane, 24.0, 0, 0, 0, 8, 0);
    double lo[3] = {-30, 4, -30}, hi[3] = {0, 4.5, 30};
    tmesh_box(&occ, lo, hi, 2);
    sss_reference_object objs[2];
    objs[0] = *obj;
    objs[0].mesh = &plane.m;
    objs[1] = object_diffuse(&occ.m, 0.5);
    const double E = 1.5, H = 2.0;
    sss_light l = light_directional(0, -1, 0, E);
    sss_reference_world w;
    memset(&w, 0, sizeof w);
    /* 64 x 16 pixels: the fov (20 degrees) is along the shorter, vertical axis. */
    camera_set(&w.camera, 0, H, 0, 0, 0, 0, 20, 64, 16);
    w.objects = objs, w.object_count = 2, w.lights = &l, w.light_count = 1;
    sss_reference_desc d;
    memset(&d, 0, sizeof d);
    d.bounces = 1; /* the single-event integral the closed forms describe */
    d.seed = 5;
    sss_image img;
    sss_reference_stats st;
    if (!render_or_die(&w, &d, &img, &st)) {
        CHECK(0);
        return;
    }
    sss_profile phys;
    sss_error err;
    CHECK(sss_profile_init(&phys, SSS_PROFILE_PBD, &obj->optical, obj->table, &err) == SSS_OK);
    double eta = obj->optical.eta, c = 1.0 - 2.0 * sss_fresnel_moment1(1.0 / eta);
    double T0 = (1.0 - sss_fresnel_dielectric(1.0, 1.0, eta)) * E;
    double th = tan(10.0 * T_PI / 180.0), thx = th * img.width / img.height;
    double worst = 0.0;
    int worst_x = -1;
    for (int x = 0; x < img.width; x++) {
        /* The pixel column's footprint on the plane: x = H * (2 px / W - 1) * tan_half_x. */
        double x0 = H * (2.0 * x / img.width - 1.0) * thx, x1 = H * (2.0 * (x + 1) / img.width - 1.0) * thx;
        for (int ch = 0; ch < 3; ch++) {
            double total = sss_profile_total(&phys, ch), avg = 0.0;
            int n = x == img.width / 2 - 1 || x == img.width / 2 ? 64 : 8; /* next to the edge: steep */
            for (int k = 0; k < n; k++) avg += edge_I(&phys, ch, x0 + (x1 - x0) * (k + 0.5) / n, total) / n;
            for (int y = 0; y < img.height; y += 5) {
                double sx = 0.5 * (x0 + x1) / H, sy = (1.0 - 2.0 * (y + 0.5) / img.height) * th;
                double cos_o = 1.0 / sqrt(1.0 + sx * sx + sy * sy);
                double co = (1.0 - sss_fresnel_dielectric(cos_o, 1.0, eta)) / (T_PI * c);
                double expect = co * T0 * avg;
                double got = img_at(&img, x, y, ch);
                /* Relative to the lit level, so the deep shadow (tiny values) is not over-weighted. */
                double dev = fabs(got - expect) / (co * T0 * total);
                if (dev > worst) worst = dev, worst_x = x;
            }
        }
    }
    CHECK_MSG(worst < 0.01, "%s: worst deviation %.4g (of the lit level) at column %d", label, worst, worst_x);
    printf("%s: %llu samples (h %.3g, R0 %.3g), worst deviation %.3g of the lit level (column %d)\n", label,
           (unsigned long long)st.surface_samples, st.spacing_min, st.split_radius_min, worst, worst_x);
    sss_image_free(&img);
    tmesh_free(&plane);
    tmesh_free(&occ);
}

int main(void)
{
    sss_error err;
    sss_pbd_table *t1, *t2;
    sss_material m1 = material_coeffs(0.5, 1.0, 2.0, 1.0, 1.5, 3.0, 1.33);
    sss_reference_object o1 = object_subsurface(NULL, &m1, &t1);
    check_edge("coefficients", &o1);
    sss_material marble;
    CHECK(sss_material_from_medium("Marble", 10.0, 1.33, &marble, &err) == SSS_OK);
    sss_reference_object o2 = object_subsurface(NULL, &marble, &t2);
    check_edge("marble x10", &o2);
    free(t1);
    free(t2);
    return CHECK_DONE();
}
