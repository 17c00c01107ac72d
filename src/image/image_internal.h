/* image/image_internal.h — shared helpers of the image module's format readers and writers
 * (internal, not public API). */
#ifndef SSS_IMAGE_INTERNAL_H
#define SSS_IMAGE_INTERNAL_H

#include <stdint.h>
#include <stdio.h>

#include "sss/image.h"

/* Checks a size read from a file header before anything is allocated: 1..SSS_IMAGE_MAX_DIM. */
sss_result sss_image_check_dims_(const char *path, long width, long height, sss_error *err);

/* A decoded 8/16-bit image's header size (PNG, JPEG) against SSS_IMAGE_MAX_DIM per side and
 * SSS_IMAGE_MAX_PNG_PIXELS in all, before stb_image allocates from it; format names it in the message. */
sss_result sss_image_check_decoded_size_(const char *path, const char *format, long width, long height,
                                         sss_error *err);

/* Validates img (non-NULL pixels, sizes in range) and refuses images holding NaN or Inf:
 * every writer calls this first, so a non-finite value never reaches a file (COMMON.md). */
sss_result sss_image_check_writable_(const char *path, const sss_image *img, sss_error *err);

/* The PBRT-v3-compatible 8-bit tone map of one value (see sss_image_to_srgb8). */
uint8_t sss_srgb8_from_linear_(float linear, float scale);
/* table[k] = the linear value of 8-bit sRGB code k (the exact inverse curve, rounded to float). */
void sss_srgb8_decode_table_(float table[256]);

/* Bytes between the stream's position and its end (regular files and fmemopen streams), or -1 when
 * the stream cannot seek (a pipe). Readers use it to refuse a header that claims more pixels than
 * the data could hold before allocating the image. The position is left unchanged. */
long long sss_image_stream_remaining_(FILE *f);

/* Format readers on an open stream positioned at the start of the data (a file, or fmemopen for
 * sss_image_decode); path names the input in every message. They do not close f. With size_only they
 * stop after the header's checks and set only out->width and out->height (no pixels). */
sss_result sss_png_read_(FILE *f, const char *path, int size_only, sss_image *out, sss_error *err);
sss_result sss_hdr_read_(FILE *f, const char *path, int size_only, sss_image *out, sss_error *err);
sss_result sss_jpeg_read_(FILE *f, const char *path, int size_only, sss_image *out, sss_error *err);
sss_result sss_pfm_read_(FILE *f, const char *path, int size_only, sss_image *out, sss_error *err);
/* OpenEXR reads through the library's own I/O: from a descriptor of sss_open_input (file_size bytes;
 * always closed), or from memory (data, size). */
sss_result sss_exr_read_(int fd, uint64_t file_size, const char *path, int size_only, sss_image *out, sss_error *err);
sss_result sss_exr_decode_(const void *data, size_t size, const char *name, sss_image *out, sss_error *err);

sss_result sss_png_write_(const char *path, const sss_image *img, double exposure, sss_error *err);
sss_result sss_hdr_write_(const char *path, const sss_image *img, sss_error *err);
sss_result sss_pfm_write_(const char *path, const sss_image *img, sss_error *err);

#endif
