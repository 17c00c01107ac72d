/* image/image.c — float RGB images, the sRGB curve, tone mapping (docs/scene-format.md render.exposure) and
 * format dispatch by file extension. */
#include "image/image_internal.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/file_util.h"

sss_result sss_image_check_dims_(const char *path, long width, long height, sss_error *err)
{
    if (width <= 0 || height <= 0)
        return sss_error_set(err, SSS_ERROR_PARSE, "%s: invalid image size %ldx%ld", path, width, height);
    if (width > SSS_IMAGE_MAX_DIM || height > SSS_IMAGE_MAX_DIM)
        return sss_error_set(err, SSS_ERROR_LIMIT, "%s: image size %ldx%ld exceeds the limit of %d pixels per side",
                             path, width, height, SSS_IMAGE_MAX_DIM);
    return SSS_OK;
}

sss_result sss_image_create(sss_image *img, int width, int height, sss_error *err)
{
    img->width = img->height = 0;
    img->pixels = NULL;
    if (width <= 0 || height <= 0)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "image size %dx%d: both sides must be positive",
                             width, height);
    if (width > SSS_IMAGE_MAX_DIM || height > SSS_IMAGE_MAX_DIM)
        return sss_error_set(err, SSS_ERROR_LIMIT, "image size %dx%d exceeds the limit of %d pixels per side",
                             width, height, SSS_IMAGE_MAX_DIM);
    size_t n = (size_t)width * (size_t)height * 3;
    float *p = calloc(n, sizeof(float));
    if (!p)
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory for a %dx%d image (%zu bytes)", width,
                             height, n * sizeof(float));
    img->width = width;
    img->height = height;
    img->pixels = p;
    return SSS_OK;
}

void sss_image_free(sss_image *img)
{
    if (!img) return;
    free(img->pixels);
    img->pixels = NULL;
    img->width = img->height = 0;
}

size_t sss_image_count_nonfinite(const sss_image *img)
{
    if (!img || !img->pixels) return 0;
    size_t n = (size_t)img->width * (size_t)img->height * 3, bad = 0;
    for (size_t i = 0; i < n; i++) bad += !isfinite(img->pixels[i]);
    return bad;
}

sss_result sss_image_require_finite(const sss_image *img, const char *name, sss_error *err)
{
    size_t bad = sss_image_count_nonfinite(img);
    if (!bad) return SSS_OK;
    size_t i = 0;
    while (isfinite(img->pixels[i])) i++;
    size_t pixel = i / 3;
    return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "%s: pixel (%zu, %zu) is %g (%zu non-finite value%s)",
                         name ? name : "image", pixel % (size_t)img->width, pixel / (size_t)img->width,
                         (double)img->pixels[i], bad, bad == 1 ? "" : "s");
}

/* IEC 61966-2-1 sRGB transfer function and its exact inverse. */
double sss_srgb_encode(double linear)
{
    if (!(linear > 0.0)) return 0.0; /* also NaN */
    if (linear >= 1.0) return 1.0;
    return linear <= 0.0031308 ? 12.92 * linear : 1.055 * pow(linear, 1.0 / 2.4) - 0.055;
}

double sss_srgb_decode(double encoded)
{
    if (!(encoded > 0.0)) return 0.0;
    if (encoded >= 1.0) return 1.0;
    return encoded <= 0.04045 ? encoded / 12.92 : pow((encoded + 0.055) / 1.055, 2.4);
}

/* docs/scene-format.md render.exposure: round(255 * srgb(clamp(linear * 2^exposure, 0, 1))). Evaluated in float
 * exactly as PBRT-v3's WriteImage does (GammaCorrect in float, then (uint8_t)(255 g + 0.5)), so that
 * at exposure 0 the bytes equal PBRT's PNG for the same linear image. */
uint8_t sss_srgb8_from_linear_(float linear, float scale)
{
    float v = linear * scale;
    if (!(v > 0.0f)) return 0; /* negative, zero or NaN */
    if (v > 1.0f) v = 1.0f;    /* also +Inf */
    float g = v <= 0.0031308f ? 12.92f * v : 1.055f * powf(v, 1.0f / 2.4f) - 0.055f;
    float b = 255.0f * g + 0.5f;
    if (b <= 0.0f) return 0;
    if (b >= 255.0f) return 255;
    return (uint8_t)b;
}

void sss_srgb8_decode_table_(float table[256])
{
    for (int i = 0; i < 256; i++) table[i] = (float)sss_srgb_decode(i / 255.0);
}

void sss_image_to_srgb8(const sss_image *img, double exposure, uint8_t *dst)
{
    float scale = (float)exp2(exposure);
    size_t n = (size_t)img->width * (size_t)img->height * 3;
    for (size_t i = 0; i < n; i++) dst[i] = sss_srgb8_from_linear_(img->pixels[i], scale);
}

