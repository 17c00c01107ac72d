/* glTF accessors and buffer views (glTF 2.0 spec, section 3.6): every byte an accessor can reach is
 * checked against its buffer view and buffer before anything is read. */
#include <stdio.h>
#include <string.h>

#include "scene/gltf_internal.h"

static int component_size(long type)
{
    switch (type) {
    case 5120: case 5121: return 1; /* BYTE, UNSIGNED_BYTE */
    case 5122: case 5123: return 2; /* SHORT, UNSIGNED_SHORT */
    case 5125: case 5126: return 4; /* UNSIGNED_INT, FLOAT */
    default: return 0;
    }
}

static int type_components(const char *type)
{
    static const struct { const char *name; int n; } types[] = {
        {"SCALAR", 1}, {"VEC2", 2}, {"VEC3", 3}, {"VEC4", 4}, {"MAT2", 4}, {"MAT3", 9}, {"MAT4", 16}};
    for (size_t i = 0; i < sizeof types / sizeof types[0]; i++)
        if (strcmp(type, types[i].name) == 0) return types[i].n;
    return 0;
}

/* The byte range [*start, *start + *length) of bufferViews[index] inside its buffer (or decoded from
 * its EXT_meshopt_compression data), and its stride. */
static sss_result buffer_view(gltf_ctx *c, long index, const char *use, const unsigned char **start,
                              size_t *length, long *stride)
{
    const cJSON *view = gltf_item(c, GLTF_BUFFER_VIEWS, index);
    if (!view)
        return gltf_fail(c, SSS_ERROR_PARSE, "%s: bufferView %ld does not exist (%zu buffer views)", use, index,
                         gltf_count(c, GLTF_BUFFER_VIEWS));
    char path[64];
    snprintf(path, sizeof path, "bufferViews[%ld]", index);
    sss_result res;
    long buffer = 0, offset = 0, byte_length = 0;
    if ((res = gltf_object(c, view, path)) != SSS_OK ||
        (res = gltf_int(c, view, path, "buffer", 1, 0, 0, 1L << 30, &buffer)) != SSS_OK ||
        (res = gltf_int(c, view, path, "byteOffset", 0, 0, 0, 1L << 40, &offset)) != SSS_OK ||
        (res = gltf_int(c, view, path, "byteLength", 1, 0, 1, 1L << 40, &byte_length)) != SSS_OK ||
        (res = gltf_int(c, view, path, "byteStride", 0, 0, 4, 252, stride)) != SSS_OK)
        return res;
    if (*stride % 4 != 0)
        return gltf_fail(c, SSS_ERROR_PARSE, "%s.byteStride: %ld is not a multiple of 4", path, *stride);
    const cJSON *meshopt = gltf_get(gltf_get(view, "extensions"), "EXT_meshopt_compression");
    if (meshopt) { /* the view's own buffer is a fallback, perhaps without data: not read */
        *length = (size_t)byte_length;
        return gltf_meshopt_view(c, index, meshopt, *stride, start, length);
    }
    char buffer_path[80];
    snprintf(buffer_path, sizeof buffer_path, "%s.buffer", path);
    const unsigned char *data;
    size_t size;
    if ((res = gltf_buffer_data(c, buffer, buffer_path, &data, &size)) != SSS_OK) return res;
    if ((unsigned long)offset > size || (unsigned long)byte_length > size - (size_t)offset)
        return gltf_fail(c, SSS_ERROR_PARSE, "%s: bytes %ld..%ld are beyond buffers[%ld] (%zu bytes)", path, offset,
                         offset + byte_length, buffer, size);
    *start = data + offset;
    *length = (size_t)byte_length;
    return SSS_OK;
}

