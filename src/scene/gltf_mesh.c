/* glTF mesh primitives (glTF 2.0 spec, section 3.7.2) baked into world-space sss meshes: their accessors
 * (KHR_mesh_quantization's integer types included) or their KHR_draco_mesh_compression data. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/gltf_internal.h"

enum { MODE_TRIANGLES = 4, MODE_TRIANGLE_STRIP = 5, MODE_TRIANGLE_FAN = 6 };

/* Triangle t of a primitive of the given mode as positions in the index list (strips alternate
 * their winding so that every triangle keeps the first one's orientation; spec 3.7.2.1). */
static void triangle_corners(int mode, size_t t, size_t corner[3])
{
    if (mode == MODE_TRIANGLES) {
        corner[0] = 3 * t, corner[1] = 3 * t + 1, corner[2] = 3 * t + 2;
    } else if (mode == MODE_TRIANGLE_STRIP) {
        corner[0] = t + (t & 1), corner[1] = t + 1 - (t & 1), corner[2] = t + 2;
    } else {
        corner[0] = t + 1, corner[1] = t + 2, corner[2] = 0;
    }
}

/* The triangles of the source's index list (or of the vertices in order when it has none) by mode. */
static sss_result read_indices(gltf_ctx *c, const gltf_source *src, const char *path, int mode, size_t vertex_count,
                               sss_mesh *m)
{
    size_t corners = src->has_idx ? src->idx.count : vertex_count;
    char use[192];
    snprintf(use, sizeof use, "%s.indices", path);
    if (mode == MODE_TRIANGLES && corners % 3 != 0)
        return gltf_fail(c, SSS_ERROR_PARSE, "%s: %zu indices, not a multiple of 3", path, corners);
    size_t tris = mode == MODE_TRIANGLES ? corners / 3 : corners >= 3 ? corners - 2 : 0;
    if (tris == 0) return gltf_fail(c, SSS_ERROR_PARSE, "%s: no triangles", path);
    if (tris > SSS_MESH_MAX_TRIANGLES)
        return gltf_fail(c, SSS_ERROR_LIMIT, "%s: %zu triangles, more than the %u accepted", path, tris,
                         (unsigned)SSS_MESH_MAX_TRIANGLES);
    if (!(m->indices = malloc(3 * tris * sizeof *m->indices)))
        return gltf_fail(c, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    m->triangle_count = (uint32_t)tris;
    for (size_t t = 0; t < tris; t++) {
        size_t corner[3];
        triangle_corners(mode, t, corner);
        for (int k = 0; k < 3; k++) {
            uint32_t v = src->has_idx ? gltf_accessor_uint(&src->idx, corner[k]) : (uint32_t)corner[k];
            if (v >= vertex_count && src->idx_accessor >= 0)
                return gltf_fail(c, SSS_ERROR_PARSE, "%s: accessors[%ld][%zu] = %u is out of range (%zu vertices)",
                                 use, src->idx_accessor, corner[k], v, vertex_count);
            if (v >= vertex_count)
                return gltf_fail(c, SSS_ERROR_PARSE, "%s: decoded index %zu = %u is out of range (%zu vertices)", use,
                                 corner[k], v, vertex_count);
            m->indices[3 * t + (size_t)k] = v;
        }
    }
    return SSS_OK;
}

/* Component types the core spec allows per attribute (3.7.2.1), and those KHR_mesh_quantization adds:
 * POSITION float (+ [u]byte, [u]short, normalized or not); NORMAL float (+ byte, short normalized);
 * TEXCOORD float, normalized ubyte/ushort (+ byte, short, normalized or not; ubyte, ushort not). */
static int attribute_type_ok(int attribute, const gltf_accessor *a, int quantization)
{
    int t = a->component_type, n = a->normalized;
    if (t == 5126) return !n;
    if (t == 5125) return 0;
    if (attribute == 0) return quantization;                                             /* POSITION */
    if (attribute == 1) return quantization && n && (t == 5120 || t == 5122);            /* NORMAL */
    return (n && (t == 5121 || t == 5123)) || (quantization && (t == 5120 || t == 5122 || !n)); /* TEXCOORD */
}

/* POSITION, NORMAL and TEXCOORD_0 (the ones present) and the indices of a primitive without Draco: its
 * accessors, each of an allowed component type. */
static sss_result plain_source(gltf_ctx *c, const cJSON *primitive, const cJSON *attributes, const char *path,
                               gltf_source *src)
{
    static const char *const names[3] = {"POSITION", "NORMAL", "TEXCOORD_0"};
    gltf_accessor *acc[3] = {&src->pos, &src->nrm, &src->uv};
    int *has[3] = {NULL, &src->has_nrm, &src->has_uv};
    char use[256], at[160];
    snprintf(at, sizeof at, "%s.attributes", path);
    sss_result res;
    for (int i = 0; i < 3; i++) {
        long index = 0;
        if (i > 0 && !(*has[i] = gltf_get(attributes, names[i]) != NULL)) continue;
        snprintf(use, sizeof use, "%s.%s", at, names[i]);
        if ((res = gltf_int(c, attributes, at, names[i], 1, 0, 0, 1L << 30, &index)) != SSS_OK ||
            (res = gltf_accessor_get(c, index, use, i == 2 ? 2 : 3, acc[i])) != SSS_OK)
            return res;
        if (!attribute_type_ok(i, acc[i], c->quantization))
            return gltf_fail(c, SSS_ERROR_UNSUPPORTED, "%s: accessors[%ld] has componentType %d%s, not allowed%s", use,
                             index, acc[i]->component_type, acc[i]->normalized ? " (normalized)" : "",
                             c->quantization ? "" : " without KHR_mesh_quantization");
    }
    snprintf(use, sizeof use, "%s.indices", path);
    if ((res = gltf_int(c, primitive, path, "indices", 0, -1, 0, 1L << 30, &src->idx_accessor)) != SSS_OK) return res;
    if (!(src->has_idx = src->idx_accessor >= 0)) return SSS_OK;
    if ((res = gltf_accessor_get(c, src->idx_accessor, use, 1, &src->idx)) != SSS_OK) return res;
    if (src->idx.component_type != 5121 && src->idx.component_type != 5123 && src->idx.component_type != 5125)
        return gltf_fail(c, SSS_ERROR_PARSE, "%s: accessors[%ld] must hold unsigned integers", use, src->idx_accessor);
    return SSS_OK;
}

void gltf_source_free(gltf_source *src)
{
    for (int i = 0; i < 4; i++) free(src->owned[i]);
    memset(src, 0, sizeof *src);
}

/* The cofactor matrix of the upper 3x3 of a row-major 4x4: normals transform with it (it is
 * det(M) M^-T, defined also for singular M). */
static void cofactor3(const double m[16], double cof[9])
{
#define A(r, c) m[4 * (r) + (c)]
    for (int r = 0; r < 3; r++)
        for (int col = 0; col < 3; col++) {
            int r1 = (r + 1) % 3, r2 = (r + 2) % 3, c1 = (col + 1) % 3, c2 = (col + 2) % 3;
            cof[3 * r + col] = A(r1, c1) * A(r2, c2) - A(r1, c2) * A(r2, c1);
        }
#undef A
}

static double det3(const double m[16])
{
    return m[0] * (m[5] * m[10] - m[6] * m[9]) - m[1] * (m[4] * m[10] - m[6] * m[8]) +
           m[2] * (m[4] * m[9] - m[5] * m[8]);
}

/* The source's POSITION, NORMAL, TEXCOORD_0 into m (world space); *normals_ok = 0 when the file has no
 * normals or one of them vanishes (they are then computed from the triangles). */
static sss_result read_vertices(gltf_ctx *c, long node, const gltf_source *src, const char *path,
                                const double world[16], sss_mesh *m, int *normals_ok)
{
    const gltf_accessor *pos = &src->pos, *nrm = &src->nrm, *uv = &src->uv;
    if (pos->count > SSS_MESH_MAX_VERTICES)
        return gltf_fail(c, SSS_ERROR_LIMIT, "%s.attributes.POSITION: %zu vertices, more than the %u accepted", path,
                         pos->count, (unsigned)SSS_MESH_MAX_VERTICES);
    size_t n = pos->count;
    int has_normals = src->has_nrm, has_uvs = src->has_uv;
    if (has_normals && nrm->count != n)
        return gltf_fail(c, SSS_ERROR_PARSE, "%s.attributes.NORMAL: %zu normals for %zu positions", path, nrm->count, n);
    if (has_uvs && uv->count != n)
        return gltf_fail(c, SSS_ERROR_PARSE, "%s.attributes.TEXCOORD_0: %zu UVs for %zu positions", path, uv->count, n);
    m->vertex_count = (uint32_t)n;
    m->positions = malloc(3 * n * sizeof *m->positions);
    m->normals = malloc(3 * n * sizeof *m->normals);
    m->uvs = has_uvs ? malloc(2 * n * sizeof *m->uvs) : NULL;
    if (!m->positions || !m->normals || (has_uvs && !m->uvs))
        return gltf_fail(c, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory for %zu vertices", path, n);
    double cof[9];
    cofactor3(world, cof);
    double sign = det3(world) < 0 ? -1.0 : 1.0; /* cof = det(M) M^-T: undo a negative det's flip */
    *normals_ok = has_normals;
    for (size_t i = 0; i < n; i++) {
        for (int r = 0; r < 3; r++) {
            double p = world[4 * r + 3];
            for (int k = 0; k < 3; k++) p += world[4 * r + k] * gltf_accessor_float(pos, i, k);
            if (isnan(p)) return gltf_fail(c, SSS_ERROR_PARSE, "%s: vertex %zu is not a number", path, i);
            /* the scene loader's world range (sss/scene.h), named here by the node that puts it there */
            if (!(fabs(p) <= SSS_SCENE_MAX_WORLD_COORD))
                return gltf_fail(c, SSS_ERROR_LIMIT,
                                 "nodes[%ld] places %s vertex %zu at %g, beyond %g (the real-time renderer's "
                                 "single-precision range; docs/limits.md)",
                                 node, path, i, p, SSS_SCENE_MAX_WORLD_COORD);
            m->positions[3 * i + (size_t)r] = (float)p;
        }
        if (has_normals) {
            double w[3], len2 = 0;
            for (int r = 0; r < 3; r++) {
                w[r] = 0;
                for (int k = 0; k < 3; k++) w[r] += sign * cof[3 * r + k] * gltf_accessor_float(nrm, i, k);
                len2 += w[r] * w[r];
            }
            if (!(len2 > 0) || !isfinite(len2)) *normals_ok = 0;
            for (int r = 0; r < 3; r++) m->normals[3 * i + (size_t)r] = *normals_ok ? (float)(w[r] / sqrt(len2)) : 0.0f;
        }
        if (has_uvs) {
            /* glTF's UV origin is the image's top-left corner; sss's (OpenGL's) the bottom-left. */
            m->uvs[2 * i] = (float)gltf_accessor_float(uv, i, 0);
            m->uvs[2 * i + 1] = (float)(1.0 - gltf_accessor_float(uv, i, 1));
            if (!isfinite(m->uvs[2 * i]) || !isfinite(m->uvs[2 * i + 1]))
                return gltf_fail(c, SSS_ERROR_PARSE, "%s: TEXCOORD_0 of vertex %zu is not finite", path, i);
        }
    }
    return SSS_OK;
}

sss_result gltf_primitive_mesh(gltf_ctx *c, long node, long mesh_index, long prim, const cJSON *primitive,
                               const double world[16], sss_mesh *out, int *has_uvs)
{
    char path[96];
    snprintf(path, sizeof path, "meshes[%ld].primitives[%ld]", mesh_index, prim);
    memset(out, 0, sizeof *out);
    long mode = MODE_TRIANGLES;
    sss_result res = gltf_object(c, primitive, path);
    if (res == SSS_OK) res = gltf_int(c, primitive, path, "mode", 0, MODE_TRIANGLES, 0, 6, &mode);
    if (res == SSS_OK && mode < MODE_TRIANGLES)
        res = gltf_fail(c, SSS_ERROR_UNSUPPORTED, "%s.mode: %ld (points or lines) is not supported", path, mode);
    const cJSON *attributes = gltf_get(primitive, "attributes");
    if (res == SSS_OK && !cJSON_IsObject(attributes))
        res = gltf_fail(c, SSS_ERROR_PARSE, "%s.attributes: expected an object", path);
    const cJSON *draco = gltf_get(gltf_get(primitive, "extensions"), "KHR_draco_mesh_compression");
    char dp[160];
    snprintf(dp, sizeof dp, "%s.extensions.KHR_draco_mesh_compression", path);
    /* Draco decodes a triangle list (its faces); strips and fans are not defined for it here */
    if (res == SSS_OK && draco && mode != MODE_TRIANGLES)
        res = gltf_fail(c, SSS_ERROR_UNSUPPORTED, "%s: mode %ld with Draco (only triangle lists are supported)", dp, mode);
    gltf_source src = {.idx_accessor = -1};
    if (res == SSS_OK)
        res = draco ? gltf_draco_source(c, primitive, draco, path, &src)
                    : plain_source(c, primitive, attributes, path, &src);
    int normals_ok = 0;
    if (res == SSS_OK) res = read_vertices(c, node, &src, path, world, out, &normals_ok);
    if (res == SSS_OK) res = read_indices(c, &src, path, (int)mode, out->vertex_count, out);
    gltf_source_free(&src);
    if (res == SSS_OK && det3(world) < 0) /* a mirroring transform turns counter-clockwise into clockwise */
        for (uint32_t t = 0; t < out->triangle_count; t++) {
            uint32_t tmp = out->indices[3 * t + 1];
            out->indices[3 * t + 1] = out->indices[3 * t + 2];
            out->indices[3 * t + 2] = tmp;
        }
    if (res == SSS_OK && !normals_ok) res = sss_mesh_compute_normals(out, c->err);
    if (res != SSS_OK) {
        sss_mesh_free(out);
        return res;
    }
    out->source_flags = (normals_ok ? SSS_MESH_FROM_FILE_NORMALS : 0u) | (out->uvs ? SSS_MESH_FROM_FILE_UVS : 0u);
    *has_uvs = out->uvs != NULL;
    return SSS_OK;
}
