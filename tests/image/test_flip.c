/* LDR-FLIP (Andersson et al. 2020): agreement with NVIDIA's reference implementation on committed image
 * pairs (tests/data/flip/flip_reference.txt, computed outside this repository: synthetic patterns of
 * tests/data/images and a 96x64 render, reference against ssss and local, in tests/data/flip), the
 * closed form on flat fields, identity, symmetry, range, and errors. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "sss/image.h"

/* name: a path under tests/data */
static int read_image(const char *name, sss_image *img)
{
    char path[512];
    snprintf(path, sizeof path, SSS_TEST_DATA "/%s", name);
    sss_error err = {0};
    sss_result r = sss_image_read(path, img, &err);
    CHECK_MSG(r == SSS_OK, "%s", err.message);
    return r == SSS_OK;
}

/* The reference runs in single precision (21- and 19-tap filters, pow, cbrt in float) and we in double:
 * per-pixel differences of a few float ulps of the intermediate Lab values; 2e-5 is about 100 float
 * epsilons of a value near 1 (measured worst over 10 pairs: 7.5e-7 for a mean, 1.5e-6 for a pixel). */
#define FLIP_TOL 2e-5

static void test_against_nvidia(void)
{
    FILE *f = fopen(SSS_TEST_DATA "/flip/flip_reference.txt", "r");
    CHECK(f != NULL);
    if (!f) return;
    char line[512], an[128], bn[128], cur[300] = "";
    sss_image a = {0}, b = {0}, map = {0};
    int pairs = 0, points = 0;
    double worst_mean = 0.0, worst_pixel = 0.0;
    while (fgets(line, sizeof line, f)) {
        double ppd, v;
        int x, y;
        char key[300];
        if (sscanf(line, "flip %127s %127s %lf %lf", an, bn, &ppd, &v) == 4) {
            sss_image_free(&a);
            sss_image_free(&b);
            sss_image_free(&map);
            if (!read_image(an, &a) || !read_image(bn, &b)) continue;
            double mean = -1.0;
            sss_error err = {0};
            CHECK_MSG(sss_image_flip(&a, &b, 0.0, ppd, &mean, &map, &err) == SSS_OK, "%s", err.message);
            CHECK_MSG(fabs(mean - v) <= FLIP_TOL, "%s %s ppd %g: mean %.9f, reference %.9f", an, bn, ppd, mean, v);
            worst_mean = fmax(worst_mean, fabs(mean - v));
            snprintf(cur, sizeof cur, "%s %s %.17g", an, bn, ppd);
            pairs++;
        } else if (sscanf(line, "pixel %127s %127s %lf %d %d %lf", an, bn, &ppd, &x, &y, &v) == 6) {
            snprintf(key, sizeof key, "%s %s %.17g", an, bn, ppd);
            CHECK_MSG(strcmp(key, cur) == 0, "pixel line for %s follows %s", key, cur);
            if (!map.pixels || x >= map.width || y >= map.height) continue;
            double got = map.pixels[((size_t)y * (size_t)map.width + (size_t)x) * 3];
            CHECK_MSG(fabs(got - v) <= FLIP_TOL, "%s (%d, %d): %.9f, reference %.9f", key, x, y, got, v);
            worst_pixel = fmax(worst_pixel, fabs(got - v));
            points++;
        }
    }
    fclose(f);
    sss_image_free(&a);
    sss_image_free(&b);
    sss_image_free(&map);
    CHECK(pairs == 10 && points == 74);
    printf("FLIP against NVIDIA's: %d means (worst %.2g), %d pixels (worst %.2g)\n", pairs, worst_mean, points,
           worst_pixel);
}

/* Independent CIELAB of an 8-bit sRGB colour with the Hunt adjustment (paper Eq. 3), D65 white from the
 * sRGB primaries (IEC 61966-2-1 matrix rounded to 4 digits: the flat-field check does not need more). */
