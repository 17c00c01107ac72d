/* tests/gl/test_env_small_maps.c — environment maps whose median cut has regions that cannot split
 * (8x8 grey, 64x32 black, 256x128 with one bright pixel, the 32x32 map `sss reference` writes) ran
 * past the light buffers in every technique. Each renders now, through every technique, with finite
 * pixels; the black map lights nothing. Run under ASan by `make sanitize`. */
#include <stdlib.h>
#include <unistd.h>

#include "gl_test_util.h"

typedef struct test_map {
    const char *name;
    int w, h;
    float grey;      /* every pixel */
    int spike;       /* index of one bright pixel, or -1 */
} test_map;

static const test_map maps[] = {
    {"grey8.hdr", 8, 8, 0.5f, -1},
    {"black64x32.hdr", 64, 32, 0.0f, -1},
    {"spike256x128.hdr", 256, 128, 0.0f, 128 * 40 + 77},
    {"sky32.hdr", 32, 32, 0.2f, 32 * 5 + 3},
};

static int write_map(const char *dir, const test_map *m)
{
    sss_image img;
    sss_error err = {0};
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, m->name);
    if (sss_image_create(&img, m->w, m->h, &err) != SSS_OK) return 0;
    for (size_t i = 0; i < (size_t)m->w * m->h; i++)
        for (int k = 0; k < 3; k++) img.pixels[3 * i + k] = (int)i == m->spike ? 5000.0f : m->grey;
    int ok = sss_image_write(path, &img, 0.0, &err) == SSS_OK;
    if (!ok) fprintf(stderr, "%s\n", err.message);
    sss_image_free(&img);
    return ok;
}

static int load_scene(const char *dir, const char *map, sss_scene *scene)
{
    char text[1024];
    int n = snprintf(text, sizeof text,
                     "{\"camera\": {\"position\": [0, 0, 3.5], \"look_at\": [0, 0, 0], \"fov\": 40, \"width\": 32,"
                     " \"height\": 32},"
                     " \"objects\": [{\"procedural\": {\"shape\": \"sphere\", \"radius\": 1, \"subdivisions\": 2},"
                     " \"material\": {\"type\": \"subsurface\", \"medium\": \"Skin1\", \"scale\": 10}}],"
                     " \"lights\": [{\"type\": \"environment\", \"file\": \"%s\"}]}",
                     map);
    sss_error err = {0};
    if (sss_scene_parse(text, (size_t)n, dir, "env_small_maps", NULL, scene, &err) != SSS_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 0;
    }
    return 1;
}

int main(void)
{
    char dir[] = "/tmp/sss_env_maps_XXXXXX";
    CHECK(mkdtemp(dir) != NULL);
    for (size_t i = 0; i < sizeof maps / sizeof *maps; i++) CHECK(write_map(dir, &maps[i]));
    for (size_t i = 0; i < sizeof maps / sizeof *maps; i++) {
        sss_scene scene;
        if (!load_scene(dir, maps[i].name, &scene)) {
            CHECK(0);
            continue;
        }
        for (int t = 0; t < sss_gl_technique_count(); t++) {
            const char *tech = sss_gl_technique_at(t)->name;
            sss_image img;
            int ok = gt_render_k(&scene, tech, 0.0, NULL, 0, 0, &img);
            CHECK_MSG(ok, "%s with %s", tech, maps[i].name);
            if (!ok) continue;
            float max = 0.0f;
            int finite = 1;
            for (size_t p = 0; p < (size_t)img.width * img.height * 3; p++) {
                finite &= isfinite(img.pixels[p]) && img.pixels[p] >= 0.0f;
                if (img.pixels[p] > max) max = img.pixels[p];
            }
            CHECK_MSG(finite, "%s with %s: a pixel is negative, NaN or Inf", tech, maps[i].name);
            if (maps[i].grey == 0.0f && maps[i].spike < 0) CHECK_MSG(max == 0.0f, "%s: black map gives %g", tech, max);
            else CHECK_MSG(max > 0.0f, "%s with %s: black image", tech, maps[i].name);
            sss_image_free(&img);
        }
        sss_scene_free(&scene);
    }
    for (size_t i = 0; i < sizeof maps / sizeof *maps; i++) {
        char path[1024];
        snprintf(path, sizeof path, "%s/%s", dir, maps[i].name);
        unlink(path);
    }
    rmdir(dir);
    return CHECK_DONE();
}
