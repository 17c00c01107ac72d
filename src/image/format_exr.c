/* image/format_exr.c — OpenEXR through the OpenEXR 3.1 C API (OpenEXRCore).
 *
 * Reading: the first part of a file, scanline or tiled (level 0 of mip/rip maps), channels R, G, B
 * (A and others ignored) or a lone Y (grey, replicated to RGB), each half, float or uint, with any
 * compression the library decodes. The data window is returned (the display window is ignored).
 * Deep data, subsampled channels and luminance-chroma (Y with RY/BY) are rejected by name.
 * Writing: one scanline part, channels R, G, B as float (exact) or half, ZIP compression, through a
 * temporary file renamed into place. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <openexr.h>

#include "core/file_util.h"
#include "image/image_internal.h"

/* The library reports details through a callback (by default to stderr, which the library must not
 * do): keep the first message of the current call on this thread. */
static _Thread_local char exr_message[256];

static void exr_error_cb(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    (void)ctxt;
    if (!exr_message[0]) snprintf(exr_message, sizeof exr_message, "%s", msg ? msg : exr_get_default_error_message(code));
}

static const char *exr_detail(exr_result_t rv)
{
    return exr_message[0] ? exr_message : exr_get_default_error_message(rv);
}

static exr_context_initializer_t exr_init(void)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = exr_error_cb;
    init.max_image_width = SSS_IMAGE_MAX_DIM;
    init.max_image_height = SSS_IMAGE_MAX_DIM;
    /* A truncated or corrupt offset table is an error, not something to guess around. */
    init.flags = EXR_CONTEXT_FLAG_DISABLE_CHUNK_RECONSTRUCTION;
    exr_message[0] = '\0';
    return init;
}

typedef struct exr_channels {
    int grey;  /* 1: a lone Y channel */
    int count; /* channels found among R, G, B (or Y) */
} exr_channels;

static sss_result find_channels(const char *path, const exr_attr_chlist_t *list, exr_channels *ch, sss_error *err)
{
    int have[4] = {0, 0, 0, 0}; /* R, G, B, Y */
    int chroma = 0;
    static const char *names[4] = {"R", "G", "B", "Y"};
    for (int i = 0; i < list->num_channels; i++) {
        const exr_attr_chlist_entry_t *e = &list->entries[i];
        const char *name = e->name.str;
        if (strcmp(name, "RY") == 0 || strcmp(name, "BY") == 0) chroma = 1;
        for (int k = 0; k < 4; k++) {
            if (strcmp(name, names[k]) != 0) continue;
            if (e->x_sampling != 1 || e->y_sampling != 1)
                return sss_error_set(err, SSS_ERROR_UNSUPPORTED, "%s: channel %s is subsampled (%dx%d), not supported",
                                     path, name, e->x_sampling, e->y_sampling);
            have[k] = 1;
        }
    }
    ch->grey = 0;
    ch->count = have[0] + have[1] + have[2];
    if (ch->count == 3) return SSS_OK;
    if (ch->count == 0 && have[3] && !chroma) {
        ch->grey = 1;
        ch->count = 1;
        return SSS_OK;
    }
    char found[160] = "";
    for (int i = 0; i < list->num_channels && strlen(found) < sizeof found - 40; i++) {
        strcat(found, i ? ", " : "");
        strncat(found, list->entries[i].name.str, 32);
    }
    if (chroma)
        return sss_error_set(err, SSS_ERROR_UNSUPPORTED, "%s: luminance/chroma (Y, RY, BY) images are not supported",
                             path);
    return sss_error_set(err, SSS_ERROR_UNSUPPORTED, "%s: needs channels R, G and B or a lone Y; found: %s", path,
                         found[0] ? found : "none");
}

/* Decodes one chunk into img, whose pixel (0, 0) is the chunk grid's origin; x0, y0 is the chunk's
 * first pixel relative to it. */
