/* Image file formats: reading files written by an independent encoder (tools/ssim_reference.py
 * writes PNG, PFM and OpenEXR byte by byte), round trips through our writers, row order, atomic
 * writes, and the refusal of NaN/Inf. Malformed files are in test_image_malformed.c. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stb_image_write.h>

#include "check.h"
#include "image_test_util.h"
#include "sss/image.h"

#define DATA SSS_TEST_DATA "/images/"

static float px(const sss_image *img, int x, int y, int c) { return img->pixels[((size_t)y * img->width + x) * 3 + c]; }

/* Every "pixel FILE x y r g b" line of formats_reference.txt, checked exactly (the values are
 * exactly representable in the files' sample types; PNG and JPEG lines hold 8-bit codes). */
static void test_reference_files(void)
{
    FILE *f = fopen(DATA "formats_reference.txt", "r");
    CHECK(f != NULL);
    if (!f) return;
    char line[512], name[128], loaded[128] = "";
    sss_image img = {0};
    uint8_t *codes = NULL;
    int lines = 0, files = 0;
    while (fgets(line, sizeof line, f)) {
        int x, y;
        float v[3];
        if (sscanf(line, "pixel %127s %d %d %g %g %g", name, &x, &y, &v[0], &v[1], &v[2]) != 6) continue;
        if (strcmp(name, loaded) != 0) {
            sss_image_free(&img);
            free(codes);
            codes = NULL;
            char path[1024];
            snprintf(path, sizeof path, DATA "%s", name);
            sss_error err = {0};
            sss_result r = sss_image_read(path, &img, &err);
            CHECK_MSG(r == SSS_OK, "%s: %s", name, err.message);
            snprintf(loaded, sizeof loaded, "%s", name);
            files++;
            if (r != SSS_OK) continue;
            codes = malloc((size_t)img.width * img.height * 3);
            sss_image_to_srgb8(&img, 0.0, codes);
        }
        if (!img.pixels || x >= img.width || y >= img.height) {
            CHECK_MSG(0, "%s: pixel (%d, %d) outside the %dx%d image", name, x, y, img.width, img.height);
            continue;
        }
        int png = strstr(name, ".png") != NULL || strstr(name, ".jpg") != NULL;
        for (int c = 0; c < 3; c++) {
            double got = png ? codes[((size_t)y * img.width + x) * 3 + c] : px(&img, x, y, c);
            CHECK_MSG(got == v[c], "%s (%d, %d) channel %d: got %.9g, expected %.9g", name, x, y, c, got, (double)v[c]);
        }
        lines++;
    }
    fclose(f);
    sss_image_free(&img);
    free(codes);
    CHECK(files == 8);
    CHECK(lines > 80);
}

/* All 256 grey codes: decode + tone map at exposure 0 gives the codes back, and so does a PNG
 * written by our writer and read again. Known sRGB values pin the curve itself. */
