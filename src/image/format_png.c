/* image/format_png.c — PNG through stb_image / stb_image_write (Debian libstb provides the
 * implementations, so no STB_*_IMPLEMENTATION here).
 *
 * Reading: 8- or 16-bit grey, grey+alpha, RGB, RGBA and palette PNGs; grey is replicated to RGB and
 * alpha is dropped (not composited). Samples are sRGB-encoded and decoded with the exact inverse curve
 * (gAMA/iCCP chunks are ignored), so sss_image_to_srgb8 at exposure 0 returns the file's 8-bit codes.
 * Writing: 8-bit RGB, tone-mapped per SCENE.md render.exposure, via a temporary file and rename. */
#include <errno.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>

#include <stb_image.h>
#include <stb_image_write.h>

#include "core/file_util.h"
#include "image/image_internal.h"

/* stb's failure reasons are terse tokens; spell out the common one. */
static const char *stb_reason(void)
{
    const char *r = stbi_failure_reason();
    if (!r) return "unknown error";
    return strcmp(r, "outofdata") == 0 ? "truncated or corrupt data" : r;
}

static const unsigned char png_signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};

sss_result sss_png_read_(const char *path, sss_image *out, sss_error *err)
{
    FILE *f = fopen(path, "rb");
    if (!f) return sss_error_set(err, SSS_ERROR_IO, "%s: cannot open: %s", path, strerror(errno));
    unsigned char sig[8];
    size_t got = fread(sig, 1, sizeof sig, f);
    if (got != sizeof sig || memcmp(sig, png_signature, sizeof sig) != 0) {
        fclose(f);
        return sss_error_set(err, SSS_ERROR_PARSE, "%s: not a PNG file (%s)", path,
                             got == 0 ? "empty" : "bad signature");
    }
    rewind(f);
    int w = 0, h = 0, comp = 0;
    if (!stbi_info_from_file(f, &w, &h, &comp)) {
        fclose(f);
        return sss_error_set(err, SSS_ERROR_PARSE, "%s: malformed PNG header (%s)", path, stb_reason());
    }
    sss_result r = sss_image_check_dims_(path, w, h, err);
    if (r != SSS_OK) {
        fclose(f);
        return r;
    }
    /* Another part of a program may have asked stb to flip images globally; rows stay top first here. */
    stbi_set_flip_vertically_on_load_thread(0);
    int is16 = stbi_is_16_bit_from_file(f);
    void *data = is16 ? (void *)stbi_load_from_file_16(f, &w, &h, &comp, 3)
                      : (void *)stbi_load_from_file(f, &w, &h, &comp, 3);
    fclose(f);
    if (!data) return sss_error_set(err, SSS_ERROR_PARSE, "%s: cannot decode PNG (%s)", path, stb_reason());
    r = sss_image_create(out, w, h, err);
    if (r != SSS_OK) {
        stbi_image_free(data);
        sss_error_prefix(err, path);
        return r;
    }
    size_t n = (size_t)w * (size_t)h * 3;
    if (is16) {
        const unsigned short *s = data;
        for (size_t i = 0; i < n; i++) out->pixels[i] = (float)sss_srgb_decode(s[i] / 65535.0);
    } else {
        float table[256];
        sss_srgb8_decode_table_(table);
        const unsigned char *s = data;
        for (size_t i = 0; i < n; i++) out->pixels[i] = table[s[i]];
    }
    stbi_image_free(data);
    return SSS_OK;
}

static void write_to_file(void *context, void *data, int size)
{
    fwrite(data, 1, (size_t)size, (FILE *)context); /* errors surface in sss_atomic_close (ferror) */
}

sss_result sss_image_write_png8(const char *path, int width, int height, const uint8_t *rgb, sss_error *err)
{
    if (!rgb || width <= 0 || height <= 0 || width > SSS_IMAGE_MAX_DIM || height > SSS_IMAGE_MAX_DIM)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "%s: no valid image to write (%dx%d)", path, width,
                             height);
    /* stb_image_write sizes its buffers with int: keep well inside that. */
    if ((double)(3.0 * width + 1.0) * height > INT_MAX / 2)
        return sss_error_set(err, SSS_ERROR_LIMIT, "%s: %dx%d is too large for the PNG writer (at most %d bytes)",
                             path, width, height, INT_MAX / 2);
    char tmp[4096];
    FILE *f = sss_atomic_open(path, tmp, sizeof tmp, err);
    if (!f) return err ? err->code : SSS_ERROR_IO;
    if (!stbi_write_png_to_func(write_to_file, f, width, height, 3, rgb, width * 3)) {
        fclose(f);
        sss_discard_temp(tmp);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: PNG encoder failed (out of memory)", path);
    }
    return sss_atomic_close(f, tmp, path, err);
}

sss_result sss_png_write_(const char *path, const sss_image *img, double exposure, sss_error *err)
{
    sss_result r = sss_image_check_writable_(path, img, err);
    if (r != SSS_OK) return r;
    uint8_t *rgb = malloc((size_t)img->width * (size_t)img->height * 3);
    if (!rgb) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    sss_image_to_srgb8(img, exposure, rgb);
    r = sss_image_write_png8(path, img->width, img->height, rgb, err);
    free(rgb);
    return r;
}
