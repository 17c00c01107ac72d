/* Image metrics (docs/physics.md §5): SSIM/DSSIM, PSNR, RMSE against scikit-image's numbers for committed
 * image pairs (tests/data/images/ssim_reference.txt, from tools/ssim_reference.py), closed forms,
 * identity and symmetry. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "sss/image.h"

#define DATA SSS_TEST_DATA "/images/"

static int read_image(const char *name, sss_image *img)
{
    char path[512];
    snprintf(path, sizeof path, DATA "%s", name);
    sss_error err = {0};
    sss_result r = sss_image_read(path, img, &err);
    CHECK_MSG(r == SSS_OK, "%s", err.message);
    return r == SSS_OK;
}

/* Agreement with scikit-image 0.19: mean SSIM within 1e-9 (measured 5e-13, the printed precision), PSNR, RMSE,
 * max abs error, and the full SSIM map at border and interior pixels (which pins the 'reflect'
 * boundary of the Gaussian filter). */
static void test_against_skimage(void)
{
    FILE *f = fopen(DATA "ssim_reference.txt", "r");
    CHECK(f != NULL);
    if (!f) return;
    char line[512], an[128], bn[128], cur_a[128] = "", cur_b[128] = "";
    sss_image a = {0}, b = {0}, map = {0};
    int pairs = 0, points = 0;
    double worst_ssim = 0.0, worst_map = 0.0;
    while (fgets(line, sizeof line, f)) {
        double ssim, psnr, rmse, s[3];
        int maxd, x, y;
        if (sscanf(line, "pair %127s %127s %lf %lf %lf %d", an, bn, &ssim, &psnr, &rmse, &maxd) == 6) {
            sss_image_free(&a);
            sss_image_free(&b);
            sss_image_free(&map);
            if (!read_image(an, &a) || !read_image(bn, &b)) continue;
            snprintf(cur_a, sizeof cur_a, "%s", an);
            snprintf(cur_b, sizeof cur_b, "%s", bn);
            sss_image_metrics m;
            sss_error err = {0};
            CHECK_MSG(sss_image_compare(&a, &b, 0.0, &m, &map, &err) == SSS_OK, "%s", err.message);
            CHECK_NEAR(m.ssim, ssim, 1e-9); /* measured 5e-13: the printed precision */
            CHECK_NEAR(m.dssim, (1.0 - ssim) / 2.0, 0.5e-9);
            CHECK_REL(m.psnr, psnr, 1e-9);
            CHECK_REL(m.rmse, rmse, 1e-9);
            CHECK(m.max_abs == maxd);
            worst_ssim = fmax(worst_ssim, fabs(m.ssim - ssim));
            pairs++;
        } else if (sscanf(line, "map %127s %127s %d %d %lf %lf %lf", an, bn, &x, &y, &s[0], &s[1], &s[2]) == 7) {
            CHECK(strcmp(an, cur_a) == 0 && strcmp(bn, cur_b) == 0);
            if (!map.pixels || x >= map.width || y >= map.height) continue;
            for (int c = 0; c < 3; c++) {
                double got = map.pixels[((size_t)y * map.width + x) * 3 + c];
                CHECK_NEAR(got, (1.0 - s[c]) / 2.0, 1e-6); /* the map is stored as float */
                worst_map = fmax(worst_map, fabs(got - (1.0 - s[c]) / 2.0));
            }
            points++;
        }
    }
    fclose(f);
    sss_image_free(&a);
    sss_image_free(&b);
    sss_image_free(&map);
    CHECK(pairs == 6 && points == 48);
    printf("agreement with scikit-image: max |SSIM - ref| = %.3g over %d pairs, max |DSSIM map - ref| = %.3g "
           "over %d pixels x 3 channels\n", worst_ssim, pairs, worst_map, points);
}

/* Identical images: SSIM exactly 1, DSSIM 0, PSNR infinite; symmetry in the arguments. */
static void test_identity_and_symmetry(void)
{
    sss_image a = {0}, b = {0}, map = {0}, map2 = {0};
    if (!read_image("base.png", &a) || !read_image("noise.png", &b)) return;
    sss_image_metrics m, m2;
    CHECK(sss_image_compare(&a, &a, 0.0, &m, &map, NULL) == SSS_OK);
    CHECK(m.ssim == 1.0 && m.dssim == 0.0 && isinf(m.psnr) && m.psnr > 0 && m.rmse == 0.0 && m.max_abs == 0.0);
    size_t n = (size_t)a.width * a.height * 3, nonzero = 0;
    for (size_t i = 0; i < n; i++) nonzero += map.pixels[i] != 0.0f;
    CHECK(nonzero == 0);
    sss_image_free(&map);
    CHECK(sss_image_compare(&a, &b, 0.0, &m, &map, NULL) == SSS_OK);
    CHECK(sss_image_compare(&b, &a, 0.0, &m2, &map2, NULL) == SSS_OK);
    CHECK(m.ssim == m2.ssim && m.psnr == m2.psnr && m.rmse == m2.rmse && m.max_abs == m2.max_abs);
    CHECK(map.pixels && map2.pixels && memcmp(map.pixels, map2.pixels, n * sizeof(float)) == 0);
    CHECK(m.ssim < 1.0 && m.dssim > 0.0 && m.dssim == (1.0 - m.ssim) / 2.0);
    /* The map's interior mean is the reported DSSIM. */
    double sum = 0.0;
    for (int y = 5; y < a.height - 5; y++)
        for (int x = 5; x < a.width - 5; x++)
            for (int c = 0; c < 3; c++) sum += map.pixels[((size_t)y * a.width + x) * 3 + c];
    CHECK_NEAR(sum / ((a.width - 10.0) * (a.height - 10.0) * 3.0), m.dssim, 1e-7);
    sss_image_free(&map);
    sss_image_free(&map2);
    sss_image_free(&a);
    sss_image_free(&b);
}