static void test_png_grey_levels(const char *dir)
{
    sss_image img = {0}, back = {0};
    sss_error err = {0};
    CHECK(sss_image_read(DATA "grey256.png", &img, &err) == SSS_OK);
    if (!img.pixels) return;
    CHECK(img.width == 16 && img.height == 16);
    uint8_t codes[16 * 16 * 3];
    sss_image_to_srgb8(&img, 0.0, codes);
    int bad = 0;
    for (int k = 0; k < 256; k++)
        for (int c = 0; c < 3; c++) bad += codes[3 * k + c] != k;
    CHECK_MSG(bad == 0, "%d codes changed by decode + tone map", bad);
    /* sRGB: code 255 is 1, 0 is 0; code 128 is 0.2158605 and 188 is 0.5028865 (IEC 61966-2-1). */
    CHECK(px(&img, 15, 15, 0) == 1.0f && px(&img, 0, 0, 1) == 0.0f);
    CHECK_NEAR(px(&img, 0, 8, 0), 0.2158605, 1e-6);
    CHECK_NEAR(px(&img, 12, 11, 2), 0.5028865, 1e-6);

    char path[256];
    snprintf(path, sizeof path, "%s/grey.png", dir);
    CHECK(sss_image_write(path, &img, 0.0, &err) == SSS_OK);
    CHECK(sss_image_read(path, &back, &err) == SSS_OK);
    if (back.pixels) {
        uint8_t again[16 * 16 * 3];
        sss_image_to_srgb8(&back, 0.0, again);
        CHECK(memcmp(again, codes, sizeof codes) == 0);
        CHECK(memcmp(back.pixels, img.pixels, sizeof(float) * 16 * 16 * 3) == 0);
    }
    /* 16-bit grey + alpha holding 257 k decodes to code k (alpha dropped, grey replicated). */
    sss_image g16 = {0};
    CHECK(sss_image_read(DATA "grey16_alpha.png", &g16, &err) == SSS_OK);
    if (g16.pixels) {
        uint8_t c16[16 * 16 * 3];
        sss_image_to_srgb8(&g16, 0.0, c16);
        CHECK(memcmp(c16, codes, sizeof codes) == 0);
    }
    sss_image_free(&g16);
    sss_image_free(&img);
    sss_image_free(&back);
    remove(path);
}

/* docs/scene-format.md render.exposure: out = round(255 srgb(clamp(linear 2^E, 0, 1))). */
static void test_tone_map(void)
{
    sss_image img = {0};
    CHECK(sss_image_create(&img, 8, 1, NULL) == SSS_OK);
    float v[8] = {0.5f, 0.18f, 2.0f, -1.0f, NAN, INFINITY, 0.25f, 0.001f};
    memcpy(img.pixels, (float[24]){0}, sizeof(float) * 24);
    for (int i = 0; i < 8; i++) img.pixels[3 * i] = img.pixels[3 * i + 1] = img.pixels[3 * i + 2] = v[i];
    uint8_t b[24], b2[24];
    sss_image_to_srgb8(&img, 0.0, b);
    CHECK(b[0] == 188);  /* linear 0.5 -> sRGB 0.7354 -> 187.5 -> 188 */
    CHECK(b[3] == 118);  /* 18% grey -> 117.65 -> 118 */
    CHECK(b[6] == 255 && b[9] == 0 && b[12] == 0 && b[15] == 255);
    CHECK(b[21] == 3);   /* linear 0.001 is on the linear segment: 12.92e-3 * 255 = 3.29 */
    sss_image_to_srgb8(&img, 1.0, b2); /* one stop up: 0.25 looks like 0.5 at exposure 0 */
    CHECK(b2[18] == b[0]);
    CHECK(b2[0] == 255);
    sss_image_to_srgb8(&img, -2.0, b2); /* two stops down: 2.0 looks like 0.5 */
    CHECK(b2[6] == b[0]);
    /* The curve and its inverse. */
    for (int i = 0; i <= 100; i++) {
        double x = i / 100.0;
        CHECK_NEAR(sss_srgb_encode(sss_srgb_decode(x)), x, 1e-12);
    }
    CHECK_NEAR(sss_srgb_encode(0.0031308), 0.040449936, 1e-9); /* the two segments meet */
    sss_image_free(&img);
}

/* An asymmetric test image: distinct values everywhere, negatives, tiny and large magnitudes. */
static void fill_pattern(sss_image *img, int allow_negative)
{
    uint32_t s = 12345;
    for (int y = 0; y < img->height; y++)
        for (int x = 0; x < img->width; x++)
            for (int c = 0; c < 3; c++) {
                s = s * 1664525u + 1013904223u;
                double u = (s >> 8) / 16777216.0;
                double v = pow(10.0, -4.0 + 7.0 * u) * (allow_negative && (s & 1) ? -1.0 : 1.0);
                if (x == 0 && y == 0) v = 0.0;
                img->pixels[((size_t)y * img->width + x) * 3 + c] = (float)v;
            }
}

