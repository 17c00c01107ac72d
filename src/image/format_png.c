/* image/format_png.c — PNG through stb_image / stb_image_write (Debian libstb provides the
 * implementations, so no STB_*_IMPLEMENTATION here).
 *
 * Reading: 8- or 16-bit grey, grey+alpha, RGB, RGBA and palette PNGs; grey is replicated to RGB and
 * alpha is dropped (not composited). Samples are sRGB-encoded and decoded with the exact inverse curve
 * (gAMA/iCCP chunks are ignored), so sss_image_to_srgb8 at exposure 0 returns the file's 8-bit codes.
 * Writing: 8-bit RGB, tone-mapped per docs/scene-format.md render.exposure, via a temporary file and rename. */
#include <errno.h>
#include <limits.h>
#include <math.h>
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
    if (!r || !*r) return "unknown error";
    return strcmp(r, "outofdata") == 0 ? "truncated or corrupt data" : r;
}

static const unsigned char png_signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};

static uint32_t be32(const unsigned char *b)
{
    return (uint32_t)b[0] << 24 | (uint32_t)b[1] << 16 | (uint32_t)b[2] << 8 | (uint32_t)b[3];
}

/* Deflate cannot expand data by more than 1032:1 (a 258-byte match in at most 2 bits): the IDAT
 * chunks must hold at least raw / 1032 bytes. Checked before stb_image, which allocates its whole
 * inflate buffer from the header's size, so a 100-byte file cannot claim 32768 x 32768 pixels. */
#define DEFLATE_MAX_RATIO 1032.0

/* CRC-32 of PNG chunks (ISO 3309, the PNG specification's Annex D), which stb_image does not check.
 * The table is built per file (2048 steps): no shared state between threads. */
static void crc_table(uint32_t table[256])
{
    for (uint32_t k = 0; k < 256; k++) {
        uint32_t c = k;
        for (int j = 0; j < 8; j++) c = c & 1 ? 0xedb88320u ^ (c >> 1) : c >> 1;
        table[k] = c;
    }
}

static uint32_t crc_update(const uint32_t table[256], uint32_t crc, const unsigned char *b, size_t n)
{
    for (size_t i = 0; i < n; i++) crc = table[(crc ^ b[i]) & 0xff] ^ (crc >> 8);
    return crc;
}

/* Reads the rest of a chunk (len data bytes and the CRC) and checks the CRC over type and data;
 * head holds the chunk's length and type. Returns 0 when it matches, 1 when the data is short, 2 on
 * a CRC mismatch. */
static int check_chunk(FILE *f, const uint32_t table[256], const unsigned char head[8], uint32_t len,
                       const unsigned char *data)
{
    uint32_t crc = crc_update(table, 0xffffffffu, head + 4, 4);
    unsigned char buf[8192];
    for (uint32_t done = 0; done < len;) {
        size_t n = len - done < sizeof buf ? len - done : sizeof buf;
        if (data) memcpy(buf, data + done, n);
        else if (fread(buf, 1, n, f) != n) return 1;
        crc = crc_update(table, crc, buf, n);
        done += (uint32_t)n;
    }
    unsigned char stored[4];
    if (fread(stored, 1, 4, f) != 4) return 1;
    return be32(stored) == (crc ^ 0xffffffffu) ? 0 : 2;
}

static sss_result chunk_error(const char *path, const unsigned char head[8], int status, sss_error *err)
{
    char type[5] = {0};
    for (int i = 0; i < 4; i++) type[i] = head[4 + i] >= 0x20 && head[4 + i] < 0x7f ? (char)head[4 + i] : '?';
    if (status == 1) return sss_error_set(err, SSS_ERROR_PARSE, "%s: truncated in chunk %s", path, type);
    return sss_error_set(err, SSS_ERROR_PARSE, "%s: corrupt: chunk %s fails its CRC check", path, type);
}

/* The header's size against SSS_IMAGE_MAX_DIM per side and SSS_IMAGE_MAX_PNG_PIXELS in all (the budget of
 * every 8/16-bit format decoded through stb_image). */
sss_result sss_image_check_decoded_size_(const char *path, const char *format, long w, long h, sss_error *err)
{
    sss_result r = sss_image_check_dims_(path, w, h, err);
    if (r == SSS_OK && (double)w * (double)h > (double)SSS_IMAGE_MAX_PNG_PIXELS)
        r = sss_error_set(err, SSS_ERROR_LIMIT, "%s: %s of %ldx%ld pixels exceeds the limit of %ld pixels decoded",
                          path, format, w, h, (long)SSS_IMAGE_MAX_PNG_PIXELS);
    return r;
}

static sss_result check_size(const char *path, long w, long h, sss_error *err)
{
    return sss_image_check_decoded_size_(path, "PNG", w, h, err);
}

/* Checks the header (f just past the signature) before anything is decoded: IHDR's CRC, the size
 * against SSS_IMAGE_MAX_DIM and SSS_IMAGE_MAX_PNG_PIXELS; then (unless size_only) every chunk's CRC and
 * that the IDAT bytes can hold the pixels (stb_image allocates its whole inflate buffer from the
 * header). An image without IHDR first or of an unknown colour type is left to stb to report. */
