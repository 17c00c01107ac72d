/* EXT_meshopt_compression (KhronosGroup/glTF extensions/2.0/Vendor/EXT_meshopt_compression): a buffer
 * view whose bytes are decoded by meshoptimizer from a compressed range of another buffer. The
 * extension's rules ("For the extension object to be valid, the following must hold") are checked and
 * the compressed range is checked against its buffer before anything is decoded; the decoded size
 * (count x byteStride, which must be the view's byteLength) counts against SSS_GLTF_MAX_DECODED_SIZE.
 * meshoptimizer's decoders are "safe to use for untrusted input" (meshoptimizer.h): they never read or
 * write outside the ranges given, and garbage in gives garbage out (indices are range-checked later). */
#include <meshoptimizer.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/gltf_internal.h"

enum { MODE_ATTRIBUTES, MODE_TRIANGLES, MODE_INDICES };
enum { FILTER_NONE, FILTER_OCTAHEDRAL, FILTER_QUATERNION, FILTER_EXPONENTIAL };

/* *out: the index in names of the string member key of obj; absent: def, or an error when def < 0. */
static sss_result enum_member(gltf_ctx *c, const cJSON *obj, const char *path, const char *key,
                              const char *const *names, int count, int def, int *out)
{
    const cJSON *v = gltf_get(obj, key);
    *out = def;
    if (!v && def < 0) return gltf_fail(c, SSS_ERROR_PARSE, "%s.%s: required field missing", path, key);
    if (!v) return SSS_OK;
    for (*out = 0; cJSON_IsString(v) && *out < count; (*out)++)
        if (strcmp(v->valuestring, names[*out]) == 0) return SSS_OK;
    return gltf_fail(c, SSS_ERROR_PARSE, "%s.%s: expected %s, %s, %s%s%s", path, key, names[0], names[1], names[2],
                     count > 3 ? " or " : "", count > 3 ? names[3] : "");
}

/* The extension's rules on mode, filter, stride and count; view_stride 0: the view has none. */
static sss_result check_layout(gltf_ctx *c, const char *path, int mode, int filter, long stride, long count,
                               long view_stride)
{
    if (view_stride && view_stride != stride)
        return gltf_fail(c, SSS_ERROR_PARSE, "%s.byteStride: %ld, but the buffer view's is %ld", path, stride,
                         view_stride);
    if (mode == MODE_ATTRIBUTES && (stride % 4 != 0 || stride > 256))
        return gltf_fail(c, SSS_ERROR_PARSE, "%s.byteStride: %ld (ATTRIBUTES needs a multiple of 4, at most 256)", path,
                         stride);
    if (mode != MODE_ATTRIBUTES && stride != 2 && stride != 4)
        return gltf_fail(c, SSS_ERROR_PARSE, "%s.byteStride: %ld (indices need 2 or 4)", path, stride);
    if (mode == MODE_TRIANGLES && count % 3 != 0)
        return gltf_fail(c, SSS_ERROR_PARSE, "%s.count: %ld is not a multiple of 3 (TRIANGLES)", path, count);
    if (mode != MODE_ATTRIBUTES && filter != FILTER_NONE)
        return gltf_fail(c, SSS_ERROR_PARSE, "%s.filter: indices take no filter", path);
    if ((filter == FILTER_OCTAHEDRAL && stride != 4 && stride != 8) || (filter == FILTER_QUATERNION && stride != 8) ||
        (filter == FILTER_EXPONENTIAL && stride % 4 != 0))
        return gltf_fail(c, SSS_ERROR_PARSE, "%s.byteStride: %ld does not suit the filter", path, stride);
    return SSS_OK;
}

/* meshoptimizer's decoder of the mode, then the filter in place; 0 on success. */
static int decode(unsigned char *dst, size_t count, size_t stride, const unsigned char *src, size_t size, int mode,
                  int filter)
{
    int rc = mode == MODE_ATTRIBUTES ? meshopt_decodeVertexBuffer(dst, count, stride, src, size)
             : mode == MODE_TRIANGLES ? meshopt_decodeIndexBuffer(dst, count, stride, src, size)
                                      : meshopt_decodeIndexSequence(dst, count, stride, src, size);
    if (rc != 0) return rc;
    if (filter == FILTER_OCTAHEDRAL) meshopt_decodeFilterOct(dst, count, stride);
    if (filter == FILTER_QUATERNION) meshopt_decodeFilterQuat(dst, count, stride);
    if (filter == FILTER_EXPONENTIAL) meshopt_decodeFilterExp(dst, count, stride);
    return 0;
}

