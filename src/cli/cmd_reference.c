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

#define CMD "reference"

enum {
    OPT_OUTPUT, OPT_EXR, OPT_PFM, OPT_WIDTH, OPT_HEIGHT, OPT_QUALITY, OPT_THREADS, OPT_TIME, OPT_SEED, OPT_EXACT,
    OPT_SPECULAR, OPT_SPP, OPT_DENSITY, OPT_BOUNCES, OPT_STATS
};
static const cli_option options[] = {
    {OPT_OUTPUT, "--output", "-o", CLI_ARG_FILE, "OUT",
     "the image: .png is tone-mapped with the scene's render.exposure\n"
     "(out = srgb(clamp(linear 2^exposure, 0, 1))); .exr, .pfm, .hdr hold linear values",
     NULL, CLI_REQUIRED},
    {OPT_EXR, "--exr", NULL, CLI_ARG_FILE, "OUT.exr", "also write the linear image as OpenEXR", NULL, NULL},
    {OPT_PFM, "--pfm", NULL, CLI_ARG_FILE, "OUT.pfm", "also write the linear image as PFM", NULL, NULL},
    {OPT_WIDTH, "--width", NULL, CLI_ARG_NUMBER, "W", "image width", NULL, "the scene camera's"},
    {OPT_HEIGHT, "--height", NULL, CLI_ARG_NUMBER, "H", "image height", NULL, "the scene camera's"},
    {OPT_QUALITY, "--quality", NULL, CLI_ARG_TEXT, "Q",
     "final: 16 samples per pixel (64 more at edges), surface samples every\n"
     "half pixel at the object's nearest visible points; draft: 1 sample\n"
     "per pixel, surface samples every pixel",
     "draft final", "final"},
    {OPT_THREADS, "--threads", NULL, CLI_ARG_NUMBER, "N", "worker threads", NULL, "all cores"},
    {OPT_TIME, "--time", NULL, CLI_ARG_NUMBER, "T", "animation time in seconds", NULL, "0"},
    {OPT_SEED, "--seed", NULL, CLI_ARG_NUMBER, "S",
     "random seed, a non-negative integer; the image depends only on\n"
     "the seed, not on the thread count",
     NULL, "0"},
    {OPT_EXACT, "--exact", NULL, CLI_ARG_NONE, NULL, "sum over every surface sample instead of the tree (slow; for validation)",
     NULL, NULL},
    {OPT_SPECULAR, "--specular", NULL, CLI_ARG_NONE, NULL,
     "add the camera ray's smooth dielectric reflection F_r off subsurface objects\n"
     "(environment, area lights and lit surfaces; PBRT's path tracer includes it)",
     NULL, NULL},
    {OPT_SPP, "--spp", NULL, CLI_ARG_NUMBER, "N", "base samples per pixel (rounded up to a square)", NULL,
     "16 final, 1 draft"},
    {OPT_DENSITY, "--density", NULL, CLI_ARG_NUMBER, "D", "multiply the surface-sample density by D (> 0; 4 = half the spacing)",
     NULL, "1"},
    {OPT_BOUNCES, "--bounces", NULL, CLI_ARG_NUMBER, "N",
     "surface-to-surface bounces, 1.." CLI_STR(SSS_REFERENCE_MAX_BOUNCES) ": 1 = the single-event integral (direct\n"
     "light only); default: until a bounce adds less than a set fraction of\n"
     "bounce 2's light (below)",
     NULL, NULL},
    {OPT_STATS, "--stats", NULL, CLI_ARG_NONE, NULL, "print sample counts, tree statistics and timings to stdout", NULL,
     NULL},
};

static void print_more(FILE *f)
{
    fprintf(f, "Without --bounces, bounces stop when one adds less than %g%% of bounce 2's light.\n",
            100.0 * SSS_REFERENCE_BOUNCE_STOP);
}