static void test_round_trips(const char *dir)
{
    sss_image img = {0}, back = {0};
    sss_error err = {0};
    CHECK(sss_image_create(&img, 37, 23, &err) == SSS_OK);
    fill_pattern(&img, 1);
    size_t n = (size_t)img.width * img.height * 3;
    char path[256];

    /* PFM and EXR float: exact. */
    const char *exact[] = {"rt.pfm", "rt.exr", "RT.EXR"};
    for (int i = 0; i < 3; i++) {
        snprintf(path, sizeof path, "%s/%s", dir, exact[i]);
        CHECK_MSG(sss_image_write(path, &img, 0.0, &err) == SSS_OK, "%s", err.message);
        CHECK_MSG(sss_image_read(path, &back, &err) == SSS_OK, "%s", err.message);
        CHECK(back.width == img.width && back.height == img.height);
        if (back.pixels) CHECK_MSG(memcmp(back.pixels, img.pixels, n * sizeof(float)) == 0, "%s differs", exact[i]);
        sss_image_free(&back);
    }

    /* EXR half: within half precision (relative 2^-11, absolute 2^-25 for subnormals). */
    snprintf(path, sizeof path, "%s/half.exr", dir);
    CHECK_MSG(sss_image_write_exr(path, &img, 1, &err) == SSS_OK, "%s", err.message);
    CHECK(sss_image_read(path, &back, &err) == SSS_OK);
    if (back.pixels) {
        int bad = 0;
        double worst = 0.0;
        for (size_t i = 0; i < n; i++) {
            double v = img.pixels[i], e = fabs(back.pixels[i] - v);
            double tol = fmax(fabs(v) * ldexp(1.0, -11), ldexp(1.0, -25));
            bad += e > tol || (back.pixels[i] < 0) != (v < 0);
            if (fabs(v) > 1e-3) worst = fmax(worst, e / fabs(v));
        }
        CHECK_MSG(bad == 0, "%d half values off", bad);
        CHECK(worst > 0.0); /* it really was stored as half */
    }
    sss_image_free(&back);
    /* Half cannot hold 70000: refused, no file. */
    img.pixels[5] = 70000.0f;
    snprintf(path, sizeof path, "%s/over.exr", dir);
    CHECK(sss_image_write_exr(path, &img, 1, &err) == SSS_ERROR_LIMIT);
    CHECK(!file_exists(path));
    img.pixels[5] = 1.0f;

    /* HDR: RGBE keeps 8 bits of mantissa relative to the brightest channel; negatives become 0. */
    snprintf(path, sizeof path, "%s/rt.hdr", dir);
    CHECK_MSG(sss_image_write(path, &img, 0.0, &err) == SSS_OK, "%s", err.message);
    CHECK_MSG(sss_image_read(path, &back, &err) == SSS_OK, "%s", err.message);
    if (back.pixels) {
        int bad = 0;
        for (size_t p = 0; p < n / 3; p++) {
            double m = 0.0;
            for (int c = 0; c < 3; c++) m = fmax(m, img.pixels[3 * p + c]);
            for (int c = 0; c < 3; c++) {
                double v = fmax(img.pixels[3 * p + c], 0.0);
                bad += fabs(back.pixels[3 * p + c] - v) > m / 256.0 * (1 + 1e-6);
            }
        }
        CHECK_MSG(bad == 0, "%d RGBE values off", bad);
    }
    sss_image_free(&back);
    /* Values with few mantissa bits survive RGBE exactly. */
    for (size_t i = 0; i < n; i++) img.pixels[i] = (float)ldexp((double)(i % 200 + 56), (int)(i % 40) - 20);
    for (size_t p = 0; p < n / 3; p++) img.pixels[3 * p + 1] = img.pixels[3 * p + 2] = img.pixels[3 * p];
    CHECK(sss_image_write(path, &img, 0.0, &err) == SSS_OK);
    CHECK(sss_image_read(path, &back, &err) == SSS_OK);
    if (back.pixels) CHECK(memcmp(back.pixels, img.pixels, n * sizeof(float)) == 0);
    sss_image_free(&back);
    /* Too bright for RGBE's exponent (>= 2^128 after rounding) -> refused. */
    img.pixels[0] = 3e38f;
    CHECK(sss_image_write(path, &img, 0.0, &err) == SSS_ERROR_LIMIT);
    sss_image_free(&img);
}

