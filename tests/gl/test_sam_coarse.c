/* Technique "sam" with the back side on a lower-tessellation mesh (Maisch & Ropinski 2017, section 4.4 and its
 * appendix) on the back-lit dragon (scenes/gl_backlit.json, 51k vertices, against the cached reference
 * tests/data/gl/ref_backlit.exr). The dragon is Maisch & Ropinski 2017's hard case: at n = 3 the links to three
 * neighbouring back-side vertices of the fine mesh cover a tiny part of the back side. On a coarse mesh
 * the same n links cover far more, so the image at equal n is closer to the reference.
 *
 * Measured (llvmpipe, Mesa 22.3, surface ssss, 64 Monte Carlo pairs; DSSIM):
 *   back side                  n = 3    n = 10   n = 50
 *   the mesh itself (100k)     0.165    0.143    0.110
 *   simplified to 5000         0.108    0.081    0.057
 *   splat_mesh dragon_low 11k  0.136    0.116    0.085
 * Checked here, at n = 3 unless said: simplified to 5000 below 0.13 (measured + a fifth) and at least
 * 0.03 below the mesh itself; n = 10 below n = 3 on the same coarse mesh; the scene's splat_mesh as back
 * side (backside_splat) below the mesh itself; every image finite. */
#include "gl_test_util.h"

/* Under AddressSanitizer the maps are built with 8 Monte Carlo pairs per form factor instead of 64. */
#if defined(__SANITIZE_ADDRESS__)
#define MAP_SAMPLES 8
#else
#define MAP_SAMPLES 64
#endif

static double dragon(const sss_scene *scene, const sss_image *ref, double n, double back_tris, double splat)
{
    sss_gl_param_value p[4] = {{"samples", MAP_SAMPLES}, {"n", n}, {"backside_triangles", back_tris},
                               {"backside_splat", splat}};
    return gt_technique_dssim(scene, ref, "sam", p, 4);
}

int main(void)
{
    sss_scene scene;
    sss_image ref;
    if (!gt_load("gl_backlit.json", &scene) || !gt_read_ref("ref_backlit.exr", &ref)) return 1;
    double fine3 = dragon(&scene, &ref, 3, 0, 0);
    double coarse3 = dragon(&scene, &ref, 3, 5000, 0);
    double coarse10 = dragon(&scene, &ref, 10, 5000, 0);
    double splat3 = dragon(&scene, &ref, 3, 0, 1);
    printf("backlit dragon, DSSIM: n = 3 on the mesh itself %.4f, on 5000 triangles %.4f (n = 10: %.4f), on the "
           "splat mesh %.4f\n",
           fine3, coarse3, coarse10, splat3);
    CHECK_MSG(coarse3 < 0.13, "coarse n = 3: %g", coarse3);
    CHECK_MSG(coarse3 < fine3 - 0.03, "coarse %g, fine %g", coarse3, fine3);
    CHECK(coarse10 < coarse3);
    CHECK_MSG(splat3 < fine3, "splat mesh %g, fine %g", splat3, fine3);
    /* both back-side parameters at once is an error, not a guess */
    sss_gl_param_value both[2] = {{"backside_triangles", 5000}, {"backside_splat", 1}};
    sss_gl_renderer_desc d;
    memset(&d, 0, sizeof d);
    d.technique = "sam";
    d.params = both;
    d.param_count = 2;
    sss_gl_renderer *r = NULL;
    sss_error err = {0};
    CHECK(sss_gl_renderer_create(gt_ctx(), &scene, &d, &r, &err) != SSS_OK);
    printf("both: %s\n", err.message);
    CHECK(strstr(err.message, "exclude") != NULL);
    sss_gl_renderer_destroy(r);
    sss_image_free(&ref);
    sss_scene_free(&scene);
    return CHECK_DONE();
}
