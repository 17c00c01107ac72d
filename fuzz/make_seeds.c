/* fuzz/make_seeds.c — writes the generated part of the seed corpora into fuzz/corpus/<target>/:
 * OpenEXR in every compression (scanline and tiled, half and float; OpenEXRCore is not instrumented,
 * so seeds are how the fuzzer reaches each decompressor), Radiance HDR flat and run-length, PNG in
 * every colour type, PFM in both byte orders, binary PLY in both byte orders. Small files only.
 * Built with the fuzz targets (fuzz_make_seeds); run as  fuzz_make_seeds <repo>/fuzz/corpus  and commit. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <openexr.h>
#include <stb_image_write.h>

#include "sss/image.h"
#include "sss/mesh.h"

static const char *root;
static int failures;

static void path_of(char *out, size_t cap, const char *target, const char *name)
{
    snprintf(out, cap, "%s/%s/%s", root, target, name);
}

static void spit(const char *target, const char *name, const void *data, size_t size)
{
    char p[1024];
    path_of(p, sizeof p, target, name);
    FILE *f = fopen(p, "wb");
    if (!f || fwrite(data, 1, size, f) != size || fclose(f) != 0) {
        fprintf(stderr, "cannot write %s\n", p);
        failures++;
    }
}

/* Exactly representable as half: multiples of 1/64 below 4. */
static float sample(int x, int y, int c) { return (float)((x * 7 + y * 3 + c * 11) % 256) / 64.0f; }

static uint16_t to_half(float f)
{
    /* Only for the values of sample(): positive, normal, exact in 10 bits. */
    if (f == 0.0f) return 0;
    int e;
    float m = frexpf(f, &e); /* f = m 2^e, m in [0.5, 1) */
    return (uint16_t)((e - 1 + 15) << 10 | (uint16_t)lrintf((2.0f * m - 1.0f) * 1024.0f));
}

static void exr_seed(const char *name, exr_compression_t comp, int tiled, int half, int w, int h, int grey)
{
    char p[1024];
    path_of(p, sizeof p, "exr", name);
    int nch = grey ? 1 : 3;
    static const char *rgb[3] = {"B", "G", "R"}, *y_name[1] = {"Y"};
    const char **names = grey ? y_name : rgb;
    size_t bytes = half ? 2 : 4;
    unsigned char *plane[3];
    for (int c = 0; c < nch; c++) {
        plane[c] = malloc((size_t)w * h * bytes);
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++) {
                float v = sample(x, y, c);
                if (half) ((uint16_t *)plane[c])[y * w + x] = to_half(v);
                else ((float *)plane[c])[y * w + x] = v;
            }
    }
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    exr_context_t ctx = NULL;
    int part = 0;
    exr_pixel_type_t type = half ? EXR_PIXEL_HALF : EXR_PIXEL_FLOAT;
    exr_result_t rv = exr_start_write(&ctx, p, EXR_WRITE_FILE_DIRECTLY, &init);
    if (!rv) rv = exr_add_part(ctx, NULL, tiled ? EXR_STORAGE_TILED : EXR_STORAGE_SCANLINE, &part);
    if (!rv) rv = exr_initialize_required_attr_simple(ctx, part, w, h, comp);
    if (!rv && tiled) rv = exr_set_tile_descriptor(ctx, part, 8, 8, EXR_TILE_ONE_LEVEL, EXR_TILE_ROUND_DOWN);
    for (int c = 0; c < nch && !rv; c++) rv = exr_add_channel(ctx, part, names[c], type, EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1);
    if (!rv) rv = exr_write_header(ctx);
    exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
    int have_enc = 0;
    int32_t lines = 0;
    if (!rv && !tiled) rv = exr_get_scanlines_per_chunk(ctx, part, &lines);
    int nx = tiled ? (w + 7) / 8 : 1, ny = tiled ? (h + 7) / 8 : (lines > 0 ? (h + lines - 1) / lines : 0);
    for (int ty = 0; ty < ny && !rv; ty++)
        for (int tx = 0; tx < nx && !rv; tx++) {
            exr_chunk_info_t ci;
            rv = tiled ? exr_write_tile_chunk_info(ctx, part, tx, ty, 0, 0, &ci)
                       : exr_write_scanline_chunk_info(ctx, part, ty * lines, &ci);
            if (rv) break;
            rv = have_enc ? exr_encoding_update(ctx, part, &ci, &enc) : exr_encoding_initialize(ctx, part, &ci, &enc);
            if (rv) break;
            for (int i = 0; i < enc.channel_count; i++) {
                exr_coding_channel_info_t *ch = &enc.channels[i];
                int k = 0;
                for (int c = 0; c < nch; c++)
                    if (strcmp(ch->channel_name, names[c]) == 0) k = c;
                size_t at = ((size_t)ci.start_y * w + (size_t)ci.start_x) * bytes;
                ch->encode_from_ptr = plane[k] + at;
                ch->user_bytes_per_element = (int16_t)bytes;
                ch->user_data_type = (uint16_t)type;
                ch->user_pixel_stride = (int32_t)bytes;
                ch->user_line_stride = (int32_t)(w * bytes);
            }
            if (!have_enc) {
                have_enc = 1;
                rv = exr_encoding_choose_default_routines(ctx, part, &enc);
                if (rv) break;
            }
            rv = exr_encoding_run(ctx, part, &enc);
        }
    if (have_enc) exr_encoding_destroy(ctx, &enc);
    exr_result_t fin = ctx ? exr_finish(&ctx) : 0;
    for (int c = 0; c < nch; c++) free(plane[c]);
    if (rv || fin) {
        fprintf(stderr, "%s: %s\n", p, exr_get_default_error_message(rv ? rv : fin));
        remove(p);
        failures++;
        return;
    }
    /* The seed must be readable, or it teaches the fuzzer nothing beyond the header. */
    sss_image img;
    sss_error err;
    if (sss_image_read(p, &img, &err) != SSS_OK) {
        fprintf(stderr, "%s: written but not readable: %s\n", p, err.message);
        failures++;
    }
    sss_image_free(&img);
}

