/* bench_sam — Spatial Adjacency Maps (Maisch & Ropinski 2017): build time of `sss sam build` for the bunny and the
 * dragon with Marble at a scattering distance comparable to the model's size (1 / sigma_tr of the red
 * channel, 8.5 mm, against a 10 mm bunny at scale 1 and a 10 mm dragon at scale 50), n = 3 and 50,
 * all cores; then milliseconds per pass of the technique `sam` at 960x540 on the back-lit dragon
 * (scenes/gl_backlit.json), medians over frames, timed with glFinish on software GL.
 * Usage: bench_sam [frames [repo-root]] (default 5 frames, the current folder). Maisch & Ropinski 2017 report 20.16 min (Happy Buddha) and 23.83 h
 * (Chinese Dragon) of precomputation. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"
#include "sss/gl.h"
#include "sss/sam.h"
#include "sss/scene.h"

static const char *root = "."; /* the repository (argv[2]; run from it by default) */

static void build(const char *mesh_name, double scale, uint32_t n, sss_pbd_table *table)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/assets/%s", root, mesh_name);
    sss_error err = {0};
    sss_mesh m;
    sss_material mat;
    sss_profile p;
    if (sss_mesh_read(path, &m, &err) != SSS_OK || sss_material_from_medium("Marble", scale, 1.33, &mat, &err) != SSS_OK ||
        sss_profile_init(&p, SSS_PROFILE_PBD, &mat, table, &err) != SSS_OK) {
        fprintf(stderr, "%s\n", err.message);
        return;
    }
    sss_sam_desc d;
    memset(&d, 0, sizeof d);
    d.n = n;
    sss_sam s;
    sss_sam_stats st;
    if (sss_sam_build(&m, &p, &d, &s, &st, &err) != SSS_OK) {
        fprintf(stderr, "%s\n", err.message);
        sss_mesh_free(&m);
        return;
    }
    double pairs = (double)m.vertex_count * m.vertex_count;
    printf("sam build %-11s %6u vertices %6u triangles  Marble scale %-4g n = %-2u %8.2f s  tested %.3f%% of pairs, "
           "%llu form factors (%.1f per vertex)\n",
           mesh_name, m.vertex_count, m.triangle_count, scale, n, st.seconds, 100.0 * st.vertices_tested / pairs,
           (unsigned long long)st.form_factors, (double)st.form_factors / m.vertex_count);
    sss_sam_free(&s);
    sss_mesh_free(&m);
}

static void passes(int frames)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/scenes/gl_backlit.json", root);
    sss_error err = {0};
    sss_scene scene;
    if (sss_scene_load(path, NULL, &scene, &err) != SSS_OK) {
        fprintf(stderr, "%s\n", err.message);
        return;
    }
    sss_gl_context *ctx = NULL;
    if (sss_gl_context_create(NULL, &ctx, &err) != SSS_OK) {
        fprintf(stderr, "%s\n", err.message);
        sss_scene_free(&scene);
        return;
    }
    sss_gl_renderer_desc d;
    memset(&d, 0, sizeof d);
    d.technique = "sam";
    d.width = 960;
    d.height = 540;
    d.timings = 1;
    sss_gl_renderer *r = NULL;
    double t0 = sss_time_seconds();
    if (sss_gl_renderer_create(ctx, &scene, &d, &r, &err) != SSS_OK) {
        fprintf(stderr, "%s\n", err.message);
    } else {
        printf("renderer creation (map of the %u-vertex dragon built, n = 3): %.2f s\n",
               scene.objects[0].mesh.vertex_count, sss_time_seconds() - t0);
        double ms[SSS_GL_MAX_PASSES][64];
        const char *names[SSS_GL_MAX_PASSES];
        int np = 0;
        if (frames > 64) frames = 64;
        for (int f = 0; f <= frames; f++) { /* frame 0 compiles the shaders: not counted */
            if (sss_gl_renderer_render(r, 0.0, &err) != SSS_OK) {
                fprintf(stderr, "%s\n", err.message);
                break;
            }
            sss_gl_timings t;
            sss_gl_renderer_timings(r, &t);
            np = t.pass_count;
            for (int p = 0; p < t.pass_count; p++) {
                names[p] = t.passes[p].name;
                if (f > 0) ms[p][f - 1] = t.passes[p].ms;
            }
        }
        double total = 0.0, sam_total = 0.0;
        printf("technique sam, 960x540, back-lit dragon, median of %d frames (glFinish + monotonic clock):\n", frames);
        for (int p = 0; p < np; p++) {
            double med = sss_median(ms[p], frames);
            printf("  %-16s %9.2f ms\n", names[p], med);
            total += med;
            if (strncmp(names[p], "sam_", 4) == 0) sam_total += med;
        }
        printf("  %-16s %9.2f ms (sam's own passes %.2f ms)\n", "total", total, sam_total);
    }
    sss_gl_renderer_destroy(r);
    sss_gl_context_destroy(ctx);
    sss_scene_free(&scene);
}

static sss_pbd_table table;

static void bunny_n3(void *ctx)
{
    (void)ctx;
    build("bunny.ply", 1.0, 3, &table);
}

int main(int argc, char **argv)
{
    int frames = argc > 1 ? atoi(argv[1]) : 5;
    if (argc > 2) root = argv[2];
    if (frames < 1) frames = 1;
    sss_error err = {0};
    if (sss_pbd_table_build(1.33, 0.0, &table, &err) != SSS_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
    bench_run("sam build bunny n = 3 (whole call, with reading)", 3, bunny_n3, NULL);
    build("bunny.ply", 1.0, 50, &table);
    build("dragon.ply", 50.0, 3, &table);
    build("dragon.ply", 50.0, 50, &table);
    passes(frames);
    return 0;
}
