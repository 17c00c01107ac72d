/* Supersampling antialiasing keeps the image (sss_gl_renderer_desc.supersample): on the flat plane of
 * splat_plane_util.h (Skin1, lit head-on by a directional light, E = 1, filling the view), far from any
 * edge, the central half of the image at k = 2 equals the one at k = 1:
 *  - techniques with no parameter counted in pixels (local, ssss and its kernels, sam): every pixel
 *    within half-float precision (2^-11 relative; the images differ only in float rounding, measured
 *    < 3e-7), and local also at k = 3 and 4;
 *  - maisch2020 and screen, whose pattern (n, n_l, layers) and translucency_divisor count output
 *    pixels and follow k (docs/supersampling.md): mean within 0.75% per channel, every pixel within 1%
 *    (measured 0.45% both: the inner square is sampled at k^2 the density, a finer quadrature of the
 *    same integral, 0.4% closer to c_o F_t E rho_eff in red). Without the scaling, layer i lands where
 *    layer i + 1 was and gets sqrt(i) instead of sqrt(i + 1) (section 6.1's brightening): +11% in red;
 *  - mertens2003 (pattern x k): Monte Carlo noise per pixel (bound 5%, measured 2.3%), mean within
 *    0.1% (measured 0.02%);
 *  - chen2012 and dss, whose shell pyramid counts output pixels (common/shells.h) and dss's
 *    surfel_pixels too: without the render-resolution level (fine_radius / view_fine_radius 0) the
 *    k = 1 image itself, every pixel within 2.5e-4 (float sums; measured 2e-5 dss, 1.4e-6 chen2012), at
 *    k = 2 (the level-0 receivers are means of the four render pixels around the output pixel's
 *    centre) and k = 3 (its centre pixel); before, the pyramid started at the render pixel and the
 *    means were 0.4% and 1.2% off. With the default fine level (2.5 output pixels: the nearest splats'
 *    transport sampled per render pixel) the splats' lattice, narrower than a pixel in blue, is sampled
 *    at other points and the 32 x 32 window's mean moves: chen2012 mean within 1% (measured 0.60%),
 *    pixels 3% (1.6%); dss, whose k = 1 lattice gives single pixels -65%, mean within 3% (measured
 *    1.4%: test_dss measures -1.6 .. +2.5% for where the lattice falls), no pixel bound. Its energy is
 *    checked where the lattice is fine: dss with one-pixel surfels and splat_energy 1 at k = 2 shows
 *    c_o F_t E rho_eff within 0.5% (measured +0.04%, +0.11%, +0.17%; k = 1 -0.14% with half-pixel
 *    surfels), so the fine level moves transport between a pixel and its level-0 receiver without
 *    adding or losing any (a hard split of the near shell between the two counted it twice where the
 *    fine shell holds 69% of the red and 99.6% of the blue light: +69 .. +100%; weighting the
 *    receiver's term by the pixel's distance +2 .. +4.5%).
 *    Supersampling must not buy more splatting (docs/supersampling.md): dss's surfels stay within 5%
 *    of k = 1 (measured equal; surfel_pixels in render pixels made 3.2x), the splatting pass's fragment
 *    shader invocations are those of k = 1 within 1% without the fine level (measured equal) and within
 *    1.75x with it (measured 1.57x, 1.56x: the plane's kernels reach 3 pixels, so its k = 1 work is
 *    only 36-48 fragments a splat and the fine level's quads, (2 (2.5 + 0.375) k)^2 = 132, weigh; +5%
 *    on eval_backlit, +10% on eval_front). The pyramid starting at the render pixel made 3.0x
 *    (chen2012) and 12x (dss). */
#include "splat_plane_util.h"
#include "gl_test_util.h"

typedef struct plane_case {
    const char *technique;
    int k;
    double mean_tol, pixel_tol; /* relative; pixel_tol 0: not checked */
    double fine;                /* chen2012/dss: the fine level's radius, < 0: default */
    double work_tol;            /* chen2012/dss: largest splatting work k vs 1 (0: not checked) */
} plane_case;