static void exr_seeds(void)
{
    static const struct {
        const char *tag;
        exr_compression_t comp;
    } comps[] = {{"none", EXR_COMPRESSION_NONE}, {"rle", EXR_COMPRESSION_RLE},     {"zips", EXR_COMPRESSION_ZIPS},
                 {"zip", EXR_COMPRESSION_ZIP},   {"piz", EXR_COMPRESSION_PIZ},     {"pxr24", EXR_COMPRESSION_PXR24},
                 {"b44", EXR_COMPRESSION_B44},   {"b44a", EXR_COMPRESSION_B44A}};
    /* DWAA/DWAB: OpenEXRCore 3.1 cannot write (or read) them. */
    char name[64];
    for (size_t i = 0; i < sizeof comps / sizeof comps[0]; i++) {
        snprintf(name, sizeof name, "scan_%s_half.exr", comps[i].tag);
        exr_seed(name, comps[i].comp, 0, 1, 13, 9, 0);
        snprintf(name, sizeof name, "tile_%s_float.exr", comps[i].tag);
        exr_seed(name, comps[i].comp, 1, 0, 11, 10, 0);
    }
    exr_seed("scan_zip_grey_float.exr", EXR_COMPRESSION_ZIP, 0, 0, 6, 5, 1);
}

static void stb_seeds(void)
{
    unsigned char px[16 * 12 * 4];
    float fx[16 * 12 * 3];
    for (int i = 0; i < 16 * 12 * 4; i++) px[i] = (unsigned char)(i * 37 % 251);
    for (int i = 0; i < 16 * 12 * 3; i++) fx[i] = (float)(i % 17) / 4.0f + (i % 5 ? 0.0f : 300.0f);
    char p[1024], name[64];
    for (int comp = 1; comp <= 4; comp++) {
        snprintf(name, sizeof name, "stb_%d.png", comp);
        path_of(p, sizeof p, "png", name);
        if (!stbi_write_png(p, 9, 7, comp, px, 9 * comp)) failures++;
    }
    /* stb writes run-length scanlines for widths 8..32767 and flat ones otherwise. */
    path_of(p, sizeof p, "hdr", "stb_rle_16x12.hdr");
    if (!stbi_write_hdr(p, 16, 12, 3, fx)) failures++;
    path_of(p, sizeof p, "hdr", "stb_flat_5x4.hdr");
    if (!stbi_write_hdr(p, 5, 4, 3, fx)) failures++;
}