static void hunt_lab(const uint8_t c[3], double lab[3])
{
    double l[3];
    for (int k = 0; k < 3; k++) {
        double s = c[k] / 255.0;
        l[k] = s <= 0.04045 ? s / 12.92 : pow((s + 0.055) / 1.055, 2.4);
    }
    const double M[3][3] = {{0.4124, 0.3576, 0.1805}, {0.2126, 0.7152, 0.0722}, {0.0193, 0.1192, 0.9505}};
    double t[3];
    for (int i = 0; i < 3; i++) {
        double xyz = M[i][0] * l[0] + M[i][1] * l[1] + M[i][2] * l[2];
        double white = M[i][0] + M[i][1] + M[i][2];
        double r = xyz / white, d = 6.0 / 29.0;
        t[i] = r > d * d * d ? cbrt(r) : r / (3 * d * d) + 4.0 / 29.0;
    }
    lab[0] = 116 * t[1] - 16;
    lab[1] = 0.01 * lab[0] * 500 * (t[0] - t[1]);
    lab[2] = 0.01 * lab[0] * 200 * (t[1] - t[2]);
}

static double hyab(const double p[3], const double q[3])
{
    return fabs(p[0] - q[0]) + hypot(p[1] - q[1], p[2] - q[2]);
}

/* Flat fields: the filters sum to 1 and the edge/point detectors to 0, so FLIP is the colour term of
 * Eq. 5 of the two colours everywhere. */
static void test_flat_fields(void)
{
    const uint8_t pairs[][2][3] = {{{0, 0, 0}, {255, 255, 255}}, {{120, 60, 30}, {125, 60, 30}},
                                   {{0, 255, 0}, {0, 0, 255}},   {{200, 180, 40}, {40, 90, 210}}};
    const uint8_t green[3] = {0, 255, 0}, blue[3] = {0, 0, 255};
    double lg[3], lb[3];
    hunt_lab(green, lg);
    hunt_lab(blue, lb);
    double cmax = pow(hyab(lg, lb), 0.7), pc = 0.4 * cmax;
    const int w = 40, h = 30;
    uint8_t *a = malloc((size_t)w * h * 3), *b = malloc((size_t)w * h * 3);
    for (size_t p = 0; p < sizeof pairs / sizeof pairs[0]; p++) {
        for (int i = 0; i < w * h; i++) memcpy(a + 3 * i, pairs[p][0], 3), memcpy(b + 3 * i, pairs[p][1], 3);
        double la[3], lb2[3];
        hunt_lab(pairs[p][0], la);
        hunt_lab(pairs[p][1], lb2);
        double e = pow(hyab(la, lb2), 0.7);
        double expect = e < pc ? e * 0.95 / pc : 0.95 + (e - pc) / (cmax - pc) * 0.05;
        double mean = -1;
        sss_image map = {0};
        CHECK(sss_image_flip_srgb8(a, b, w, h, SSS_FLIP_DEFAULT_PPD, &mean, &map, NULL) == SSS_OK);
        CHECK_MSG(fabs(mean - expect) < 1e-3, "pair %zu: mean %.6f, closed form %.6f", p, mean, expect);
        double lo = 1, hi = 0;
        for (int i = 0; i < w * h; i++) lo = fmin(lo, map.pixels[3 * i]), hi = fmax(hi, map.pixels[3 * i]);
        CHECK_MSG(hi - lo < 1e-5, "pair %zu: flat field gives %.6f..%.6f", p, lo, hi);
        sss_image_free(&map);
    }
    free(a);
    free(b);
}

static uint32_t lcg(uint32_t *s) { return *s = *s * 1664525u + 1013904223u; }

/* FLIP(a, a) = 0; FLIP(a, b) = FLIP(b, a) (both pipelines are symmetric); every pixel in [0, 1], also
 * for the largest differences (black against white noise); compare fills metrics.flip, compare_maps
 * also the map. */
