/* image/metrics.c — SSIM / DSSIM, PSNR, RMSE and max abs error on tone-mapped 8-bit images (docs/physics.md §5);
 * the mean FLIP comes from image/flip.c.
 *
 * SSIM after Wang et al. 2004 as scikit-image 0.19 computes it with gaussian_weights=True, sigma=1.5,
 * use_sample_covariance=False, data_range=255, per channel (channel_axis) and averaged:
 *  - local means/variances/covariance come from scipy.ndimage.gaussian_filter(mode='reflect',
 *    truncate=3.5): an 11-tap kernel exp(-x^2 / (2 sigma^2)), x = -5..5, normalised to sum 1, applied
 *    along rows (axis 0) first, then along columns, in double; 'reflect' repeats the edge sample
 *    (d c b a | a b c d | d c b a);
 *  - S = (2 ux uy + C1)(2 vxy + C2) / ((ux^2 + uy^2 + C1)(vx + vy + C2)), C1 = (0.01 * 255)^2,
 *    C2 = (0.03 * 255)^2, population (co)variances v = E[xy] - E[x]E[y];
 *  - the mean leaves out a border of (win_size - 1) / 2 = 5 pixels (skimage's crop(S, pad)).
 * The evaluation order of each sum follows scipy's symmetric correlate1d so results agree to
 * rounding. Computed one output row at a time: memory is O(width). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "image/image_internal.h"

#define SSIM_RADIUS 5 /* int(3.5 * 1.5 + 0.5), as scipy derives it from truncate */
#define SSIM_TAPS (2 * SSIM_RADIUS + 1)

/* scipy.ndimage._gaussian_kernel1d(1.5, 0, 5); the sum in numpy's pairwise order for 11 terms
 * (eight partial sums combined as a tree, then the remaining three added one by one). */
static void ssim_weights(double w[SSIM_RADIUS + 1])
{
    const double sigma = 1.5;
    double phi[SSIM_TAPS];
    for (int i = 0; i < SSIM_TAPS; i++) {
        double x = i - SSIM_RADIUS;
        phi[i] = exp(-0.5 / (sigma * sigma) * (x * x));
    }
    double sum = ((phi[0] + phi[1]) + (phi[2] + phi[3])) + ((phi[4] + phi[5]) + (phi[6] + phi[7]));
    sum += phi[8];
    sum += phi[9];
    sum += phi[10];
    for (int j = 0; j <= SSIM_RADIUS; j++) w[j] = phi[SSIM_RADIUS + j] / sum;
}

static inline int reflect(int i, int n) /* valid for n > SSIM_RADIUS */
{
    return i < 0 ? -i - 1 : i >= n ? 2 * n - i - 1 : i;
}

enum { Q_A, Q_B, Q_AA, Q_BB, Q_AB, Q_COUNT };

/* One channel: returns the mean SSIM over the cropped interior; writes (1 - S) / 2 into channel c of
 * map (if any). a, b: interleaved 8-bit RGB. v, hz: Q_COUNT * w doubles of scratch each. */
static double ssim_channel(const uint8_t *a, const uint8_t *b, int w, int h, int c, const double wt[],
                           double *v, double *hz, float *map)
{
    const double K1R = 0.01 * 255.0, K2R = 0.03 * 255.0;
    const double C1 = K1R * K1R, C2 = K2R * K2R;
    double sum = 0.0;
    for (int y = 0; y < h; y++) {
        /* Vertical pass for row y: acc = in(0) w0 + sum_{j=5..1} (in(-j) + in(+j)) wj. */
        for (int x = 0; x < w; x++) {
            size_t at = ((size_t)y * (size_t)w + (size_t)x) * 3 + (size_t)c;
            double pa = a[at], pb = b[at];
            double acc[Q_COUNT] = {pa * wt[0], pb * wt[0], pa * pa * wt[0], pb * pb * wt[0], pa * pb * wt[0]};
            for (int j = SSIM_RADIUS; j >= 1; j--) {
                size_t up = ((size_t)reflect(y - j, h) * (size_t)w + (size_t)x) * 3 + (size_t)c;
                size_t dn = ((size_t)reflect(y + j, h) * (size_t)w + (size_t)x) * 3 + (size_t)c;
                double a0 = a[up], a1 = a[dn], b0 = b[up], b1 = b[dn];
                acc[Q_A] += (a0 + a1) * wt[j];
                acc[Q_B] += (b0 + b1) * wt[j];
                acc[Q_AA] += (a0 * a0 + a1 * a1) * wt[j];
                acc[Q_BB] += (b0 * b0 + b1 * b1) * wt[j];
                acc[Q_AB] += (a0 * b0 + a1 * b1) * wt[j];
            }
            for (int q = 0; q < Q_COUNT; q++) v[(size_t)q * (size_t)w + (size_t)x] = acc[q];
        }
        /* Horizontal pass over the vertically filtered row. */
        for (int q = 0; q < Q_COUNT; q++) {
            const double *src = v + (size_t)q * (size_t)w;
            double *dst = hz + (size_t)q * (size_t)w;
            for (int x = 0; x < w; x++) {
                double acc = src[x] * wt[0];
                for (int j = SSIM_RADIUS; j >= 1; j--) acc += (src[reflect(x - j, w)] + src[reflect(x + j, w)]) * wt[j];
                dst[x] = acc;
            }
        }
        int inside_y = y >= SSIM_RADIUS && y < h - SSIM_RADIUS;
        for (int x = 0; x < w; x++) {
            double ux = hz[x], uy = hz[(size_t)w + x];
            double uxx = hz[2 * (size_t)w + x], uyy = hz[3 * (size_t)w + x], uxy = hz[4 * (size_t)w + x];
            double vx = uxx - ux * ux, vy = uyy - uy * uy, vxy = uxy - ux * uy;
            double A1 = 2.0 * ux * uy + C1, A2 = 2.0 * vxy + C2;
            double B1 = ux * ux + uy * uy + C1, B2 = vx + vy + C2;
            double S = (A1 * A2) / (B1 * B2);
            if (inside_y && x >= SSIM_RADIUS && x < w - SSIM_RADIUS) sum += S;
            if (map) map[((size_t)y * (size_t)w + (size_t)x) * 3 + (size_t)c] = (float)((1.0 - S) / 2.0);
        }
    }
    return sum / ((double)(w - 2 * SSIM_RADIUS) * (double)(h - 2 * SSIM_RADIUS));
}

