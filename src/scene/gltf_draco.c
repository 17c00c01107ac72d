/* KHR_draco_mesh_compression (KhronosGroup/glTF extensions/2.0/Khronos/KHR_draco_mesh_compression): a
 * primitive whose attributes and indices are one Draco stream in a buffer view. The accessors the
 * primitive names keep their types and counts ("must match the decompressed data") and have no bytes.
 * Before the decoder (gltf_draco_decode.cpp) sees the stream, its header is read here (the Draco
 * bitstream specification, google.github.io/draco/spec: the header, the metadata, the connectivity's
 * counts): the decoder sizes its tables by the triangle count it finds there, so that count must be the
 * indices accessor's, within SSS_MESH_MAX_TRIANGLES and within the decoding budget
 * (SSS_GLTF_DRACO_BYTES_PER_TRIANGLE each) first. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/gltf_draco.h"
#include "scene/gltf_internal.h"

typedef struct reader {
    const unsigned char *p, *end;
} reader;

static int read_u8(reader *r, uint32_t *v)
{
    if (r->p >= r->end) return 0;
    *v = *r->p++;
    return 1;
}

static int read_u32(reader *r, uint32_t *v)
{
    if (r->end - r->p < 4) return 0;
    *v = (uint32_t)r->p[0] | (uint32_t)r->p[1] << 8 | (uint32_t)r->p[2] << 16 | (uint32_t)r->p[3] << 24;
    r->p += 4;
    return 1;
}

/* Draco's unsigned varint: 7 bits a byte, lowest first, at most 5 bytes, wrapping in 32 bits as Draco's
 * DecodeVarint<uint32_t> does (so that the count read here is the one the decoder uses). */
static int read_varint(reader *r, uint32_t *v)
{
    *v = 0;
    for (int i = 0; i < 5; i++) {
        uint32_t byte;
        if (!read_u8(r, &byte)) return 0;
        *v |= (byte & 0x7f) << (7 * i);
        if (!(byte & 0x80)) return 1;
    }
    return 0;
}

static int skip(reader *r, uint32_t n)
{
    if ((uint64_t)(r->end - r->p) < n) return 0;
    r->p += n;
    return 1;
}

/* One metadata tree: blocks of (name, except the first) entries (name, size, bytes) and a count of
 * sub-blocks, which follow; every block has that shape wherever it sits, so counting them suffices. */
static int skip_metadata_tree(reader *r)
{
    uint64_t pending = 1;
    for (int first = 1; pending > 0; first = 0, pending--) {
        uint32_t n = 0, len = 0, sub = 0;
        if (!first && (!read_u8(r, &len) || !skip(r, len))) return 0;
        if (!read_varint(r, &n)) return 0;
        for (uint32_t i = 0; i < n; i++)
            if (!read_u8(r, &len) || !skip(r, len) || !read_varint(r, &len) || len == 0 || !skip(r, len)) return 0;
        if (!read_varint(r, &sub)) return 0;
        pending += sub;
    }
    return 1;
}

/* The geometry metadata: per attribute (count first) its id and tree, then the geometry's tree. */
static int skip_metadata(reader *r)
{
    uint32_t n = 0, id = 0;
    if (!read_varint(r, &n)) return 0;
    for (uint32_t i = 0; i < n; i++)
        if (!read_varint(r, &id) || !skip_metadata_tree(r)) return 0;
    return skip_metadata_tree(r);
}

/* A count of the connectivity: 32 bits before bitstream version `varint_from`, a varint from it on. */
static int read_count(reader *r, unsigned version, unsigned varint_from, uint32_t *v)
{
    return version < varint_from ? read_u32(r, v) : read_varint(r, v);
}

/* The triangle count of the Draco mesh stream data[0..size): header ("DRACO", version, encoder type 1
 * = mesh, method 0 = sequential or 1 = edgebreaker, flags), metadata when flagged (from version 1.3),
 * then sequential: faces, points; edgebreaker: traversal type, (new vertices before 2.2), encoded
 * vertices, faces; 32-bit counts before 2.2 (sequential) or 2.0 (edgebreaker), varints after. */