/* Row order: our PFM stores the bottom row first, our HDR the top row first ("-Y"), and PNG/EXR
 * come back in place. Checked on the raw bytes, independently of our readers. */
static void test_row_order(const char *dir)
{
    sss_image img = {0};
    CHECK(sss_image_create(&img, 3, 2, NULL) == SSS_OK);
    for (int y = 0; y < 2; y++)
        for (int x = 0; x < 3; x++)
            for (int c = 0; c < 3; c++) img.pixels[(y * 3 + x) * 3 + c] = (float)(1 + x + 3 * y) / 8.0f;
    char path[256];
    size_t size = 0;
    snprintf(path, sizeof path, "%s/order.pfm", dir);
    CHECK(sss_image_write(path, &img, 0.0, NULL) == SSS_OK);
    unsigned char *b = slurp(path, &size);
    CHECK(b && size == strlen("PF\n3 2\n-1\n") + 72 && memcmp(b, "PF\n3 2\n-1\n", 10) == 0);
    if (b && size >= 14) {
        float first;
        uint32_t u = (uint32_t)b[10] | (uint32_t)b[11] << 8 | (uint32_t)b[12] << 16 | (uint32_t)b[13] << 24;
        memcpy(&first, &u, 4);
        CHECK(first == 4.0f / 8.0f); /* pixel (0, 1): the bottom-left one */
    }
    free(b);
    snprintf(path, sizeof path, "%s/order.hdr", dir);
    CHECK(sss_image_write(path, &img, 0.0, NULL) == SSS_OK);
    b = slurp(path, &size);
    CHECK(b && size > 24);
    if (b && size > 24) {
        CHECK(strstr((char *)b, "\n-Y 2 +X 3\n") != NULL);
        const unsigned char *d = b + size - 24; /* 6 flat RGBE pixels */
        CHECK(d[0] == 128 && d[3] == 128 - 2);  /* (0, 0) = 1/8 = 128 * 2^(126 - 136) */
    }
    free(b);
    const char *names[] = {"order.png", "order.exr"};
    for (int i = 0; i < 2; i++) {
        sss_image back = {0};
        snprintf(path, sizeof path, "%s/%s", dir, names[i]);
        CHECK(sss_image_write(path, &img, 0.0, NULL) == SSS_OK);
        CHECK(sss_image_read(path, &back, NULL) == SSS_OK);
        if (back.pixels) {
            uint8_t x[18], y[18];
            sss_image_to_srgb8(&img, 0.0, x);
            sss_image_to_srgb8(&back, 0.0, y);
            CHECK_MSG(memcmp(x, y, 18) == 0, "%s rows differ", names[i]);
        }
        sss_image_free(&back);
    }
    sss_image_free(&img);
}

/* Writers refuse NaN/Inf and leave nothing behind; an existing file stays untouched; a missing
 * folder is an error naming the path. */
