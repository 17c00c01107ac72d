/* image/format_pfm.c — Portable Float Map reader and writer.
 *
 * Format: "PF" (RGB) or "Pf" (grey), whitespace, width, height, scale, one whitespace byte, then
 * 32-bit floats row by row from the BOTTOM row up; scale < 0 means little-endian, > 0 big-endian.
 * Like PBRT-v3's ReadImagePFM, samples are multiplied by |scale| when it is not 1. Grey is replicated
 * to RGB. The writer emits "PF", little-endian, scale -1. */
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "core/file_util.h"
#include "image/image_internal.h"

static int is_space(int c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

/* Reads a whitespace-delimited token and the single whitespace byte that ends it. Returns 0 on end
 * of file or a token longer than cap - 1. */
static int read_token(FILE *f, char *tok, size_t cap)
{
    int c;
    do c = getc(f);
    while (c != EOF && is_space(c));
    size_t n = 0;
    while (c != EOF && !is_space(c)) {
        if (n + 1 >= cap) return 0;
        tok[n++] = (char)c;
        c = getc(f);
    }
    tok[n] = '\0';
    return n > 0 && c != EOF;
}

static int parse_int(const char *s, long *out)
{
    char *end = NULL;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (end == s || *end != '\0' || errno == ERANGE) return 0;
    *out = v;
    return 1;
}

sss_result sss_pfm_read_(FILE *f, const char *path, int size_only, sss_image *out, sss_error *err)
{
    char magic[4], tw[32], th[32], ts[64];
    long w = 0, h = 0;
    sss_result r = SSS_OK;
    if (!read_token(f, magic, sizeof magic) || (strcmp(magic, "PF") != 0 && strcmp(magic, "Pf") != 0))
        return sss_error_set(err, SSS_ERROR_PARSE, "%s: not a PFM file (expected 'PF' or 'Pf')", path);
    int channels = magic[1] == 'F' ? 3 : 1;
    if (!read_token(f, tw, sizeof tw) || !read_token(f, th, sizeof th) || !read_token(f, ts, sizeof ts))
        return sss_error_set(err, SSS_ERROR_PARSE, "%s: incomplete PFM header", path);
    char *end = NULL;
    double scale = strtod(ts, &end);
    if (!parse_int(tw, &w) || !parse_int(th, &h) || end == ts || *end != '\0' || !isfinite(scale) ||
        scale == 0.0)
        return sss_error_set(err, SSS_ERROR_PARSE, "%s: malformed PFM header '%s %s %s %s'", path, magic, tw, th, ts);
    r = sss_image_check_dims_(path, w, h, err);
    if (r != SSS_OK) return r;
    /* Check the data is all there before allocating the image. */
    size_t row_bytes = (size_t)w * (size_t)channels * 4, need = row_bytes * (size_t)h;
    long long have = sss_image_stream_remaining_(f);
    if (have >= 0 && (uint64_t)have < (uint64_t)need)
        return sss_error_set(err, SSS_ERROR_PARSE, "%s: truncated: %lld bytes of pixel data for %ldx%ld, expected %zu",
                             path, have, w, h, need);
    if (size_only) {
        out->width = (int)w;
        out->height = (int)h;
        return SSS_OK;
    }
    unsigned char *row = malloc(row_bytes);
    if (!row) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    r = sss_image_create(out, (int)w, (int)h, err);
    if (r != SSS_OK) {
        free(row);
        sss_error_prefix(err, path);
        return r;
    }
    int little = scale < 0.0;
    float mult = (float)fabs(scale);
    for (long y = 0; y < h; y++) {
        if (fread(row, 1, row_bytes, f) != row_bytes) {
            r = sss_error_set(err, SSS_ERROR_PARSE, "%s: truncated at row %ld of %ld", path, y, h);
            break;
        }
        float *dst = out->pixels + (size_t)(h - 1 - y) * (size_t)w * 3; /* rows are stored bottom first */
        for (long x = 0; x < w; x++) {
            for (int c = 0; c < channels; c++) {
                const unsigned char *b = row + 4 * (x * channels + c);
                uint32_t u = little ? (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24
                                    : (uint32_t)b[3] | (uint32_t)b[2] << 8 | (uint32_t)b[1] << 16 | (uint32_t)b[0] << 24;
                float v;
                memcpy(&v, &u, sizeof v);
                if (mult != 1.0f) v *= mult;
                if (channels == 3) dst[3 * x + c] = v;
                else dst[3 * x] = dst[3 * x + 1] = dst[3 * x + 2] = v;
            }
        }
    }
    free(row);
    if (r != SSS_OK) sss_image_free(out);
    return r;
}

sss_result sss_pfm_write_(const char *path, const sss_image *img, sss_error *err)
{
    sss_result r = sss_image_check_writable_(path, img, err);
    if (r != SSS_OK) return r;
    size_t row_bytes = (size_t)img->width * 12;
    unsigned char *row = malloc(row_bytes);
    if (!row) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    char tmp[4096];
    FILE *f = sss_atomic_open(path, tmp, sizeof tmp, err);
    if (!f) {
        free(row);
        return err ? err->code : SSS_ERROR_IO;
    }
    fprintf(f, "PF\n%d %d\n-1\n", img->width, img->height);
    for (int y = img->height - 1; y >= 0; y--) {
        const float *src = img->pixels + (size_t)y * (size_t)img->width * 3;
        for (size_t i = 0; i < (size_t)img->width * 3; i++) {
            uint32_t u;
            memcpy(&u, &src[i], sizeof u);
            row[4 * i] = (unsigned char)u;
            row[4 * i + 1] = (unsigned char)(u >> 8);
            row[4 * i + 2] = (unsigned char)(u >> 16);
            row[4 * i + 3] = (unsigned char)(u >> 24);
        }
        fwrite(row, 1, row_bytes, f);
    }
    free(row);
    return sss_atomic_close(f, tmp, path, err);
}
