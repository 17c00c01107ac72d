/* sss reference — the CPU ground truth of a scene (sss/reference.h): tone-mapped PNG plus linear
 * EXR/PFM, progress on stderr. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli/cli.h"
#include "core/file_util.h"
#include "sss/reference.h"
#include "sss/scene.h"

static const char *const CMD = "reference";

static void print_help(void)
{
    printf("usage: sss reference SCENE.json -o OUT.png [--exr OUT.exr] [--pfm OUT.pfm]\n"
           "                     [--quality draft|final] [--threads N] [--time T] [--seed S] [--exact]\n"
           "                     [--specular] [--spp N] [--density D] [--bounces N] [--stats] [--quiet]\n"
           "\n"
           "Renders the ground truth of a scene: the subsurface integral of docs/physics.md §1 as PBRT-v3's\n"
           "`subsurface` material converges to it (Embree 3 rays, surface samples with their irradiance,\n"
           "summed hierarchically), with the light that scatters between surfaces bounce after bounce\n"
           "(PBRT's path tracer; --bounces 1: direct light only, PBRT's maxdepth 1). Diffuse objects are\n"
           "Lambertian; area lights are visible; rays that miss see the environment map (black without one).\n"
           "\n"
           "options:\n"
           "  -o OUT         the image: .png is tone-mapped with the scene's render.exposure\n"
           "                 (out = srgb(clamp(linear 2^exposure, 0, 1))); .exr, .pfm, .hdr hold linear values\n"
           "  --exr OUT.exr  also write the linear image as OpenEXR\n"
           "  --pfm OUT.pfm  also write the linear image as PFM\n"
           "  --quality Q    final (default): 16 samples per pixel (64 more at edges), surface samples\n"
           "                 every half pixel at the object's nearest visible points; draft: 1 sample\n"
           "                 per pixel, surface samples every pixel\n"
           "  --threads N    worker threads (default: all cores)\n"
           "  --time T       animation time in seconds (default 0)\n"
           "  --seed S       random seed, a non-negative integer (default 0); the image depends only on\n"
           "                 the seed, not on the thread count\n"
           "  --exact        sum over every surface sample instead of the tree (slow; for validation)\n"
           "  --specular     add the smooth dielectric reflection F_r of environment maps and area lights\n"
           "                 on subsurface objects (PBRT comparisons leave it out)\n"
           "  --spp N        base samples per pixel (rounded up to a square)\n"
           "  --density D    multiply the surface-sample density by D (> 0; 4 = half the spacing)\n"
           "  --bounces N    surface-to-surface bounces, 1..%d: 1 = the single-event integral (direct\n"
           "                 light only); default: until a bounce adds less than %g%% of bounce 2's light\n"
           "  --stats        print sample counts, tree statistics and timings to stdout\n"
           "  --quiet        no progress on stderr\n"
           "\n"
           "Progress goes to stderr: a bar with the time left when stderr is a terminal, otherwise a line\n"
           "'NN%%' every 10%%. Nothing is written when the scene or an option is invalid.\n"
           "exit status: 0 done, 1 invalid scene or failed render or write, 2 usage error\n",
           SSS_REFERENCE_MAX_BOUNCES, 100.0 * SSS_REFERENCE_BOUNCE_STOP);
}

typedef struct progress_state {
    int tty, last_percent;
    double start;
} progress_state;

static void progress(void *user, double fraction, const char *stage)
{
    progress_state *p = user;
    int percent = (int)floor(100.0 * fraction);
    if (p->tty) {
        double elapsed = sss_time_seconds() - p->start;
        char eta[32] = "--:--";
        if (fraction > 0.02) {
            double left = elapsed * (1.0 - fraction) / fraction;
            int s = (int)(left + 0.5);
            snprintf(eta, sizeof eta, "%d:%02d", s / 60, s % 60);
        }
        char bar[31];
        int filled = (int)(30.0 * fraction);
        for (int i = 0; i < 30; i++) bar[i] = i < filled ? '#' : '.';
        bar[30] = '\0';
        fprintf(stderr, "\r[%s] %3d%%  ETA %s  %-16s", bar, percent, eta, stage ? stage : "");
        fflush(stderr);
    } else if (percent / 10 > p->last_percent / 10 || (percent == 100 && p->last_percent < 100)) {
        fprintf(stderr, "%d%%\n", percent - percent % 10);
    }
    if (percent > p->last_percent) p->last_percent = percent;
}

static int parse_seed(const char *text, uint64_t *out)
{
    char *end = NULL;
    errno = 0;
    if (text[0] == '-' || text[0] == '+' || text[0] == '\0') return 0;
    unsigned long long v = strtoull(text, &end, 10);
    if (*end != '\0' || errno == ERANGE) return 0;
    *out = (uint64_t)v;
    return 1;
}

static int has_extension(const char *path, const char *const *allowed)
{
    char ext[8];
    sss_path_extension(path, ext, sizeof ext);
    for (int i = 0; allowed[i]; i++)
        if (strcmp(ext, allowed[i]) == 0) return 1;
    return 0;
}

int sss_cmd_reference(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) {
        print_help();
        return CLI_EXIT_OK;
    }
    const char *scene_path = NULL, *out_path = NULL, *exr_path = NULL, *pfm_path = NULL;
    sss_reference_desc desc;
    memset(&desc, 0, sizeof desc);
    int stats = 0, quiet = 0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *v;
        if (strcmp(a, "-o") == 0 || strcmp(a, "--output") == 0) {
            if (!(out_path = cli_option_value(CMD, argc, argv, &i))) return CLI_EXIT_USAGE;
        } else if (strcmp(a, "--exr") == 0) {
            if (!(exr_path = cli_option_value(CMD, argc, argv, &i))) return CLI_EXIT_USAGE;
        } else if (strcmp(a, "--pfm") == 0) {
            if (!(pfm_path = cli_option_value(CMD, argc, argv, &i))) return CLI_EXIT_USAGE;
        } else if (strcmp(a, "--quality") == 0) {
            if (!(v = cli_option_value(CMD, argc, argv, &i))) return CLI_EXIT_USAGE;
            if (strcmp(v, "final") == 0)
                desc.quality = SSS_REFERENCE_FINAL;
            else if (strcmp(v, "draft") == 0)
                desc.quality = SSS_REFERENCE_DRAFT;
            else
                return cli_usage_error(CMD, "--quality must be draft or final, got '%s'", v);
        } else if (strcmp(a, "--threads") == 0) {
            if (!(v = cli_option_value(CMD, argc, argv, &i)) || !cli_parse_int(CMD, "--threads", v, &desc.threads))
                return CLI_EXIT_USAGE;
            if (desc.threads < 1 || desc.threads > 4096)
                return cli_usage_error(CMD, "--threads must be in 1..4096, got %d", desc.threads);
        } else if (strcmp(a, "--time") == 0) {
            if (!(v = cli_option_value(CMD, argc, argv, &i)) || !cli_parse_double(CMD, "--time", v, &desc.time))
                return CLI_EXIT_USAGE;
        } else if (strcmp(a, "--seed") == 0) {
            if (!(v = cli_option_value(CMD, argc, argv, &i))) return CLI_EXIT_USAGE;
            if (!parse_seed(v, &desc.seed))
                return cli_usage_error(CMD, "--seed expects a non-negative integer, got '%s'", v);
        } else if (strcmp(a, "--spp") == 0) {
            if (!(v = cli_option_value(CMD, argc, argv, &i)) || !cli_parse_int(CMD, "--spp", v, &desc.spp))
                return CLI_EXIT_USAGE;
            if (desc.spp < 1 || desc.spp > 4096) return cli_usage_error(CMD, "--spp must be in 1..4096, got %d", desc.spp);
        } else if (strcmp(a, "--density") == 0) {
            if (!(v = cli_option_value(CMD, argc, argv, &i)) || !cli_parse_double(CMD, "--density", v, &desc.density))
                return CLI_EXIT_USAGE;
            if (!(desc.density > 0.0) || desc.density > 1024.0)
                return cli_usage_error(CMD, "--density must be in (0, 1024], got %g", desc.density);
        } else if (strcmp(a, "--bounces") == 0) {
            if (!(v = cli_option_value(CMD, argc, argv, &i)) || !cli_parse_int(CMD, "--bounces", v, &desc.bounces))
                return CLI_EXIT_USAGE;
            if (desc.bounces < 1 || desc.bounces > SSS_REFERENCE_MAX_BOUNCES)
                return cli_usage_error(CMD, "--bounces must be in 1..%d, got %d", SSS_REFERENCE_MAX_BOUNCES,
                                       desc.bounces);
        } else if (strcmp(a, "--exact") == 0) {
            desc.exact = 1;
        } else if (strcmp(a, "--specular") == 0) {
            desc.specular = 1;
        } else if (strcmp(a, "--stats") == 0) {
            stats = 1;
        } else if (strcmp(a, "--quiet") == 0 || strcmp(a, "-q") == 0) {
            quiet = 1;
        } else if (a[0] == '-' && a[1] != '\0') {
            return cli_usage_error(CMD, "unknown option '%s'", a);
        } else {
            if (scene_path) return cli_usage_error(CMD, "expects one scene, got a second: '%s'", a);
            scene_path = a;
        }
    }
    if (!scene_path) return cli_usage_error(CMD, "expects a scene file");
    if (!out_path) return cli_usage_error(CMD, "needs an output image: -o OUT.png");
    static const char *const any[] = {"png", "exr", "pfm", "hdr", NULL}, *const exr[] = {"exr", NULL},
                             *const pfm[] = {"pfm", NULL};
    if (!has_extension(out_path, any))
        return cli_usage_error(CMD, "-o needs a .png, .exr, .pfm or .hdr file name, got '%s'", out_path);
    if (exr_path && !has_extension(exr_path, exr))
        return cli_usage_error(CMD, "--exr needs a .exr file name, got '%s'", exr_path);
    if (pfm_path && !has_extension(pfm_path, pfm))
        return cli_usage_error(CMD, "--pfm needs a .pfm file name, got '%s'", pfm_path);

    sss_scene scene;
    sss_error err;
    memset(&err, 0, sizeof err);
    if (sss_scene_load(scene_path, NULL, &scene, &err) != SSS_OK) return cli_fail(CMD, &err);
    const char *paths[3] = {out_path, exr_path, pfm_path};
    if (cli_check_outputs(CMD, paths, 3, NULL, 0, &scene) != CLI_EXIT_OK) {
        sss_scene_free(&scene);
        return CLI_EXIT_ERROR;
    }
    progress_state ps = {isatty(fileno(stderr)), -1, sss_time_seconds()};
    sss_image img = {0};
    sss_reference_stats st;
    sss_result r = sss_reference_render(&scene, &desc, &img, quiet ? NULL : progress, &ps, &st, &err);
    if (!quiet && ps.tty) fputc('\n', stderr);
    int status = CLI_EXIT_OK;
    if (r != SSS_OK) {
        status = cli_fail(CMD, &err);
        goto done;
    }
    if (sss_image_count_nonfinite(&img) != 0) {
        status = cli_failf(CMD, "%s: the image has NaN or Inf values; nothing written", scene_path);
        goto done;
    }
    for (int k = 0; k < 3; k++) {
        if (!paths[k]) continue;
        if (sss_image_write(paths[k], &img, scene.render.exposure, &err) != SSS_OK) {
            status = cli_fail(CMD, &err);
            goto done;
        }
    }
    if (stats) {
        printf("surface_samples=%llu spacing=%.6g..%.6g split_radius=%.6g\n", (unsigned long long)st.surface_samples,
               st.spacing_min, st.spacing_max, st.split_radius_min);
        printf("tree_nodes=%llu tree_leaves=%llu tree_depth=%u\n", (unsigned long long)st.tree_nodes,
               (unsigned long long)st.tree_leaves, st.tree_depth);
        printf("camera_samples=%llu refined_pixels=%llu sums=%llu nodes_per_sum=%.1f\n",
               (unsigned long long)st.camera_samples, (unsigned long long)st.adaptive_pixels,
               (unsigned long long)st.lookups, st.nodes_per_lookup);
        printf("seconds: setup=%.3f samples=%.3f tree=%.3f pixels=%.3f total=%.3f\n", st.seconds_setup,
               st.seconds_samples, st.seconds_tree, st.seconds_pixels, st.seconds_total);
        printf("bounces=%u transport_samples=%llu\n", st.bounces, (unsigned long long)st.transport_samples);
        for (uint32_t k = 0; k < st.bounces && k < SSS_REFERENCE_MAX_BOUNCES; k++)
            printf("bounce %u: seconds=%.3f light=%.4f (of bounce 2)\n", k + 1, st.seconds_bounce[k],
                   st.bounce_fraction[k]);
    }
done:
    sss_image_free(&img);
    sss_scene_free(&scene);
    return status;
}
