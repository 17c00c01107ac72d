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

enum {
    OPT_OUTPUT, OPT_EXR, OPT_PFM, OPT_WIDTH, OPT_HEIGHT, OPT_QUALITY, OPT_THREADS, OPT_TIME, OPT_SEED, OPT_EXACT,
    OPT_SPECULAR, OPT_SPP, OPT_DENSITY, OPT_BOUNCES, OPT_STATS
};
static const cli_option options[] = {
    {OPT_OUTPUT, "--output", "-o", CLI_ARG_FILE, "OUT",
     "the image: .png is tone-mapped with the scene's render.exposure\n"
     "(out = srgb(clamp(linear 2^exposure, 0, 1))); .exr, .pfm, .hdr hold linear values",
     NULL},
    {OPT_EXR, "--exr", NULL, CLI_ARG_FILE, "OUT.exr", "also write the linear image as OpenEXR", NULL},
    {OPT_PFM, "--pfm", NULL, CLI_ARG_FILE, "OUT.pfm", "also write the linear image as PFM", NULL},
    {OPT_WIDTH, "--width", NULL, CLI_ARG_NUMBER, "W", "image width (default: the scene camera's)", NULL},
    {OPT_HEIGHT, "--height", NULL, CLI_ARG_NUMBER, "H", "image height (default: the scene camera's)", NULL},
    {OPT_QUALITY, "--quality", NULL, CLI_ARG_TEXT, "Q",
     "final (default): 16 samples per pixel (64 more at edges), surface samples\n"
     "every half pixel at the object's nearest visible points; draft: 1 sample\n"
     "per pixel, surface samples every pixel",
     "draft final"},
    {OPT_THREADS, "--threads", NULL, CLI_ARG_NUMBER, "N", "worker threads (default: all cores)", NULL},
    {OPT_TIME, "--time", NULL, CLI_ARG_NUMBER, "T", "animation time in seconds (default 0)", NULL},
    {OPT_SEED, "--seed", NULL, CLI_ARG_NUMBER, "S",
     "random seed, a non-negative integer (default 0); the image depends only on\n"
     "the seed, not on the thread count",
     NULL},
    {OPT_EXACT, "--exact", NULL, CLI_ARG_NONE, NULL, "sum over every surface sample instead of the tree (slow; for validation)",
     NULL},
    {OPT_SPECULAR, "--specular", NULL, CLI_ARG_NONE, NULL,
     "add the camera ray's smooth dielectric reflection F_r off subsurface objects\n"
     "(environment, area lights and lit surfaces; PBRT's path tracer includes it)",
     NULL},
    {OPT_SPP, "--spp", NULL, CLI_ARG_NUMBER, "N", "base samples per pixel (rounded up to a square)", NULL},
    {OPT_DENSITY, "--density", NULL, CLI_ARG_NUMBER, "D", "multiply the surface-sample density by D (> 0; 4 = half the spacing)",
     NULL},
    {OPT_BOUNCES, "--bounces", NULL, CLI_ARG_NUMBER, "N",
     "surface-to-surface bounces, 1.." CLI_STR(SSS_REFERENCE_MAX_BOUNCES) ": 1 = the single-event integral (direct\n"
     "light only); default: until a bounce adds less than a set fraction of\n"
     "bounce 2's light (below)",
     NULL},
    {OPT_STATS, "--stats", NULL, CLI_ARG_NONE, NULL, "print sample counts, tree statistics and timings to stdout", NULL},
};
const cli_command_spec cli_spec_reference = {"reference", options, CLI_COUNT(options), CLI_ARG_FILE, NULL};

static void print_help(void)
{
    printf("usage: sss reference SCENE.json -o OUT.png [--exr OUT.exr] [--pfm OUT.pfm] [--width W] [--height H]\n"
           "                     [--quality draft|final] [--threads N] [--time T] [--seed S] [--exact]\n"
           "                     [--specular] [--spp N] [--density D] [--bounces N] [--stats]\n"
           "                     [--quiet | --progress]\n"
           "\n"
           "Renders the ground truth of a scene: the subsurface integral of docs/physics.md §1 as PBRT-v3's\n"
           "`subsurface` material converges to it (Embree 3 rays, surface samples with their irradiance,\n"
           "summed hierarchically), with the light that scatters between surfaces bounce after bounce\n"
           "(PBRT's path tracer; --bounces 1: direct light only, PBRT's maxdepth 1). Diffuse objects are\n"
           "Lambertian; area lights are visible; rays that miss see the environment map (black without one).\n"
           "\n");
    cli_print_options(stdout, &cli_spec_reference);
    printf("\n"
           "Without --bounces, bounces stop when one adds less than %g%% of bounce 2's light.\n"
           "Progress goes to stderr when it is a terminal (a bar with the time left) or with --progress\n"
           "(otherwise a line 'NN%%' every 10%%); never with --quiet. Nothing is written when the scene or\n"
           "an option is invalid.\n"
           "exit status: 0 done, 1 invalid scene or failed render or write, 2 usage error\n",
           100.0 * SSS_REFERENCE_BOUNCE_STOP);
}

