/* sss compare — DSSIM, PSNR, RMSE and FLIP of two images (docs/physics.md §5), optionally a DSSIM map. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "core/file_util.h"
#include "sss/image.h"

static const char *const CMD = "compare";

enum { OPT_EXPOSURE, OPT_MAP, OPT_MAP_SCALE };
#define DEFAULT_MAP_SCALE 10
static const cli_option options[] = {
    {OPT_EXPOSURE, "--exposure", NULL, CLI_ARG_NUMBER, "E", "stops applied to both images before the comparison", NULL,
     "0"},
    {OPT_MAP, "--map", NULL, CLI_ARG_FILE, "OUT",
     "write the per-pixel DSSIM of R, G and B (full size). OUT.png holds\n"
     "round(255 * min(1, S * dssim)) per channel, S = --map-scale, so black is\n"
     "identical and with S = 10 white means DSSIM >= 0.1; OUT.exr, .pfm or .hdr\n"
     "hold the raw DSSIM values (0 = identical, up to 1)",
     NULL, NULL},
    {OPT_MAP, "--output", "-o", CLI_ARG_FILE, "OUT", "the same as --map", NULL, NULL},
    {OPT_MAP_SCALE, "--map-scale", NULL, CLI_ARG_NUMBER, "S", "gain of the PNG map", NULL, CLI_STR(DEFAULT_MAP_SCALE)},
};
const cli_command_spec cli_spec_compare = {
    "compare", options, CLI_COUNT(options), CLI_ARG_FILE, NULL, "A B",
    "Compares two images (.png, .hdr, .pfm, .exr) after tone-mapping both to 8-bit sRGB with\n"
    "exposure E stops (default 0): round(255 srgb(clamp(linear 2^E, 0, 1))), docs/scene-format.md render.exposure.\n"
    "Prints one line:  dssim=D psnr=P rmse=R max=M flip=F\n"
    "  dssim  (1 - SSIM) / 2, SSIM of Wang et al. 2004 per colour channel (11x11 Gaussian window,\n"
    "         sigma 1.5, K1 0.01, K2 0.03, range 255) averaged over R, G, B; the mean leaves out a\n"
    "         5-pixel border. Equals scikit-image structural_similarity(gaussian_weights=True,\n"
    "         sigma=1.5, use_sample_covariance=False, data_range=255, channel_axis=2).\n"
    "  psnr   dB on the 8-bit images ('inf' when identical); rmse and max in 8-bit codes.\n"
    "  flip   mean LDR-FLIP (Andersson et al. 2020) in [0, 1], A taken as the reference, viewed at\n"
    "         67 pixels per degree (a 0.7 m wide 3840-pixel monitor at 0.7 m); 0 = identical\n"
    "Images must be the same size and at least 11x11 pixels.\n",
    "exit status: 0 done, 1 a file is missing, unreadable or malformed, or the sizes differ,\n"
    "2 usage error\n",
    NULL};

typedef struct compare_options {
    const char *files[2], *map_path;
    int nfiles;
    double exposure, map_scale;
    cli_common common;
} compare_options;

static int is_map_format(const char *path)
{
    char ext[8];
    sss_path_extension(path, ext, sizeof ext);
    return strcmp(ext, "png") == 0 || strcmp(ext, "exr") == 0 || strcmp(ext, "pfm") == 0 || strcmp(ext, "hdr") == 0;
}

static int write_map(const char *path, const sss_image *map, double scale, sss_error *err)
{
    char ext[8];
    sss_path_extension(path, ext, sizeof ext);
    if (strcmp(ext, "png") != 0) return sss_image_write(path, map, 0.0, err);
    size_t n = (size_t)map->width * (size_t)map->height * 3;
    uint8_t *rgb = malloc(n);
    if (!rgb) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    for (size_t i = 0; i < n; i++) {
        double v = scale * map->pixels[i];
        v = v > 0.0 ? (v < 1.0 ? v : 1.0) : 0.0; /* also NaN -> 0 */
        rgb[i] = (uint8_t)floor(255.0 * v + 0.5);
    }
    sss_result r = sss_image_write_png8(path, map->width, map->height, rgb, err);
    free(rgb);
    return r;
}

static void warn_nonfinite(const char *path, const sss_image *img)
{
    size_t bad = sss_image_count_nonfinite(img);
    if (bad)
        cli_message(CMD, "warning: %s holds %zu NaN/Inf values (compared as: NaN and -Inf black, +Inf white)", path,
                    bad);
}