const cli_command_spec cli_spec_reference = {
    "reference", options, CLI_COUNT(options), CLI_ARG_FILE, NULL, "SCENE.json",
    "Renders the ground truth of a scene: the subsurface integral of docs/physics.md §1 as PBRT-v3's\n"
    "`subsurface` material converges to it (Embree 3 rays, surface samples with their irradiance,\n"
    "summed hierarchically), with the light that scatters between surfaces bounce after bounce\n"
    "(PBRT's path tracer; --bounces 1: direct light only, PBRT's maxdepth 1). Diffuse objects are\n"
    "Lambertian; area lights are visible; rays that miss see the environment map (black without one).\n",
    "Progress goes to stderr when it is a terminal (a bar with the time left) or with --progress\n"
    "(otherwise a line 'NN%' every 10%); never with --quiet. Nothing is written when the scene or\n"
    "an option is invalid.\n"
    "exit status: 0 done, 1 invalid scene or failed render or write, 2 usage error\n",
    print_more};

typedef struct reference_options {
    const char *scene_path, *paths[3]; /* -o, --exr, --pfm */
    sss_reference_desc desc;
    int stats, width, height;
    cli_common common;
} reference_options;

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

static int set_number(reference_options *o, int id, const char *v)
{
    sss_reference_desc *d = &o->desc;
    switch (id) {
    case OPT_THREADS:
        if (!cli_parse_int(CMD, "--threads", v, &d->threads)) return CLI_EXIT_USAGE;
        if (d->threads < 1 || d->threads > 4096)
            return cli_usage_error(CMD, "--threads must be in 1..4096, got %d", d->threads);
        break;
    case OPT_TIME:
        if (!cli_parse_double(CMD, "--time", v, &d->time)) return CLI_EXIT_USAGE;
        break;
    case OPT_SEED:
        if (!parse_seed(v, &d->seed)) return cli_usage_error(CMD, "--seed expects a non-negative integer, got '%s'", v);
        break;
    case OPT_SPP:
        if (!cli_parse_int(CMD, "--spp", v, &d->spp)) return CLI_EXIT_USAGE;
        if (d->spp < 1 || d->spp > 4096) return cli_usage_error(CMD, "--spp must be in 1..4096, got %d", d->spp);
        break;
    case OPT_DENSITY:
        if (!cli_parse_double(CMD, "--density", v, &d->density)) return CLI_EXIT_USAGE;
        if (!(d->density > 0.0) || d->density > 1024.0)
            return cli_usage_error(CMD, "--density must be in (0, 1024], got %g", d->density);
        break;
    default: /* OPT_BOUNCES */
        if (!cli_parse_int(CMD, "--bounces", v, &d->bounces)) return CLI_EXIT_USAGE;
        if (d->bounces < 1 || d->bounces > SSS_REFERENCE_MAX_BOUNCES)
            return cli_usage_error(CMD, "--bounces must be in 1..%d, got %d", SSS_REFERENCE_MAX_BOUNCES, d->bounces);
    }
    return CLI_EXIT_OK;
}

static int set_option(void *opts, int id, const char *a, const char *v)
{
    reference_options *o = opts;
    switch (id) {
    case OPT_OUTPUT:
    case OPT_EXR:
    case OPT_PFM: o->paths[id == OPT_OUTPUT ? 0 : id == OPT_EXR ? 1 : 2] = v; break;
    case OPT_WIDTH:
    case OPT_HEIGHT:
        if (!cli_parse_size(CMD, a, v, id == OPT_WIDTH ? &o->width : &o->height)) return CLI_EXIT_USAGE;
        break;
    case OPT_QUALITY:
        if (strcmp(v, "final") == 0) o->desc.quality = SSS_REFERENCE_FINAL;
        else if (strcmp(v, "draft") == 0) o->desc.quality = SSS_REFERENCE_DRAFT;
        else return cli_usage_error(CMD, "--quality must be draft or final, got '%s'", v);
        break;
    case OPT_EXACT: o->desc.exact = 1; break;
    case OPT_SPECULAR: o->desc.specular = 1; break;
    case OPT_STATS: o->stats = 1; break;
    case CLI_OPERAND:
        if (o->scene_path) return cli_usage_error(CMD, "expects one scene, got a second: '%s'", v);
        o->scene_path = v;
        break;
    default: return set_number(o, id, v);
    }
    return CLI_EXIT_OK;
}