static void progress(void *user, double fraction, const char *stage)
{
    cli_progress_update(user, fraction, stage);
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
    int stats = 0, width = 0, height = 0;
    cli_parser args;
    cli_parser_init(&args, &cli_spec_reference, argc, argv, 1);
    for (int o; (o = cli_next(&args)) != CLI_DONE;) {
        const char *a = args.given, *v = args.value;
        switch (o) {
        case CLI_BAD: return CLI_EXIT_USAGE;
        case OPT_OUTPUT: out_path = v; break;
        case OPT_EXR: exr_path = v; break;
        case OPT_PFM: pfm_path = v; break;
        case OPT_WIDTH:
        case OPT_HEIGHT:
            if (!cli_parse_size(CMD, a, v, o == OPT_WIDTH ? &width : &height)) return CLI_EXIT_USAGE;
            break;
        case OPT_QUALITY:
            if (strcmp(v, "final") == 0)
                desc.quality = SSS_REFERENCE_FINAL;
            else if (strcmp(v, "draft") == 0)
                desc.quality = SSS_REFERENCE_DRAFT;
            else
                return cli_usage_error(CMD, "--quality must be draft or final, got '%s'", v);
            break;
        case OPT_THREADS:
            if (!cli_parse_int(CMD, "--threads", v, &desc.threads)) return CLI_EXIT_USAGE;
            if (desc.threads < 1 || desc.threads > 4096)
                return cli_usage_error(CMD, "--threads must be in 1..4096, got %d", desc.threads);
            break;
        case OPT_TIME:
            if (!cli_parse_double(CMD, "--time", v, &desc.time)) return CLI_EXIT_USAGE;
            break;
        case OPT_SEED:
            if (!parse_seed(v, &desc.seed)) return cli_usage_error(CMD, "--seed expects a non-negative integer, got '%s'", v);
            break;
        case OPT_SPP:
            if (!cli_parse_int(CMD, "--spp", v, &desc.spp)) return CLI_EXIT_USAGE;
            if (desc.spp < 1 || desc.spp > 4096) return cli_usage_error(CMD, "--spp must be in 1..4096, got %d", desc.spp);
            break;
        case OPT_DENSITY:
            if (!cli_parse_double(CMD, "--density", v, &desc.density)) return CLI_EXIT_USAGE;
            if (!(desc.density > 0.0) || desc.density > 1024.0)
                return cli_usage_error(CMD, "--density must be in (0, 1024], got %g", desc.density);
            break;
        case OPT_BOUNCES:
            if (!cli_parse_int(CMD, "--bounces", v, &desc.bounces)) return CLI_EXIT_USAGE;
            if (desc.bounces < 1 || desc.bounces > SSS_REFERENCE_MAX_BOUNCES)
                return cli_usage_error(CMD, "--bounces must be in 1..%d, got %d", SSS_REFERENCE_MAX_BOUNCES,
                                       desc.bounces);
            break;
        case OPT_EXACT: desc.exact = 1; break;
        case OPT_SPECULAR: desc.specular = 1; break;
        case OPT_STATS: stats = 1; break;
        default: /* CLI_OPERAND */
            if (scene_path) return cli_usage_error(CMD, "expects one scene, got a second: '%s'", v);
            scene_path = v;
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
    if (cli_scene_resize(CMD, &scene, width, height) != CLI_EXIT_OK) {
        sss_scene_free(&scene);
        return CLI_EXIT_ERROR;
    }
    const char *paths[3] = {out_path, exr_path, pfm_path};
    if (cli_check_outputs(CMD, paths, 3, NULL, 0, &scene) != CLI_EXIT_OK) {
        sss_scene_free(&scene);
        return CLI_EXIT_ERROR;
    }
    cli_progress ps;
    cli_progress_init(&ps, &args);
    sss_image img = {0};
    sss_reference_stats st;
    sss_result r = sss_reference_render(&scene, &desc, &img, ps.active ? progress : NULL, &ps, &st, &err);
    cli_progress_end(&ps);
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