static int set_option(void *opts, int id, const char *given, const char *v)
{
    (void)given;
    compare_options *o = opts;
    if (id == OPT_EXPOSURE) {
        if (!cli_parse_double(CMD, "--exposure", v, &o->exposure)) return CLI_EXIT_USAGE;
    } else if (id == OPT_MAP) {
        o->map_path = v;
    } else if (id == OPT_MAP_SCALE) {
        if (!cli_parse_double(CMD, "--map-scale", v, &o->map_scale)) return CLI_EXIT_USAGE;
        if (o->map_scale <= 0.0) return cli_usage_error(CMD, "--map-scale must be positive, got '%s'", v);
    } else { /* CLI_OPERAND */
        if (o->nfiles == 2) return cli_usage_error(CMD, "expects two images, got a third: '%s'", v);
        o->files[o->nfiles++] = v;
    }
    return CLI_EXIT_OK;
}

static int compare_parse(int argc, char **argv, compare_options *o)
{
    memset(o, 0, sizeof *o);
    o->map_scale = DEFAULT_MAP_SCALE;
    int status = cli_parse(&cli_spec_compare, argc, argv, 1, set_option, o, &o->common);
    if (status != CLI_EXIT_OK) return status;
    if (o->nfiles != 2) return cli_usage_error(CMD, "expects two images A and B");
    if (o->exposure < -126.0 || o->exposure > 126.0)
        return cli_usage_error(CMD, "--exposure must lie in [-126, 126] stops, got %g", o->exposure);
    if (o->map_path && !is_map_format(o->map_path))
        return cli_usage_error(CMD, "--map needs a .png, .exr, .pfm or .hdr file name, got '%s'", o->map_path);
    return CLI_EXIT_OK;
}

/* Both images, their sizes compared from the headers first: neither is decoded when they differ. */
static int read_pair(const compare_options *o, sss_image img[2])
{
    sss_error err = {0};
    int w[2], h[2];
    for (int k = 0; k < 2; k++)
        if (sss_image_read_size(o->files[k], &w[k], &h[k], &err) != SSS_OK) return cli_fail(CMD, &err);
    if (w[0] != w[1] || h[0] != h[1])
        return cli_failf(CMD, "image sizes differ: %s is %dx%d, %s is %dx%d", o->files[0], w[0], h[0], o->files[1],
                         w[1], h[1]);
    for (int k = 0; k < 2; k++)
        if (sss_image_read(o->files[k], &img[k], &err) != SSS_OK) return cli_fail(CMD, &err);
    if (!o->common.quiet) {
        warn_nonfinite(o->files[0], &img[0]);
        warn_nonfinite(o->files[1], &img[1]);
    }
    return CLI_EXIT_OK;
}

static int compare_run(const compare_options *o)
{
    sss_image img[2] = {{0}, {0}}, map = {0};
    sss_error err = {0};
    if (cli_check_outputs(CMD, &o->map_path, 1, o->files, 2, NULL) != CLI_EXIT_OK) return CLI_EXIT_ERROR;
    int status = read_pair(o, img);
    sss_image_metrics m;
    if (status == CLI_EXIT_OK &&
        sss_image_compare(&img[0], &img[1], o->exposure, &m, o->map_path ? &map : NULL, &err) != SSS_OK) {
        const char *msg = strncmp(err.message, "compare: ", 9) == 0 ? err.message + 9 : err.message;
        status = cli_failf(CMD, "%s vs %s: %s", o->files[0], o->files[1], msg);
    }
    if (status == CLI_EXIT_OK && o->map_path && write_map(o->map_path, &map, o->map_scale, &err) != SSS_OK)
        status = cli_fail(CMD, &err);
    if (status == CLI_EXIT_OK)
        printf("dssim=%.6f psnr=%.3f rmse=%.4f max=%.0f flip=%.6f\n", m.dssim, m.psnr, m.rmse, m.max_abs, m.flip);
    sss_image_free(&img[0]);
    sss_image_free(&img[1]);
    sss_image_free(&map);
    return status;
}

int sss_cmd_compare(int argc, char **argv)
{
    compare_options o;
    int status = compare_parse(argc, argv, &o);
    return status == CLI_EXIT_OK ? compare_run(&o) : status;
}
