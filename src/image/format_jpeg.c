/* image/format_jpeg.c — JPEG reading through stb_image (baseline and progressive, grey or colour;
 * the common format of textures inside glTF assets). Samples are 8-bit sRGB, decoded with the same
 * exact inverse curve as PNG. No writer: sss writes PNG, HDR, PFM and EXR. */
#include <stdlib.h>
#include <string.h>

#include <stb_image.h>

#include "image/image_internal.h"

/* A JPEG's entropy-coded data is not chunked: stb_image decodes it from memory, where the end of the
 * data is exact (its stdio callbacks can loop forever on a cut file: fseek past the end clears EOF). */
#define JPEG_MAX_FILE_BYTES (256u << 20)

static sss_result read_all(FILE *f, const char *path, unsigned char **bytes, size_t *size, sss_error *err)
{
    long long have = sss_image_stream_remaining_(f);
    if (have < 0) return sss_error_set(err, SSS_ERROR_IO, "%s: cannot tell the JPEG's size", path);
    if ((unsigned long long)have > JPEG_MAX_FILE_BYTES)
        return sss_error_set(err, SSS_ERROR_LIMIT, "%s: JPEG of %lld bytes, more than the %u accepted", path, have,
                             JPEG_MAX_FILE_BYTES);
    if (!(*bytes = malloc(have ? (size_t)have : 1))) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    *size = fread(*bytes, 1, (size_t)have, f);
    return SSS_OK;
}

sss_result sss_jpeg_read_(FILE *f, const char *path, int size_only, sss_image *out, sss_error *err)
{
    unsigned char *bytes = NULL;
    size_t size = 0;
    sss_result r = read_all(f, path, &bytes, &size, err);
    if (r != SSS_OK) return r;
    int w = 0, h = 0, comp = 0;
    if (size < 3 || bytes[0] != 0xFF || bytes[1] != 0xD8 || bytes[2] != 0xFF)
        r = sss_error_set(err, SSS_ERROR_PARSE, "%s: not a JPEG file (%s)", path, size == 0 ? "empty" : "bad signature");
    else if (!stbi_info_from_memory(bytes, (int)size, &w, &h, &comp))
        r = sss_error_set(err, SSS_ERROR_PARSE, "%s: malformed JPEG header (%s)", path, stbi_failure_reason());
    /* the header's size before stb allocates from it, with the PNG budget of decoded pixels */
    else
        r = sss_image_check_decoded_size_(path, "JPEG", w, h, err);
    unsigned char *data = NULL;
    if (r == SSS_OK && !size_only) {
        stbi_set_flip_vertically_on_load_thread(0);
        if (!(data = stbi_load_from_memory(bytes, (int)size, &w, &h, &comp, 3)))
            r = sss_error_set(err, SSS_ERROR_PARSE, "%s: cannot decode JPEG (%s)", path, stbi_failure_reason());
    }
    free(bytes);
    if (r != SSS_OK || size_only) {
        out->width = r == SSS_OK ? w : 0;
        out->height = r == SSS_OK ? h : 0;
        return r;
    }
    if ((r = sss_image_create(out, w, h, err)) != SSS_OK) {
        stbi_image_free(data);
        sss_error_prefix(err, path);
        return r;
    }
    float table[256];
    sss_srgb8_decode_table_(table);
    size_t n = (size_t)w * (size_t)h * 3;
    for (size_t i = 0; i < n; i++) out->pixels[i] = table[data[i]];
    stbi_image_free(data);
    return SSS_OK;
}
