/* image/format_hdr.c — Radiance RGBE (.hdr) reader and writer.
 *
 * Own code rather than stb_image because stb reads past the end of a truncated file as zeros; this
 * reader reports truncation and malformed run-length data. Reads flat and "new" run-length encoded
 * scanlines with the resolution line "-Y H +X W" (top row first) or "+Y H +X W" (bottom row first);
 * FORMAT must be 32-bit_rle_rgbe when given (XYZE is rejected), EXPOSURE lines are ignored.
 * Decoding follows stb_image and Greg Ward's rgbe.c reader as used by OpenImageIO: value =
 * mantissa * 2^(exponent - 136), zero exponent = black. The writer rounds mantissas to nearest, so
 * those readers see no bias (error <= max channel / 256) and exactly representable values survive;
 * it writes flat (uncompressed) scanlines, which every reader accepts. RGBE cannot hold negative
 * values: the writer stores them as 0. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/file_util.h"
#include "image/image_internal.h"

#define HDR_LINE_MAX 4096
#define HDR_HEADER_LINES_MAX 4096

/* Reads one header line without its newline; returns 0 at end of file or on an overlong line. */
static int read_line(FILE *f, char *line, size_t cap, int *overlong)
{
    size_t n = 0;
    int c;
    *overlong = 0;
    while ((c = getc(f)) != EOF && c != '\n') {
        if (n + 1 >= cap) {
            *overlong = 1;
            return 0;
        }
        line[n++] = (char)c;
    }
    line[n] = '\0';
    return c == '\n'; /* a line cut short by the end of the file is a truncated header */
}

static void rgbe_to_float(const unsigned char rgbe[4], float *px)
{
    if (rgbe[3] == 0) {
        px[0] = px[1] = px[2] = 0.0f;
        return;
    }
    float f = ldexpf(1.0f, (int)rgbe[3] - 136);
    px[0] = rgbe[0] * f;
    px[1] = rgbe[1] * f;
    px[2] = rgbe[2] * f;
}

/* Decodes one scanline of width w into scan (w * 4 bytes, RGBE). Returns 0 on success, 1 on end of
 * file, 2 on corrupt run-length data, 3 on the old run-length scheme. */
static int read_scanline(FILE *f, int w, unsigned char *scan)
{
    if (w < 8 || w > 0x7fff) return fread(scan, 4, (size_t)w, f) == (size_t)w ? 0 : 1;
    unsigned char head[4];
    if (fread(head, 1, 4, f) != 4) return 1;
    if (head[0] != 2 || head[1] != 2 || (head[2] & 0x80)) {
        /* Flat scanline: the four bytes are its first pixel. */
        if (head[0] == 1 && head[1] == 1 && head[2] == 1) return 3;
        memcpy(scan, head, 4);
        return fread(scan + 4, 4, (size_t)w - 1, f) == (size_t)w - 1 ? 0 : 1;
    }
    if (((int)head[2] << 8 | head[3]) != w) return 2;
    /* New RLE: the four components one after another, each as runs (count > 128) or literals. */
    for (int k = 0; k < 4; k++) {
        int i = 0;
        while (i < w) {
            int count = getc(f);
            if (count == EOF) return 1;
            if (count > 128) {
                count -= 128;
                int value = getc(f);
                if (value == EOF) return 1;
                if (count > w - i) return 2;
                for (int j = 0; j < count; j++) scan[4 * (i++) + k] = (unsigned char)value;
            } else {
                if (count == 0 || count > w - i) return 2;
                for (int j = 0; j < count; j++) {
                    int value = getc(f);
                    if (value == EOF) return 1;
                    scan[4 * (i++) + k] = (unsigned char)value;
                }
            }
        }
    }
    return 0;
}

