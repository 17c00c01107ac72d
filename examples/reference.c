/* examples/reference.c — the CPU ground truth of a scene (what the real-time techniques approximate).
 *
 *   example_reference SCENE.json OUT.png [draft|final]      e.g.  example_reference scene.json ref.png draft
 *
 * Renders the subsurface integral of every translucent object under direct lighting with Embree 3 and
 * OpenMP (all cores); `draft` is fast and noisier, `final` (the default) the converged image. OUT.png
 * is tone-mapped with the scene's exposure; an .exr/.pfm/.hdr name keeps the linear values. The image depends only on the scene, the quality and the seed (0 here), not on the thread
 * count: `sss reference SCENE.json --quality Q -o OUT.png` writes the same pixels.
 *
 * Build: cc reference.c $(pkg-config --cflags --libs sss), or CMake: find_package(sss) and sss::sss.
 */
#include <stdio.h>
#include <string.h>

#include <sss/sss.h>

/* Called by the renderer now and then with the fraction done; prints every 25%. */
static void report_progress(void *user, double fraction, const char *stage)
{
    int *last_quarter = user;
    int quarter = (int)(4.0 * fraction);
    if (quarter > *last_quarter) {
        *last_quarter = quarter;
        fprintf(stderr, "%3d%% %s\n", 25 * quarter, stage ? stage : "");
    }
}

int main(int argc, char **argv)
{
    if (argc < 3 || argc > 4 || (argc == 4 && strcmp(argv[3], "draft") != 0 && strcmp(argv[3], "final") != 0)) {
        fprintf(stderr, "usage: %s SCENE.json OUT.png [draft|final]\n", argv[0]);
        return 2;
    }
    const char *scene_path = argv[1], *output = argv[2];
    sss_error err = {0};

    sss_scene scene;
    if (sss_scene_load(scene_path, NULL, &scene, &err) != SSS_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
    /* Zero-initialised: final quality, all cores, time 0, seed 0. */
    sss_reference_desc desc = {0};
    if (argc == 4 && strcmp(argv[3], "draft") == 0) desc.quality = SSS_REFERENCE_DRAFT;

    sss_image image = {0};
    int last_quarter = 0;
    /* The statistics (sample counts, timings) are optional: NULL. */
    sss_result result = sss_reference_render(&scene, &desc, &image, report_progress, &last_quarter, NULL, &err);
    /* A guard the sss tool has too: never write NaN or Inf pixels. */
    if (result == SSS_OK && sss_image_count_nonfinite(&image) != 0)
        result = sss_error_set(&err, SSS_ERROR_NUMERIC, "%s: the image has NaN or Inf values", scene_path);
    if (result == SSS_OK) result = sss_image_write(output, &image, scene.render.exposure, &err);
    if (result != SSS_OK) fprintf(stderr, "%s\n", err.message);
    sss_image_free(&image);
    sss_scene_free(&scene);
    return result == SSS_OK ? 0 : 1;
}
