/* bench_reference — the CPU ground truth on the Stanford dragon (assets/dragon.ply, ~100k triangles)
 * at 512x512 in Marble with `scale` such that the mean free path 1/sigma_t' of the largest channel
 * (blue: sigma_t' = 3.0071 / mm) is a tenth of the model's largest bounding-box extent, lit by one
 * point light from behind.
 *
 * Reports: wall time of `final` quality on the available cores (target: under 60 s on 2 cores), the
 * DSSIM between `final` and a render with 4x the samples (4x the surface-sample density and 4x the
 * pixel samples; target: under 0.002), the surface-sample count and tree statistics.
 * usage: bench_reference [--assets DIR] [--out DIR] [--quick]
 *   --assets: folder holding dragon.ply (default: assets, i.e. run from the repository root)
 *   --out: where bench_reference_{final,4x}.{png,exr} are written (default: the current folder)
 *   --quick: 256x256, draft vs final, for a smoke run */
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sss/common.h"
#include "sss/reference.h"
#include "sss/scene.h"

static const char *scene_fmt =
    "{\n"
    "  \"camera\": { \"position\": [0.0, 0.125, 0.45], \"look_at\": [-0.006, 0.125, -0.0046],\n"
    "              \"fov\": 30.0, \"width\": %d, \"height\": %d },\n"
    "  \"objects\": [ { \"mesh\": \"dragon.ply\",\n"
    "      \"material\": { \"type\": \"subsurface\", \"medium\": \"Marble\", \"scale\": %.6f, \"eta\": 1.33 } } ],\n"
    "  \"lights\": [ { \"type\": \"point\", \"position\": [0.03, 0.22, -0.3], \"intensity\": [0.25, 0.25, 0.25] } ],\n"
    "  \"render\": { \"exposure\": 0.0 }\n"
    "}\n";

static void print_stats(const char *label, const sss_reference_stats *s)
{
    printf("%s: %.2f s total (setup %.2f, samples %.2f, tree %.2f, pixels %.2f)\n", label, s->seconds_total,
           s->seconds_setup, s->seconds_samples, s->seconds_tree, s->seconds_pixels);
    printf("  surface samples %llu, spacing h %.3g, R0 %.3g; tree %llu nodes, %llu leaves, depth %u\n",
           (unsigned long long)s->surface_samples, s->spacing_min, s->split_radius_min,
           (unsigned long long)s->tree_nodes, (unsigned long long)s->tree_leaves, s->tree_depth);
    printf("  camera samples %llu (%llu pixels refined), sums %llu, %.0f nodes+samples per sum\n",
           (unsigned long long)s->camera_samples, (unsigned long long)s->adaptive_pixels,
           (unsigned long long)s->lookups, s->nodes_per_lookup);
}

static int render(const sss_scene *scene, const sss_reference_desc *d, sss_image *img, sss_reference_stats *st,
                  const char *dir, const char *name)
{
    sss_error err;
    if (sss_reference_render(scene, d, img, NULL, NULL, st, &err) != SSS_OK) {
        fprintf(stderr, "bench_reference: %s\n", err.message);
        return 0;
    }
    char path[1024];
    snprintf(path, sizeof path, "%s/bench_reference_%s.png", dir, name);
    if (sss_image_write(path, img, scene->render.exposure, &err) != SSS_OK) fprintf(stderr, "%s\n", err.message);
    snprintf(path, sizeof path, "%s/bench_reference_%s.exr", dir, name);
    if (sss_image_write(path, img, 0.0, &err) != SSS_OK) fprintf(stderr, "%s\n", err.message);
    return 1;
}

int main(int argc, char **argv)
{
    const char *dir = ".", *assets = "assets";
    int quick = 0;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--quick") == 0) {
            quick = 1;
        } else if (strcmp(argv[i], "--assets") == 0 && i + 1 < argc) {
            assets = argv[++i];
        } else if (strcmp(argv[i], "--out") == 0 && i + 1 < argc) {
            dir = argv[++i];
        } else {
            fprintf(stderr, "usage: bench_reference [--assets DIR] [--out DIR] [--quick]\n");
            return 2;
        }
    }
    /* Largest bounding-box extent of dragon.ply (assets/README.md): x, 0.0965 - (-0.1083). */
    double extent = 0.0965 + 0.1083;
    double scale = 1.0 / (3.0071 * 0.1 * extent); /* mm per scene unit: 1/sigma_t' = extent / 10 */
    int size = quick ? 256 : 512;
    char json[2048];
    snprintf(json, sizeof json, scene_fmt, size, size, scale);
    sss_scene scene;
    sss_error err;
    if (sss_scene_parse(json, strlen(json), assets, "bench_dragon", NULL, &scene, &err) != SSS_OK) {
        fprintf(stderr, "bench_reference: %s\n", err.message);
        return 1;
    }
    printf("dragon %dx%d, Marble scale %.3f (mfp %.4g = extent / 10), %d threads\n", size, size, scale,
           0.1 * extent, omp_get_max_threads());
    sss_reference_desc d;
    memset(&d, 0, sizeof d);
    d.quality = quick ? SSS_REFERENCE_DRAFT : SSS_REFERENCE_FINAL;
    sss_image a, b;
    sss_reference_stats sa, sb;
    if (!render(&scene, &d, &a, &sa, dir, quick ? "draft" : "final")) return 1;
    print_stats(quick ? "draft" : "final", &sa);
    /* 4x the samples: 4x the surface density, 4x the pixel samples of the quality. */
    sss_reference_desc d4 = d;
    if (quick) {
        d4.quality = SSS_REFERENCE_FINAL;
    } else {
        d4.density = 4.0;
        d4.spp = 64; /* final's default is 16 */
    }
    if (!render(&scene, &d4, &b, &sb, dir, quick ? "final" : "4x")) return 1;
    print_stats(quick ? "final" : "4x samples", &sb);
    sss_image_metrics m;
    if (sss_image_compare(&a, &b, scene.render.exposure, &m, NULL, &err) != SSS_OK) {
        fprintf(stderr, "bench_reference: %s\n", err.message);
        return 1;
    }
    printf("DSSIM %s vs %s: %.5f (PSNR %.2f dB, RMSE %.3f, max abs %.0f)\n", quick ? "draft" : "final",
           quick ? "final" : "4x", m.dssim, m.psnr, m.rmse, m.max_abs);
    sss_image_free(&a);
    sss_image_free(&b);
    sss_scene_free(&scene);
    return 0;
}
