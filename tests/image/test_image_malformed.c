/* Malformed image files: empty, not an image, truncated at every length, bad headers, zero and huge
 * sizes. Every one must fail with a message naming the file, without crashing or leaking (run
 * under ASan), and huge sizes must be refused before any large allocation. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stb_image_write.h>

#include "check.h"
#include "image_test_util.h"
#include "sss/image.h"

#define DATA SSS_TEST_DATA "/images/"

/* Reading path must fail with a message that names it (and, if code != SSS_OK, with that code). */
static void expect_failure(const char *path, sss_result code, const char *what)
{
    sss_image img = {0};
    sss_error err = {0};
    sss_result r = sss_image_read(path, &img, &err);
    CHECK_MSG(r != SSS_OK, "%s: read succeeded", what);
    if (code != SSS_OK) CHECK_MSG(r == code, "%s: code %d, expected %d (%s)", what, r, code, err.message);
    CHECK_MSG(strstr(err.message, path) != NULL, "%s: message does not name the file: %s", what, err.message);
    CHECK(img.pixels == NULL && img.width == 0);
    sss_image_free(&img);
}

/* Writes data[0..len) to path and expects reading it to fail. */
static void expect_bytes_fail(const char *path, const void *data, size_t len, sss_result code, const char *what)
{
    CHECK(spit(path, data, len));
    expect_failure(path, code, what);
}

/* Prefixes of a valid file (all but the last tail_ok bytes missing or more) must fail. */
static void truncations(const char *dir, const char *valid, const char *ext, size_t tail_ok)
{
    size_t size = 0;
    unsigned char *b = slurp(valid, &size);
    CHECK(b != NULL && size > tail_ok);
    if (!b) return;
    char path[256], what[128];
    snprintf(path, sizeof path, "%s/cut.%s", dir, ext);
    int failures = 0;
    /* Every length near the start (headers) and the end, a stride through the middle. */
    for (size_t len = 0; len + tail_ok < size; len = len < 2048 || len + 40 >= size ? len + 1 : len + 97) {
        snprintf(what, sizeof what, "%s cut to %zu of %zu bytes", valid, len, size);
        CHECK(spit(path, b, len));
        sss_image img = {0};
        sss_error err = {0};
        sss_result r = sss_image_read(path, &img, &err);
        if (r == SSS_OK || !strstr(err.message, path)) {
            failures++;
            if (failures < 4) CHECK_MSG(0, "%s: %s", what, r == SSS_OK ? "read succeeded" : err.message);
        }
        sss_image_free(&img);
    }
    CHECK_MSG(failures == 0, "%s: %d truncated copies accepted", valid, failures);
    remove(path);
    free(b);
}

static void write_to_file(void *context, void *data, int size) { fwrite(data, 1, (size_t)size, (FILE *)context); }

static void test_truncated(const char *dir)
{
    sss_image img = {0};
    CHECK(sss_image_create(&img, 13, 7, NULL) == SSS_OK);
    for (size_t i = 0; i < 13 * 7 * 3; i++) img.pixels[i] = (float)((i * 37) % 101) / 50.0f;
    const char *ext[] = {"png", "hdr", "pfm", "exr"};
    char path[256];
    for (int i = 0; i < 4; i++) {
        snprintf(path, sizeof path, "%s/valid.%s", dir, ext[i]);
        CHECK(sss_image_write(path, &img, 0.0, NULL) == SSS_OK);
        /* stb_image stops at the IEND chunk without reading its CRC: a PNG missing only those 4
         * bytes still has all its pixels and is accepted. */
        truncations(dir, path, ext[i], i == 0 ? 4 : 0);
        remove(path);
    }
    /* Files from the independent encoder of tools/ssim_reference.py, and a run-length encoded HDR
     * (our writer's are flat) from stb_image_write: */
    truncations(dir, DATA "asym_half.exr", "exr", 0);
    truncations(dir, DATA "tiled_rgba.exr", "exr", 0);
    truncations(dir, DATA "grey_be.pfm", "pfm", 0);
    truncations(dir, DATA "base.png", "png", 4);
    static float wide[40 * 9 * 3];
    for (size_t i = 0; i < sizeof wide / sizeof wide[0]; i++) wide[i] = (float)((i / 3) % 5) * 0.5f + (float)(i % 3);
    snprintf(path, sizeof path, "%s/rle.hdr", dir);
    FILE *f = fopen(path, "wb");
    CHECK(f && stbi_write_hdr_to_func(write_to_file, f, 40, 9, 3, wide));
    if (f) fclose(f);
    truncations(dir, path, "hdr", 0);
    sss_image_free(&img);
}

