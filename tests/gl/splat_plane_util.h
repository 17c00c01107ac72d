/* tests/gl/splat_plane_util.h — the flat-plane fixture of the splatting techniques' energy tests
 * (dss, chen2012): a finely gridded plane seen head-on under one or two directional lights. */
#ifndef SSS_SPLAT_PLANE_UTIL_H
#define SSS_SPLAT_PLANE_UTIL_H

#include <unistd.h>

#include "gl_test_util.h"

/* A 2 x 2 plane in the xz-plane facing +y as an OBJ grid of 32 x 32 cells (2048 triangles, within the
 * default splat mesh budget, so the splat mesh is this grid): the surfels then tile it about a pixel
 * apart. (The procedural plane's two triangles reach only 1/64 of their 2.8-unit edge, the
 * tessellation limit: their surfels' pattern, 5 pixels wide, made a 32-pixel window's mean depend on
 * where the window falls by 3%.) */
static char grid_path[256];

/* The plane as nx x nz cells (two triangles each); tag names the temporary file (one per test program). */
static inline int write_grid_cells(const char *tag, int nx, int nz)
{
    snprintf(grid_path, sizeof grid_path, "/tmp/sss_test_%s_%ld.obj", tag, (long)getpid());
    FILE *f = fopen(grid_path, "w");
    if (!f) return 0;
    for (int j = 0; j <= nz; j++)
        for (int i = 0; i <= nx; i++) fprintf(f, "v %g 0 %g\n", -1.0 + 2.0 * i / nx, -1.0 + 2.0 * j / nz);
    for (int j = 0; j < nz; j++)
        for (int i = 0; i < nx; i++) {
            int a = j * (nx + 1) + i + 1, b = a + 1, c = a + nx + 1, d = c + 1;
            fprintf(f, "f %d %d %d\nf %d %d %d\n", a, c, b, b, c, d); /* counter-clockwise seen from +y */
        }
    return fclose(f) == 0;
}

/* The 32 x 32 grid above. */
static inline int write_grid(const char *tag)
{
    return write_grid_cells(tag, 32, 32);
}

/* Skin1 at 200 mm per unit (the red kernel reaches ~0.08 units) seen head-on from 1 unit, 64 x 64,
 * under the lights of `lights` (the JSON array's contents). */
static inline int plane_scene_lights(const char *lights, const char *name, sss_scene *scene)
{
    char json[2048];
    snprintf(json, sizeof json,
             "{\"camera\": {\"position\": [0, 1, 0], \"look_at\": [0, 0, 0], \"up\": [0, 0, -1], \"fov\": 30,"
             " \"width\": 64, \"height\": 64},"
             " \"objects\": [{\"mesh\": \"%s\","
             " \"material\": {\"type\": \"subsurface\", \"medium\": \"Skin1\", \"scale\": 200.0, \"eta\": 1.33}}],"
             " \"lights\": [%s]}",
             grid_path, lights);
    sss_error err = {0};
    if (sss_scene_parse(json, strlen(json), ".", name, NULL, scene, &err) != SSS_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 0;
    }
    return 1;
}

/* The plane under directional light(s) travelling straight down (and a second, oblique one). */
static inline int plane_scene(int two_lights, int which, sss_scene *scene)
{
    const char *l1 = "{\"type\": \"directional\", \"direction\": [0, -1, 0], \"radiance\": [1, 1, 1]}";
    const char *l2 = "{\"type\": \"directional\", \"direction\": [0.3, -1, 0.2], \"radiance\": [0.5, 0.7, 0.9]}";
    char lights[512];
    if (two_lights) snprintf(lights, sizeof lights, "%s, %s", l1, l2);
    else snprintf(lights, sizeof lights, "%s", which == 0 ? l1 : l2);
    return plane_scene_lights(lights, "plane", scene);
}

/* Linearity in the lights: the plane under both directional lights renders as the sum of the two
 * renders under each alone (largest relative difference per pixel below 1e-3). */
static inline void plane_lights_add(const char *technique, const sss_gl_param_value *params, int nparams)
{
    sss_scene both, a, b;
    if (!plane_scene(1, 0, &both) || !plane_scene(0, 0, &a) || !plane_scene(0, 1, &b)) {
        CHECK(0);
        return;
    }
    sss_image ib, ia, ic;
    CHECK(gt_render(&both, technique, 0.0, params, nparams, &ib));
    CHECK(gt_render(&a, technique, 0.0, params, nparams, &ia));
    CHECK(gt_render(&b, technique, 0.0, params, nparams, &ic));
    double worst = 0.0;
    for (size_t i = 0; i < 3 * (size_t)ib.width * ib.height; i++) {
        double sum = ia.pixels[i] + ic.pixels[i];
        double d = fabs(ib.pixels[i] - sum) / (sum > 1e-6 ? sum : 1e-6);
        if (d > worst) worst = d;
    }
    printf("%s, two lights vs the sum of each alone: largest relative difference %.2e\n", technique, worst);
    CHECK(worst < 1e-3);
    sss_image_free(&ib);
    sss_image_free(&ia);
    sss_image_free(&ic);
    sss_scene_free(&both);
    sss_scene_free(&a);
    sss_scene_free(&b);
}

/* Mean of the central half of the image per channel. */
static inline void centre_mean(const sss_image *im, double m[3])
{
    m[0] = m[1] = m[2] = 0.0;
    int n = 0;
    for (int y = im->height / 4; y < 3 * im->height / 4; y++)
        for (int x = im->width / 4; x < 3 * im->width / 4; x++, n++)
            for (int c = 0; c < 3; c++) m[c] += im->pixels[3 * ((size_t)y * im->width + x) + c];
    for (int c = 0; c < 3; c++) m[c] /= n;
}

#endif
