/* The interreflection stage (src/gl/core/interreflection.c, docs/interreflection.md) against what
 * physics fixes:
 *  - form factor: a 4 x 4 floor lit by a directional light travelling parallel to a 4 x 4 wall that
 *    stands on the floor's back edge. The wall gets no direct light and casts no shadow; one bounce
 *    gives it E(p) = M_floor F(p), M_floor the floor's exitance and F the form factor from the wall's
 *    point p to the floor, integrated here by a 300 x 300 midpoint rule (independent of the code). The
 *    wall shows rho_w / pi E. Floor diffuse (M = rho_f E_0) and subsurface with a short kernel (M = F_t E_0
 *    rho_eff, the PBD albedo of the medium: Jensen et al. 2001's total diffuse reflectance);
 *  - energy never grows: a black floor lights nothing (the wall stays exactly 0), a black wall stays 0;
 *  - no second surface: a lone sphere and a lone plane render bit for bit as without the stage;
 *  - preset=paper turns it off (bit for bit as interreflection=0).
 * Measured with the defaults (512 sources, stride 8): printed below. */
#include "gl/gl_test.h"
#include "gl_test_util.h"
#include "sss/profile.h"

#define SIZE 96

static int parse(const char *json, sss_scene *scene)
{
    sss_error err = {0};
    if (sss_scene_parse(json, strlen(json), ".", "interreflection", NULL, scene, &err) != SSS_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 0;
    }
    return 1;
}

/* Floor (material `floor`) and wall (diffuse, reflectance rho_w) under a light travelling along
 * (0.6, -0.8, 0): E_0 = 0.8 on the floor, 0 on the wall (normal +z). */
static int plates(const char *floor, double rho_w, sss_scene *scene)
{
    char json[2048];
    snprintf(json, sizeof json,
             "{\"camera\": {\"position\": [0, 2, 9], \"look_at\": [0, 2, -2], \"up\": [0, 1, 0], \"fov\": 34,"
             " \"width\": %d, \"height\": %d},"
             " \"objects\": [{\"procedural\": {\"shape\": \"plane\", \"size\": 4.0}, \"material\": %s},"
             " {\"procedural\": {\"shape\": \"plane\", \"size\": 4.0},"
             "  \"transform\": {\"rotate\": [1, 0, 0, 90], \"translate\": [0, 2, -2]},"
             "  \"material\": {\"type\": \"diffuse\", \"reflectance\": [%g, %g, %g]}}],"
             " \"lights\": [{\"type\": \"directional\", \"direction\": [0.6, -0.8, 0], \"radiance\": [1, 1, 1]}]}",
             SIZE, SIZE, floor, rho_w, rho_w, rho_w);
    return parse(json, scene);
}

/* Form factor from the wall point (px, py, -2), normal +z, to the floor [-2, 2] x {0} x [-2, 2]. */
static double form_factor(double px, double py)
{
    const int n = 300;
    const double h = 4.0 / n;
    double sum = 0.0;
    for (int i = 0; i < n; i++)
        for (int k = 0; k < n; k++) {
            double dx = -2.0 + (i + 0.5) * h - px, dy = -py, dz = -2.0 + (k + 0.5) * h + 2.0;
            double d2 = dx * dx + dy * dy + dz * dz;
            sum += dz * -dy / (d2 * d2); /* cos_w cos_f / d^2 with cosines dz / d and -dy / d */
        }
    return sum * h * h / M_PI;
}

/* Renders `final` and the G-buffer positions (when pos is not NULL) with the library's defaults but for p. */
static int render(const sss_scene *scene, const char *technique, const sss_gl_param_value *p, int np, sss_image *out,
                  sss_image *pos)
{
    sss_error err = {0};
    sss_gl_renderer_desc d; /* not gt_desc, which turns the stage off */
    memset(&d, 0, sizeof d);
    d.technique = technique;
    d.params = p;
    d.param_count = np;
    sss_gl_renderer *r = NULL;
    memset(out, 0, sizeof *out);
    if (pos) memset(pos, 0, sizeof *pos);
    int ok = sss_gl_renderer_create(gt_ctx(), scene, &d, &r, &err) == SSS_OK &&
             sss_gl_renderer_render(r, 0.0, &err) == SSS_OK &&
             sss_image_create(out, scene->camera.width, scene->camera.height, &err) == SSS_OK &&
             sss_gl_renderer_read(r, out, &err) == SSS_OK;
    if (ok && pos) {
        const gl_core *core = gl_test_renderer_core(r);
        ok = gl_read_texture_rgb(core->frame.pos, 0, core->width, core->height, pos, &err) == SSS_OK;
    }
    if (!ok) fprintf(stderr, "render failed: %s\n", err.message);
    sss_gl_renderer_destroy(r);
    return ok;
}