/* The splatting work of a frame: splats drawn (sss_gl_stats.splat_drawn) and, for the shell splatting
 * of chen2012 and dss, the fragment shader invocations of the splatting pass (-1: not counted). */
typedef struct splat_work {
    unsigned drawn;
    long long fragments;
} splat_work;

/* gt_render_k that also reads the splatting work before the renderer goes. */
static int render_k(const sss_scene *scene, const char *technique, const sss_gl_param_value *params, int nparams,
                    int k, sss_image *out, splat_work *work)
{
    sss_error err = {0};
    sss_gl_renderer_desc d = gt_desc(technique, params, nparams, k);
    sss_gl_renderer *r = NULL;
    memset(out, 0, sizeof *out);
    work->drawn = 0;
    work->fragments = -1;
    if (sss_gl_renderer_create(gt_ctx(), scene, &d, &r, &err) != SSS_OK ||
        sss_gl_renderer_render(r, 0.0, &err) != SSS_OK ||
        sss_image_create(out, scene->camera.width, scene->camera.height, &err) != SSS_OK ||
        sss_gl_renderer_read(r, out, &err) != SSS_OK) {
        fprintf(stderr, "%s, supersample %d: render failed: %s\n", technique, k, err.message);
        sss_gl_renderer_destroy(r);
        sss_image_free(out);
        return 0;
    }
    sss_gl_stats st;
    sss_gl_renderer_stats(r, &st);
    work->drawn = st.splat_drawn;
    work->fragments = st.splat_fragments;
    sss_gl_renderer_destroy(r);
    return 1;
}

static int is_shell(const char *technique) { return !strcmp(technique, "chen2012") || !strcmp(technique, "dss"); }

static void check_work(const plane_case *pc, const splat_work *wa, const splat_work *wb)
{
    if (!strcmp(pc->technique, "dss")) {
        double ratio = (double)wb->drawn / (wa->drawn ? wa->drawn : 1);
        printf("%-12s k = %d: surfels %u -> %u (x%.3f, bound 1.05)\n", pc->technique, pc->k, wa->drawn, wb->drawn,
               ratio);
        CHECK_MSG(wa->drawn > 0 && ratio <= 1.05, "dss: k = %d draws %.2fx the surfels of k = 1", pc->k, ratio);
    }
    if (wa->fragments < 0 || wb->fragments < 0) {
        printf("%-12s: the GL counts no fragment shader invocations: splatting work not checked\n", pc->technique);
        return;
    }
    double ratio = (double)wb->fragments / (double)(wa->fragments ? wa->fragments : 1);
    printf("%-12s k = %d: splatting fragments %lld -> %lld (x%.3f, bound %.2f)\n", pc->technique, pc->k,
           wa->fragments, wb->fragments, ratio, pc->work_tol);
    CHECK_MSG(wa->fragments > 0 && ratio <= pc->work_tol, "%s: k = %d splats %.2fx the fragments of k = 1",
              pc->technique, pc->k, ratio);
}