sss_result sss_image_check_writable_(const char *path, const sss_image *img, sss_error *err)
{
    if (!img || !img->pixels || img->width <= 0 || img->height <= 0 || img->width > SSS_IMAGE_MAX_DIM ||
        img->height > SSS_IMAGE_MAX_DIM)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "%s: no valid image to write", path);
    size_t bad = sss_image_count_nonfinite(img);
    if (bad)
        return sss_error_set(err, SSS_ERROR_NUMERIC,
                             "%s: image has %zu non-finite values (NaN or Inf); refusing to write it", path, bad);
    return SSS_OK;
}

long long sss_image_stream_remaining_(FILE *f)
{
    long here = ftell(f);
    if (here < 0 || fseek(f, 0, SEEK_END) != 0) return -1;
    long end = ftell(f);
    if (fseek(f, here, SEEK_SET) != 0 || end < here) return -1;
    return (long long)end - here;
}

typedef sss_result (*stream_reader)(FILE *f, const char *path, int size_only, sss_image *out, sss_error *err);

/* The stream reader of an extension (NULL for exr, which has its own I/O, and unknown ones). */
static stream_reader reader_for(const char *ext)
{
    if (strcmp(ext, "png") == 0) return sss_png_read_;
    if (strcmp(ext, "hdr") == 0) return sss_hdr_read_;
    if (strcmp(ext, "pfm") == 0) return sss_pfm_read_;
    if (strcmp(ext, "jpg") == 0 || strcmp(ext, "jpeg") == 0) return sss_jpeg_read_;
    return NULL;
}

static sss_result unknown_format(const char *path, sss_error *err)
{
    return sss_error_set(err, SSS_ERROR_UNSUPPORTED,
                         "%s: unknown image format (expected the extension .png, .hdr, .pfm or .exr; .jpg or .jpeg to read)", path);
}

/* Opens path with sss_open_input (a FIFO or folder fails at once) and runs the format's reader. */
static sss_result read_file(const char *path, int size_only, sss_image *out, sss_error *err)
{
    out->width = out->height = 0;
    out->pixels = NULL;
    char ext[8];
    sss_path_extension(path, ext, sizeof ext);
    stream_reader read = reader_for(ext);
    if (!read && strcmp(ext, "exr") != 0) return unknown_format(path, err);
    uint64_t size = 0;
    int fd = sss_open_input(path, SSS_FILE_ANY_SIZE, &size, err);
    if (fd < 0) return err ? err->code : SSS_ERROR_IO;
    if (!read) return sss_exr_read_(fd, size, path, size_only, out, err); /* closes fd */
    FILE *f = fdopen(fd, "rb");
    if (!f) {
        close(fd);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: cannot open: %s", path, strerror(errno));
    }
    sss_result r = read(f, path, size_only, out, err);
    fclose(f);
    return r;
}

sss_result sss_image_read(const char *path, sss_image *out, sss_error *err)
{
    return read_file(path, 0, out, err);
}

sss_result sss_image_read_size(const char *path, int *width, int *height, sss_error *err)
{
    sss_image header;
    sss_result r = read_file(path, 1, &header, err);
    *width = header.width;
    *height = header.height;
    return r;
}

sss_result sss_image_decode(const void *data, size_t size, const char *name, sss_image *out, sss_error *err)
{
    out->width = out->height = 0;
    out->pixels = NULL;
    if (!name) name = "image";
    if (!data && size > 0) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "%s: no data", name);
    char ext[8];
    sss_path_extension(name, ext, sizeof ext);
    if (strcmp(ext, "exr") == 0) return sss_exr_decode_(data, size, name, out, err);
    stream_reader read = reader_for(ext);
    if (!read) return unknown_format(name, err);
    /* The stream readers then serve files and memory alike. fmemopen does not accept an empty
     * buffer everywhere: an empty input is simply a one-byte stream that ends at once. */
    static const char empty[1] = {0};
    FILE *f = fmemopen(size ? (void *)data : (void *)empty, size ? size : 1, "rb");
    if (!f) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: cannot open a memory stream", name);
    if (size == 0) (void)getc(f); /* position at the end: the readers see an empty input */
    sss_result r = read(f, name, 0, out, err);
    fclose(f);
    return r;
}

sss_result sss_image_write(const char *path, const sss_image *img, double exposure, sss_error *err)
{
    char ext[8];
    sss_path_extension(path, ext, sizeof ext);
    if (strcmp(ext, "png") == 0) {
        if (!isfinite(exposure))
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "%s: exposure must be finite", path);
        return sss_png_write_(path, img, exposure, err);
    }
    if (strcmp(ext, "hdr") == 0) return sss_hdr_write_(path, img, err);
    if (strcmp(ext, "pfm") == 0) return sss_pfm_write_(path, img, err);
    if (strcmp(ext, "exr") == 0) return sss_image_write_exr(path, img, 0, err);
    return unknown_format(path, err);
}
