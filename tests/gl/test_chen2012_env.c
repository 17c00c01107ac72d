/* chen2012 under environment lighting (src/gl/techniques/chen2012/tech_chen2012.c; issue 5).
 *
 * An environment map becomes 32 directional lights (median cut, src/gl/core/lights.c), each with its own
 * irradiance buffer and splats, so the splats of all lights together run into the millions. The
 * splat buffer had a fixed capacity (1M): every splat past it was dropped, i.e. the last lights
 * whole; on eval_skin_env half the directions and the point light after them vanished (DSSIM 0.12).
 * That code fails the energy check below by -52% (measured, with this file built against it).
 *
 *  - energy: a large flat plane under a sky of constant radiance L = 1 over the upper hemisphere
 *    (black below). Its middle shows c_o F_t E rho_eff (docs/physics.md §1), as in the single-light test of
 *    test_chen2012.c, where F_t E is what the 32 lights deliver: the camera pass's per-pixel sum over
 *    the same lights (read back as "irradiance"; no light-view buffer, no splat involved). With
 *    splat_energy = 1 the splats keep the kernel's integral, so bound 0.75% as there (measured
 *    -0.06% .. -0.09%). The 32 lights select ~0.5M splats here, more than the first splat buffer
 *    holds, so it grows while the lights are drawn. The lights themselves are checked against the
 *    closed form E_t = int L F_t(mu) mu d(omega) = 2 pi L int_0^1 F_t(mu) mu d(mu) (F_t from the
 *    physics module, Gauss-Legendre here): median cut puts each region's light at its centroid
 *    direction, which overestimates mu: +2.46% measured (+2.43% from lights.c's split rule replayed
 *    offline), bound 3.5%;
 *  - one more light after the environment's: the sky + a directional light equals the sum of the
 *    images of each alone (relative 1e-3 where the sum is not tiny; measured 2e-6). With
 *    env_buffer_size 256 the sky selects ~0.5M splats and the directional light (last) ~0.12M: the
 *    buffer grows twice, the second time with the sky's splats kept;
 *  - the committed environment scene gl_env.json against its cached reference (DSSIM bound). */
#include "splat_plane_util.h"
#include "sss/kernel.h"
#include "sss/material.h"

static char sky_path[256];

/* Equirectangular map (docs/scene-format.md: +y up, rows from the zenith down) with radiance 1 over the upper
 * hemisphere and 0 below; the row boundary at h / 2 lies exactly on the horizon. */
static int write_sky(void)
{
    snprintf(sky_path, sizeof sky_path, "/tmp/sss_test_chen_env_%ld.exr", (long)getpid());
    sss_image im;
    sss_error err = {0};
    if (sss_image_create(&im, 64, 32, &err) != SSS_OK) return 0;
    for (int y = 0; y < im.height / 2; y++)
        for (int x = 0; x < im.width; x++)
            for (int c = 0; c < 3; c++) im.pixels[3 * ((size_t)y * im.width + x) + c] = 1.0f;
    int ok = sss_image_write_exr(sky_path, &im, 0, &err) == SSS_OK;
    if (!ok) fprintf(stderr, "%s\n", err.message);
    sss_image_free(&im);
    return ok;
}

/* The plane of splat_plane_util.h under the sky and/or one directional light. */
static int env_scene(int sky, int directional, sss_scene *scene)
{
    char lights[512] = "";
    if (sky) snprintf(lights, sizeof lights, "{\"type\": \"environment\", \"file\": \"%s\"}", sky_path);
    if (directional)
        snprintf(lights + strlen(lights), sizeof lights - strlen(lights),
                 "%s{\"type\": \"directional\", \"direction\": [0.3, -1, 0.2], \"radiance\": [0.5, 0.7, 0.9]}",
                 sky ? ", " : "");
    return plane_scene_lights(lights, "plane_env", scene);
}

/* int_0^1 F_t(mu) mu d(mu) by 4-point Gauss-Legendre on each of 16 sub-intervals (F_t is smooth in mu
 * except near grazing, where mu weights it down). */