sss_result gltf_accessor_meta(gltf_ctx *c, long index, const char *use, int components, gltf_accessor *a,
                              long *view, long *offset)
{
    memset(a, 0, sizeof *a);
    const cJSON *acc = gltf_item(c, GLTF_ACCESSORS, index);
    if (!acc)
        return gltf_fail(c, SSS_ERROR_PARSE, "%s: accessor %ld does not exist (%zu accessors)", use, index,
                         gltf_count(c, GLTF_ACCESSORS));
    char path[64];
    snprintf(path, sizeof path, "accessors[%ld]", index);
    sss_result res;
    long ctype = 0, n = 0;
    if ((res = gltf_object(c, acc, path)) != SSS_OK ||
        (res = gltf_int(c, acc, path, "componentType", 1, 0, 5120, 5126, &ctype)) != SSS_OK ||
        (res = gltf_int(c, acc, path, "count", 1, 0, 1, (long)SSS_MESH_MAX_TRIANGLES * 3, &n)) != SSS_OK ||
        (res = gltf_int(c, acc, path, "byteOffset", 0, 0, 0, 1L << 40, offset)) != SSS_OK ||
        (res = gltf_int(c, acc, path, "bufferView", 0, -1, 0, 1L << 30, view)) != SSS_OK)
        return res;
    const cJSON *type = gltf_get(acc, "type");
    int comps = cJSON_IsString(type) ? type_components(type->valuestring) : 0;
    int csize = component_size(ctype);
    if (!comps) return gltf_fail(c, SSS_ERROR_PARSE, "%s.type: expected SCALAR, VEC2, VEC3, VEC4 or MAT2..4", path);
    if (!csize) return gltf_fail(c, SSS_ERROR_PARSE, "%s.componentType: %ld is not a glTF component type", path, ctype);
    if (comps != components)
        return gltf_fail(c, SSS_ERROR_PARSE, "%s: %s has %d components, %s needs %d", path, type->valuestring, comps,
                         use, components);
    if (gltf_get(acc, "sparse"))
        return gltf_fail(c, SSS_ERROR_UNSUPPORTED, "%s.sparse: sparse accessors are not supported", path);
    a->normalized = cJSON_IsTrue(gltf_get(acc, "normalized"));
    a->count = (size_t)n;
    a->components = comps;
    a->component_type = (int)ctype;
    a->stride = (size_t)comps * (size_t)csize;
    return SSS_OK;
}

sss_result gltf_accessor_get(gltf_ctx *c, long index, const char *use, int components, gltf_accessor *a)
{
    long offset = 0, view = -1;
    sss_result res = gltf_accessor_meta(c, index, use, components, a, &view, &offset);
    if (res != SSS_OK) return res;
    /* Without a buffer view an accessor is all zeros (spec 3.6.2.3), only useful with sparse data:
     * refused, also because its count is backed by no bytes of the file. */
    if (view < 0)
        return gltf_fail(c, SSS_ERROR_UNSUPPORTED,
                         "accessors[%ld]: no bufferView (zero-filled accessors are not supported)", index);
    const unsigned char *start = NULL;
    size_t length = 0;
    long stride = 0;
    char path[64];
    snprintf(path, sizeof path, "accessors[%ld]", index);
    if ((res = buffer_view(c, view, path, &start, &length, &stride)) != SSS_OK) return res;
    size_t element = a->stride;
    if (stride) a->stride = (size_t)stride;
    if (a->stride < element)
        return gltf_fail(c, SSS_ERROR_PARSE, "%s: bufferViews[%ld].byteStride %zu is smaller than an element (%zu)",
                         path, view, a->stride, element);
    /* The last element must end inside the view: offset + stride (count - 1) + element <= length. */
    unsigned long long end = (unsigned long long)offset + (unsigned long long)a->stride * (a->count - 1) + element;
    if (end > length)
        return gltf_fail(c, SSS_ERROR_PARSE, "%s: %zu elements from byte %ld need %llu bytes, bufferViews[%ld] has %zu",
                         path, a->count, offset, end, view, length);
    a->base = start + offset;
    return SSS_OK;
}

sss_result gltf_buffer_view(gltf_ctx *c, long index, const char *use, const unsigned char **start, size_t *length)
{
    long stride = 0;
    return buffer_view(c, index, use, start, length, &stride);
}

double gltf_accessor_float(const gltf_accessor *a, size_t i, int k)
{
    if (!a->base) return 0.0;
    const unsigned char *p = a->base + i * a->stride;
    switch (a->component_type) {
    case 5126: { float f; memcpy(&f, p + 4 * k, 4); return f; }
    case 5121: return a->normalized ? p[k] / 255.0 : p[k];
    case 5120: { double v = (signed char)p[k]; return a->normalized ? (v / 127.0 < -1 ? -1 : v / 127.0) : v; }
    case 5123: { uint16_t v; memcpy(&v, p + 2 * k, 2); return a->normalized ? v / 65535.0 : v; }
    case 5122: { int16_t v; memcpy(&v, p + 2 * k, 2); return a->normalized ? (v / 32767.0 < -1 ? -1 : v / 32767.0) : v; }
    default: { uint32_t v; memcpy(&v, p + 4 * k, 4); return a->normalized ? v / 4294967295.0 : v; }
    }
}

uint32_t gltf_accessor_uint(const gltf_accessor *a, size_t i)
{
    if (!a->base) return 0;
    const unsigned char *p = a->base + i * a->stride;
    switch (a->component_type) {
    case 5121: return p[0];
    case 5123: { uint16_t v; memcpy(&v, p, 2); return v; }
    default: { uint32_t v; memcpy(&v, p, 4); return v; }
    }
}