static void pfm_seeds(void)
{
    /* "PF" big-endian and "Pf" little-endian (the sss writer makes "PF" little-endian). */
    const char *hdr_be = "PF\n3 2\n1.0\n";
    unsigned char buf[64 + 3 * 2 * 12];
    size_t n = strlen(hdr_be);
    memcpy(buf, hdr_be, n);
    for (int i = 0; i < 18; i++) {
        float v = (float)i / 8.0f;
        uint32_t u;
        memcpy(&u, &v, 4);
        buf[n++] = (unsigned char)(u >> 24);
        buf[n++] = (unsigned char)(u >> 16);
        buf[n++] = (unsigned char)(u >> 8);
        buf[n++] = (unsigned char)u;
    }
    spit("pfm", "rgb_be_3x2.pfm", buf, n);
    const char *hdr_le = "Pf\n2 3\n-0.5\n";
    n = strlen(hdr_le);
    memcpy(buf, hdr_le, n);
    for (int i = 0; i < 6; i++) {
        float v = (float)i * 3.0f;
        memcpy(buf + n, &v, 4);
        n += 4;
    }
    spit("pfm", "grey_le_2x3.pfm", buf, n);
}

static void sss_written_seeds(void)
{
    sss_image img;
    char p[1024];
    if (sss_image_create(&img, 12, 11, NULL) != SSS_OK) {
        failures++;
        return;
    }
    for (int i = 0; i < 12 * 11 * 3; i++) img.pixels[i] = sample(i % 12, i / 36, i % 3);
    path_of(p, sizeof p, "pfm", "sss_12x11.pfm");
    failures += sss_image_write(p, &img, 0.0, NULL) != SSS_OK;
    path_of(p, sizeof p, "hdr", "sss_flat_12x11.hdr");
    failures += sss_image_write(p, &img, 0.0, NULL) != SSS_OK;
    path_of(p, sizeof p, "png", "sss_12x11.png");
    failures += sss_image_write(p, &img, 0.0, NULL) != SSS_OK;
    path_of(p, sizeof p, "exr", "sss_zip_12x11.exr");
    failures += sss_image_write(p, &img, 0.0, NULL) != SSS_OK;
    sss_image_free(&img);

    sss_mesh m;
    if (sss_mesh_sphere(1.0, 0, &m, NULL) != SSS_OK) {
        failures++;
        return;
    }
    path_of(p, sizeof p, "ply", "sphere0_binary_le.ply");
    failures += sss_mesh_write_ply(p, &m, NULL) != SSS_OK;
    sss_mesh_free(&m);
    if (sss_mesh_plane(2.0, &m, NULL) != SSS_OK) {
        failures++;
        return;
    }
    path_of(p, sizeof p, "ply", "plane_uv_binary_le.ply");
    failures += sss_mesh_write_ply(p, &m, NULL) != SSS_OK;
    sss_mesh_free(&m);
}

/* A big-endian PLY with a uchar/int face list, a double coordinate and an extra property. */
static void ply_be_seed(void)
{
    const char *head = "ply\nformat binary_big_endian 1.0\ncomment seed\nelement vertex 4\n"
                       "property float x\nproperty float y\nproperty double z\nproperty uchar red\n"
                       "element face 2\nproperty list uchar int vertex_indices\nend_header\n";
    unsigned char buf[512];
    size_t n = strlen(head);
    memcpy(buf, head, n);
    static const float xy[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int v = 0; v < 4; v++) {
        for (int k = 0; k < 2; k++) {
            uint32_t u;
            memcpy(&u, &xy[v][k], 4);
            for (int b = 3; b >= 0; b--) buf[n++] = (unsigned char)(u >> (8 * b));
        }
        double z = 0.5 * v;
        uint64_t u;
        memcpy(&u, &z, 8);
        for (int b = 7; b >= 0; b--) buf[n++] = (unsigned char)(u >> (8 * b));
        buf[n++] = (unsigned char)(v * 60);
    }
    static const int faces[2][3] = {{0, 1, 2}, {0, 2, 3}};
    for (int f = 0; f < 2; f++) {
        buf[n++] = 3;
        for (int k = 0; k < 3; k++)
            for (int b = 3; b >= 0; b--) buf[n++] = (unsigned char)((uint32_t)faces[f][k] >> (8 * b));
    }
    spit("ply", "quad_binary_be.ply", buf, n);
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: fuzz_make_seeds CORPUS_DIR (the folders exr, hdr, png, pfm, ply must exist)\n");
        return 2;
    }
    root = argv[1];
    exr_seeds();
    stb_seeds();
    pfm_seeds();
    sss_written_seeds();
    ply_be_seed();
    if (failures) fprintf(stderr, "%d seeds failed\n", failures);
    return failures ? 1 : 0;
}
