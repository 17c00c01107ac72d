/* sss/image.h — linear float RGB images, their file formats, tone mapping and image metrics.
 *
 * Does: read/write PNG (8-bit sRGB), Radiance HDR, PFM and OpenEXR (half or float RGB), read JPEG (8-bit
 * sRGB, as glTF assets carry textures); encode PNG in memory; tone map
 * exactly as docs/scene-format.md render.exposure; SSIM/DSSIM (Wang et al. 2004, docs/physics.md §5), PSNR, RMSE, max abs
 * error, LDR-FLIP (Andersson et al. 2020); find NaN/Inf. Does not: resample, colour-manage beyond sRGB, GL.
 * Pixels are linear RGB floats, row-major, top row first. PNG files are decoded with the exact inverse
 * of the sRGB curve, so writing a decoded PNG again at exposure 0 gives back the same bytes.
 */
#ifndef SSS_IMAGE_H
#define SSS_IMAGE_H

#include <stdint.h>

#include "sss/common.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Largest accepted width or height, for reading and creating (documented limit). */
#define SSS_IMAGE_MAX_DIM 32768
/* Largest PNG or JPEG decoded, width x height (2^27: e.g. 16384 x 8192, 1.6 GB as floats). Deflate expands up
 * to 1032:1, so a PNG of under a megabyte can claim gigabytes: the claim is refused from the header
 * (SSS_ERROR_LIMIT) before anything is decoded. */
#define SSS_IMAGE_MAX_PNG_PIXELS (1L << 27)

typedef struct sss_image {
    int width, height;
    float *pixels; /* width * height * 3 */
} sss_image;

SSS_API sss_result sss_image_create(sss_image *img, int width, int height, sss_error *err); /* zero-filled */
SSS_API void sss_image_free(sss_image *img);

/* Format by file extension (case-insensitive): .png, .hdr, .pfm, .exr; reading also .jpg, .jpeg.
 * Errors name the path.
 * A header that claims more pixels than the file's data could hold (given the format's best
 * compression) is refused before the image is allocated. */
SSS_API sss_result sss_image_read(const char *path, sss_image *out, sss_error *err);
/* Only the size, from the file's header, with sss_image_read's checks up to decoding the pixels (so
 * that two images can be compared in size before either is decoded). */
SSS_API sss_result sss_image_read_size(const char *path, int *width, int *height, sss_error *err);
/* sss_image_read from memory (size bytes; for fuzzing and embedded data): the format comes from name's
 * extension, which also names the input in messages (NULL = "image", which has no format). */
SSS_API sss_result sss_image_decode(const void *data, size_t size, const char *name, sss_image *out, sss_error *err);
/* The image as PNG bytes (8-bit sRGB, tone-mapped as sss_image_write with that exposure), for
 * containers that embed images (glTF). *bytes is malloc'd (free it); NaN or Inf is refused as by the
 * writers. */
SSS_API sss_result sss_image_encode_png(const sss_image *img, double exposure, unsigned char **bytes, size_t *size,
                                        sss_error *err);
/* PNG is tone-mapped with exposure; HDR, PFM and EXR store linear values (exposure ignored).
 * The file is written to a temporary name in the same folder and renamed when complete.
 * Writers REFUSE images holding NaN or Inf (SSS_ERROR_NUMERIC, the message gives the count; see
 * sss_image_count_nonfinite) and never leave a partial or temporary file behind on any error.
 * EXR is written as 32-bit float (exact), ZIP compressed; HDR is flat RGBE (negative values become 0,
 * relative precision about 1/256 of the brightest channel); PFM is little-endian "PF". */
SSS_API sss_result sss_image_write(const char *path, const sss_image *img, double exposure, sss_error *err);

/* OpenEXR with a choice of sample type: half != 0 writes 16-bit half floats (fails with
 * SSS_ERROR_LIMIT if a value rounds beyond the half range, |v| >= 65520), else 32-bit float. */
SSS_API sss_result sss_image_write_exr(const char *path, const sss_image *img, int half, sss_error *err);

/* Writes ready-made 8-bit sRGB bytes (width * height * 3, row-major, top row first) as a PNG,
 * atomically (for false-colour maps and the like). */
SSS_API sss_result sss_image_write_png8(const char *path, int width, int height, const uint8_t *rgb, sss_error *err);

/* out = round(255 * srgb(clamp(linear * 2^exposure, 0, 1))) per channel; NaN maps to 0.
 * dst holds width * height * 3 bytes. Evaluated in float exactly as PBRT-v3 writes PNGs, so at
 * exposure 0 the bytes equal PBRT's; decoding a PNG with sss_image_read and mapping it again at
 * exposure 0 returns the file's bytes. */
