/* mesh/ply_write.c — binary little-endian PLY (float positions, normals, optional UVs; uchar/uint
 * triangle lists), written through a temporary file so a failed run leaves nothing behind. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/file_util.h"
#include "mesh/mesh_internal.h"

typedef struct out_buffer {
    FILE *f;
    size_t used;
    unsigned char data[1 << 16];
} out_buffer;

static void flush(out_buffer *b)
{
    if (b->used) fwrite(b->data, 1, b->used, b->f); /* errors surface in sss_atomic_close (ferror) */
    b->used = 0;
}

/* Explicit little-endian bytes, whatever the host's byte order. */
static void put_u32(out_buffer *b, uint32_t v)
{
    if (b->used + 4 > sizeof b->data) flush(b);
    for (int i = 0; i < 4; i++) b->data[b->used++] = (unsigned char)(v >> (8 * i));
}

static void put_f32(out_buffer *b, float f)
{
    uint32_t v;
    memcpy(&v, &f, sizeof v);
    put_u32(b, v);
}

static sss_result validate(const char *path, const sss_mesh *m, sss_error *err)
{
    if (!m || !m->positions || !m->indices || m->vertex_count == 0 || m->triangle_count == 0)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "%s: nothing to write (empty mesh)", path);
    if (m->vertex_count > SSS_MESH_MAX_VERTICES || m->triangle_count > SSS_MESH_MAX_TRIANGLES)
        return sss_error_set(err, SSS_ERROR_LIMIT, "%s: mesh exceeds the size limits", path);
    for (size_t i = 0; i < (size_t)m->vertex_count * 3; i++)
        if (!isfinite(m->positions[i]) || (m->normals && !isfinite(m->normals[i])))
            return sss_error_set(err, SSS_ERROR_NUMERIC, "%s: vertex %zu has a non-finite position or normal", path, i / 3);
    if (m->uvs)
        for (size_t i = 0; i < (size_t)m->vertex_count * 2; i++)
            if (!isfinite(m->uvs[i]))
                return sss_error_set(err, SSS_ERROR_NUMERIC, "%s: vertex %zu has a non-finite UV", path, i / 2);
    for (size_t i = 0; i < (size_t)m->triangle_count * 3; i++)
        if (m->indices[i] >= m->vertex_count)
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "%s: triangle %zu: index %u out of range (%u vertices)",
                                 path, i / 3, m->indices[i], m->vertex_count);
    return SSS_OK;
}

sss_result sss_mesh_write_ply(const char *path, const sss_mesh *mesh, sss_error *err)
{
    sss_result r = validate(path, mesh, err);
    if (r != SSS_OK) return r;
    char tmp[4096];
    FILE *f = sss_atomic_open(path, tmp, sizeof tmp, err);
    if (!f) return err ? err->code : SSS_ERROR_IO;
    fprintf(f, "ply\nformat binary_little_endian 1.0\ncomment written by sss\nelement vertex %u\n"
               "property float x\nproperty float y\nproperty float z\n",
            mesh->vertex_count);
    if (mesh->normals) fprintf(f, "property float nx\nproperty float ny\nproperty float nz\n");
    if (mesh->uvs) fprintf(f, "property float u\nproperty float v\n");
    fprintf(f, "element face %u\nproperty list uchar uint vertex_indices\nend_header\n", mesh->triangle_count);
    out_buffer *ob = malloc(sizeof *ob); /* 64 KiB: kept off the stack */
    if (!ob) {
        fclose(f);
        sss_discard_temp(tmp);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    }
    ob->f = f;
    ob->used = 0;
    for (size_t v = 0; v < mesh->vertex_count; v++) {
        for (int k = 0; k < 3; k++) put_f32(ob, mesh->positions[3 * v + (size_t)k]);
        if (mesh->normals)
            for (int k = 0; k < 3; k++) put_f32(ob, mesh->normals[3 * v + (size_t)k]);
        if (mesh->uvs)
            for (int k = 0; k < 2; k++) put_f32(ob, mesh->uvs[2 * v + (size_t)k]);
    }
    for (size_t t = 0; t < mesh->triangle_count; t++) {
        if (ob->used + 1 > sizeof ob->data) flush(ob);
        ob->data[ob->used++] = 3;
        for (int k = 0; k < 3; k++) put_u32(ob, mesh->indices[3 * t + (size_t)k]);
    }
    flush(ob);
    free(ob);
    return sss_atomic_close(f, tmp, path, err);
}