static sss_result stream_faces(gltf_ctx *c, const unsigned char *data, size_t size, const char *path, uint32_t *faces)
{
    reader r = {data, data + size};
    uint32_t major = 0, minor = 0, type = 0, method = 0, flags = 0, skip_count = 0;
    if (size < 5 || memcmp(data, "DRACO", 5) != 0)
        return gltf_fail(c, SSS_ERROR_PARSE, "%s: the buffer view does not hold a Draco stream", path);
    r.p += 5;
    if (!read_u8(&r, &major) || !read_u8(&r, &minor) || !read_u8(&r, &type) || !read_u8(&r, &method) ||
        !read_u8(&r, &flags) || !read_u8(&r, &skip_count))
        return gltf_fail(c, SSS_ERROR_PARSE, "%s: truncated Draco header", path);
    unsigned version = major << 8 | minor;
    flags |= skip_count << 8; /* little-endian 16 bits */
    if (major < 1 || version > 0x0202)
        return gltf_fail(c, SSS_ERROR_UNSUPPORTED, "%s: Draco bitstream version %u.%u (1.0 to 2.2 are read)", path,
                         major, minor);
    if (type != 1) return gltf_fail(c, SSS_ERROR_PARSE, "%s: a Draco point cloud, not a mesh", path);
    if (method > 1) return gltf_fail(c, SSS_ERROR_PARSE, "%s: unknown Draco method %u", path, method);
    int ok = version < 0x0103 || !(flags & 0x8000) || skip_metadata(&r);
    uint32_t points = 0, traversal = 0, new_vertices = 0;
    if (ok && method == 0)
        ok = read_count(&r, version, 0x0202, faces) && read_count(&r, version, 0x0202, &points);
    else if (ok)
        ok = read_u8(&r, &traversal) && (version >= 0x0202 || read_count(&r, version, 0x0200, &new_vertices)) &&
             read_count(&r, version, 0x0200, &points) && read_count(&r, version, 0x0200, faces);
    if (!ok) return gltf_fail(c, SSS_ERROR_PARSE, "%s: truncated Draco header (metadata or connectivity)", path);
    return SSS_OK;
}

/* The attributes the importer reads, with the components each must have. */
static const char *const names[3] = {"POSITION", "NORMAL", "TEXCOORD_0"};
static const int components[3] = {3, 3, 2};

/* Per attribute present in the extension: its unique id (ids) and the primitive's accessor for it
 * (counts: its count); present[i] says which; POSITION is required. */
static sss_result draco_attributes(gltf_ctx *c, const cJSON *primitive, const cJSON *ext, const char *dp,
                                   gltf_draco_attribute *attrs, size_t counts[3], int present[3])
{
    const cJSON *ids = gltf_get(ext, "attributes"), *accessors = gltf_get(primitive, "attributes");
    char ap[192], use[256];
    snprintf(ap, sizeof ap, "%s.attributes", dp);
    if (!cJSON_IsObject(ids)) return gltf_fail(c, SSS_ERROR_PARSE, "%s: expected an object", ap);
    for (int i = 0; i < 3; i++) {
        long id = 0, index = 0;
        gltf_accessor meta;
        long view = -1, offset = 0;
        if (!(present[i] = gltf_get(ids, names[i]) != NULL)) {
            if (i == 0) return gltf_fail(c, SSS_ERROR_PARSE, "%s.POSITION: required field missing", ap);
            continue;
        }
        snprintf(use, sizeof use, "%s.%s", ap, names[i]);
        sss_result res;
        if ((res = gltf_int(c, ids, ap, names[i], 1, 0, 0, 0xffffffffL, &id)) != SSS_OK ||
            (res = gltf_int(c, accessors, ap, names[i], 1, 0, 0, 1L << 30, &index)) != SSS_OK ||
            (res = gltf_accessor_meta(c, index, use, components[i], &meta, &view, &offset)) != SSS_OK)
            return res;
        attrs[i].unique_id = (uint32_t)id;
        attrs[i].components = components[i];
        counts[i] = meta.count;
    }
    return SSS_OK;
}

/* The decoded data as the source's accessors (floats, 32-bit indices), owned by src. */
static void fill_source(const gltf_draco_mesh *mesh, gltf_draco_attribute *attrs, const int present[3],
                        gltf_source *src)
{
    gltf_accessor *acc[3] = {&src->pos, &src->nrm, &src->uv};
    for (int i = 0; i < 3; i++) {
        if (!present[i]) continue;
        *acc[i] = (gltf_accessor){.base = (const unsigned char *)attrs[i].values, .count = mesh->point_count,
                                  .stride = (size_t)components[i] * 4, .components = components[i],
                                  .component_type = 5126};
        src->owned[i] = attrs[i].values;
    }
    src->has_nrm = present[1];
    src->has_uv = present[2];
    src->idx = (gltf_accessor){.base = (const unsigned char *)mesh->indices, .count = 3 * (size_t)mesh->face_count,
                               .stride = 4, .components = 1, .component_type = 5125};
    src->has_idx = 1;
    src->idx_accessor = -1;
    src->owned[3] = mesh->indices;
}