static void test_properties(void)
{
    const int w = 48, h = 36;
    size_t n = (size_t)w * h * 3;
    uint8_t *a = malloc(n), *b = malloc(n);
    uint32_t seed = 7;
    for (size_t i = 0; i < n; i++) a[i] = (uint8_t)(lcg(&seed) >> 24), b[i] = (lcg(&seed) >> 31) ? 255 : 0;
    double m_aa = -1, m_ab = -1, m_ba = -1;
    sss_image map_ab = {0}, map_ba = {0};
    CHECK(sss_image_flip_srgb8(a, a, w, h, SSS_FLIP_DEFAULT_PPD, &m_aa, NULL, NULL) == SSS_OK);
    CHECK(m_aa == 0.0);
    CHECK(sss_image_flip_srgb8(a, b, w, h, 30.0, &m_ab, &map_ab, NULL) == SSS_OK);
    CHECK(sss_image_flip_srgb8(b, a, w, h, 30.0, &m_ba, &map_ba, NULL) == SSS_OK);
    CHECK(m_ab > 0.1 && m_ab == m_ba);
    int in_range = 1, same = 1;
    for (size_t i = 0; i < n; i++) {
        in_range &= map_ab.pixels[i] >= 0.0f && map_ab.pixels[i] <= 1.0f;
        same &= map_ab.pixels[i] == map_ba.pixels[i];
    }
    CHECK(in_range && same);
    sss_image_free(&map_ab);
    sss_image_free(&map_ba);

    /* sss_image_compare's flip is the mean at the default viewing condition */
    sss_image ia = {0}, ib = {0};
    if (read_image("images/base.png", &ia) && read_image("images/blur.png", &ib)) {
        sss_image_metrics m;
        double mean = -1;
        CHECK(sss_image_compare(&ia, &ib, 0.0, &m, NULL, NULL) == SSS_OK);
        CHECK(sss_image_flip(&ia, &ib, 0.0, SSS_FLIP_DEFAULT_PPD, &mean, NULL, NULL) == SSS_OK);
        CHECK(m.flip == mean && mean > 0);
        /* compare_maps: the same metrics and the same FLIP map as sss_image_flip's */
        sss_image_metrics m2;
        sss_image fmap = {0}, fmap2 = {0}, dmap = {0};
        CHECK(sss_image_flip(&ia, &ib, 0.0, SSS_FLIP_DEFAULT_PPD, &mean, &fmap, NULL) == SSS_OK);
        CHECK(sss_image_compare_maps(&ia, &ib, 0.0, &m2, &dmap, &fmap2, NULL) == SSS_OK);
        CHECK(m2.flip == m.flip && m2.ssim == m.ssim && dmap.pixels && fmap2.pixels);
        CHECK(fmap2.pixels && fmap.pixels &&
              memcmp(fmap.pixels, fmap2.pixels, sizeof(float) * 3 * (size_t)ia.width * (size_t)ia.height) == 0);
        sss_image_free(&fmap);
        sss_image_free(&fmap2);
        sss_image_free(&dmap);
    }
    sss_image_free(&ia);
    sss_image_free(&ib);
    free(a);
    free(b);
}

static void test_errors(void)
{
    sss_image a = {0}, b = {0}, map = {0};
    sss_error err = {0};
    double mean;
    CHECK(sss_image_create(&a, 20, 12, NULL) == SSS_OK);
    CHECK(sss_image_create(&b, 12, 20, NULL) == SSS_OK);
    CHECK(sss_image_flip(&a, &b, 0.0, SSS_FLIP_DEFAULT_PPD, &mean, &map, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK_MSG(strstr(err.message, "20x12") && strstr(err.message, "12x20"), "%s", err.message);
    CHECK(map.pixels == NULL);
    CHECK(sss_image_flip(&a, &a, 0.0, 0.5, &mean, &map, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK_MSG(strstr(err.message, "pixels per degree"), "%s", err.message);
    CHECK(sss_image_flip(&a, &a, 0.0, NAN, &mean, &map, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(sss_image_flip(&a, &a, INFINITY, 67.0, &mean, &map, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(map.pixels == NULL);
    /* a single pixel is a valid image: the filters repeat the edge */
    sss_image one = {0};
    CHECK(sss_image_create(&one, 1, 1, NULL) == SSS_OK);
    CHECK(sss_image_flip(&one, &one, 0.0, SSS_FLIP_MAX_PPD, &mean, &map, &err) == SSS_OK && mean == 0.0);
    sss_image_free(&map);
    sss_image_free(&one);
    sss_image_free(&a);
    sss_image_free(&b);
}

int main(void)
{
    test_against_nvidia();
    test_flat_fields();
    test_properties();
    test_errors();
    return CHECK_DONE();
}