/* Closed forms on constant images (zero variance everywhere, borders included):
 * S = (2ab + C1) / (a^2 + b^2 + C1); PSNR of a one-code offset = 20 log10(255). */
static void test_closed_forms(void)
{
    enum { W = 19, H = 13 };
    static uint8_t a[W * H * 3], b[W * H * 3];
    memset(a, 100, sizeof a);
    memset(b, 120, sizeof b);
    sss_image_metrics m;
    sss_image map = {0};
    CHECK(sss_image_compare_srgb8(a, b, W, H, &m, &map, NULL) == SSS_OK);
    const double C1 = (0.01 * 255) * (0.01 * 255);
    double S = (2.0 * 100 * 120 + C1) / (100.0 * 100 + 120.0 * 120 + C1);
    CHECK_NEAR(m.ssim, S, 1e-12);
    CHECK_NEAR(map.pixels[0], (1.0 - S) / 2.0, 1e-7);
    CHECK_NEAR(map.pixels[W * H * 3 - 1], (1.0 - S) / 2.0, 1e-7);
    CHECK_NEAR(m.psnr, 10.0 * log10(255.0 * 255.0 / 400.0), 1e-12);
    CHECK(m.rmse == 20.0 && m.max_abs == 20.0);
    sss_image_free(&map);
    for (int i = 0; i < W * H * 3; i++) b[i] = (uint8_t)(100 + (i % 2 ? 1 : -1));
    CHECK(sss_image_compare_srgb8(a, b, W, H, &m, NULL, NULL) == SSS_OK);
    CHECK_NEAR(m.psnr, 20.0 * log10(255.0), 1e-12);
    CHECK(m.rmse == 1.0 && m.max_abs == 1.0);
}

/* Exposure: comparing at exposure E equals comparing the images scaled by 2^E at exposure 0. */
static void test_exposure(void)
{
    sss_image a = {0}, b = {0};
    if (!read_image("base.png", &a) || !read_image("blur.png", &b)) return;
    sss_image_metrics m1, m2;
    CHECK(sss_image_compare(&a, &b, -1.0, &m1, NULL, NULL) == SSS_OK);
    size_t n = (size_t)a.width * a.height * 3;
    for (size_t i = 0; i < n; i++) a.pixels[i] *= 0.5f, b.pixels[i] *= 0.5f;
    CHECK(sss_image_compare(&a, &b, 0.0, &m2, NULL, NULL) == SSS_OK);
    CHECK(m1.ssim == m2.ssim && m1.psnr == m2.psnr);
    CHECK(sss_image_compare(&a, &b, NAN, &m2, NULL, NULL) == SSS_ERROR_INVALID_ARGUMENT);
    sss_image_free(&a);
    sss_image_free(&b);
}

static void test_errors(void)
{
    sss_image a = {0}, b = {0}, map = {0};
    sss_error err = {0};
    sss_image_metrics m;
    CHECK(sss_image_create(&a, 20, 12, NULL) == SSS_OK);
    CHECK(sss_image_create(&b, 12, 20, NULL) == SSS_OK);
    CHECK(sss_image_compare(&a, &b, 0.0, &m, &map, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK_MSG(strstr(err.message, "20x12") && strstr(err.message, "12x20"), "%s", err.message);
    CHECK(map.pixels == NULL);
    sss_image_free(&b);
    CHECK(sss_image_create(&b, 20, 10, NULL) == SSS_OK);
    sss_image_free(&a);
    CHECK(sss_image_create(&a, 20, 10, NULL) == SSS_OK);
    CHECK(sss_image_compare(&a, &b, 0.0, &m, &map, &err) == SSS_ERROR_INVALID_ARGUMENT); /* < 11 rows */
    CHECK(map.pixels == NULL);
    sss_image_free(&a);
    sss_image_free(&b);
    CHECK(sss_image_compare(&a, &b, 0.0, &m, NULL, &err) == SSS_ERROR_INVALID_ARGUMENT); /* empty */
}

int main(void)
{
    test_against_skimage();
    test_identity_and_symmetry();
    test_closed_forms();
    test_exposure();
    test_errors();
    return CHECK_DONE();
}
