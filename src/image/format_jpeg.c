/* image/format_jpeg.c — JPEG reading through libjpeg-turbo (baseline and progressive, grey or colour;
 * the common format of textures inside glTF assets). Samples are 8-bit sRGB, decoded with the same
 * exact inverse curve as PNG. No writer: sss writes PNG, HDR, PFM and EXR.
 *
 * Strict: a libjpeg warning (corrupt or cut entropy data, which libjpeg would fill with grey) fails the
 * read like an error, and the library's messages go into sss_error instead of stderr. */
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <jpeglib.h>

#include "image/image_internal.h"

#define JPEG_MAX_FILE_BYTES (256u << 20)
/* A progressive file can hold any number of scans, each a pass over the whole image: libjpeg-turbo's
 * own fuzzers and djpeg -maxscan bound them; real encoders write about 10. */
#define JPEG_MAX_SCANS 500

typedef struct jpeg_failure {
    struct jpeg_error_mgr pub; /* first: libjpeg hands back this pointer */
    jmp_buf jump;
    char message[JMSG_LENGTH_MAX];
} jpeg_failure;

static void fail_with_message(j_common_ptr cinfo)
{
    jpeg_failure *f = (jpeg_failure *)cinfo->err;
    f->pub.format_message(cinfo, f->message);
    longjmp(f->jump, 1);
}

/* msg_level -1 is a warning about corrupt data: refused. Trace messages (>= 0) are dropped. */
static void on_message(j_common_ptr cinfo, int msg_level)
{
    if (msg_level < 0) fail_with_message(cinfo);
}

static void bound_scans(j_common_ptr cinfo)
{
    j_decompress_ptr d = (j_decompress_ptr)cinfo;
    if (cinfo->is_decompressor && d->input_scan_number > JPEG_MAX_SCANS) {
        jpeg_failure *f = (jpeg_failure *)cinfo->err;
        snprintf(f->message, sizeof f->message, "more than %d scans", JPEG_MAX_SCANS);
        longjmp(f->jump, 1);
    }
}

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

/* Decodes the scanlines into out, allocated by the caller at the header's size; cinfo is past
 * jpeg_read_header. */
static sss_result decode_pixels(j_decompress_ptr cinfo, const char *path, unsigned char *row, sss_image *out,
                                sss_error *err)
{
    float table[256];
    sss_srgb8_decode_table_(table);
    jpeg_start_decompress(cinfo);
    size_t w = cinfo->output_width;
    for (float *p = out->pixels; cinfo->output_scanline < cinfo->output_height;) {
        JSAMPROW rows[1] = {row};
        if (jpeg_read_scanlines(cinfo, rows, 1) != 1)
            return sss_error_set(err, SSS_ERROR_PARSE, "%s: cannot decode JPEG (no scanline)", path);
        for (size_t i = 0; i < 3 * w; i++) *p++ = table[row[i]];
    }
    jpeg_finish_decompress(cinfo);
    return SSS_OK;
}

/* What a read owns. It lives in the caller of the function that calls setjmp, so its fields keep their
 * values across libjpeg's longjmp. */
typedef struct jpeg_job {
    struct jpeg_decompress_struct cinfo;
    struct jpeg_progress_mgr progress;
    jpeg_failure failure;
    unsigned char *row;
    sss_image image;
    int width, height; /* the header's, kept for size_only: cinfo is not read after its destroy */
} jpeg_job;

static sss_result decode(jpeg_job *job, const unsigned char *bytes, size_t size, const char *path, int size_only,
                         sss_error *err)
{
    j_decompress_ptr cinfo = &job->cinfo;
    if (setjmp(job->failure.jump))
        return sss_error_set(err, SSS_ERROR_PARSE, "%s: malformed JPEG (%s)", path, job->failure.message);
    jpeg_mem_src(cinfo, bytes, (unsigned long)size);
    jpeg_read_header(cinfo, TRUE);
    job->width = (int)cinfo->image_width, job->height = (int)cinfo->image_height;
    /* the header's size before anything is allocated from it, with the PNG budget of decoded pixels */
    sss_result r = sss_image_check_decoded_size_(path, "JPEG", (long)cinfo->image_width, (long)cinfo->image_height, err);
    if (r != SSS_OK || size_only) return r;
    cinfo->out_color_space = JCS_RGB; /* grey is replicated; CMYK and YCCK are refused by libjpeg */
    if (!(job->row = malloc((size_t)job->width * 3))) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    if ((r = sss_image_create(&job->image, job->width, job->height, err)) != SSS_OK) {
        sss_error_prefix(err, path);
        return r;
    }
    return decode_pixels(cinfo, path, job->row, &job->image, err);
}

sss_result sss_jpeg_read_(FILE *f, const char *path, int size_only, sss_image *out, sss_error *err)
{
    unsigned char *bytes = NULL;
    size_t size = 0;
    sss_result r = read_all(f, path, &bytes, &size, err);
    if (r != SSS_OK) return r;
    if (size < 3 || bytes[0] != 0xFF || bytes[1] != 0xD8 || bytes[2] != 0xFF) {
        free(bytes);
        return sss_error_set(err, SSS_ERROR_PARSE, "%s: not a JPEG file (%s)", path, size == 0 ? "empty" : "bad signature");
    }
    jpeg_job *job = calloc(1, sizeof *job);
    if (!job) {
        free(bytes);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    }
    job->cinfo.err = jpeg_std_error(&job->failure.pub);
    job->failure.pub.error_exit = fail_with_message;
    job->failure.pub.emit_message = on_message;
    jpeg_create_decompress(&job->cinfo);
    job->progress.progress_monitor = bound_scans;
    job->cinfo.progress = &job->progress;
    r = decode(job, bytes, size, path, size_only, err);
    jpeg_destroy_decompress(&job->cinfo);
    free(job->row);
    free(bytes);
    if (r != SSS_OK) sss_image_free(&job->image);
    if (r == SSS_OK && !size_only)
        *out = job->image;
    else
        out->width = r == SSS_OK ? job->width : 0, out->height = r == SSS_OK ? job->height : 0;
    free(job);
    return r;
}