static exr_result_t decode_chunk(exr_context_t ctx, const exr_chunk_info_t *cinfo, int x0, int y0, sss_image *img,
                                 int grey)
{
    exr_decode_pipeline_t dec = EXR_DECODE_PIPELINE_INITIALIZER;
    exr_result_t rv = exr_decoding_initialize(ctx, 0, cinfo, &dec);
    if (rv != EXR_ERR_SUCCESS) return rv;
    if (x0 < 0 || y0 < 0 || x0 + cinfo->width > img->width || y0 + cinfo->height > img->height) {
        exr_decoding_destroy(ctx, &dec);
        return EXR_ERR_CORRUPT_CHUNK;
    }
    for (int i = 0; i < dec.channel_count; i++) {
        exr_coding_channel_info_t *c = &dec.channels[i];
        const char *name = c->channel_name;
        int k = -1;
        if (grey ? strcmp(name, "Y") == 0 : strcmp(name, "R") == 0) k = 0;
        else if (!grey && strcmp(name, "G") == 0) k = 1;
        else if (!grey && strcmp(name, "B") == 0) k = 2;
        if (k < 0) {
            c->decode_to_ptr = NULL; /* skipped */
            continue;
        }
        float *dst = img->pixels + ((size_t)y0 * (size_t)img->width + (size_t)x0) * 3 + k;
        c->decode_to_ptr = (uint8_t *)dst;
        c->user_pixel_stride = 3 * (int32_t)sizeof(float);
        c->user_line_stride = 3 * (int32_t)sizeof(float) * img->width;
        c->user_bytes_per_element = (int16_t)sizeof(float);
        c->user_data_type = EXR_PIXEL_FLOAT;
    }
    rv = exr_decoding_choose_default_routines(ctx, 0, &dec);
    if (rv == EXR_ERR_SUCCESS) rv = exr_decoding_run(ctx, 0, &dec);
    exr_decoding_destroy(ctx, &dec);
    return rv;
}

/* Largest ratio of decoded to stored bytes that each compression can reach, to refuse a header that
 * claims far more pixels than the file could hold before the image (12 bytes per pixel) and the
 * library's chunk buffers are allocated. NONE stores raw data; RLE repeats one byte at most 128 times
 * per 2 bytes; deflate (ZIPS, ZIP, PXR24, which also packs 32-bit floats into 24 bits) cannot exceed
 * 1032:1; B44(A) stores 16 half samples (32 bytes) in at least 3 bytes; PIZ's Huffman coder repeats a
 * value at most 255 times per run code (>= 9 bits); DWA is lossy with no such bound: generous. */
static double max_expansion(int compression)
{
    switch (compression) {
    case EXR_COMPRESSION_NONE: return 1.0;
    case EXR_COMPRESSION_RLE: return 64.0;
    case EXR_COMPRESSION_ZIPS:
    case EXR_COMPRESSION_ZIP: return 1032.0;
    case EXR_COMPRESSION_PXR24: return 1032.0 * 4.0 / 3.0;
    case EXR_COMPRESSION_B44:
    case EXR_COMPRESSION_B44A: return 32.0 / 3.0;
    case EXR_COMPRESSION_PIZ: return 1024.0;
    default: return 65536.0;
    }
}

/* The part's chunk grid: scanline blocks, or level-0 tiles. */
typedef struct exr_grid {
    int tiled;
    int32_t lines;     /* scanline: lines per chunk */
    uint32_t tw, th;   /* tiled: tile size */
    long nx, ny;       /* chunks along x (1 for scanlines) and y */
} exr_grid;

static exr_result_t chunk_info(exr_context_t ctx, const exr_grid *g, const exr_attr_box2i_t *dw, long cx, long cy,
                               exr_chunk_info_t *cinfo)
{
    if (g->tiled) return exr_read_tile_chunk_info(ctx, 0, (int)cx, (int)cy, 0, 0, cinfo);
    return exr_read_scanline_chunk_info(ctx, 0, (int)(dw->min.y + cy * g->lines), cinfo);
}

/* Reads every chunk's table entry and header before anything large is allocated: all must exist, and
 * their stored bytes must be able to expand to what the header claims. */
