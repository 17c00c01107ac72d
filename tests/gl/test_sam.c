/* Technique "sam" (Maisch & Ropinski 2017) against the CPU ground truth (cached references, tests/data/gl/README.md).
 *
 * Convergence (Maisch & Ropinski 2017, Fig. 10): on a back-lit sphere of 162 vertices (tests/data/gl/sam_backlit.json,
 * Marble at 5 mm per unit: the scattering distance is about the radius) the RMSE against the reference
 * falls with every step of n = 3, 10, 20, 50 (measured 44.9, 38.3, 32.0, 19.1 in 8-bit codes). The links
 * rank form factors, not light: the nearest back-side vertices (past the sphere's equator as seen from
 * x_o) come first, the lit cap opposite later, so convergence is slow here as in the paper's Fig. 10.
 * With every back-side vertex linked (n = 100) the centre of the sphere, where Eq. 13-14's back side
 * holds all the light that enters, has the reference's brightness (same absolute units: measured
 * within 2%).
 *
 * The two test scenes of the issue, DSSIM bounds = the value measured when the test was written
 * (llvmpipe, Mesa 22.3, n = 3, surface ssss) plus about a fifth, each below a baseline that misses
 * what it tests:
 *   scene            measured   bound   baselines
 *   backlit dragon   0.165      0.185   translucency off 0.186, local 0.190 (n = 50: 0.110)
 *   shadow edge      0.018      0.025   local 0.040
 *   twist t = 1      0.018      0.025   (deforming: links updated through adjacency)
 * The back-lit dragon is Maisch & Ropinski 2017's hard case (section 5.2: a finely tessellated model, small against
 * the mean free path): three links cover three reduced fans, a small part of the back side that
 * transmits light, so the image is darker than the reference; more links converge (n = 50 measured).
 * Time (Eq. 17-18): the first frame is never blended; a frame one second later converges to the
 * single-frame result (alpha = 1 - 1e-20); a base of 0.5 mixes in the previous frame. */
#include <unistd.h>

#include "gl_test_util.h"
#include "sss/sam.h"

/* Under AddressSanitizer the maps of the 51k-vertex dragon and 55k-vertex head are built with 8 Monte
 * Carlo pairs per form factor instead of 64 (measured: the same DSSIM to three decimals). */
#if defined(__SANITIZE_ADDRESS__)
#define MAP_SAMPLES 8
#else
#define MAP_SAMPLES 64
#endif

static int render_with(const sss_scene *scene, const char *data, const sss_gl_param_value *params, int nparams,
                       const double *times, int ntimes, sss_image *out, sss_error *err)
{
    sss_gl_renderer_desc d = gt_desc("sam", params, nparams, 0); /* single-event, as the references */
    d.data_file = data;
    sss_gl_renderer *r = NULL;
    memset(out, 0, sizeof *out);
    int ok = sss_gl_renderer_create(gt_ctx(), scene, &d, &r, err) == SSS_OK;
    for (int i = 0; ok && i < ntimes; i++) ok = sss_gl_renderer_render(r, times[i], err) == SSS_OK;
    ok = ok && sss_image_create(out, scene->camera.width, scene->camera.height, err) == SSS_OK &&
         sss_gl_renderer_read(r, out, err) == SSS_OK;
    if (!ok) sss_image_free(out);
    sss_gl_renderer_destroy(r);
    return ok;
}

static int load_data_scene(const char *name, sss_scene *scene)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/gl/%s", SSS_TEST_DATA, name);
    sss_error err = {0};
    if (sss_scene_load(path, NULL, scene, &err) != SSS_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 0;
    }
    return 1;
}

/* Mean of the central 16 x 16 pixels: there the back side of Eq. 13-14 is where the light enters
 * (towards the silhouette part of the lit surface is neither visible nor "back", and the split of
 * section 3.2 leaves it out: the whole image's mean is lower than the reference's by design). */
static void block_mean(const sss_image *a, double mean[3])
{
    mean[0] = mean[1] = mean[2] = 0.0;
    int x0 = a->width / 2 - 8, y0 = a->height / 2 - 8;
    for (int y = y0; y < y0 + 16; y++)
        for (int x = x0; x < x0 + 16; x++)
            for (int c = 0; c < 3; c++) mean[c] += a->pixels[3 * ((size_t)y * a->width + x) + c] / 256.0;
}

