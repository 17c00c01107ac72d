/* image/flip.c — LDR-FLIP (Andersson et al. 2020, "FLIP: A Difference Evaluator for Alternating
 * Images", HPG 2020) on 8-bit sRGB images: a per-pixel error in [0, 1] and its mean.
 *
 * The two pipelines of the paper (section 4), in double precision:
 *  - colour: sRGB -> linear RGB -> XYZ -> YCxCz (linear opponent space, D65 white); each channel
 *    filtered with the contrast sensitivity function of Eq. 2 as a sum of Gaussians in visual degrees
 *    (Table 1 constants; radius 3 standard deviations of the widest); back to linear RGB clamped to
 *    [0, 1]; CIELAB with the Hunt adjustment a*, b* x 0.01 L* (Eq. 3); HyAB distance (Eq. 4) raised
 *    to qc = 0.7 and mapped to [0, 1] by Eq. 5 (pc = 0.4, pt = 0.95, cmax = HyAB(green, blue)^qc);
 *  - features: the luminance Y (as (Y* + 16) / 116, i.e. Y / Yn in [0, 1]) filtered with the first
 *    and second derivatives of a Gaussian of standard deviation 0.5 w ppd, w = 0.082 degrees, each
 *    normalised so its positive weights sum to 1 and its negative ones to -1 (Eq. 6-7); the feature
 *    difference is (max(|edge_a| - |edge_b|, |point_a| - |point_b|) / sqrt(2))^qf, qf = 0.5 (Eq. 8);
 *  - FLIP = colour^(1 - feature) (Eq. 9).
 * The 2D filters are Gaussians (or a sum of two), so they are applied as two 1D passes; images are
 * extended by repeating their edge pixels. Both pipelines are symmetric in the two images. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "image/image_internal.h"

/* Paper, Table 1 and section 4: CSF Gaussians (a1, b1, a2, b2) of the Y, Cx and Cz channels. */
static const double CSF_A1[3] = {1.0, 1.0, 34.1}, CSF_B1[3] = {0.0047, 0.0053, 0.04};
static const double CSF_A2[3] = {0.0, 0.0, 13.5}, CSF_B2[3] = {1e-5, 1e-5, 0.025};
#define FLIP_QC 0.7
#define FLIP_PC 0.4
#define FLIP_PT 0.95
#define FLIP_W 0.082 /* degrees: feature detector width */
#define FLIP_QF 0.5
/* The largest filter the paper's constants give at SSS_FLIP_MAX_PPD (keeps the kernels on the stack). */
#define FLIP_MAX_RADIUS 200

/* D65 white of the sRGB primaries (XYZ of linear RGB (1, 1, 1)). */
static const double WHITE[3] = {0.950428545, 1.0, 1.088900371};

static void rgb_to_xyz(const double c[3], double xyz[3])
{
    /* sRGB primaries, D65 (the exact rational form of the IEC 61966-2-1 matrix) */
    xyz[0] = (10135552.0 * c[0] + 8788810.0 * c[1] + 4435075.0 * c[2]) / 24577794.0;
    xyz[1] = (2613072.0 * c[0] + 8788810.0 * c[1] + 887015.0 * c[2]) / 12288897.0;
    xyz[2] = (1425312.0 * c[0] + 8788810.0 * c[1] + 70074185.0 * c[2]) / 73733382.0;
}

static void xyz_to_rgb(const double xyz[3], double c[3])
{
    c[0] = 3.241003275 * xyz[0] - 1.537398934 * xyz[1] - 0.498615861 * xyz[2];
    c[1] = -0.969224334 * xyz[0] + 1.875930071 * xyz[1] + 0.041554224 * xyz[2];
    c[2] = 0.055639423 * xyz[0] - 0.204011202 * xyz[1] + 1.057148933 * xyz[2];
}

static double lab_f(double t)
{
    const double d = 6.0 / 29.0;
    return t > d * d * d ? cbrt(t) : t / (3.0 * d * d) + 4.0 / 29.0;
}

/* Linear RGB -> CIELAB with the Hunt adjustment (paper Eq. 3). */
static void rgb_to_lab_hunt(const double c[3], double lab[3])
{
    double xyz[3];
    rgb_to_xyz(c, xyz);
    double fx = lab_f(xyz[0] / WHITE[0]), fy = lab_f(xyz[1] / WHITE[1]), fz = lab_f(xyz[2] / WHITE[2]);
    lab[0] = 116.0 * fy - 16.0;
    lab[1] = 0.01 * lab[0] * 500.0 * (fx - fy);
    lab[2] = 0.01 * lab[0] * 200.0 * (fy - fz);
}