static void test_not_images(const char *dir)
{
    const char *ext[] = {"png", "hdr", "pfm", "exr"};
    char path[256];
    for (int i = 0; i < 4; i++) {
        snprintf(path, sizeof path, "%s/empty.%s", dir, ext[i]);
        expect_bytes_fail(path, "", 0, SSS_ERROR_PARSE, "empty file");
        snprintf(path, sizeof path, "%s/text.%s", dir, ext[i]);
        const char *text = "this is not an image at all, just some text\n";
        expect_bytes_fail(path, text, strlen(text), SSS_ERROR_PARSE, "text file");
        snprintf(path, sizeof path, "%s/missing.%s", dir, ext[i]);
        expect_failure(path, SSS_ERROR_IO, "missing file");
        /* A folder is not an image either. */
        expect_failure(dir, SSS_OK, "folder");
    }
    /* A real file of another format under a wrong extension. */
    expect_failure(DATA "formats_reference.txt", SSS_ERROR_UNSUPPORTED, "unknown extension");
    size_t size = 0;
    unsigned char *png = slurp(DATA "base.png", &size);
    snprintf(path, sizeof path, "%s/png_in_disguise.exr", dir);
    expect_bytes_fail(path, png, size, SSS_ERROR_PARSE, "PNG named .exr");
    snprintf(path, sizeof path, "%s/png_in_disguise.pfm", dir);
    expect_bytes_fail(path, png, size, SSS_ERROR_PARSE, "PNG named .pfm");
    free(png);
}

