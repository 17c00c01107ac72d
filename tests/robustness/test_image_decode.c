/* sss_image_decode (from memory) against sss_image_read (from the file) on every test image, the fuzz
 * seeds and the malformed images of tests/data/bad: the same result code, the same message, bit-identical
 * pixels; and every prefix of a few valid files (truncation) refused alike. The two paths share the
 * format readers but not the I/O (fmemopen and OpenEXR's custom reader versus files). */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "sss/image.h"

static unsigned char *slurp(const char *path, size_t *size)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    unsigned char *b = malloc(n > 0 ? (size_t)n : 1);
    size_t got = b ? fread(b, 1, (size_t)n, f) : 0;
    fclose(f);
    if (!b || got != (size_t)n) {
        free(b);
        return NULL;
    }
    *size = (size_t)n;
    return b;
}

static int is_image(const char *name)
{
    const char *dot = strrchr(name, '.');
    return dot && (!strcmp(dot, ".png") || !strcmp(dot, ".hdr") || !strcmp(dot, ".pfm") || !strcmp(dot, ".exr") ||
                   !strcmp(dot, ".jpg"));
}

/* Read and decode agree on path, whose bytes are data[0..size). */
static void same_result(const char *path, const unsigned char *data, size_t size, const char *what)
{
    sss_image a = {0}, b = {0};
    sss_error ea = {0}, eb = {0};
    sss_result ra = sss_image_read(path, &a, &ea);
    sss_result rb = sss_image_decode(data, size, path, &b, &eb);
    CHECK_MSG(ra == rb, "%s: read %d (%s), decode %d (%s)", what, ra, ea.message, rb, eb.message);
    if (ra == SSS_OK && rb == SSS_OK) {
        CHECK_MSG(a.width == b.width && a.height == b.height, "%s: sizes differ", what);
        if (a.width == b.width && a.height == b.height)
            CHECK_MSG(memcmp(a.pixels, b.pixels, (size_t)a.width * a.height * 3 * sizeof(float)) == 0,
                      "%s: pixels differ", what);
    } else {
        CHECK_MSG(strcmp(ea.message, eb.message) == 0, "%s: messages differ:\n  read:   %s\n  decode: %s", what,
                  ea.message, eb.message);
        CHECK(b.pixels == NULL && b.width == 0 && b.height == 0);
    }
    sss_image_free(&a);
    sss_image_free(&b);
}

static int compare_dir(const char *dir)
{
    DIR *d = opendir(dir);
    CHECK_MSG(d != NULL, "cannot open %s", dir);
    if (!d) return 0;
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (!is_image(e->d_name)) continue;
        char path[2048];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        size_t size = 0;
        unsigned char *data = slurp(path, &size);
        CHECK_MSG(data != NULL, "cannot read %s", path);
        if (!data) continue;
        same_result(path, data, size, path);
        free(data);
        n++;
    }
    closedir(d);
    return n;
}

/* Every prefix of a valid file, written out and decoded from memory: both refuse it alike. */
static void truncations(const char *path)
{
    size_t size = 0;
    unsigned char *data = slurp(path, &size);
    CHECK_MSG(data != NULL, "cannot read %s", path);
    if (!data) return;
    const char *ext = strrchr(path, '.');
    char cut[256];
    snprintf(cut, sizeof cut, "test_image_decode_cut%s", ext);
    for (size_t len = 0; len < size; len += len < 256 ? 1 : 7) {
        FILE *f = fopen(cut, "wb");
        CHECK(f != NULL);
        if (!f) break;
        fwrite(data, 1, len, f);
        fclose(f);
        char what[512];
        snprintf(what, sizeof what, "%s cut to %zu bytes", path, len);
        same_result(cut, data, len, what);
    }
    remove(cut);
    free(data);
}

int main(void)
{
    int n = compare_dir(SSS_TEST_DATA "/images");
    n += compare_dir(SSS_TEST_DATA "/bad");
    const char *seeds[] = {"png", "hdr", "pfm", "exr", "jpg"};
    for (int i = 0; i < 5; i++) {
        char dir[1024];
        snprintf(dir, sizeof dir, "%s/fuzz/corpus/%s", SSS_SOURCE_DIR, seeds[i]);
        n += compare_dir(dir);
    }
    CHECK(n > 60);
    truncations(SSS_SOURCE_DIR "/fuzz/corpus/exr/tile_piz_float.exr");
    truncations(SSS_SOURCE_DIR "/fuzz/corpus/hdr/stb_rle_16x12.hdr");
    truncations(SSS_SOURCE_DIR "/fuzz/corpus/png/stb_4.png");
    truncations(SSS_SOURCE_DIR "/fuzz/corpus/pfm/rgb_be_3x2.pfm");

    /* Edge cases of the memory interface itself. */
    sss_image img = {0};
    sss_error err = {0};
    CHECK(sss_image_decode(NULL, 0, "empty.png", &img, &err) == SSS_ERROR_PARSE && strstr(err.message, "empty.png"));
    CHECK(sss_image_decode(NULL, 0, "empty.exr", &img, &err) == SSS_ERROR_PARSE && strstr(err.message, "empty.exr"));
    CHECK(sss_image_decode(NULL, 5, "x.png", &img, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(sss_image_decode("PF", 2, NULL, &img, &err) == SSS_ERROR_UNSUPPORTED && strstr(err.message, "image"));
    CHECK(sss_image_decode("PF", 2, "noext", &img, &err) == SSS_ERROR_UNSUPPORTED);
    CHECK(img.pixels == NULL);
    printf("compared %d files\n", n);
    return CHECK_DONE();
}