/* The wall's pixels away from its edges (0.6 <= y <= 3.4, |x| <= 1.4): mean and worst ratio of the
 * rendered radiance to rho_w / pi M F, per channel. */
static void wall_ratio(const sss_image *img, const sss_image *pos, double rho_w, const double M[3], double mean[3],
                       double worst[3], int *count)
{
    double sum[3] = {0, 0, 0};
    *count = 0;
    for (int c = 0; c < 3; c++) worst[c] = 1.0;
    for (size_t i = 0; i < (size_t)img->width * img->height; i++) {
        const float *p = pos->pixels + 3 * i;
        if (fabs(p[2] + 2.0) > 1e-3 || p[1] < 0.6 || p[1] > 3.4 || fabs(p[0]) > 1.4) continue;
        double f = form_factor(p[0], p[1]);
        for (int c = 0; c < 3; c++) {
            double ratio = img->pixels[3 * i + (size_t)c] / (rho_w / M_PI * M[c] * f);
            sum[c] += ratio;
            if (fabs(ratio - 1.0) > fabs(worst[c] - 1.0)) worst[c] = ratio;
        }
        (*count)++;
    }
    for (int c = 0; c < 3; c++) mean[c] = *count ? sum[c] / *count : 0.0;
}

/* The form factor gives the first bounce (a second would return the wall's light via the floor). */
static const sss_gl_param_value one_bounce[1] = {{"interreflection_bounces", 1}};

/* At 96 rows the default gathers at every pixel; 12 rows gather every 8th and upsample. */
static void test_diffuse_plates(void)
{
    sss_scene s;
    if (!plates("{\"type\": \"diffuse\", \"reflectance\": [0.5, 0.5, 0.5]}", 0.8, &s)) {
        CHECK(0);
        return;
    }
    for (int k = 0; k < 2; k++) {
        sss_gl_param_value p[2] = {one_bounce[0], {"interreflection_rows", k ? 12 : 68}};
        sss_image img, pos;
        if (render(&s, "screen", p, 2, &img, &pos)) {
            double M[3] = {0.5 * 0.8, 0.5 * 0.8, 0.5 * 0.8}, mean[3], worst[3];
            int n;
            wall_ratio(&img, &pos, 0.8, M, mean, worst, &n);
            printf("diffuse floor -> wall, %g rows: %d pixels, mean ratio %.4f, worst %.4f\n", p[1].value, n, mean[1],
                   worst[1]);
            CHECK(n > 500);
            CHECK_NEAR(mean[1], 1.0, 0.01);
            CHECK_NEAR(worst[1], 1.0, 0.05);
        } else {
            CHECK(0);
        }
        sss_image_free(&img);
        sss_image_free(&pos);
    }
    sss_scene_free(&s);
}

/* Skin1 at 200 per unit: its longest (red) kernel falls off within ~0.02 units (1 / sigma_tr), so the 4-unit floor is an
 * infinite slab for all but its rim; M = F_t(0.8) E_0 rho_eff per channel. */
static void test_subsurface_floor(void)
{
    sss_scene s;
    if (!plates("{\"type\": \"subsurface\", \"medium\": \"Skin1\", \"scale\": 200.0, \"eta\": 1.33}", 0.8, &s)) {
        CHECK(0);
        return;
    }
    const sss_scene_material *fm = &s.objects[0].material;
    double ft = 1.0 - sss_fresnel_dielectric(0.8, 1.0, fm->optical.eta), M[3];
    for (int c = 0; c < 3; c++) {
        double sa = fm->optical.sigma_a[c], ss = fm->optical.sigma_s[c];
        M[c] = ft * 0.8 * sss_pbd_rho_eff(fm->table, ss / (sa + ss));
    }
    sss_image img, pos;
    if (render(&s, "screen", one_bounce, 1, &img, &pos)) {
        double mean[3], worst[3];
        int n;
        wall_ratio(&img, &pos, 0.8, M, mean, worst, &n);
        for (int c = 0; c < 3; c++) {
            printf("subsurface floor -> wall, channel %d (M = %.4f): mean ratio %.4f, worst %.4f\n", c, M[c], mean[c],
                   worst[c]);
            CHECK_NEAR(mean[c], 1.0, 0.01);
            CHECK_NEAR(worst[c], 1.0, 0.05);
        }
    } else {
        CHECK(0);
    }
    sss_image_free(&img);
    sss_image_free(&pos);
    sss_scene_free(&s);
}