static void compare(const sss_scene *scene, const plane_case *pc)
{
    sss_gl_param_value p = {!strcmp(pc->technique, "dss") ? "fine_radius" : "view_fine_radius", pc->fine};
    int np = is_shell(pc->technique) && pc->fine >= 0 ? 1 : 0;
    sss_image a, b;
    splat_work wa, wb;
    if (!render_k(scene, pc->technique, &p, np, 1, &a, &wa) ||
        !render_k(scene, pc->technique, &p, np, pc->k, &b, &wb)) {
        CHECK_MSG(0, "%s failed to render", pc->technique);
        return;
    }
    CHECK(sss_image_count_nonfinite(&b) == 0);
    if (pc->work_tol > 0) check_work(pc, &wa, &wb);
    double ma[3], mb[3];
    centre_mean(&a, ma);
    centre_mean(&b, mb);
    double worst = 0.0, worst_mean = 0.0;
    for (int y = a.height / 4; y < 3 * a.height / 4; y++)
        for (int x = a.width / 4; x < 3 * a.width / 4; x++)
            for (int c = 0; c < 3; c++) {
                size_t i = 3 * ((size_t)y * a.width + x) + c;
                worst = fmax(worst, fabs(b.pixels[i] / a.pixels[i] - 1.0));
            }
    for (int c = 0; c < 3; c++) worst_mean = fmax(worst_mean, fabs(mb[c] / ma[c] - 1.0));
    const sss_scene_material *m = &scene->objects[0].material;
    double co, ft = gt_normal_transmission(m, &co), e = co * ft * m->albedo[0];
    char tag[64];
    snprintf(tag, sizeof tag, np ? "%s:%s=%g" : "%s", pc->technique, p.name, p.value);
    printf("%-12s k = %d: mean %+.2e (bound %.1e), worst pixel %.2e (bound %s%.1e); red vs c_o F_t E rho_eff: "
           "k = 1 %+.4f, k = %d %+.4f\n",
           tag, pc->k, worst_mean, pc->mean_tol, worst, pc->pixel_tol > 0 ? "" : "none, ", pc->pixel_tol,
           ma[0] / e - 1.0, pc->k, mb[0] / e - 1.0);
    CHECK_MSG(worst_mean <= pc->mean_tol, "%s: k = %d mean differs by %.3g", tag, pc->k, worst_mean);
    if (pc->pixel_tol > 0) CHECK_MSG(worst <= pc->pixel_tol, "%s: k = %d pixel differs by %.3g", tag, pc->k, worst);
    sss_image_free(&a);
    sss_image_free(&b);
}

/* dss at k = 2 with the fine level on a plane with a fine surfel lattice: the mean is c_o F_t E rho_eff. */
static void dss_fine_energy(const sss_scene *scene)
{
    const sss_scene_material *m = &scene->objects[0].material;
    double co, ft = gt_normal_transmission(m, &co);
    sss_gl_param_value p[2] = {{"splat_energy", 1.0}, {"surfel_pixels", 1.0}};
    sss_image im;
    splat_work w;
    if (!render_k(scene, "dss", p, 2, 2, &im, &w)) {
        CHECK(0);
        return;
    }
    double mean[3];
    centre_mean(&im, mean);
    for (int c = 0; c < 3; c++) {
        double expect = co * ft * m->albedo[c];
        printf("dss k = 2, one-pixel surfels, channel %d: %+.4f%% against c_o F_t E rho_eff (bound 0.5%%)\n", c,
               100.0 * (mean[c] / expect - 1.0));
        CHECK_REL(mean[c], expect, 0.005);
    }
    sss_image_free(&im);
}

int main(void)
{
    sss_scene scene;
    if (!write_grid("ssaa_plane") || !plane_scene(0, 0, &scene)) {
        CHECK(0);
        return CHECK_DONE();
    }
    const double half = 1.0 / 2048.0; /* half-float: 11 significant bits */
    const double same = 2.5e-4;       /* the k = 1 image: float sums of the splats */
    const plane_case cases[] = {
        {"local", 2, half, half, -1, 0},         {"local", 3, half, half, -1, 0},
        {"local", 4, half, half, -1, 0},         {"ssss", 2, half, half, -1, 0},
        {"ssss-gauss6", 2, half, half, -1, 0},   {"ssss-svd", 2, half, half, -1, 0},
        {"sam", 2, half, half, -1, 0},           {"maisch2020", 2, 0.0075, 0.01, -1, 0},
        {"screen", 2, 0.0075, 0.01, -1, 0},      {"mertens2003", 2, 0.001, 0.05, -1, 0},
        {"chen2012", 2, same, same, 0, 1.01},    {"dss", 2, same, same, 0, 1.01},
        {"dss", 3, same, same, 0, 1.01},         {"chen2012", 2, 0.01, 0.03, -1, 1.75},
        {"dss", 2, 0.03, 0.0, -1, 1.75},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) compare(&scene, &cases[i]);
    dss_fine_energy(&scene);
    sss_scene_free(&scene);
    unlink(grid_path);
    return CHECK_DONE();
}