static double hyab(const double a[3], const double b[3])
{
    double da = a[1] - b[1], db = a[2] - b[2];
    return fabs(a[0] - b[0]) + sqrt(da * da + db * db);
}

/* YCxCz of a linear RGB colour: Y* = 116 Y/Yn - 16, Cx = 500 (X/Xn - Y/Yn), Cz = 200 (Y/Yn - Z/Zn). */
static void rgb_to_ycxcz(const double c[3], float out[3])
{
    double xyz[3];
    rgb_to_xyz(c, xyz);
    double x = xyz[0] / WHITE[0], y = xyz[1] / WHITE[1], z = xyz[2] / WHITE[2];
    out[0] = (float)(116.0 * y - 16.0);
    out[1] = (float)(500.0 * (x - y));
    out[2] = (float)(200.0 * (y - z));
}

static void ycxcz_to_rgb(const double ycc[3], double c[3])
{
    double y = (ycc[0] + 16.0) / 116.0;
    double xyz[3] = {(y + ycc[1] / 500.0) * WHITE[0], y * WHITE[1], (y - ycc[2] / 200.0) * WHITE[2]};
    xyz_to_rgb(xyz, c);
    for (int k = 0; k < 3; k++) c[k] = c[k] < 0.0 ? 0.0 : c[k] > 1.0 ? 1.0 : c[k];
}

/* One 1D factor of a CSF Gaussian a sqrt(pi/b) exp(-pi^2 r^2 / b) at x degrees: the 2D Gaussian is
 * the product of two such factors in x and y, each sqrt(a sqrt(pi / b)) exp(-pi^2 x^2 / b). */
static double csf_factor(double x, double a, double b)
{
    return sqrt(a * sqrt(M_PI / b)) * exp(-M_PI * M_PI * x * x / b);
}

typedef struct flip_kernels {
    int csf_radius, feat_radius;
    /* CSF 1D factors: [0] Y, [1] Cx, [2] Cz's first Gaussian, [3] Cz's second; normalised so that each
     * 2D filter (Y, Cx: the square of its factor; Cz: the sum of the squares) sums to 1 */
    double csf[4][2 * FLIP_MAX_RADIUS + 1];
    double gauss[2 * FLIP_MAX_RADIUS + 1], d1[2 * FLIP_MAX_RADIUS + 1], d2[2 * FLIP_MAX_RADIUS + 1];
} flip_kernels;

static void normalise_signed(double *k, int n)
{
    double pos = 0.0, neg = 0.0;
    for (int i = 0; i < n; i++) {
        if (k[i] > 0) pos += k[i];
        else neg -= k[i];
    }
    for (int i = 0; i < n; i++) k[i] /= k[i] > 0 ? pos : neg;
}

static void flip_make_kernels(double ppd, flip_kernels *k)
{
    double bmax = 0.0;
    for (int c = 0; c < 3; c++) bmax = fmax(bmax, fmax(CSF_B1[c], CSF_B2[c]));
    /* 3 standard deviations of the widest Gaussian, whose sigma is sqrt(b / (2 pi^2)) degrees */
    k->csf_radius = (int)ceil(3.0 * sqrt(bmax / (2.0 * M_PI * M_PI)) * ppd);
    int n = 2 * k->csf_radius + 1;
    double sum[4] = {0};
    for (int i = 0; i < n; i++) {
        double x = (i - k->csf_radius) / ppd;
        k->csf[0][i] = csf_factor(x, CSF_A1[0], CSF_B1[0]);
        k->csf[1][i] = csf_factor(x, CSF_A1[1], CSF_B1[1]);
        k->csf[2][i] = csf_factor(x, CSF_A1[2], CSF_B1[2]);
        k->csf[3][i] = csf_factor(x, CSF_A2[2], CSF_B2[2]);
        for (int j = 0; j < 4; j++) sum[j] += k->csf[j][i];
    }
    double cz_norm = sqrt(sum[2] * sum[2] + sum[3] * sum[3]);
    for (int i = 0; i < n; i++) {
        k->csf[0][i] /= sum[0];
        k->csf[1][i] /= sum[1];
        k->csf[2][i] /= cz_norm;
        k->csf[3][i] /= cz_norm;
    }

    double sd = 0.5 * FLIP_W * ppd;
    k->feat_radius = (int)ceil(3.0 * sd);
    int m = 2 * k->feat_radius + 1;
    double gsum = 0.0;
    for (int i = 0; i < m; i++) {
        double x = i - k->feat_radius, g = exp(-x * x / (2.0 * sd * sd));
        k->gauss[i] = g;
        k->d1[i] = -x * g;
        k->d2[i] = (x * x / (sd * sd) - 1.0) * g;
        gsum += g;
    }
    for (int i = 0; i < m; i++) k->gauss[i] /= gsum;
    normalise_signed(k->d1, m);
    normalise_signed(k->d2, m);
}