static sss_result png_check(FILE *f, const char *path, int size_only, uint32_t *w, uint32_t *h, sss_error *err)
{
    unsigned char hd[8], ihdr[13];
    *w = *h = 0;
    if (fread(hd, 1, 8, f) != 8 || memcmp(hd + 4, "IHDR", 4) != 0 || be32(hd) != 13 || fread(ihdr, 1, 13, f) != 13)
        return SSS_OK;
    uint32_t table[256];
    crc_table(table);
    int status = check_chunk(f, table, hd, 13, ihdr);
    if (status) return chunk_error(path, hd, status, err);
    *w = be32(ihdr);
    *h = be32(ihdr + 4);
    sss_result r = check_size(path, *w, *h, err);
    if (r != SSS_OK || size_only) return r;
    int depth = ihdr[8], type = ihdr[9];
    int samples = type == 0 ? 1 : type == 2 ? 3 : type == 3 ? 1 : type == 4 ? 2 : type == 6 ? 4 : 0;
    if (!samples || depth < 1 || depth > 16) return SSS_OK;
    /* Non-interlaced size (interlacing only adds filter bytes): one filter byte per row. */
    double raw = (double)*h * (1.0 + ceil((double)*w * samples * depth / 8.0));
    unsigned long long idat = 0;
    for (;;) {
        if (fread(hd, 1, 8, f) != 8) break; /* missing IEND: stb decides */
        uint32_t len = be32(hd);
        long long have = sss_image_stream_remaining_(f);
        if (len > 0x7fffffffu || (have >= 0 && (long long)len + 4 > have))
            return sss_error_set(err, SSS_ERROR_PARSE, "%s: truncated (a chunk is longer than the rest of the file)",
                                 path);
        if ((status = check_chunk(f, table, hd, len, NULL)) != 0) return chunk_error(path, hd, status, err);
        if (memcmp(hd + 4, "IDAT", 4) == 0) idat += len;
        if (memcmp(hd + 4, "IEND", 4) == 0) break;
    }
    if ((double)idat * DEFLATE_MAX_RATIO + 64.0 < raw)
        return sss_error_set(err, SSS_ERROR_PARSE,
                             "%s: truncated or corrupt: %llu bytes of compressed pixel data cannot hold %ux%u pixels",
                             path, idat, *w, *h);
    return SSS_OK;
}

sss_result sss_png_read_(FILE *f, const char *path, int size_only, sss_image *out, sss_error *err)
{
    unsigned char sig[8];
    size_t got = fread(sig, 1, sizeof sig, f);
    if (got != sizeof sig || memcmp(sig, png_signature, sizeof sig) != 0)
        return sss_error_set(err, SSS_ERROR_PARSE, "%s: not a PNG file (%s)", path, got == 0 ? "empty" : "bad signature");
    uint32_t sw = 0, sh = 0;
    sss_result checked = png_check(f, path, size_only, &sw, &sh, err);
    if (checked != SSS_OK) return checked;
    if (size_only && sw > 0) {
        out->width = (int)sw;
        out->height = (int)sh;
        return SSS_OK;
    }
    rewind(f);
    int w = 0, h = 0, comp = 0;
    if (!stbi_info_from_file(f, &w, &h, &comp))
        return sss_error_set(err, SSS_ERROR_PARSE, "%s: malformed PNG header (%s)", path, stb_reason());
    sss_result r = check_size(path, w, h, err);
    if (r != SSS_OK) return r;
    if (size_only) {
        out->width = w;
        out->height = h;
        return SSS_OK;
    }
    /* Another part of a program may have asked stb to flip images globally; rows stay top first here. */
    stbi_set_flip_vertically_on_load_thread(0);
    int is16 = stbi_is_16_bit_from_file(f);
    void *data = is16 ? (void *)stbi_load_from_file_16(f, &w, &h, &comp, 3)
                      : (void *)stbi_load_from_file(f, &w, &h, &comp, 3);
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

typedef struct png_buffer {
    unsigned char *bytes;
    size_t size, cap;
    int failed;
} png_buffer;

static void write_to_buffer(void *context, void *data, int size)
{
    png_buffer *b = context;
    if (b->failed || size <= 0) return;
    if (b->size + (size_t)size > b->cap) {
        size_t cap = b->cap ? 2 * b->cap : 65536;
        while (cap < b->size + (size_t)size) cap *= 2;
        unsigned char *grown = realloc(b->bytes, cap);
        if (!grown) {
            b->failed = 1;
            return;
        }
        b->bytes = grown;
        b->cap = cap;
    }
    memcpy(b->bytes + b->size, data, (size_t)size);
    b->size += (size_t)size;
}

sss_result sss_image_encode_png(const sss_image *img, double exposure, unsigned char **bytes, size_t *size,
                                sss_error *err)
{
    *bytes = NULL;
    *size = 0;
    sss_result r = sss_image_check_writable_("PNG in memory", img, err);
    if (r != SSS_OK) return r;
    if ((double)(3.0 * img->width + 1.0) * img->height > INT_MAX / 2)
        return sss_error_set(err, SSS_ERROR_LIMIT, "%dx%d is too large for the PNG writer", img->width, img->height);
    uint8_t *rgb = malloc((size_t)img->width * (size_t)img->height * 3);
    png_buffer b = {0};
    if (rgb) {
        sss_image_to_srgb8(img, exposure, rgb);
        if (!stbi_write_png_to_func(write_to_buffer, &b, img->width, img->height, 3, rgb, img->width * 3)) b.failed = 1;
    }
    free(rgb);
    if (!rgb || b.failed) {
        free(b.bytes);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "PNG encoder: out of memory");
    }
    *bytes = b.bytes;
    *size = b.size;
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