static int bit_identical(const sss_image *a, const sss_image *b)
{
    return a->width == b->width && a->height == b->height &&
           memcmp(a->pixels, b->pixels, sizeof(float) * 3 * (size_t)a->width * a->height) == 0;
}

/* A black floor sends nothing: the frame equals the one without the stage; a black wall stays black. */
static void test_energy(void)
{
    static const sss_gl_param_value off[1] = {{"interreflection", 0}};
    sss_scene s;
    sss_image on, without, pos;
    if (plates("{\"type\": \"diffuse\", \"reflectance\": [0, 0, 0]}", 0.8, &s)) {
        if (render(&s, "screen", NULL, 0, &on, NULL) && render(&s, "screen", off, 1, &without, NULL)) {
            CHECK_MSG(bit_identical(&on, &without), "a black floor must light nothing");
        } else {
            CHECK(0);
        }
        sss_image_free(&on);
        sss_image_free(&without);
        sss_scene_free(&s);
    }
    if (plates("{\"type\": \"diffuse\", \"reflectance\": [0.5, 0.5, 0.5]}", 0.0, &s)) {
        if (render(&s, "screen", NULL, 0, &on, &pos)) {
            double peak = 0.0;
            for (size_t i = 0; i < (size_t)on.width * on.height; i++)
                if (fabs(pos.pixels[3 * i + 2] + 2.0) < 1e-3)
                    for (int c = 0; c < 3; c++) peak = fmax(peak, fabs(on.pixels[3 * i + (size_t)c]));
            CHECK_MSG(peak == 0.0, "a black wall shows %g", peak);
        } else {
            CHECK(0);
        }
        sss_image_free(&on);
        sss_image_free(&pos);
        sss_scene_free(&s);
    }
}

/* One convex object or one plane: no light leaves one surface towards another. */
static void test_no_second_surface(void)
{
    static const char *const scenes[3] = {
        "{\"camera\": {\"position\": [0, 0, 5], \"look_at\": [0, 0, 0], \"fov\": 40, \"width\": 64, \"height\": 64},"
        " \"objects\": [{\"procedural\": {\"shape\": \"sphere\", \"radius\": 1.0, \"subdivisions\": 4},"
        " \"material\": {\"type\": \"subsurface\", \"medium\": \"Marble\", \"scale\": 5.0, \"eta\": 1.33}}],"
        " \"lights\": [{\"type\": \"point\", \"position\": [3, 2, -2], \"intensity\": [20, 20, 20]}]}",
        "{\"camera\": {\"position\": [0, 3, 3], \"look_at\": [0, 0, 0], \"fov\": 50, \"width\": 64, \"height\": 64},"
        " \"objects\": [{\"procedural\": {\"shape\": \"plane\", \"size\": 4.0},"
        " \"material\": {\"type\": \"subsurface\", \"medium\": \"Marble\", \"scale\": 5.0, \"eta\": 1.33}}],"
        " \"lights\": [{\"type\": \"spot\", \"position\": [1, 2, 0], \"look_at\": [0, 0, 0], \"intensity\": [20, 20, 20],"
        " \"cone_angle\": 40, \"cone_delta\": 5}]}",
        /* 320 flat facets, fewer than the budget: the sources are halved facets on the rendered surface,
         * where rounding near shared edges once gave pairs of cosines of ~1e-7 (10 values of 1 ulp) */
        "{\"camera\": {\"position\": [0, 0.6, 5], \"look_at\": [0, 0, 0], \"fov\": 30, \"width\": 64, \"height\": 64},"
        " \"objects\": [{\"procedural\": {\"shape\": \"sphere\", \"radius\": 1.0, \"subdivisions\": 2},"
        " \"material\": {\"type\": \"subsurface\", \"medium\": \"Marble\", \"scale\": 5.0, \"eta\": 1.33}}],"
        " \"lights\": [{\"type\": \"point\", \"position\": [0.8, 1.2, -4], \"intensity\": [300, 300, 300]}]}"};
    static const sss_gl_param_value off[1] = {{"interreflection", 0}};
    const char *techniques[3] = {"screen", "ssss", "burley"}; /* deterministic ones (maisch2020 is not, run to run) */
    static const char *const names[3] = {"sphere", "plane", "coarse sphere"};
    for (int k = 0; k < 3; k++) {
        sss_scene s;
        if (!parse(scenes[k], &s)) {
            CHECK(0);
            continue;
        }
        for (int t = 0; t < 3; t++) {
            sss_image on, without;
            if (render(&s, techniques[t], NULL, 0, &on, NULL) && render(&s, techniques[t], off, 1, &without, NULL))
                CHECK_MSG(bit_identical(&on, &without), "%s, %s: the stage changed a scene with one surface",
                          names[k], techniques[t]);
            else
                CHECK(0);
            sss_image_free(&on);
            sss_image_free(&without);
        }
        sss_scene_free(&s);
    }
}