static void test_convergence(void)
{
    sss_scene scene;
    sss_image ref;
    if (!load_data_scene("sam_backlit.json", &scene) || !gt_read_ref("sam_backlit_ref.exr", &ref)) {
        CHECK(0);
        return;
    }
    static const int ns[5] = {3, 10, 20, 50, 100};
    double rmse[5], mean50[3] = {0, 0, 0}, mref[3], whole50[3] = {0, 0, 0}, whole_ref[3];
    /* one renderer: changing n rebuilds the maps (sss_gl_renderer_set_param) */
    sss_gl_renderer_desc d;
    memset(&d, 0, sizeof d);
    d.technique = "sam";
    sss_gl_renderer *r = NULL;
    sss_error err = {0};
    sss_image img = {0};
    int ok = sss_gl_renderer_create(gt_ctx(), &scene, &d, &r, &err) == SSS_OK &&
             sss_image_create(&img, scene.camera.width, scene.camera.height, &err) == SSS_OK;
    for (int i = 0; i < 5; i++) {
        rmse[i] = 1e9;
        if (!ok || sss_gl_renderer_set_param(r, "n", ns[i], &err) != SSS_OK ||
            sss_gl_renderer_render(r, 0.0, &err) != SSS_OK || sss_gl_renderer_read(r, &img, &err) != SSS_OK) {
            fprintf(stderr, "%s\n", err.message);
            CHECK(0);
            continue;
        }
        sss_image_metrics m;
        CHECK(sss_image_compare(&img, &ref, 0.0, &m, NULL, &err) == SSS_OK);
        rmse[i] = m.rmse;
        printf("sam_backlit n = %2d: RMSE %.2f, DSSIM %.4f\n", ns[i], m.rmse, m.dssim);
        if (i == 4) { /* every back-side vertex linked (about 81 of 162) */
            block_mean(&img, mean50);
            gt_mean(&img, whole50);
        }
    }
    sss_image_free(&img);
    sss_gl_renderer_destroy(r);
    for (int i = 0; i + 1 < 4; i++) CHECK_MSG(rmse[i + 1] < rmse[i], "n = %d: %g, n = %d: %g", ns[i], rmse[i], ns[i + 1], rmse[i + 1]);
    CHECK(rmse[3] < 0.6 * rmse[0]);
    block_mean(&ref, mref);
    gt_mean(&ref, whole_ref);
    for (int c = 0; c < 3; c++) {
        printf("channel %d: centre mean, all links %.4g, reference %.4g\n", c, mean50[c], mref[c]);
        CHECK_REL(mean50[c], mref[c], 0.1);
        /* the whole disc: darker (the split misses the lit rim), never brighter */
        printf("channel %d: image mean, all links %.4g, reference %.4g\n", c, whole50[c], whole_ref[c]);
        CHECK(whole50[c] < 1.05 * whole_ref[c]);
    }
    sss_image_free(&ref);
    sss_scene_free(&scene);
}

static void test_scene(const char *file, const char *ref_name, double t, double bound, int baseline)
{
    sss_scene scene;
    sss_image ref, img, off;
    if (!gt_load(file, &scene) || !gt_read_ref(ref_name, &ref)) {
        CHECK(0);
        return;
    }
    sss_error err = {0};
    sss_gl_param_value samples = {"samples", MAP_SAMPLES};
    /* renderer_read refuses NaN/Inf: a successful read is the finiteness check */
    CHECK(render_with(&scene, NULL, &samples, 1, &t, 1, &img, &err));
    if (err.message[0]) fprintf(stderr, "%s\n", err.message);
    CHECK(img.pixels && sss_image_count_nonfinite(&img) == 0);
    double d = gt_dssim(&img, &ref), dl = 1.0;
    if (baseline == 1) { /* the same technique without its translucency */
        sss_gl_param_value p = {"translucency", 0};
        CHECK(render_with(&scene, NULL, &p, 1, &t, 1, &off, &err));
        dl = gt_dssim(&off, &ref);
        sss_image_free(&off);
    } else if (baseline == 2) {
        CHECK(gt_render(&scene, "local", t, NULL, 0, &off));
        dl = gt_dssim(&off, &ref);
        sss_image_free(&off);
    }
    printf("%s t = %g: DSSIM %.4f (bound %.3f, baseline %.4f)\n", file, t, d, bound, dl);
    CHECK_MSG(d < bound, "%s: DSSIM %g >= %g", file, d, bound);
    if (baseline) CHECK(d < dl);
    sss_image_free(&img);
    sss_image_free(&ref);
    sss_scene_free(&scene);
}

static double max_rel_diff(const sss_image *a, const sss_image *b)
{
    double m = 0.0, peak = 0.0;
    size_t n = 3 * (size_t)a->width * a->height;
    for (size_t i = 0; i < n; i++) {
        double d = fabs(a->pixels[i] - b->pixels[i]);
        if (d > m) m = d;
        if (fabs(b->pixels[i]) > peak) peak = fabs(b->pixels[i]);
    }
    return peak > 0.0 ? m / peak : m;
}

static const char TWIST_SPHERE[] =
    "{\"camera\": {\"position\": [0, 0.6, 5], \"look_at\": [0, 0, 0], \"fov\": 30, \"width\": 48, \"height\": 48},"
    " \"objects\": [{\"procedural\": {\"shape\": \"sphere\", \"radius\": 1, \"subdivisions\": 2},"
    "   \"material\": {\"type\": \"subsurface\", \"medium\": \"Marble\", \"scale\": 5, \"eta\": 1.33},"
    "   \"animation\": {\"type\": \"twist\", \"amplitude\": 80, \"period\": 4}}],"
    " \"lights\": [{\"type\": \"point\", \"position\": [0.8, 1.2, -4], \"intensity\": [300, 300, 300]}]}";

