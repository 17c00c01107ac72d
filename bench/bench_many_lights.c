/* bench_many_lights — the CPU ground truth's direct light with many point lights: the Marble bunny of
 * scenes/default.json at 32 x 32, draft quality, under a square grid of N point lights of equal total
 * intensity, N = 1 .. 4096 (SSS_SCENE_MAX_LIGHTS). Up to 64 point lights every light gets a shadow ray
 * at every surface point; beyond that a light tree draws 64 of them (src/reference/ref_light_tree.c), so
 * the surface samples' time should stop growing with N there.
 * Reports per N: the median over 3 renders of the surface-sample time and of the whole render.
 * usage: bench_many_lights [--assets DIR]   (DIR holds bunny.ply; default: assets) */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sss/common.h"
#include "sss/reference.h"
#include "sss/scene.h"

#define RUNS 3

/* The scene with an n x n grid of lights 14 units above the floor, as JSON (malloc'd). */
static char *scene_json(int n)
{
    size_t cap = 1024 + (size_t)n * n * 128;
    char *json = malloc(cap);
    if (!json) return NULL;
    size_t len = (size_t)snprintf(
        json, cap,
        "{\"camera\": {\"position\": [0, 6, 30], \"look_at\": [0, 4.6, 0], \"fov\": 30, \"width\": 32, \"height\": 32},\n"
        " \"objects\": [{\"mesh\": \"bunny.ply\", \"transform\": {\"rotate\": [0, 1, 0, -20]},\n"
        "   \"material\": {\"type\": \"subsurface\", \"medium\": \"Marble\", \"scale\": 1.5, \"eta\": 1.33}},\n"
        "  {\"procedural\": {\"shape\": \"plane\", \"size\": 80}, \"material\": {\"type\": \"diffuse\", "
        "\"reflectance\": [0.5, 0.5, 0.5]}}],\n \"lights\": [");
    double intensity = 4000.0 / ((double)n * n);
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            double x = n > 1 ? -20.0 + 40.0 * i / (n - 1) : 0.0, z = n > 1 ? -20.0 + 40.0 * j / (n - 1) : 0.0;
            len += (size_t)snprintf(json + len, cap - len,
                                    "%s{\"type\": \"point\", \"position\": [%.4f, 14, %.4f], \"intensity\": [%.6g, %.6g, %.6g]}",
                                    i || j ? ", " : "", x, z, intensity, intensity, intensity);
        }
    snprintf(json + len, cap - len, "]}\n");
    return json;
}

int main(int argc, char **argv)
{
    const char *assets = "assets";
    if (argc == 3 && strcmp(argv[1], "--assets") == 0) {
        assets = argv[2];
    } else if (argc != 1) {
        fprintf(stderr, "usage: bench_many_lights [--assets DIR]\n");
        return 2;
    }
    const int grids[] = {1, 4, 8, 9, 16, 32, 64};
    printf("%8s %14s %12s   (median of %d, draft, 32 x 32, bounces 1)\n", "lights", "samples (s)", "total (s)",
           RUNS);
    for (size_t g = 0; g < sizeof grids / sizeof grids[0]; g++) {
        char *json = scene_json(grids[g]);
        sss_scene scene;
        sss_error err;
        if (!json || sss_scene_parse(json, strlen(json), assets, "many_lights", NULL, &scene, &err) != SSS_OK) {
            fprintf(stderr, "bench_many_lights: %s\n", json ? err.message : "out of memory");
            free(json);
            return 1;
        }
        free(json);
        sss_reference_desc d;
        memset(&d, 0, sizeof d);
        d.quality = SSS_REFERENCE_DRAFT;
        d.bounces = 1; /* the direct light only: interreflection does not depend on the lights' count */
        double samples[RUNS], total[RUNS];
        for (int r = 0; r < RUNS; r++) {
            sss_image img;
            sss_reference_stats st;
            if (sss_reference_render(&scene, &d, &img, NULL, NULL, &st, &err) != SSS_OK) {
                fprintf(stderr, "bench_many_lights: %s\n", err.message);
                return 1;
            }
            samples[r] = st.seconds_samples, total[r] = st.seconds_total;
            sss_image_free(&img);
        }
        printf("%8d %14.3f %12.3f\n", grids[g] * grids[g], sss_median(samples, RUNS), sss_median(total, RUNS));
        sss_scene_free(&scene);
    }
    return 0;
}