sss_result sss_hdr_read_(FILE *f, const char *path, int size_only, sss_image *out, sss_error *err)
{
    char line[HDR_LINE_MAX];
    int overlong = 0;
    sss_result r = SSS_OK;
    if (!read_line(f, line, sizeof line, &overlong) || strncmp(line, "#?", 2) != 0)
        return sss_error_set(err, SSS_ERROR_PARSE, "%s: not a Radiance HDR file (no '#?' signature)", path);
    /* Header variables up to an empty line. */
    for (int n = 0;; n++) {
        if (n >= HDR_HEADER_LINES_MAX || !read_line(f, line, sizeof line, &overlong))
            return sss_error_set(err, SSS_ERROR_PARSE, "%s: %s", path,
                                 overlong ? "header line too long" : "header has no end (truncated?)");
        if (line[0] == '\0') break;
        if (strncmp(line, "FORMAT=", 7) == 0 && strcmp(line + 7, "32-bit_rle_rgbe") != 0)
            return sss_error_set(err, SSS_ERROR_UNSUPPORTED, "%s: unsupported pixel format '%s' (only 32-bit_rle_rgbe)",
                                 path, line + 7);
    }
    if (!read_line(f, line, sizeof line, &overlong))
        return sss_error_set(err, SSS_ERROR_PARSE, "%s: missing resolution line", path);
    char ysign = 0, ychar = 0, xsign = 0, xchar = 0;
    long h = 0, w = 0;
    int used = 0;
    if (sscanf(line, "%c%c %ld %c%c %ld%n", &ysign, &ychar, &h, &xsign, &xchar, &w, &used) != 6 ||
        line[used] != '\0' || (ysign != '-' && ysign != '+') || (xsign != '-' && xsign != '+'))
        return sss_error_set(err, SSS_ERROR_PARSE, "%s: malformed resolution line '%.60s'", path, line);
    if (ychar != 'Y' || xchar != 'X' || xsign != '+')
        return sss_error_set(err, SSS_ERROR_UNSUPPORTED,
                             "%s: unsupported pixel order '%.60s' (only -Y H +X W and +Y H +X W)", path, line);
    r = sss_image_check_dims_(path, w, h, err);
    if (r != SSS_OK) return r;
    /* The smallest scanline the format allows: flat 4 bytes per pixel, or for run-length widths the
     * 4-byte marker and per component one 2-byte run per 127 pixels. Refuse a header that claims more
     * than the data can hold before allocating the image (12 bytes per pixel). */
    long long min_scan = w < 8 || w > 0x7fff ? 4LL * w : 4 + 8 * ((w + 126) / 127);
    long long have = sss_image_stream_remaining_(f);
    if (have >= 0 && have / h < min_scan)
        return sss_error_set(err, SSS_ERROR_PARSE, "%s: truncated: %lld bytes of pixel data cannot hold %ldx%ld pixels",
                             path, have, w, h);
    if (size_only) {
        out->width = (int)w;
        out->height = (int)h;
        return SSS_OK;
    }
    unsigned char *scan = malloc((size_t)w * 4);
    if (!scan) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    r = sss_image_create(out, (int)w, (int)h, err);
    if (r != SSS_OK) {
        free(scan);
        sss_error_prefix(err, path);
        return r;
    }
    for (long y = 0; y < h && r == SSS_OK; y++) {
        int status = read_scanline(f, (int)w, scan);
        if (status) {
            static const char *what[] = {"", "file is truncated", "corrupt run-length data",
                                         "old-style run-length encoding is not supported"};
            r = sss_error_set(err, status == 3 ? SSS_ERROR_UNSUPPORTED : SSS_ERROR_PARSE, "%s: scanline %ld: %s",
                              path, y, what[status]);
            break;
        }
        long row = ysign == '-' ? y : h - 1 - y;
        float *dst = out->pixels + (size_t)row * (size_t)w * 3;
        for (long x = 0; x < w; x++) rgbe_to_float(scan + 4 * x, dst + 3 * x);
    }
    free(scan);
    if (r != SSS_OK) sss_image_free(out);
    return r;
}

/* Rounds to nearest: mantissa m = round(c * 2^(8 - e)) with 2^(e-1) <= max < 2^e; a carry to 256
 * moves to the next exponent. */
static sss_result float_to_rgbe(const float *px, unsigned char rgbe[4])
{
    double c[3];
    for (int k = 0; k < 3; k++) c[k] = px[k] > 0.0f ? px[k] : 0.0;
    double m = c[0] > c[1] ? c[0] : c[1];
    if (c[2] > m) m = c[2];
    int e;
    frexp(m, &e);
    double scale = ldexp(1.0, 8 - e);
    if (m * scale + 0.5 >= 256.0) {
        e += 1;
        scale *= 0.5;
    }
    if (m == 0.0 || e + 128 < 1) { /* below the smallest RGBE value 2^-136 * 0.5 */
        memset(rgbe, 0, 4);
        return SSS_OK;
    }
    if (e + 128 > 255) return SSS_ERROR_LIMIT;
    for (int k = 0; k < 3; k++) rgbe[k] = (unsigned char)floor(c[k] * scale + 0.5);
    rgbe[3] = (unsigned char)(e + 128);
    return SSS_OK;
}

sss_result sss_hdr_write_(const char *path, const sss_image *img, sss_error *err)
{
    sss_result r = sss_image_check_writable_(path, img, err);
    if (r != SSS_OK) return r;
    char tmp[4096];
    FILE *f = sss_atomic_open(path, tmp, sizeof tmp, err);
    if (!f) return err ? err->code : SSS_ERROR_IO;
    fprintf(f, "#?RADIANCE\n# written by sss\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n", img->height, img->width);
    unsigned char *scan = malloc((size_t)img->width * 4);
    if (!scan) {
        fclose(f);
        sss_discard_temp(tmp);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    }
    for (int y = 0; y < img->height; y++) {
        const float *src = img->pixels + (size_t)y * (size_t)img->width * 3;
        for (int x = 0; x < img->width; x++) {
            if (float_to_rgbe(src + 3 * x, scan + 4 * x) != SSS_OK) {
                free(scan);
                fclose(f);
                sss_discard_temp(tmp);
                return sss_error_set(err, SSS_ERROR_LIMIT, "%s: pixel (%d, %d) is too bright for RGBE (> 2^127)",
                                     path, x, y);
            }
        }
        fwrite(scan, 4, (size_t)img->width, f);
    }
    free(scan);
    return sss_atomic_close(f, tmp, path, err);
}