static sss_result check_chunks(exr_context_t ctx, const char *path, const exr_grid *g, const exr_attr_box2i_t *dw,
                               long long file_size, sss_error *err)
{
    int32_t count = 0;
    if (exr_get_chunk_count(ctx, 0, &count) != EXR_ERR_SUCCESS || count <= 0)
        return sss_error_set(err, SSS_ERROR_PARSE, "%s: bad chunk count", path);
    /* The offset table alone holds 8 bytes per chunk (all levels of a mipmapped file). */
    if (file_size >= 0 && (long long)count > file_size / 8)
        return sss_error_set(err, SSS_ERROR_PARSE, "%s: truncated: %d chunks cannot fit in %lld bytes", path, count,
                             file_size);
    double packed = 0.0, unpacked = 0.0, bound = 0.0;
    for (long cy = 0; cy < g->ny; cy++)
        for (long cx = 0; cx < g->nx; cx++) {
            exr_chunk_info_t cinfo;
            exr_result_t rv = chunk_info(ctx, g, dw, cx, cy, &cinfo);
            if (rv != EXR_ERR_SUCCESS)
                return sss_error_set(err, SSS_ERROR_PARSE, "%s: bad or missing chunk %ld: %s", path,
                                     cy * g->nx + cx, exr_detail(rv));
            packed += (double)cinfo.packed_size;
            unpacked += (double)cinfo.unpacked_size;
            bound += (double)cinfo.packed_size * max_expansion(cinfo.compression) + 64.0;
        }
    if (unpacked > bound || (file_size >= 0 && packed > (double)file_size))
        return sss_error_set(err, SSS_ERROR_PARSE,
                             "%s: truncated or corrupt: %.0f bytes of pixel data cannot hold the %.0f the header claims",
                             path, packed, unpacked);
    return SSS_OK;
}

/* Reads the first part of an open context into out; file_size (or -1) bounds the header's claims. */
static sss_result read_context(exr_context_t ctx, const char *path, long long file_size, int size_only, sss_image *out,
                               sss_error *err)
{
    sss_result r = SSS_OK;
    exr_result_t rv = EXR_ERR_SUCCESS;
    exr_storage_t storage;
    exr_attr_box2i_t dw;
    const exr_attr_chlist_t *chlist = NULL;
    exr_channels ch = {0, 0};
    if (exr_get_storage(ctx, 0, &storage) != EXR_ERR_SUCCESS || exr_get_data_window(ctx, 0, &dw) != EXR_ERR_SUCCESS ||
        exr_get_channels(ctx, 0, &chlist) != EXR_ERR_SUCCESS || !chlist)
        return sss_error_set(err, SSS_ERROR_PARSE, "%s: incomplete OpenEXR header: %s", path,
                             exr_detail(EXR_ERR_MISSING_REQ_ATTR));
    if (storage != EXR_STORAGE_SCANLINE && storage != EXR_STORAGE_TILED)
        return sss_error_set(err, SSS_ERROR_UNSUPPORTED, "%s: deep OpenEXR images are not supported", path);
    long w = (long)dw.max.x - dw.min.x + 1, h = (long)dw.max.y - dw.min.y + 1;
    if ((r = sss_image_check_dims_(path, w, h, err)) != SSS_OK) return r;
    if ((r = find_channels(path, chlist, &ch, err)) != SSS_OK) return r;
    exr_grid g = {storage == EXR_STORAGE_TILED, 0, 0, 0, 1, 0};
    if (g.tiled) {
        exr_tile_level_mode_t level;
        exr_tile_round_mode_t round;
        rv = exr_get_tile_descriptor(ctx, 0, &g.tw, &g.th, &level, &round);
        if (rv == EXR_ERR_SUCCESS && (g.tw == 0 || g.th == 0)) rv = EXR_ERR_INVALID_ATTR;
        if (rv != EXR_ERR_SUCCESS)
            return sss_error_set(err, SSS_ERROR_PARSE, "%s: bad tile description: %s", path, exr_detail(rv));
        g.nx = (w + (long)g.tw - 1) / (long)g.tw;
        g.ny = (h + (long)g.th - 1) / (long)g.th;
    } else {
        rv = exr_get_scanlines_per_chunk(ctx, 0, &g.lines);
        if (rv == EXR_ERR_SUCCESS && g.lines <= 0) rv = EXR_ERR_INVALID_ATTR;
        if (rv != EXR_ERR_SUCCESS) return sss_error_set(err, SSS_ERROR_PARSE, "%s: %s", path, exr_detail(rv));
        g.ny = (h + g.lines - 1) / g.lines;
    }
    if ((r = check_chunks(ctx, path, &g, &dw, file_size, err)) != SSS_OK) return r;
    if (size_only) {
        out->width = (int)w;
        out->height = (int)h;
        return SSS_OK;
    }
    if ((r = sss_image_create(out, (int)w, (int)h, err)) != SSS_OK) {
        sss_error_prefix(err, path);
        return r;
    }
    for (long cy = 0; r == SSS_OK && cy < g.ny; cy++)
        for (long cx = 0; r == SSS_OK && cx < g.nx; cx++) {
            exr_chunk_info_t cinfo;
            rv = chunk_info(ctx, &g, &dw, cx, cy, &cinfo);
            if (rv == EXR_ERR_SUCCESS) {
                int x0 = g.tiled ? (int)(cx * (long)g.tw) : cinfo.start_x - dw.min.x;
                int y0 = g.tiled ? (int)(cy * (long)g.th) : cinfo.start_y - dw.min.y;
                rv = decode_chunk(ctx, &cinfo, x0, y0, out, ch.grey);
            }
            if (rv == EXR_ERR_SUCCESS) continue;
            if (g.tiled)
                r = sss_error_set(err, SSS_ERROR_PARSE, "%s: cannot decode tile (%ld, %ld): %s", path, cx, cy,
                                  exr_detail(rv));
            else
                r = sss_error_set(err, SSS_ERROR_PARSE, "%s: cannot decode scanlines from y = %ld: %s", path,
                                  (long)dw.min.y + cy * g.lines, exr_detail(rv));
        }
    if (r == SSS_OK && ch.grey) {
        size_t n = (size_t)w * (size_t)h;
        for (size_t i = 0; i < n; i++) out->pixels[3 * i + 1] = out->pixels[3 * i + 2] = out->pixels[3 * i];
    }
    if (r != SSS_OK) sss_image_free(out);
    return r;
}