static void test_time_and_files(void)
{
    sss_scene scene;
    sss_error err = {0};
    if (sss_scene_parse(TWIST_SPHERE, sizeof TWIST_SPHERE - 1, ".", "twist_sphere", NULL, &scene, &err) != SSS_OK) {
        fprintf(stderr, "%s\n", err.message);
        CHECK(0);
        return;
    }
    sss_gl_param_value fixed[3] = {{"update_steps", 0}, {"surface", 0}, {"temporal", 1}};
    sss_image single, two, blended, off, same;
    double t1 = 1.0, seq[2] = {0.0, 1.0}, rep[2] = {1.0, 1.0};
    CHECK(render_with(&scene, NULL, fixed, 3, &t1, 1, &single, &err));
    fixed[2].value = 0;
    CHECK(render_with(&scene, NULL, fixed, 3, &t1, 1, &off, &err));
    fixed[2].value = 1;
    /* the first frame is not blended: temporal on or off give the same image */
    CHECK(max_rel_diff(&single, &off) == 0.0);
    /* a second frame at the same time changes nothing */
    CHECK(render_with(&scene, NULL, fixed, 3, rep, 2, &same, &err));
    CHECK(max_rel_diff(&same, &single) == 0.0);
    /* dt = 1 s: alpha = 1 - 1e-10 (Eq. 18), the blend has converged to the current value */
    CHECK(render_with(&scene, NULL, fixed, 3, seq, 2, &two, &err));
    double d_conv = max_rel_diff(&two, &single);
    /* base 0.5: alpha = 0.5, half of the t = 0 frame stays */
    sss_gl_param_value half[4] = {{"update_steps", 0}, {"surface", 0}, {"temporal", 1}, {"blend_base", 0.5}};
    CHECK(render_with(&scene, NULL, half, 4, seq, 2, &blended, &err));
    double d_half = max_rel_diff(&blended, &single);
    printf("temporal: converged frame differs by %.2g, alpha = 0.5 by %.3g (of the peak)\n", d_conv, d_half);
    CHECK(d_conv < 1e-5);
    CHECK(d_half > 1e-3);
    sss_image_free(&single);
    sss_image_free(&two);
    sss_image_free(&blended);
    sss_image_free(&off);
    sss_image_free(&same);
    sss_scene_free(&scene);

    /* A map from a file equals the one built at creation; other meshes' files are rejected. */
    sss_scene sb;
    if (!load_data_scene("sam_backlit.json", &sb)) {
        CHECK(0);
        return;
    }
    char dir[] = "/tmp/sss_sam_glXXXXXX", path[256];
    CHECK(mkdtemp(dir) != NULL);
    snprintf(path, sizeof path, "%s/sphere.sam", dir);
    sss_sam_desc desc;
    memset(&desc, 0, sizeof desc);
    desc.n = 10;
    desc.samples = 64;
    sss_sam map;
    CHECK(sss_sam_build_object(&sb, 0, &desc, &map, NULL, &err) == SSS_OK);
    CHECK(sss_sam_write(path, &map, &err) == SSS_OK);
    sss_sam_free(&map);
    sss_gl_param_value p10 = {"n", 10};
    sss_image built, loaded;
    CHECK(render_with(&sb, NULL, &p10, 1, (double[]){0.0}, 1, &built, &err));
    CHECK(render_with(&sb, path, NULL, 0, (double[]){0.0}, 1, &loaded, &err));
    CHECK(built.pixels && loaded.pixels && max_rel_diff(&built, &loaded) == 0.0);
    sss_image_free(&built);
    sss_image_free(&loaded);
    sss_scene twist;
    CHECK(sss_scene_parse(TWIST_SPHERE, sizeof TWIST_SPHERE - 1, ".", "twist_sphere", NULL, &twist, &err) == SSS_OK);
    /* the file belongs to the mesh, material and transform, not to the scene: the twisting sphere of
     * the same size and medium uses it ... */
    sss_image tmp;
    err.message[0] = 0;
    CHECK(render_with(&twist, path, NULL, 0, (double[]){0.0}, 1, &tmp, &err));
    sss_image_free(&tmp);
    sss_scene_free(&twist);
    /* ... the bunny does not */
    sss_scene bunny;
    CHECK(gt_load("gl_twist.json", &bunny));
    CHECK(!render_with(&bunny, path, NULL, 0, (double[]){0.0}, 1, &tmp, &err));
    printf("other mesh: %s\n", err.message);
    CHECK(strstr(err.message, "different mesh") != NULL && strstr(err.message, "sphere.sam") != NULL);
    sss_scene_free(&bunny);
    unlink(path);
    rmdir(dir);
    sss_scene_free(&sb);
}

int main(void)
{
    test_convergence();
    test_time_and_files();
    test_scene("gl_backlit.json", "ref_backlit.exr", 0.0, 0.185, 1);
    test_scene("gl_shadow_edge.json", "ref_shadow_edge.exr", 0.0, 0.025, 2);
    test_scene("gl_twist.json", "ref_twist_t1.exr", 1.0, 0.025, 0);
    return CHECK_DONE();
}