/* sss_image_compare_srgb8 with the FLIP map (optional) of the same computation. */
static sss_result compare_srgb8(const uint8_t *a, const uint8_t *b, int width, int height, sss_image_metrics *out,
                                sss_image *dssim_map, sss_image *flip_map, sss_error *err)
{
    if (flip_map) flip_map->pixels = NULL, flip_map->width = flip_map->height = 0;
    if (dssim_map) dssim_map->pixels = NULL, dssim_map->width = dssim_map->height = 0;
    if (!a || !b || !out || width <= 0 || height <= 0)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "compare: no images given");
    if (width < SSIM_TAPS || height < SSIM_TAPS)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                             "compare: images are %dx%d; SSIM needs at least %dx%d pixels (its window)", width,
                             height, SSIM_TAPS, SSIM_TAPS);
    sss_result r = SSS_OK;
    if (dssim_map && (r = sss_image_create(dssim_map, width, height, err)) != SSS_OK) return r;
    double *scratch = malloc(sizeof(double) * 2 * Q_COUNT * (size_t)width);
    if (!scratch) {
        if (dssim_map) sss_image_free(dssim_map);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "compare: out of memory");
    }
    double wt[SSIM_RADIUS + 1];
    ssim_weights(wt);
    double mean[3];
    for (int c = 0; c < 3; c++)
        mean[c] = ssim_channel(a, b, width, height, c, wt, scratch, scratch + Q_COUNT * (size_t)width,
                               dssim_map ? dssim_map->pixels : NULL);
    free(scratch);

    /* PSNR and RMSE over all samples of the 8-bit images (skimage peak_signal_noise_ratio with
     * data_range 255); the integer sum of squares is exact. */
    size_t n = (size_t)width * (size_t)height * 3;
    unsigned long long sumsq = 0;
    int maxd = 0;
    for (size_t i = 0; i < n; i++) {
        int d = (int)a[i] - (int)b[i];
        if (d < 0) d = -d;
        sumsq += (unsigned long long)(d * d);
        if (d > maxd) maxd = d;
    }
    double mse = (double)sumsq / (double)n;
    double flip = 0.0;
    if ((r = sss_image_flip_srgb8(a, b, width, height, SSS_FLIP_DEFAULT_PPD, &flip, flip_map, err)) != SSS_OK) {
        if (dssim_map) sss_image_free(dssim_map);
        return r;
    }
    out->flip = flip;
    out->ssim = (mean[0] + mean[1] + mean[2]) / 3.0;
    out->dssim = (1.0 - out->ssim) / 2.0;
    out->psnr = sumsq == 0 ? INFINITY : 10.0 * log10(255.0 * 255.0 / mse);
    out->rmse = sqrt(mse);
    out->max_abs = maxd;
    return SSS_OK;
}

sss_result sss_image_compare_srgb8(const uint8_t *a, const uint8_t *b, int width, int height,
                                   sss_image_metrics *out, sss_image *dssim_map, sss_error *err)
{
    return compare_srgb8(a, b, width, height, out, dssim_map, NULL, err);
}

sss_result sss_image_compare(const sss_image *a, const sss_image *b, double exposure, sss_image_metrics *out,
                             sss_image *dssim_map, sss_error *err)
{
    return sss_image_compare_maps(a, b, exposure, out, dssim_map, NULL, err);
}

sss_result sss_image_compare_maps(const sss_image *a, const sss_image *b, double exposure, sss_image_metrics *out,
                                  sss_image *dssim_map, sss_image *flip_map, sss_error *err)
{
    if (dssim_map) dssim_map->pixels = NULL, dssim_map->width = dssim_map->height = 0;
    if (flip_map) flip_map->pixels = NULL, flip_map->width = flip_map->height = 0;
    if (!a || !b || !a->pixels || !b->pixels || !out)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "compare: no images given");
    if (a->width != b->width || a->height != b->height)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "compare: image sizes differ: %dx%d and %dx%d",
                             a->width, a->height, b->width, b->height);
    if (!isfinite(exposure))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "compare: exposure must be finite");
    size_t n = (size_t)a->width * (size_t)a->height * 3;
    uint8_t *a8 = malloc(2 * n);
    if (!a8) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "compare: out of memory");
    sss_image_to_srgb8(a, exposure, a8);
    sss_image_to_srgb8(b, exposure, a8 + n);
    sss_result r = compare_srgb8(a8, a8 + n, a->width, a->height, out, dssim_map, flip_map, err);
    free(a8);
    return r;
}