static const unsigned char exr_magic[4] = {0x76, 0x2f, 0x31, 0x01};

/* Opens with init (a custom reader, path only names the input), reads, and always finishes the
 * context. */
static sss_result read_with(const char *path, exr_context_initializer_t *init, long long file_size, int size_only,
                            sss_image *out, sss_error *err)
{
    exr_context_t ctx = NULL;
    exr_result_t rv = exr_start_read(&ctx, path, init);
    sss_result r;
    if (rv != EXR_ERR_SUCCESS)
        r = sss_error_set(err, rv == EXR_ERR_FILE_ACCESS ? SSS_ERROR_IO : SSS_ERROR_PARSE,
                          "%s: cannot read OpenEXR header: %s", path, exr_detail(rv));
    else
        r = read_context(ctx, path, file_size, size_only, out, err);
    exr_finish(&ctx);
    return r;
}

/* The library's custom I/O on the descriptor of sss_open_input (pread: no shared file position). */
static int64_t fd_read(exr_const_context_t ctxt, void *user, void *buffer, uint64_t sz, uint64_t offset,
                       exr_stream_error_func_ptr_t error_cb)
{
    (void)ctxt;
    (void)error_cb;
    uint64_t done = 0;
    while (done < sz) {
        ssize_t n = pread(*(const int *)user, (char *)buffer + done, (size_t)(sz - done), (off_t)(offset + done));
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) return -1;
        if (n == 0) break;
        done += (uint64_t)n;
    }
    return (int64_t)done;
}

static int64_t fd_size(exr_const_context_t ctxt, void *user)
{
    (void)ctxt;
    struct stat st;
    return fstat(*(const int *)user, &st) == 0 ? (int64_t)st.st_size : -1;
}

