/* sss_gl_kernel_cut (no GL context): a technique warns when a material spreads half of its light farther
 * than the technique carries it. A torus of tube radius r = 0.35 (R = 0.8): Cauchy's mean chord
 * 4 V / A of a torus is 2 r = 0.7 whatever R (V = 2 pi^2 R r^2, A = 4 pi^2 R r), the support the ssss
 * family declares. A magenta medium with a mean free path of 1 (red, blue) spreads half of its light
 * beyond the tube: ssss, ssss-svd, burley, sam (its ssss front) and local warn, naming object, material and
 * technique; with a mean free path of 0.01 none does; maisch2020 and dss, which carry light across the
 * object, never do. local's support is one pixel at the object: 2 d tan(fov / 2) / 96. */
#include <math.h>
#include <string.h>

#include "check.h"
#include "sss/gl.h"
#include "sss/scene.h"

static const char *scene_text(double mfp_rb, double mfp_g, char *buf, size_t cap)
{
    snprintf(buf, cap,
             "{\"camera\": {\"position\": [0, 0, 4], \"look_at\": [0, 0, 0], \"fov\": 40, \"width\": 96, \"height\": 96},"
             " \"objects\": [{\"procedural\": {\"shape\": \"torus\", \"major\": 0.8, \"minor\": 0.35, \"segments\": 96},"
             " \"material\": {\"type\": \"subsurface\", \"reflectance\": [0.8, 0.2, 0.8], \"mfp\": [%g, %g, %g]}},"
             " {\"procedural\": {\"shape\": \"plane\", \"size\": 6}, \"transform\": {\"translate\": [0, -1.2, 0]},"
             " \"material\": {\"type\": \"diffuse\", \"reflectance\": [0.4, 0.4, 0.4]}}],"
             " \"lights\": [{\"type\": \"point\", \"position\": [0, 2, 2], \"intensity\": [5, 5, 5]}]}",
             mfp_rb, mfp_g, mfp_rb);
    return buf;
}

static int load(double mfp_rb, double mfp_g, sss_scene *s)
{
    char text[2048];
    sss_error err = {0};
    scene_text(mfp_rb, mfp_g, text, sizeof text);
    if (sss_scene_parse(text, strlen(text), NULL, "torus", NULL, s, &err) == SSS_OK) return 1;
    fprintf(stderr, "scene: %s\n", err.message);
    return 0;
}

static int cut(const sss_scene *s, const char *tech, int object, double *reach, double *support)
{
    sss_gl_renderer_desc d;
    memset(&d, 0, sizeof d);
    d.technique = tech;
    return sss_gl_kernel_cut(s, &d, object, reach, support);
}

int main(void)
{
    sss_scene lng, shrt;
    if (!load(1.0, 0.05, &lng) || !load(0.01, 0.002, &shrt)) return 1;
    static const char *const cutting[] = {"ssss", "ssss-svd", "burley", "sam", "local"};
    double reach = 0, support = 0;
    for (size_t i = 0; i < sizeof cutting / sizeof cutting[0]; i++) {
        CHECK_MSG(cut(&lng, cutting[i], 0, &reach, &support) == 1, "%s, long mfp: reach %g, support %g", cutting[i],
                  reach, support);
        CHECK_MSG(cut(&shrt, cutting[i], 0, &reach, &support) == 0, "%s, short mfp: reach %g, support %g", cutting[i],
                  reach, support);
    }
    /* the support of ssss is the torus' mean chord 2 r (the tessellation's polygons: within 1%) */
    cut(&lng, "ssss", 0, &reach, &support);
    CHECK_REL(support, 0.7, 0.01);
    /* local: one pixel at the torus' centre, 4 units away, 96 pixels over 40 degrees */
    cut(&lng, "local", 0, &reach, &support);
    CHECK_REL(support, 2.0 * 4.0 * tan(20.0 * M_PI / 180.0) / 96.0, 1e-9);
    for (int k = 0; k < 2; k++) {
        const char *tech = k ? "dss" : "maisch2020";
        CHECK_MSG(cut(&lng, tech, 0, &reach, &support) == 0 && isinf(support), "%s cuts (support %g)", tech, support);
    }
    /* not a subsurface object, unknown technique */
    CHECK(cut(&lng, "ssss", 1, NULL, NULL) == -1);
    CHECK(cut(&lng, "nosuch", 0, NULL, NULL) == -1);
    /* the warning names the object, its material and the technique */
    sss_gl_renderer_desc d;
    memset(&d, 0, sizeof d);
    d.technique = "ssss";
    char text[1024];
    CHECK(sss_gl_kernel_cut_warnings(&lng, &d, text, sizeof text) == 1);
    CHECK_MSG(strstr(text, "object 0") && strstr(text, "reflectance 0.8 0.2 0.8, mfp 1 0.05 1") && strstr(text, "ssss"),
              "%s", text);
    CHECK(sss_gl_kernel_cut_warnings(&shrt, &d, text, sizeof text) == 0 && text[0] == '\0');
    d.technique = "maisch2020";
    CHECK(sss_gl_kernel_cut_warnings(&lng, &d, text, sizeof text) == 0);
    sss_scene_free(&lng);
    sss_scene_free(&shrt);
    return CHECK_DONE();
}
