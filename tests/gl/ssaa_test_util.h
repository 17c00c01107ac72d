/* tests/gl/ssaa_test_util.h — rendering with supersampling (sss_gl_renderer_desc.supersample) for the
 * SSAA tests. */
#ifndef SSS_SSAA_TEST_UTIL_H
#define SSS_SSAA_TEST_UTIL_H

#include "gl_test_util.h"

/* Renders scene with technique, parameters and SSAA factor k at the camera's size; out is created. */
static inline int ssaa_render(const sss_scene *scene, const char *technique, const sss_gl_param_value *params,
                              int nparams, int k, sss_image *out)
{
    sss_error err = {0};
    sss_gl_renderer_desc d;
    memset(&d, 0, sizeof d);
    d.technique = technique;
    d.params = params;
    d.param_count = nparams;
    d.supersample = k;
    sss_gl_renderer *r = NULL;
    memset(out, 0, sizeof *out);
    if (sss_gl_renderer_create(gt_ctx(), scene, &d, &r, &err) != SSS_OK || sss_gl_renderer_render(r, 0.0, &err) != SSS_OK ||
        sss_image_create(out, scene->camera.width, scene->camera.height, &err) != SSS_OK ||
        sss_gl_renderer_read(r, out, &err) != SSS_OK) {
        fprintf(stderr, "%s, supersample %d: render failed: %s\n", technique ? technique : "scene's technique", k,
                err.message);
        sss_gl_renderer_destroy(r);
        sss_image_free(out);
        return 0;
    }
    sss_gl_renderer_destroy(r);
    return 1;
}

#endif