static int64_t fd_write(exr_const_context_t ctxt, void *user, const void *buffer, uint64_t sz, uint64_t offset,
                        exr_stream_error_func_ptr_t error_cb)
{
    (void)ctxt;
    (void)error_cb;
    uint64_t done = 0;
    while (done < sz) {
        ssize_t n = pwrite(*(const int *)user, (const char *)buffer + done, (size_t)(sz - done), (off_t)(offset + done));
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return -1;
        done += (uint64_t)n;
    }
    return (int64_t)done;
}

sss_result sss_exr_read_(int fd, uint64_t file_size, const char *path, int size_only, sss_image *out, sss_error *err)
{
    unsigned char magic[4];
    ssize_t got = pread(fd, magic, 4, 0);
    sss_result r;
    if (got != 4 || memcmp(magic, exr_magic, 4) != 0) {
        r = sss_error_set(err, SSS_ERROR_PARSE, "%s: not an OpenEXR file (%s)", path, got == 0 ? "empty" : "bad signature");
    } else {
        exr_context_initializer_t init = exr_init();
        init.user_data = &fd;
        init.read_fn = fd_read;
        init.size_fn = fd_size;
        r = read_with(path, &init, (long long)file_size, size_only, out, err);
    }
    close(fd);
    return r;
}

/* The library's custom I/O on a memory buffer (pread semantics: short reads at the end). */
typedef struct exr_memory {
    const unsigned char *data;
    size_t size;
} exr_memory;

static int64_t memory_read(exr_const_context_t ctxt, void *user, void *buffer, uint64_t sz, uint64_t offset,
                           exr_stream_error_func_ptr_t error_cb)
{
    (void)ctxt;
    (void)error_cb;
    const exr_memory *m = user;
    if (offset >= m->size) return 0;
    uint64_t n = m->size - offset < sz ? m->size - offset : sz;
    memcpy(buffer, m->data + offset, (size_t)n);
    return (int64_t)n;
}

static int64_t memory_size(exr_const_context_t ctxt, void *user)
{
    (void)ctxt;
    return (int64_t)((const exr_memory *)user)->size;
}

sss_result sss_exr_decode_(const void *data, size_t size, const char *name, sss_image *out, sss_error *err)
{
    if (size < 4 || memcmp(data, exr_magic, 4) != 0)
        return sss_error_set(err, SSS_ERROR_PARSE, "%s: not an OpenEXR file (%s)", name,
                             size == 0 ? "empty" : "bad signature");
    exr_memory m = {data, size};
    exr_context_initializer_t init = exr_init();
    init.user_data = &m;
    init.read_fn = memory_read;
    init.size_fn = memory_size;
    return read_with(name, &init, (long long)size, 0, out, err);
}

/* IEEE 754 binary16 of f, rounded to nearest even; returns 0 when |f| overflows the half range
 * (rounds to >= 65520). Works in double, where every step is exact. */
static int float_to_half(float f, uint16_t *out)
{
    double a = fabs((double)f);
    uint16_t sign = signbit(f) ? 0x8000 : 0;
    if (a < ldexp(1.0, -14)) { /* subnormal: multiples of 2^-24 (1024 * 2^-24 carries into 0x0400) */
        *out = sign | (uint16_t)nearbyint(a * ldexp(1.0, 24));
        return 1;
    }
    int e;
    double m = frexp(a, &e); /* a = m 2^e, m in [0.5, 1) */
    long mant = (long)nearbyint((2.0 * m - 1.0) * 1024.0);
    long biased = e - 1 + 15;
    if (mant == 1024) {
        mant = 0;
        biased++;
    }
    if (biased > 30) return 0;
    *out = sign | (uint16_t)(biased << 10) | (uint16_t)mant;
    return 1;
}