sss_result gltf_decoded_budget(gltf_ctx *c, unsigned long long bytes, const char *path)
{
    if (bytes > SSS_GLTF_MAX_DECODED_SIZE - c->decoded_bytes)
        return gltf_fail(c, SSS_ERROR_LIMIT, "%s: decodes to %llu bytes, beyond the %u of compressed data decoded per "
                         "asset (%zu so far; docs/limits.md)", path, bytes, (unsigned)SSS_GLTF_MAX_DECODED_SIZE,
                         c->decoded_bytes);
    c->decoded_bytes += (size_t)bytes;
    return SSS_OK;
}

/* The compressed bytes: buffers[buffer] from byteOffset, byteLength long, inside the buffer. */
static sss_result source_bytes(gltf_ctx *c, const cJSON *ext, const char *path, const unsigned char **src,
                               size_t *size)
{
    long buffer = 0, offset = 0, length = 0;
    sss_result res;
    char bp[160];
    snprintf(bp, sizeof bp, "%s.buffer", path);
    const unsigned char *data;
    size_t have;
    if ((res = gltf_int(c, ext, path, "buffer", 1, 0, 0, 1L << 30, &buffer)) != SSS_OK ||
        (res = gltf_int(c, ext, path, "byteOffset", 0, 0, 0, 1L << 40, &offset)) != SSS_OK ||
        (res = gltf_int(c, ext, path, "byteLength", 1, 0, 1, 1L << 40, &length)) != SSS_OK ||
        (res = gltf_buffer_data(c, buffer, bp, &data, &have)) != SSS_OK)
        return res;
    if ((unsigned long)offset > have || (unsigned long)length > have - (size_t)offset)
        return gltf_fail(c, SSS_ERROR_PARSE, "%s: bytes %ld..%ld are beyond buffers[%ld] (%zu bytes)", path, offset,
                         offset + length, buffer, have);
    *src = data + offset;
    *size = (size_t)length;
    return SSS_OK;
}

sss_result gltf_meshopt_view(gltf_ctx *c, long index, const cJSON *ext, long view_stride, const unsigned char **start,
                             size_t *length)
{
    static const char *const modes[] = {"ATTRIBUTES", "TRIANGLES", "INDICES"};
    static const char *const filters[] = {"NONE", "OCTAHEDRAL", "QUATERNION", "EXPONENTIAL"};
    char path[96];
    snprintf(path, sizeof path, "bufferViews[%ld].extensions.EXT_meshopt_compression", index);
    size_t views = gltf_count(c, GLTF_BUFFER_VIEWS);
    if (!c->decoded_views && !(c->decoded_views = calloc(views, sizeof *c->decoded_views)))
        return gltf_fail(c, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    if (c->decoded_views[index]) {
        *start = c->decoded_views[index];
        return SSS_OK; /* *length: the view's byteLength, checked to be the decoded size */
    }
    long stride = 0, count = 0;
    int mode = 0, filter = 0;
    sss_result res;
    if ((res = gltf_object(c, ext, path)) != SSS_OK ||
        (res = gltf_int(c, ext, path, "byteStride", 1, 0, 1, 256, &stride)) != SSS_OK ||
        (res = gltf_int(c, ext, path, "count", 1, 0, 1, 1L << 40, &count)) != SSS_OK ||
        (res = enum_member(c, ext, path, "mode", modes, 3, -1, &mode)) != SSS_OK ||
        (res = enum_member(c, ext, path, "filter", filters, 4, FILTER_NONE, &filter)) != SSS_OK ||
        (res = check_layout(c, path, mode, filter, stride, count, view_stride)) != SSS_OK)
        return res;
    unsigned long long decoded = (unsigned long long)stride * (unsigned long long)count;
    if (decoded != *length)
        return gltf_fail(c, SSS_ERROR_PARSE, "%s: count %ld x byteStride %ld = %llu bytes, the buffer view's byteLength "
                         "is %zu", path, count, stride, decoded, *length);
    const unsigned char *src = NULL;
    size_t size = 0;
    if ((res = source_bytes(c, ext, path, &src, &size)) != SSS_OK ||
        (res = gltf_decoded_budget(c, decoded, path)) != SSS_OK)
        return res;
    unsigned char *dst = malloc((size_t)decoded);
    if (!dst) return gltf_fail(c, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory for %llu bytes", path, decoded);
    int rc = decode(dst, (size_t)count, (size_t)stride, src, size, mode, filter);
    if (rc != 0) {
        free(dst);
        return gltf_fail(c, SSS_ERROR_PARSE, "%s: the %s data does not decode (meshoptimizer error %d)", path,
                         modes[mode], rc);
    }
    c->decoded_views[index] = dst;
    *start = dst;
    return SSS_OK;
}