static int reference_parse(int argc, char **argv, reference_options *o)
{
    memset(o, 0, sizeof *o);
    int status = cli_parse(&cli_spec_reference, argc, argv, 1, set_option, o, &o->common);
    if (status != CLI_EXIT_OK) return status;
    if (!o->scene_path) return cli_usage_error(CMD, "expects a scene file");
    if (!o->paths[0]) return cli_usage_error(CMD, "needs an output image: -o OUT.png");
    static const char *const any[] = {"png", "exr", "pfm", "hdr", NULL}, *const exr[] = {"exr", NULL},
                             *const pfm[] = {"pfm", NULL};
    if (!has_extension(o->paths[0], any))
        return cli_usage_error(CMD, "-o needs a .png, .exr, .pfm or .hdr file name, got '%s'", o->paths[0]);
    if (o->paths[1] && !has_extension(o->paths[1], exr))
        return cli_usage_error(CMD, "--exr needs a .exr file name, got '%s'", o->paths[1]);
    if (o->paths[2] && !has_extension(o->paths[2], pfm))
        return cli_usage_error(CMD, "--pfm needs a .pfm file name, got '%s'", o->paths[2]);
    return CLI_EXIT_OK;
}

static void print_stats(const sss_reference_stats *st)
{
    printf("surface_samples=%llu spacing=%.6g..%.6g split_radius=%.6g\n", (unsigned long long)st->surface_samples,
           st->spacing_min, st->spacing_max, st->split_radius_min);
    printf("tree_nodes=%llu tree_leaves=%llu tree_depth=%u\n", (unsigned long long)st->tree_nodes,
           (unsigned long long)st->tree_leaves, st->tree_depth);
    printf("camera_samples=%llu refined_pixels=%llu sums=%llu nodes_per_sum=%.1f\n",
           (unsigned long long)st->camera_samples, (unsigned long long)st->adaptive_pixels,
           (unsigned long long)st->lookups, st->nodes_per_lookup);
    printf("seconds: setup=%.3f samples=%.3f tree=%.3f pixels=%.3f total=%.3f\n", st->seconds_setup,
           st->seconds_samples, st->seconds_tree, st->seconds_pixels, st->seconds_total);
    printf("bounces=%u transport_samples=%llu\n", st->bounces, (unsigned long long)st->transport_samples);
    for (uint32_t k = 0; k < st->bounces && k < SSS_REFERENCE_MAX_BOUNCES; k++)
        printf("bounce %u: seconds=%.3f light=%.4f (of bounce 2)\n", k + 1, st->seconds_bounce[k],
               st->bounce_fraction[k]);
}

/* Renders the loaded scene and writes its images (nothing when it holds NaN or Inf). */
static int render_and_write(const reference_options *o, const sss_scene *scene)
{
    cli_progress ps;
    cli_progress_init(&ps, &o->common);
    sss_image img = {0};
    sss_reference_stats st;
    sss_error err = {0};
    sss_result r = sss_reference_render(scene, &o->desc, &img, ps.active ? progress : NULL, &ps, &st, &err);
    cli_progress_end(&ps);
    int status = r == SSS_OK ? CLI_EXIT_OK : cli_fail(CMD, &err);
    if (status == CLI_EXIT_OK && sss_image_count_nonfinite(&img) != 0)
        status = cli_failf(CMD, "%s: the image has NaN or Inf values; nothing written", o->scene_path);
    for (int k = 0; k < 3 && status == CLI_EXIT_OK; k++)
        if (o->paths[k] && sss_image_write(o->paths[k], &img, scene->render.exposure, &err) != SSS_OK)
            status = cli_fail(CMD, &err);
    if (status == CLI_EXIT_OK && o->stats) print_stats(&st);
    sss_image_free(&img);
    return status;
}

static int reference_run(const reference_options *o)
{
    sss_scene scene;
    sss_error err = {0};
    if (sss_scene_load(o->scene_path, NULL, &scene, &err) != SSS_OK) return cli_fail(CMD, &err);
    int status = cli_scene_resize(CMD, &scene, o->width, o->height);
    if (status == CLI_EXIT_OK) status = cli_check_outputs(CMD, o->paths, 3, NULL, 0, &scene);
    if (status == CLI_EXIT_OK) status = render_and_write(o, &scene);
    sss_scene_free(&scene);
    return status;
}

int sss_cmd_reference(int argc, char **argv)
{
    reference_options o;
    int status = reference_parse(argc, argv, &o);
    return status == CLI_EXIT_OK ? reference_run(&o) : status;
}