static void test_paper_preset(void)
{
    static const sss_gl_param_value paper[1] = {{"preset", SSS_GL_PRESET_PAPER}}, off[1] = {{"interreflection", 0}};
    sss_scene s;
    if (!plates("{\"type\": \"diffuse\", \"reflectance\": [0.5, 0.5, 0.5]}", 0.8, &s)) {
        CHECK(0);
        return;
    }
    sss_image a, b, c;
    if (render(&s, "screen", paper, 1, &a, NULL) && render(&s, "screen", off, 1, &b, NULL) &&
        render(&s, "screen", NULL, 0, &c, NULL)) {
        CHECK_MSG(bit_identical(&a, &b), "preset=paper must leave the stage off");
        CHECK_MSG(!bit_identical(&a, &c), "the default must have it on");
        CHECK(sss_gl_paper_value("maisch2020", "interreflection") == 0.0);
        CHECK(sss_gl_paper_value("burley", "interreflection") == 0.0);
    } else {
        CHECK(0);
    }
    sss_image_free(&a);
    sss_image_free(&b);
    sss_image_free(&c);
    sss_scene_free(&s);
}

/* Many objects: the sources stay within the budget (shared by area once an equal share would fall below
 * 8 triangles) and the frame renders; an equal share for a few. */
static void test_budget(void)
{
    char json[32768];
    int n = snprintf(json, sizeof json,
                     "{\"camera\": {\"position\": [0, 6, 12], \"look_at\": [0, 0, 0], \"fov\": 40, \"width\": 32,"
                     " \"height\": 32}, \"objects\": [{\"procedural\": {\"shape\": \"plane\", \"size\": 20.0},"
                     " \"material\": {\"type\": \"diffuse\", \"reflectance\": [0.5, 0.5, 0.5]}}");
    for (int i = 0; i < 150; i++)
        n += snprintf(json + n, sizeof json - (size_t)n,
                      ", {\"procedural\": {\"shape\": \"sphere\", \"radius\": 0.2, \"subdivisions\": 2},"
                      " \"transform\": {\"translate\": [%d, 0.2, %d]},"
                      " \"material\": {\"type\": \"subsurface\", \"medium\": \"Marble\", \"scale\": 20.0}}",
                      i % 15 - 7, i / 15 - 5);
    snprintf(json + n, sizeof json - (size_t)n,
             "], \"lights\": [{\"type\": \"point\", \"position\": [2, 6, 2], \"intensity\": [50, 50, 50]}]}");
    sss_scene s;
    if (!parse(json, &s)) {
        CHECK(0);
        return;
    }
    for (int k = 0; k < 2; k++) {
        sss_gl_param_value p = {"interreflection_sources", k ? 4096 : 512};
        sss_gl_renderer_desc d;
        memset(&d, 0, sizeof d);
        d.technique = "screen";
        d.params = &p;
        d.param_count = 1;
        sss_gl_renderer *r = NULL;
        sss_error err = {0};
        int ok = sss_gl_renderer_create(gt_ctx(), &s, &d, &r, &err) == SSS_OK && sss_gl_renderer_render(r, 0.0, &err) == SSS_OK;
        CHECK_MSG(ok, "%s", err.message);
        if (ok) {
            int count = gl_test_renderer_core(r)->gs.bounce_count;
            printf("151 objects, budget %g: %d sources\n", p.value, count);
            CHECK(count > 0 && count <= (int)p.value);
        }
        sss_gl_renderer_destroy(r);
    }
    sss_scene_free(&s);
}

int main(void)
{
    test_budget();
    test_diffuse_plates();
    test_subsurface_floor();
    test_energy();
    test_no_second_surface();
    test_paper_preset();
    return CHECK_DONE();
}