static void test_refusals(const char *dir)
{
    sss_image img = {0};
    sss_error err = {0};
    CHECK(sss_image_create(&img, 4, 4, NULL) == SSS_OK);
    char path[256];
    snprintf(path, sizeof path, "%s/keep.pfm", dir);
    CHECK(sss_image_write(path, &img, 0.0, NULL) == SSS_OK);
    size_t before_size = 0;
    unsigned char *before = slurp(path, &before_size);
    int entries = count_entries(dir);
    img.pixels[7] = NAN;
    img.pixels[20] = -INFINITY;
    const char *names[] = {"bad.png", "bad.hdr", "bad.pfm", "bad.exr", "keep.pfm"};
    for (int i = 0; i < 5; i++) {
        snprintf(path, sizeof path, "%s/%s", dir, names[i]);
        sss_result r = sss_image_write(path, &img, 0.0, &err);
        CHECK_MSG(r == SSS_ERROR_NUMERIC, "%s: %d", names[i], r);
        CHECK(strstr(err.message, path) != NULL && strstr(err.message, "2 non-finite") != NULL);
    }
    CHECK(sss_image_write_exr(path, &img, 1, &err) == SSS_ERROR_NUMERIC);
    CHECK(count_entries(dir) == entries);
    size_t after_size = 0;
    unsigned char *after = slurp(path, &after_size);
    CHECK(before && after && before_size == after_size && memcmp(before, after, before_size) == 0);
    free(before);
    free(after);
    CHECK(sss_image_count_nonfinite(&img) == 2);

    img.pixels[7] = img.pixels[20] = 0.5f;
    const char *missing[] = {"png", "hdr", "pfm", "exr"};
    for (int i = 0; i < 4; i++) {
        snprintf(path, sizeof path, "%s/no/such/folder/out.%s", dir, missing[i]);
        CHECK(sss_image_write(path, &img, 0.0, &err) == SSS_ERROR_IO);
        CHECK_MSG(strstr(err.message, path) != NULL, "%s", err.message);
    }
    snprintf(path, sizeof path, "%s/out.jpg", dir);
    CHECK(sss_image_write(path, &img, 0.0, &err) == SSS_ERROR_UNSUPPORTED);
    snprintf(path, sizeof path, "%s/out.png", dir);
    CHECK(sss_image_write(path, &img, NAN, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(count_entries(dir) == entries);

    /* create: sizes outside 1..SSS_IMAGE_MAX_DIM. */
    sss_image none = {0};
    CHECK(sss_image_create(&none, 0, 5, &err) == SSS_ERROR_INVALID_ARGUMENT && none.pixels == NULL);
    CHECK(sss_image_create(&none, 5, SSS_IMAGE_MAX_DIM + 1, &err) == SSS_ERROR_LIMIT && none.pixels == NULL);
    sss_image_free(&none);
    sss_image_free(&img);
}

static void write_to_file(void *context, void *data, int size) { fwrite(data, 1, (size_t)size, (FILE *)context); }

/* Run-length encoded HDR from an outside encoder (stb_image_write, which truncates mantissas:
 * error < max channel / 128), including long runs of equal pixels and a width with a short tail. */
static void test_hdr_from_stb(const char *dir)
{
    enum { W = 301, H = 5 };
    static float v[W * H * 3];
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            for (int c = 0; c < 3; c++)
                v[(y * W + x) * 3 + c] = x < 150 ? 0.75f * (float)(y + 1) : (float)(1 + (x * 7 + c * 13) % 97) * 0.03f;
    char path[256];
    snprintf(path, sizeof path, "%s/stb.hdr", dir);
    FILE *f = fopen(path, "wb");
    CHECK(f && stbi_write_hdr_to_func(write_to_file, f, W, H, 3, v));
    if (f) fclose(f);
    sss_image img = {0};
    sss_error err = {0};
    CHECK_MSG(sss_image_read(path, &img, &err) == SSS_OK, "%s", err.message);
    if (img.pixels) {
        CHECK(img.width == W && img.height == H);
        int bad = 0;
        for (int p = 0; p < W * H; p++) {
            double m = fmax(v[3 * p], fmax(v[3 * p + 1], v[3 * p + 2]));
            for (int c = 0; c < 3; c++) {
                double e = v[3 * p + c] - img.pixels[3 * p + c];
                bad += e < 0.0 || e > m / 128.0;
            }
        }
        CHECK_MSG(bad == 0, "%d values off", bad);
        CHECK(img.pixels[0] == 0.75f && img.pixels[3 * W * (H - 1)] == 3.75f); /* top row first */
    }
    sss_image_free(&img);
    remove(path);
}

int main(void)
{
    char dir[64];
    CHECK(make_temp_dir(dir, sizeof dir));
    test_reference_files();
    test_png_grey_levels(dir);
    test_tone_map();
    test_round_trips(dir);
    test_row_order(dir);
    test_refusals(dir);
    test_hdr_from_stb(dir);
    remove_dir(dir);
    return CHECK_DONE();
}
