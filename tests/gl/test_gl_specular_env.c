/* The interface's specular reflection of an environment map (docs/scene-format.md `specular`): under a constant
 * environment of radiance L, a smooth interface adds exactly F_r(n . v) L to what the camera sees,
 * whatever the mip level the roughness selects, and nothing is added without `specular`. At the
 * centre of a sphere facing the camera n . v = 1, so the added radiance is ((eta - 1)/(eta + 1))^2 L. */
#include <unistd.h>

#include "gl_test_util.h"

static const char *scene_fmt =
    "{\"camera\": {\"position\": [0, 0, 4], \"look_at\": [0, 0, 0], \"fov\": 30, \"width\": 64, \"height\": 64},"
    " \"objects\": [{\"procedural\": {\"shape\": \"sphere\", \"radius\": 1, \"subdivisions\": 5},"
    "   \"material\": {\"type\": \"subsurface\", \"medium\": \"Marble\", \"scale\": 10, \"eta\": %g%s}}],"
    " \"lights\": [{\"type\": \"environment\", \"file\": \"const.hdr\", \"scale\": [%g, %g, %g]}]}";

static int render(const char *dir, double eta, const char *specular, const double L[3], sss_image *out)
{
    char json[2048];
    snprintf(json, sizeof json, scene_fmt, eta, specular, L[0], L[1], L[2]);
    sss_scene scene = {0};
    sss_error err = {0};
    if (sss_scene_parse(json, strlen(json), dir, "specular.json", NULL, &scene, &err) != SSS_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 0;
    }
    int ok = gt_render(&scene, "maisch2020", 0.0, NULL, 0, out);
    sss_scene_free(&scene);
    return ok;
}

static void centre(const sss_image *img, double out[3])
{
    /* mean of the 2 x 2 pixels around the image centre (the sphere's point facing the camera) */
    for (int c = 0; c < 3; c++) {
        out[c] = 0.0;
        for (int y = 31; y <= 32; y++)
            for (int x = 31; x <= 32; x++) out[c] += 0.25 * img->pixels[3 * ((size_t)y * img->width + x) + c];
    }
}

int main(void)
{
    char dir[] = "/tmp/sss-spec-XXXXXX";
    if (!mkdtemp(dir)) return 1;
    char map[512];
    snprintf(map, sizeof map, "%s/const.hdr", dir);
    sss_image env;
    sss_error err = {0};
    CHECK(sss_image_create(&env, 32, 16, &err) == SSS_OK);
    for (size_t i = 0; i < 32 * 16 * 3; i++) env.pixels[i] = 1.0f;
    CHECK(sss_image_write(map, &env, 0.0, &err) == SSS_OK);
    sss_image_free(&env);

    const double L[3] = {0.5, 1.0, 2.0};
    const double etas[2] = {1.33, 1.8};
    const char *roughness[2] = {", \"specular\": {\"roughness\": 0}", ", \"specular\": {\"roughness\": 0.6}"};
    for (int e = 0; e < 2; e++) {
        sss_image plain, shiny;
        CHECK(render(dir, etas[e], "", L, &plain));
        double f0 = pow((etas[e] - 1.0) / (etas[e] + 1.0), 2.0), a[3], b[3];
        centre(&plain, a);
        for (int r = 0; r < 2; r++) {
            CHECK(render(dir, etas[e], roughness[r], L, &shiny));
            centre(&shiny, b);
            for (int c = 0; c < 3; c++)
                CHECK_MSG(fabs((b[c] - a[c]) - f0 * L[c]) <= 0.02 * f0 * L[c],
                          "eta %g roughness #%d channel %d: added %g, expected F L = %g", etas[e], r, c,
                          b[c] - a[c], f0 * L[c]);
            CHECK(sss_image_count_nonfinite(&shiny) == 0);
            sss_image_free(&shiny);
        }
        sss_image_free(&plain);
    }
    remove(map);
    rmdir(dir);
    return CHECK_DONE();
}
