/* bench_ssim — image comparison (SSIM, PSNR, FLIP) and file I/O timings at 1920x1080 (medians).
 * Run: build/bench/bench_ssim [folder for temporary files, default /tmp] */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "bench.h"
#include "sss/image.h"

typedef struct ctx {
    sss_image a, b, map, back;
    char path[4][512];
} ctx;

static void run_compare(void *p)
{
    ctx *c = p;
    sss_image_metrics m;
    sss_image_compare(&c->a, &c->b, 0.0, &m, NULL, NULL);
}

static void run_flip(void *p)
{
    ctx *c = p;
    double mean;
    sss_image_flip(&c->a, &c->b, 0.0, SSS_FLIP_DEFAULT_PPD, &mean, NULL, NULL);
}

static void run_compare_map(void *p)
{
    ctx *c = p;
    sss_image_metrics m;
    sss_image_free(&c->map);
    sss_image_compare(&c->a, &c->b, 0.0, &m, &c->map, NULL);
}

#define IO_BENCH(fmt, i)                                                                   \
    static void run_write_##fmt(void *p)                                                   \
    {                                                                                      \
        ctx *c = p;                                                                        \
        sss_image_write(c->path[i], &c->a, 0.0, NULL);                                     \
    }                                                                                      \
    static void run_read_##fmt(void *p)                                                    \
    {                                                                                      \
        ctx *c = p;                                                                        \
        sss_image_free(&c->back);                                                          \
        sss_image_read(c->path[i], &c->back, NULL);                                        \
    }
IO_BENCH(png, 0)
IO_BENCH(exr, 1)
IO_BENCH(pfm, 2)
IO_BENCH(hdr, 3)

int main(int argc, char **argv)
{
    const char *dir = argc > 1 ? argv[1] : "/tmp";
    ctx c = {0};
    if (sss_image_create(&c.a, 1920, 1080, NULL) != SSS_OK || sss_image_create(&c.b, 1920, 1080, NULL) != SSS_OK)
        return 1;
    unsigned s = 1;
    for (size_t i = 0; i < 1920u * 1080u * 3u; i++) {
        s = s * 1664525u + 1013904223u;
        size_t x = (i / 3) % 1920, y = (i / 3) / 1920;
        c.a.pixels[i] = (float)(0.5 + 0.4 * sin(x * 0.01 + (double)(i % 3)) * cos(y * 0.013));
        c.b.pixels[i] = c.a.pixels[i] * (0.95f + 0.1f * (float)(s >> 8) / 16777216.0f);
    }
    const char *ext[4] = {"png", "exr", "pfm", "hdr"};
    for (int i = 0; i < 4; i++) snprintf(c.path[i], sizeof c.path[i], "%s/bench_ssim_tmp.%s", dir, ext[i]);
    bench_run("compare 1920x1080 (SSIM+PSNR+FLIP)", 5, run_compare, &c);
    bench_run("FLIP alone 1920x1080 (67 ppd)", 5, run_flip, &c);
    bench_run("compare 1920x1080 with DSSIM map", 5, run_compare_map, &c);
    bench_run("write PNG 1920x1080", 3, run_write_png, &c);
    bench_run("read PNG 1920x1080", 5, run_read_png, &c);
    bench_run("write EXR float ZIP 1920x1080", 3, run_write_exr, &c);
    bench_run("read EXR float ZIP 1920x1080", 5, run_read_exr, &c);
    bench_run("write PFM 1920x1080", 3, run_write_pfm, &c);
    bench_run("read PFM 1920x1080", 5, run_read_pfm, &c);
    bench_run("write HDR 1920x1080", 3, run_write_hdr, &c);
    bench_run("read HDR 1920x1080", 5, run_read_hdr, &c);
    for (int i = 0; i < 4; i++) remove(c.path[i]);
    sss_image_free(&c.a);
    sss_image_free(&c.b);
    sss_image_free(&c.map);
    sss_image_free(&c.back);
    return 0;
}