static double ft_cos_moment(double eta)
{
    static const double x[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
    static const double w[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};
    double s = 0.0;
    int n = 16;
    for (int i = 0; i < n; i++) {
        double a = (double)i / n, b = (double)(i + 1) / n;
        for (int k = 0; k < 4; k++) {
            double mu = 0.5 * (a + b) + 0.5 * (b - a) * x[k];
            s += 0.5 * (b - a) * w[k] * (1.0 - sss_fresnel_dielectric(mu, 1.0, eta)) * mu;
        }
    }
    return s;
}

/* Renders with chen2012 and reads the final image and the camera pass's F_t E ("irradiance"). */
static int render_with_irradiance(const char *label, const sss_scene *scene, const sss_gl_param_value *params,
                                  int nparams, sss_image *img, sss_image *irr)
{
    sss_error err = {0};
    sss_gl_renderer_desc d;
    memset(&d, 0, sizeof d);
    d.technique = "chen2012";
    d.params = params;
    d.param_count = nparams;
    sss_gl_renderer *r = NULL;
    memset(img, 0, sizeof *img);
    memset(irr, 0, sizeof *irr);
    int ok = sss_gl_renderer_create(gt_ctx(), scene, &d, &r, &err) == SSS_OK &&
             sss_gl_renderer_render(r, 0.0, &err) == SSS_OK &&
             sss_image_create(img, scene->camera.width, scene->camera.height, &err) == SSS_OK &&
             sss_gl_renderer_read(r, img, &err) == SSS_OK &&
             sss_gl_renderer_read_buffer(r, "irradiance", irr, &err) == SSS_OK; /* creates irr */
    if (ok) {
        sss_gl_stats st;
        sss_gl_renderer_stats(r, &st);
        printf("%s: %u splats\n", label, st.splat_drawn);
    } else {
        fprintf(stderr, "render failed: %s\n", err.message);
    }
    sss_gl_renderer_destroy(r);
    return ok;
}

static void test_sky_energy(void)
{
    sss_scene scene;
    if (!env_scene(1, 0, &scene)) {
        CHECK(0);
        return;
    }
    const sss_scene_material *m = &scene.objects[0].material;
    double eta = m->optical.eta, co;
    gt_normal_transmission(m, &co);
    double et = 2.0 * M_PI * 1.0 * ft_cos_moment(eta);
    sss_image img, irr;
    sss_gl_param_value p = {"splat_energy", 1.0};
    if (!render_with_irradiance("sky on the plane", &scene, &p, 1, &img, &irr)) {
        CHECK(0);
        sss_image_free(&img);
        sss_image_free(&irr);
        sss_scene_free(&scene);
        return;
    }
    double mean[3], e[3];
    centre_mean(&img, mean);
    centre_mean(&irr, e);
    for (int c = 0; c < 3; c++) {
        double expect = co * e[c] * m->albedo[c];
        printf("sky on the plane, channel %d: camera-pass F_t E %.5f (closed form %.5f, %+.2f%%); c_o F_t E rho_eff "
               "%.6f, chen2012 %.6f (%+.2f%%)\n",
               c, e[c], et, 100.0 * (e[c] / et - 1.0), expect, mean[c], 100.0 * (mean[c] / expect - 1.0));
        CHECK_REL(mean[c], expect, 0.0075);
        CHECK_REL(e[c], et, 0.035);
    }
    CHECK(sss_image_count_nonfinite(&img) == 0);
    sss_image_free(&img);
    sss_image_free(&irr);
    sss_scene_free(&scene);
}

static void test_sky_plus_light(void)
{
    sss_scene both, sky, dir;
    if (!env_scene(1, 1, &both) || !env_scene(1, 0, &sky) || !env_scene(0, 1, &dir)) {
        CHECK(0);
        return;
    }
    sss_image ib, is, id, irr;
    sss_gl_param_value p = {"env_buffer_size", 256};
    CHECK(render_with_irradiance("sky + directional light", &both, &p, 1, &ib, &irr));
    sss_image_free(&irr);
    CHECK(render_with_irradiance("sky", &sky, &p, 1, &is, &irr));
    sss_image_free(&irr);
    CHECK(render_with_irradiance("directional light", &dir, &p, 1, &id, &irr));
    sss_image_free(&irr);
    double worst = 1.0;
    if (ib.pixels && is.pixels && id.pixels) {
        worst = 0.0;
        for (size_t i = 0; i < 3 * (size_t)ib.width * ib.height; i++) {
            double sum = is.pixels[i] + id.pixels[i];
            double d = fabs(ib.pixels[i] - sum) / (sum > 1e-6 ? sum : 1e-6);
            if (d > worst) worst = d;
        }
    }
    printf("sky + directional light vs the sum of each alone: largest relative difference %.2e\n", worst);
    CHECK(worst < 1e-3);
    sss_image_free(&ib);
    sss_image_free(&is);
    sss_image_free(&id);
    sss_scene_free(&both);
    sss_scene_free(&sky);
    sss_scene_free(&dir);
}

/* The committed environment scene (a Marble torus under gl_sky.hdr, 96 x 96) against its cached
 * reference. Measured DSSIM 0.0063 (env_buffer_size 2048: 0.0050; the capped splat buffer: 0.048):
 * bound +1/3 as test_chen2012.c's scenes. */
static void test_env_scene(void)
{
    sss_scene scene;
    if (!gt_load("gl_env.json", &scene)) {
        CHECK(0);
        return;
    }
    sss_image ref, img;
    double d = 1.0;
    if (gt_read_ref("ref_env.exr", &ref)) {
        if (gt_render(&scene, "chen2012", 0.0, NULL, 0, &img)) {
            d = gt_dssim(&img, &ref);
            CHECK(sss_image_count_nonfinite(&img) == 0);
            sss_image_free(&img);
        }
        sss_image_free(&ref);
    }
    printf("gl_env.json, chen2012: DSSIM %.4f\n", d);
    CHECK_MSG(d < 0.0085, "gl_env.json chen2012: DSSIM %g >= 0.0085", d);
    sss_scene_free(&scene);
}

int main(void)
{
    CHECK(write_grid("chen_env"));
    CHECK(write_sky());
    test_sky_energy();
    test_sky_plus_light();
    test_env_scene();
    remove(grid_path);
    remove(sky_path);
    return CHECK_DONE();
}