sss_result sss_image_write_exr(const char *path, const sss_image *img, int half, sss_error *err)
{
    sss_result r = sss_image_check_writable_(path, img, err);
    if (r != SSS_OK) return r;
    int w = img->width, h = img->height;
    size_t n = (size_t)w * (size_t)h * 3;
    uint16_t *halves = NULL;
    if (half) {
        halves = malloc(n * sizeof *halves);
        if (!halves) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
        size_t over = 0;
        for (size_t i = 0; i < n; i++) over += !float_to_half(img->pixels[i], &halves[i]);
        if (over) {
            free(halves);
            return sss_error_set(err, SSS_ERROR_LIMIT,
                                 "%s: %zu values exceed the half-float range (|v| >= 65520); write float instead", path,
                                 over);
        }
    }
    /* The library writes through fd_write into the temporary file of sss_atomic_open (created
     * exclusively), never reopening a name. */
    char tmp[4096];
    FILE *file = sss_atomic_open(path, tmp, sizeof tmp, err);
    if (!file) {
        free(halves);
        return err ? err->code : SSS_ERROR_IO;
    }
    int fd = fileno(file);
    exr_context_initializer_t init = exr_init();
    init.user_data = &fd;
    init.write_fn = fd_write;
    exr_context_t ctx = NULL;
    exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
    int have_enc = 0, part = 0;
    exr_pixel_type_t type = half ? EXR_PIXEL_HALF : EXR_PIXEL_FLOAT;
    exr_result_t rv = exr_start_write(&ctx, tmp, EXR_WRITE_FILE_DIRECTLY, &init);
    if (rv == EXR_ERR_SUCCESS) rv = exr_add_part(ctx, NULL, EXR_STORAGE_SCANLINE, &part);
    if (rv == EXR_ERR_SUCCESS) rv = exr_initialize_required_attr_simple(ctx, part, w, h, EXR_COMPRESSION_ZIP);
    static const char *names[3] = {"R", "G", "B"};
    for (int c = 0; c < 3 && rv == EXR_ERR_SUCCESS; c++)
        rv = exr_add_channel(ctx, part, names[c], type, EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1);
    if (rv == EXR_ERR_SUCCESS) rv = exr_write_header(ctx);
    int32_t lines = 0;
    if (rv == EXR_ERR_SUCCESS) rv = exr_get_scanlines_per_chunk(ctx, part, &lines);
    if (rv == EXR_ERR_SUCCESS && lines <= 0) rv = EXR_ERR_INVALID_ATTR;
    for (int y = 0; rv == EXR_ERR_SUCCESS && y < h; y += lines) {
        exr_chunk_info_t cinfo;
        rv = exr_write_scanline_chunk_info(ctx, part, y, &cinfo);
        if (rv != EXR_ERR_SUCCESS) break;
        rv = have_enc ? exr_encoding_update(ctx, part, &cinfo, &enc) : exr_encoding_initialize(ctx, part, &cinfo, &enc);
        if (rv != EXR_ERR_SUCCESS) break;
        for (int i = 0; i < enc.channel_count; i++) {
            exr_coding_channel_info_t *c = &enc.channels[i];
            int k = c->channel_name[0] == 'R' ? 0 : c->channel_name[0] == 'G' ? 1 : 2;
            size_t at = (size_t)y * (size_t)w * 3 + (size_t)k;
            c->encode_from_ptr = half ? (const uint8_t *)(halves + at) : (const uint8_t *)(img->pixels + at);
            c->user_bytes_per_element = half ? 2 : 4;
            c->user_data_type = (uint16_t)type;
            c->user_pixel_stride = 3 * c->user_bytes_per_element;
            c->user_line_stride = w * c->user_pixel_stride;
        }
        if (!have_enc) {
            have_enc = 1;
            rv = exr_encoding_choose_default_routines(ctx, part, &enc);
            if (rv != EXR_ERR_SUCCESS) break;
        }
        rv = exr_encoding_run(ctx, part, &enc);
    }
    if (have_enc) exr_encoding_destroy(ctx, &enc);
    if (rv != EXR_ERR_SUCCESS)
        r = sss_error_set(err, SSS_ERROR_IO, "%s: cannot write OpenEXR: %s", path, exr_detail(rv));
    exr_result_t fin = ctx ? exr_finish(&ctx) : EXR_ERR_SUCCESS;
    if (r == SSS_OK && fin != EXR_ERR_SUCCESS)
        r = sss_error_set(err, SSS_ERROR_IO, "%s: cannot finish OpenEXR: %s", path, exr_detail(fin));
    free(halves);
    if (r != SSS_OK) {
        fclose(file);
        sss_discard_temp(tmp);
        return r;
    }
    return sss_atomic_close(file, tmp, path, err);
}