SSS_API void sss_image_to_srgb8(const sss_image *img, double exposure, uint8_t *dst);
SSS_API double sss_srgb_encode(double linear);  /* sRGB OETF, [0,1] -> [0,1] */
SSS_API double sss_srgb_decode(double encoded); /* its inverse */

/* Number of NaN or infinite values (0 means the image is safe to write). */
SSS_API size_t sss_image_count_nonfinite(const sss_image *img);
/* Fails with SSS_ERROR_INVALID_ARGUMENT when img holds NaN or Inf, naming name, the first such pixel and
 * the count ("sky.pfm: pixel (1, 3) is nan (1 non-finite value)"): for inputs such as environment
 * maps, where one NaN would spread through every light. */
SSS_API sss_result sss_image_require_finite(const sss_image *img, const char *name, sss_error *err);

typedef struct sss_image_metrics {
    double ssim;     /* mean SSIM over pixels and channels, 8-bit sRGB, data range 255 */
    double dssim;    /* (1 - ssim) / 2 */
    double psnr;     /* dB on the 8-bit images; INFINITY when identical */
    double rmse;     /* on the 8-bit images, in [0, 255] */
    double max_abs;  /* largest absolute 8-bit difference */
    double flip;     /* mean LDR-FLIP in [0, 1] at SSS_FLIP_DEFAULT_PPD (see sss_image_flip) */
} sss_image_metrics;

/* Compares a and b after tone mapping both with exposure (metrics.flip as sss_image_flip at
 * SSS_FLIP_DEFAULT_PPD; the rest docs/physics.md §5: 11x11 Gaussian window,
 * sigma 1.5, K1 0.01, K2 0.03, per channel, averaged; borders as scikit-image, which crops 5 pixels).
 * dssim_map (optional, may be NULL) receives a width x height image whose three channels hold the
 * per-pixel DSSIM of R, G and B. Images of different sizes are an error. */
SSS_API sss_result sss_image_compare(const sss_image *a, const sss_image *b, double exposure,
                                     sss_image_metrics *out, sss_image *dssim_map, sss_error *err);
/* sss_image_compare that also returns the FLIP map (optional, may be NULL; as sss_image_flip's), with
 * FLIP computed once for both. */
SSS_API sss_result sss_image_compare_maps(const sss_image *a, const sss_image *b, double exposure,
                                          sss_image_metrics *out, sss_image *dssim_map, sss_image *flip_map,
                                          sss_error *err);

/* The same on ready-made 8-bit sRGB images (width * height * 3 bytes each). Both compare functions
 * need width and height >= 11 (the SSIM window), as scikit-image does. dssim_map, when given, must
 * not hold an image: it is allocated here (free it with sss_image_free) and left empty on error.
 * Border pixels of the map use the same 'reflect' boundary as the filter (scikit-image's full map). */
SSS_API sss_result sss_image_compare_srgb8(const uint8_t *a, const uint8_t *b, int width, int height,
                                           sss_image_metrics *out, sss_image *dssim_map, sss_error *err);

/* LDR-FLIP (Andersson et al. 2020, "FLIP: A Difference Evaluator for Alternating Images", HPG 2020):
 * the difference an observer sees when flipping between reference and test, per pixel in [0, 1]
 * (0: none), from a colour pipeline (contrast sensitivity filtering, Hunt-adjusted HyAB distance) and
 * a feature pipeline (edges and points). It depends on the viewing condition, given as pixels per
 * degree of visual angle: SSS_FLIP_DEFAULT_PPD is the paper's default of about 67 ppd, a 0.7 m wide
 * 3840-pixel monitor seen from 0.7 m (the value NVIDIA's reference implementation computes). The result is symmetric in the two images. Computed on the tone-mapped 8-bit sRGB
 * images (as the other metrics); mean is the mean over pixels. flip_map (optional, may be NULL; must
 * not hold an image) receives a width x height image with the per-pixel FLIP in all three channels
 * (free it with sss_image_free; left empty on error). ppd outside [SSS_FLIP_MIN_PPD, SSS_FLIP_MAX_PPD]
 * and images of different sizes are errors. */
#define SSS_FLIP_DEFAULT_PPD 67.02064327658226 /* 0.7 m * (3840 px / 0.7 m) * pi / 180 */
#define SSS_FLIP_MIN_PPD 1.0
#define SSS_FLIP_MAX_PPD 1000.0
SSS_API sss_result sss_image_flip(const sss_image *reference, const sss_image *test, double exposure, double ppd,
                                  double *mean, sss_image *flip_map, sss_error *err);
/* The same on ready-made 8-bit sRGB images (width * height * 3 bytes each). */
SSS_API sss_result sss_image_flip_srgb8(const uint8_t *reference, const uint8_t *test, int width, int height,
                                        double ppd, double *mean, sss_image *flip_map, sss_error *err);

#ifdef __cplusplus
}
#endif
#endif