static inline int clampi(int v, int lo, int hi) { return v < lo ? lo : v > hi ? hi : v; }

/* Filters each of nplanes planes (w x h floats) along x with kernels[p] (radius r) into out. */
static void filter_rows(const float *const *in, float *const *out, const double *const *kern, int nplanes, int r,
                        int w, int h)
{
    for (int p = 0; p < nplanes; p++)
        for (int y = 0; y < h; y++) {
            const float *row = in[p] + (size_t)y * (size_t)w;
            float *dst = out[p] + (size_t)y * (size_t)w;
            for (int x = 0; x < w; x++) {
                double acc = 0.0;
                for (int i = -r; i <= r; i++) acc += kern[p][i + r] * row[clampi(x + i, 0, w - 1)];
                dst[x] = (float)acc;
            }
        }
}

/* The value at (x, y) of plane filtered along y with kern (radius r). */
static inline double filter_column(const float *plane, const double *kern, int r, int x, int y, int w, int h)
{
    double acc = 0.0;
    for (int i = -r; i <= r; i++) acc += kern[i + r] * plane[(size_t)clampi(y + i, 0, h - 1) * (size_t)w + (size_t)x];
    return acc;
}

/* Colour pipeline: writes the colour difference (Eq. 5, in [0, 1]) into diff. ycc[img][channel] are
 * YCxCz planes; tmp holds 8 planes of scratch. */
static void flip_colour(float *ycc[2][3], float *tmp[8], const flip_kernels *k, int w, int h, float *diff)
{
    /* per image: Y, Cx, Cz with Gaussian 1, Cz with Gaussian 2 */
    for (int im = 0; im < 2; im++) {
        const float *in[4] = {ycc[im][0], ycc[im][1], ycc[im][2], ycc[im][2]};
        const double *kern[4] = {k->csf[0], k->csf[1], k->csf[2], k->csf[3]};
        filter_rows(in, tmp + 4 * im, kern, 4, k->csf_radius, w, h);
    }
    const double green[3] = {0, 1, 0}, blue[3] = {0, 0, 1};
    double lg[3], lb[3];
    rgb_to_lab_hunt(green, lg);
    rgb_to_lab_hunt(blue, lb);
    const double cmax = pow(hyab(lg, lb), FLIP_QC), pccmax = FLIP_PC * cmax;
    int r = k->csf_radius;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double lab[2][3];
            for (int im = 0; im < 2; im++) {
                float *const *t = tmp + 4 * im;
                double f[3] = {filter_column(t[0], k->csf[0], r, x, y, w, h), filter_column(t[1], k->csf[1], r, x, y, w, h),
                               filter_column(t[2], k->csf[2], r, x, y, w, h) +
                                   filter_column(t[3], k->csf[3], r, x, y, w, h)};
                double rgb[3];
                ycxcz_to_rgb(f, rgb);
                rgb_to_lab_hunt(rgb, lab[im]);
            }
            double e = pow(hyab(lab[0], lab[1]), FLIP_QC);
            e = e < pccmax ? e * FLIP_PT / pccmax : FLIP_PT + (e - pccmax) / (cmax - pccmax) * (1.0 - FLIP_PT);
            diff[(size_t)y * (size_t)w + (size_t)x] = (float)e;
        }
}

/* Feature pipeline and Eq. 9: diff holds the colour difference on entry, FLIP on return. lum[img] are
 * the Y / Yn planes; tmp, 8 planes of scratch (the colour pipeline is done with them). */
static void flip_features(float *lum[2], float *tmp[8], const flip_kernels *k, int w, int h, float *diff)
{
    /* along x: d/dx G, d2/dx2 G and G (for the y derivatives) */
    for (int im = 0; im < 2; im++) {
        const float *in[3] = {lum[im], lum[im], lum[im]};
        const double *kern[3] = {k->d1, k->d2, k->gauss};
        filter_rows(in, tmp + 3 * im, kern, 3, k->feat_radius, w, h);
    }
    int r = k->feat_radius;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double edge[2], point[2];
            for (int im = 0; im < 2; im++) {
                float *const *t = tmp + 3 * im;
                double dx = filter_column(t[0], k->gauss, r, x, y, w, h);
                double ddx = filter_column(t[1], k->gauss, r, x, y, w, h);
                double dy = filter_column(t[2], k->d1, r, x, y, w, h);
                double ddy = filter_column(t[2], k->d2, r, x, y, w, h);
                edge[im] = sqrt(dx * dx + dy * dy);
                point[im] = sqrt(ddx * ddx + ddy * ddy);
            }
            double fd = pow(fmax(fabs(edge[0] - edge[1]), fabs(point[0] - point[1])) / sqrt(2.0), FLIP_QF);
            size_t at = (size_t)y * (size_t)w + (size_t)x;
            diff[at] = (float)pow(diff[at], 1.0 - fd);
        }
}