/* The stream's triangles against the indices accessor, the limit and the budget. */
static sss_result check_faces(gltf_ctx *c, const cJSON *primitive, const char *path, const char *dp, uint32_t faces)
{
    long index = -1, view = -1, offset = 0;
    gltf_accessor meta;
    char use[192];
    snprintf(use, sizeof use, "%s.indices", path);
    sss_result res = gltf_int(c, primitive, path, "indices", 0, -1, 0, 1L << 30, &index);
    if (res == SSS_OK && index >= 0) res = gltf_accessor_meta(c, index, use, 1, &meta, &view, &offset);
    if (res != SSS_OK) return res;
    if (index >= 0 && meta.count != 3 * (size_t)faces)
        return gltf_fail(c, SSS_ERROR_PARSE, "%s: the Draco stream holds %u triangles, accessors[%ld] %zu indices", dp,
                         faces, index, meta.count);
    if (faces == 0) return gltf_fail(c, SSS_ERROR_PARSE, "%s: no triangles", dp);
    if (faces > SSS_MESH_MAX_TRIANGLES)
        return gltf_fail(c, SSS_ERROR_LIMIT, "%s: %u triangles, more than the %u accepted", dp, faces,
                         (unsigned)SSS_MESH_MAX_TRIANGLES);
    return gltf_decoded_budget(c, (unsigned long long)faces * SSS_GLTF_DRACO_BYTES_PER_TRIANGLE, dp);
}

sss_result gltf_draco_source(gltf_ctx *c, const cJSON *primitive, const cJSON *ext, const char *path,
                             gltf_source *src)
{
    char dp[160], vp[192];
    snprintf(dp, sizeof dp, "%s.extensions.KHR_draco_mesh_compression", path);
    snprintf(vp, sizeof vp, "%s.bufferView", dp);
    gltf_draco_attribute attrs[3] = {{0}};
    size_t counts[3] = {0};
    int present[3] = {0};
    long view = 0;
    const unsigned char *data = NULL;
    size_t size = 0;
    uint32_t faces = 0;
    sss_result res;
    if ((res = gltf_object(c, ext, dp)) != SSS_OK ||
        (res = gltf_int(c, ext, dp, "bufferView", 1, 0, 0, 1L << 30, &view)) != SSS_OK ||
        (res = draco_attributes(c, primitive, ext, dp, attrs, counts, present)) != SSS_OK ||
        (res = gltf_buffer_view(c, view, vp, &data, &size)) != SSS_OK ||
        (res = stream_faces(c, data, size, dp, &faces)) != SSS_OK ||
        (res = check_faces(c, primitive, path, dp, faces)) != SSS_OK)
        return res;
    gltf_draco_attribute taken[3];
    int n = 0, slot[3];
    for (int i = 0; i < 3; i++)
        if (present[i]) slot[i] = n, taken[n++] = attrs[i];
    gltf_draco_mesh mesh;
    char msg[256];
    if (gltf_draco_decode(data, size, taken, n, &mesh, msg, sizeof msg) != 0)
        return gltf_fail(c, SSS_ERROR_PARSE, "%s: %s", dp, msg);
    for (int i = 0; i < 3; i++)
        if (present[i]) attrs[i] = taken[slot[i]];
    fill_source(&mesh, attrs, present, src);
    /* what the accessors say the decoded data holds (the spec: they "must match") */
    for (int i = 0; i < 3; i++)
        if (present[i] && counts[i] != mesh.point_count)
            return gltf_fail(c, SSS_ERROR_PARSE, "%s: the Draco stream decodes to %u points, the %s accessor has %zu",
                             dp, mesh.point_count, names[i], counts[i]);
    if (mesh.face_count != faces)
        return gltf_fail(c, SSS_ERROR_PARSE, "%s: %u triangles decoded, the header gives %u", dp, mesh.face_count, faces);
    return SSS_OK;
}