static void test_pfm_headers(const char *dir)
{
    char path[256];
    snprintf(path, sizeof path, "%s/h.pfm", dir);
    static const struct {
        const char *bytes;
        sss_result code;
    } cases[] = {
        {"PX\n3 2\n-1\n", SSS_ERROR_PARSE},
        {"PF\n-3 2\n-1\n", SSS_ERROR_PARSE},
        {"PF\n0 2\n-1\n", SSS_ERROR_PARSE},
        {"PF\n3 0\n-1\n", SSS_ERROR_PARSE},
        {"PF\n3 2\n0\n", SSS_ERROR_PARSE},
        {"PF\n3 2\nabc\n", SSS_ERROR_PARSE},
        {"PF\n3 2\nnan\n", SSS_ERROR_PARSE},
        {"PF\n3x 2\n-1\n", SSS_ERROR_PARSE},
        {"PF\n3 2\n", SSS_ERROR_PARSE},
        {"PF\n3", SSS_ERROR_PARSE},
        {"PF\n40000 2\n-1\n", SSS_ERROR_LIMIT},
        {"PF\n99999999999999999999 2\n-1\n", SSS_ERROR_PARSE},
        /* Within the size limit but nearly 11 GB of floats missing: refused before allocating. */
        {"PF\n30000 30000\n-1\n", SSS_ERROR_PARSE},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
        expect_bytes_fail(path, cases[i].bytes, strlen(cases[i].bytes), cases[i].code, cases[i].bytes);
}

static void test_hdr_headers(const char *dir)
{
    char path[256];
    snprintf(path, sizeof path, "%s/h.hdr", dir);
    static const struct {
        const char *bytes;
        sss_result code;
    } cases[] = {
        {"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n", SSS_ERROR_PARSE},                        /* no blank line */
        {"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n", SSS_ERROR_PARSE},                      /* no size */
        {"#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n-Y 1 +X 1\nabcd", SSS_ERROR_UNSUPPORTED},
        {"#?RADIANCE\n\n-Y 0 +X 4\n", SSS_ERROR_PARSE},
        {"#?RADIANCE\n\n-Y 2 +X -4\n", SSS_ERROR_PARSE},
        {"#?RADIANCE\n\n-Y 2 +X 100000\n", SSS_ERROR_LIMIT},
        {"#?RADIANCE\n\n+X 2 -Y 2\n", SSS_ERROR_UNSUPPORTED},
        {"#?RADIANCE\n\n-Y 2 -X 2\n", SSS_ERROR_UNSUPPORTED},
        {"#?RADIANCE\n\n-Y two +X 2\n", SSS_ERROR_PARSE},
        {"#?RADIANCE\n\n-Y 1 +X 1\nab", SSS_ERROR_PARSE},                              /* truncated */
        {"#?RADIANCE\n\n-Y 30000 +X 30000\n", SSS_ERROR_PARSE},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
        expect_bytes_fail(path, cases[i].bytes, strlen(cases[i].bytes), cases[i].code, cases[i].bytes);
    /* Run-length data: width 8, "2 2 0 8" then runs; a run longer than the line is corrupt. */
    const char head[] = "#?RADIANCE\n\n-Y 1 +X 8\n";
    unsigned char buf[64];
    size_t n = strlen(head);
    memcpy(buf, head, n);
    const unsigned char bad_run[] = {2, 2, 0, 8, 128 + 9, 7};
    memcpy(buf + n, bad_run, sizeof bad_run);
    expect_bytes_fail(path, buf, n + sizeof bad_run, SSS_ERROR_PARSE, "RLE run too long");
    const unsigned char zero_literal[] = {2, 2, 0, 8, 0};
    memcpy(buf + n, zero_literal, sizeof zero_literal);
    expect_bytes_fail(path, buf, n + sizeof zero_literal, SSS_ERROR_PARSE, "RLE zero count");
    const unsigned char wrong_len[] = {2, 2, 0, 9, 128 + 8, 1};
    memcpy(buf + n, wrong_len, sizeof wrong_len);
    expect_bytes_fail(path, buf, n + sizeof wrong_len, SSS_ERROR_PARSE, "RLE length mismatch");
    /* A complete run-length line: R runs 8 x 64, G literals, B run, E run 129 -> known values. */
    const unsigned char good[] = {2, 2, 0, 8, 128 + 8, 64, 8, 0, 16, 32, 48, 64, 80, 96, 112,
                                  128 + 8, 128, 128 + 8, 129};
    memcpy(buf + n, good, sizeof good);
    CHECK(spit(path, buf, n + sizeof good));
    sss_image img = {0};
    sss_error err = {0};
    CHECK_MSG(sss_image_read(path, &img, &err) == SSS_OK, "%s", err.message);
    if (img.pixels) {
        CHECK(img.width == 8 && img.height == 1);
        for (int x = 0; x < 8; x++) {
            /* value = mantissa * 2^(129 - 136) */
            CHECK(img.pixels[3 * x] == 64.0f / 128.0f);
            CHECK(img.pixels[3 * x + 1] == (float)(16 * x) / 128.0f);
            CHECK(img.pixels[3 * x + 2] == 1.0f);
        }
    }
    sss_image_free(&img);
    /* Bottom-up files ("+Y") are flipped into top-first order. */
    const char up[] = "#?RADIANCE\n\n+Y 2 +X 1\n";
    n = strlen(up);
    memcpy(buf, up, n);
    const unsigned char two[] = {128, 128, 128, 129, 128, 128, 128, 130}; /* bottom 1.0, top 2.0 */
    memcpy(buf + n, two, sizeof two);
    CHECK(spit(path, buf, n + sizeof two));
    CHECK(sss_image_read(path, &img, &err) == SSS_OK);
    if (img.pixels) CHECK(img.pixels[0] == 2.0f && img.pixels[3] == 1.0f);
    sss_image_free(&img);
}

/* CRC-32 as the PNG specification's Annex D computes it, bit by bit. */
static uint32_t png_crc(const unsigned char *p, size_t n)
{
    uint32_t c = 0xffffffffu;
    for (size_t i = 0; i < n; i++) {
        c ^= p[i];
        for (int k = 0; k < 8; k++) c = c & 1 ? 0xedb88320u ^ (c >> 1) : c >> 1;
    }
    return c ^ 0xffffffffu;
}

/* A PNG header alone (IHDR with its CRC), with a chosen size. */
static size_t png_header(unsigned char *b, uint32_t w, uint32_t h)
{
    static const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    memcpy(b, sig, 8);
    unsigned char ihdr[25] = {0, 0, 0, 13, 'I', 'H', 'D', 'R'};
    for (int i = 0; i < 4; i++) {
        ihdr[8 + i] = (unsigned char)(w >> (24 - 8 * i));
        ihdr[12 + i] = (unsigned char)(h >> (24 - 8 * i));
    }
    ihdr[16] = 8; /* bit depth */
    ihdr[17] = 2; /* RGB */
    uint32_t crc = png_crc(ihdr + 4, 17);
    for (int i = 0; i < 4; i++) ihdr[21 + i] = (unsigned char)(crc >> (24 - 8 * i));
    memcpy(b + 8, ihdr, sizeof ihdr);
    return 8 + sizeof ihdr;
}

static void test_png_sizes(const char *dir)
{
    char path[256];
    unsigned char b[64];
    snprintf(path, sizeof path, "%s/h.png", dir);
    expect_bytes_fail(path, b, png_header(b, 40000, 10), SSS_ERROR_LIMIT, "PNG too wide");
    expect_bytes_fail(path, b, png_header(b, 10, 0), SSS_ERROR_PARSE, "PNG zero height");
    /* Within the pixel budget of 2^27 (11585^2 = 134,212,225) a header without data is refused as
     * such; one pixel row beyond it (11585 x 11586 = 134,223,810) by the budget, before any data. */
    expect_bytes_fail(path, b, png_header(b, 11585, 11585), SSS_ERROR_PARSE, "PNG without data");
    expect_bytes_fail(path, b, png_header(b, 11585, 11586), SSS_ERROR_LIMIT, "PNG beyond the pixel budget");
    expect_bytes_fail(path, b, png_header(b, 16384, 16384), SSS_ERROR_LIMIT, "PNG of 16384^2");
}

/* JPEG: a frame header beyond the limits is refused before decoding; a cut file fails. */
static void test_jpeg(const char *dir)
{
    size_t size = 0;
    unsigned char *b = slurp(SSS_TEST_DATA "/images/two_colours.jpg", &size);
    CHECK(b != NULL && size > 200);
    if (!b) return;
    char path[256];
    snprintf(path, sizeof path, "%s/j.jpg", dir);
    size_t sof = 2;
    while (sof + 9 < size && !(b[sof] == 0xFF && (b[sof + 1] == 0xC0 || b[sof + 1] == 0xC2))) sof++;
    CHECK(sof + 9 < size);
    if (sof + 9 < size) { /* SOF: FF Cn, length(2), precision(1), height(2), width(2) */
        b[sof + 5] = 0x80, b[sof + 6] = 0x00, b[sof + 7] = 0x80, b[sof + 8] = 0x00; /* 32768 x 32768 */
        expect_bytes_fail(path, b, size, SSS_ERROR_LIMIT, "JPEG beyond the pixel budget");
        b[sof + 5] = 0x00, b[sof + 6] = 0x00; /* height 0 */
        expect_bytes_fail(path, b, size, SSS_OK, "JPEG of height 0");
    }
    expect_bytes_fail(path, "\xFF\xD8\xFF\xE0", 4, SSS_OK, "JPEG of 4 bytes");
    expect_bytes_fail(path, "GIF89a", 6, SSS_ERROR_PARSE, "GIF named .jpg");
    free(b);
    truncations(dir, SSS_TEST_DATA "/images/two_colours.jpg", "jpg", 0);
}

/* A valid PNG with one bit of a stored chunk CRC flipped (stb_image decodes it regardless). */
static void test_png_crc(const char *dir)
{
    size_t size = 0;
    unsigned char *b = slurp(DATA "base.png", &size);
    CHECK(b != NULL && size > 64);
    if (!b) return;
    char path[256];
    snprintf(path, sizeof path, "%s/crc.png", dir);
    b[32] ^= 1; /* the last byte of IHDR's CRC: signature 8, length and type 8, data 13 */
    expect_bytes_fail(path, b, size, SSS_ERROR_PARSE, "PNG with a bad IHDR CRC");
    b[32] ^= 1;
    unsigned char *idat = NULL;
    for (size_t i = 33; i + 4 <= size && !idat; i++)
        if (memcmp(b + i, "IDAT", 4) == 0) idat = b + i;
    CHECK(idat != NULL);
    if (idat) {
        size_t len = (size_t)idat[-4] << 24 | (size_t)idat[-3] << 16 | (size_t)idat[-2] << 8 | idat[-1];
        CHECK((size_t)(idat - b) + 8 + len <= size);
        idat[4 + len] ^= 0x80; /* the first byte of its CRC */
        expect_bytes_fail(path, b, size, SSS_ERROR_PARSE, "PNG with a bad IDAT CRC");
    }
    free(b);
}

/* OpenEXR with its data window patched: too large, empty. */
static void test_exr_sizes(const char *dir)
{
    size_t size = 0;
    unsigned char *b = slurp(DATA "asym_half.exr", &size);
    CHECK(b != NULL);
    if (!b) return;
    const char key[] = "dataWindow\0box2i";
    unsigned char *at = NULL;
    for (size_t i = 0; i + sizeof key < size && !at; i++)
        if (memcmp(b + i, key, sizeof key) == 0) at = b + i + sizeof key + 4; /* skip the size field */
    CHECK(at != NULL);
    if (!at) {
        free(b);
        return;
    }
    char path[256];
    snprintf(path, sizeof path, "%s/win.exr", dir);
    unsigned char saved[16];
    memcpy(saved, at, 16);
    /* max.x = 40000 -> 40001 pixels wide */
    at[8] = 0x40, at[9] = 0x9c, at[10] = 0, at[11] = 0;
    expect_bytes_fail(path, b, size, SSS_OK, "EXR too wide");
    memcpy(at, saved, 16);
    /* max.y = -5 < min.y = 0 */
    at[12] = 0xfb, at[13] = 0xff, at[14] = 0xff, at[15] = 0xff;
    expect_bytes_fail(path, b, size, SSS_OK, "EXR empty data window");
    memcpy(at, saved, 16);
    /* Corrupt the channel list's pixel type of the first channel (7 is no type). */
    const char chl[] = "channels\0chlist";
    for (size_t i = 0; i + sizeof chl < size; i++)
        if (memcmp(b + i, chl, sizeof chl) == 0) {
            unsigned char *t = b + i + sizeof chl + 4 + 2; /* size field, then "B\0" */
            t[0] = 7;
            break;
        }
    expect_bytes_fail(path, b, size, SSS_OK, "EXR bad pixel type");
    free(b);
}

/* Channels we cannot use are rejected by name. */
static void test_exr_channels(const char *dir)
{
    size_t size = 0;
    unsigned char *b = slurp(DATA "grey_y.exr", &size);
    CHECK(b != NULL);
    if (!b) return;
    /* Rename the lone channel "Y" to "Z": no R, G, B or Y left. */
    const char chl[] = "channels\0chlist";
    for (size_t i = 0; i + sizeof chl < size; i++)
        if (memcmp(b + i, chl, sizeof chl) == 0) {
            b[i + sizeof chl + 4] = 'Z';
            break;
        }
    char path[256];
    snprintf(path, sizeof path, "%s/z.exr", dir);
    CHECK(spit(path, b, size));
    sss_image img = {0};
    sss_error err = {0};
    CHECK(sss_image_read(path, &img, &err) == SSS_ERROR_UNSUPPORTED);
    CHECK_MSG(strstr(err.message, path) && strstr(err.message, "found: Z"), "%s", err.message);
    free(b);
}

int main(void)
{
    char dir[64];
    CHECK(make_temp_dir(dir, sizeof dir));
    test_truncated(dir);
    test_not_images(dir);
    test_pfm_headers(dir);
    test_hdr_headers(dir);
    test_png_sizes(dir);
    test_png_crc(dir);
    test_jpeg(dir);
    test_exr_sizes(dir);
    test_exr_channels(dir);
    remove_dir(dir);
    return CHECK_DONE();
}