sss_result sss_image_flip_srgb8(const uint8_t *reference, const uint8_t *test, int width, int height, double ppd,
                                double *mean, sss_image *flip_map, sss_error *err)
{
    if (flip_map) flip_map->pixels = NULL, flip_map->width = flip_map->height = 0;
    if (!reference || !test || !mean || width <= 0 || height <= 0)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "flip: no images given");
    if (!(ppd >= SSS_FLIP_MIN_PPD && ppd <= SSS_FLIP_MAX_PPD))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "flip: pixels per degree %g is outside [%g, %g]", ppd,
                             SSS_FLIP_MIN_PPD, SSS_FLIP_MAX_PPD);
    size_t n = (size_t)width * (size_t)height;
    /* 6 input planes (YCxCz of both), 8 scratch, 1 result */
    float *mem = malloc(sizeof(float) * 15 * n);
    flip_kernels *k = malloc(sizeof *k);
    if (!mem || !k) {
        free(mem);
        free(k);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "flip: out of memory (%dx%d)", width, height);
    }
    float *ycc[2][3], *tmp[8], *diff = mem + 14 * n;
    for (int p = 0; p < 6; p++) ycc[p / 3][p % 3] = mem + (size_t)p * n;
    for (int p = 0; p < 8; p++) tmp[p] = mem + (size_t)(6 + p) * n;
    float lin[256];
    sss_srgb8_decode_table_(lin);
    for (size_t i = 0; i < n; i++)
        for (int im = 0; im < 2; im++) {
            const uint8_t *px = (im ? test : reference) + 3 * i;
            double c[3] = {lin[px[0]], lin[px[1]], lin[px[2]]};
            float v[3];
            rgb_to_ycxcz(c, v);
            for (int ch = 0; ch < 3; ch++) ycc[im][ch][i] = v[ch];
        }
    flip_make_kernels(ppd, k);
    flip_colour(ycc, tmp, k, width, height, diff);
    /* the luminance Y / Yn = (Y* + 16) / 116, in place of Y* (Cx and Cz are no longer needed) */
    float *lum[2] = {ycc[0][0], ycc[1][0]};
    for (int im = 0; im < 2; im++)
        for (size_t i = 0; i < n; i++) lum[im][i] = (lum[im][i] + 16.0f) / 116.0f;
    flip_features(lum, tmp, k, width, height, diff);
    free(k);

    double sum = 0.0;
    for (size_t i = 0; i < n; i++) sum += diff[i];
    *mean = sum / (double)n;
    sss_result r = SSS_OK;
    if (flip_map && (r = sss_image_create(flip_map, width, height, err)) == SSS_OK)
        for (size_t i = 0; i < n; i++)
            for (int ch = 0; ch < 3; ch++) flip_map->pixels[3 * i + (size_t)ch] = diff[i];
    free(mem);
    return r;
}

sss_result sss_image_flip(const sss_image *reference, const sss_image *test, double exposure, double ppd,
                          double *mean, sss_image *flip_map, sss_error *err)
{
    if (flip_map) flip_map->pixels = NULL, flip_map->width = flip_map->height = 0;
    if (!reference || !test || !reference->pixels || !test->pixels || !mean)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "flip: no images given");
    if (reference->width != test->width || reference->height != test->height)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "flip: image sizes differ: %dx%d and %dx%d",
                             reference->width, reference->height, test->width, test->height);
    if (!isfinite(exposure)) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "flip: exposure must be finite");
    size_t n = (size_t)reference->width * (size_t)reference->height * 3;
    uint8_t *a8 = malloc(2 * n);
    if (!a8) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "flip: out of memory");
    sss_image_to_srgb8(reference, exposure, a8);
    sss_image_to_srgb8(test, exposure, a8 + n);
    sss_result r = sss_image_flip_srgb8(a8, a8 + n, reference->width, reference->height, ppd, mean, flip_map, err);
    free(a8);
    return r;
}
