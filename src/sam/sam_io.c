/* sam/sam_io.c — the .sam file: a versioned little-endian header that ties the map to its mesh
 * (counts + hash of positions and indices), material, profile model and transform, then the per-vertex
 * data and a checksum. Version 2 adds the back-side mesh (sam_back.c); maps without one are written as
 * version 1. Written atomically; reading checks every size before allocating. docs/sam_format.md. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/file_util.h"
#include "sam/sam_internal.h"

static const char MAGIC[8] = {'S', 'S', 'S', 'S', 'A', 'M', '1', '\n'};
#define HEADER_BYTES 320 /* fixed: see put_header */

/* ---- little-endian encoding with a running FNV-1a 64 checksum --------------------------------- */

typedef struct writer {
    FILE *f;
    uint64_t hash;
    int failed;
} writer;

static void w_bytes(writer *w, const void *data, size_t n)
{
    const uint8_t *p = data;
    for (size_t i = 0; i < n; i++) w->hash = (w->hash ^ p[i]) * 0x100000001b3ull;
    if (fwrite(data, 1, n, w->f) != n) w->failed = 1;
}

static void w_u32(writer *w, uint32_t v)
{
    uint8_t b[4] = {(uint8_t)v, (uint8_t)(v >> 8), (uint8_t)(v >> 16), (uint8_t)(v >> 24)};
    w_bytes(w, b, 4);
}

static void w_u64(writer *w, uint64_t v)
{
    w_u32(w, (uint32_t)v);
    w_u32(w, (uint32_t)(v >> 32));
}

static void w_f64(writer *w, double d)
{
    uint64_t u;
    memcpy(&u, &d, 8);
    w_u64(w, u);
}

static void w_f32s(writer *w, const float *v, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        uint32_t u;
        memcpy(&u, &v[i], 4);
        w_u32(w, u);
    }
}

typedef struct reader {
    const uint8_t *p;
    size_t at, size;
} reader;

static uint32_t r_u32(reader *r)
{
    const uint8_t *b = r->p + r->at;
    r->at += 4;
    return (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24;
}

static uint64_t r_u64(reader *r)
{
    uint64_t lo = r_u32(r);
    return lo | (uint64_t)r_u32(r) << 32;
}

static double r_f64(reader *r)
{
    uint64_t u = r_u64(r);
    double d;
    memcpy(&d, &u, 8);
    return d;
}

static float r_f32(reader *r)
{
    uint32_t u = r_u32(r);
    float f;
    memcpy(&f, &u, 4);
    return f;
}

static uint64_t fnv(const uint8_t *p, size_t n)
{
    uint64_t h = 0xcbf29ce484222325ull;
    for (size_t i = 0; i < n; i++) h = (h ^ p[i]) * 0x100000001b3ull;
    return h;
}

#define BACK_HAS_UVS 1u

/* Header layout (320 bytes): magic[8], version u32, header bytes u32, vertex count u32, triangle count
 * u32, n u32, samples u32, mesh hash u64, seed u64, profile model u32, reserved u32, energy f64,
 * sigma_a[3] f64, sigma_s[3] f64, eta f64, g f64, transform[16] f64; version 2 only: back-side vertex
 * count u32, back-side triangle count u32, back-side mesh hash u64, back-side flags u32 (bit 0: UVs),
 * reserved u32; zero padding to 320. */
static void put_header(writer *w, const sss_sam *s)
{
    int v2 = s->back_vertex_count > 0;
    w_bytes(w, MAGIC, 8);
    w_u32(w, v2 ? 2u : 1u);
    w_u32(w, HEADER_BYTES);
    w_u32(w, s->vertex_count);
    w_u32(w, s->triangle_count);
    w_u32(w, s->n);
    w_u32(w, s->samples);
    w_u64(w, s->mesh_hash);
    w_u64(w, s->seed);
    w_u32(w, (uint32_t)s->model);
    w_u32(w, 0);
    w_f64(w, s->energy);
    for (int c = 0; c < 3; c++) w_f64(w, s->material.sigma_a[c]);
    for (int c = 0; c < 3; c++) w_f64(w, s->material.sigma_s[c]);
    w_f64(w, s->material.eta);
    w_f64(w, s->material.g);
    for (int i = 0; i < 16; i++) w_f64(w, s->transform[i]);
    /* 8 + 4*6 + 8*2 + 4*2 + 8 + 8*8 + 8*16 = 256 bytes so far */
    size_t at = 256;
    if (v2) {
        w_u32(w, s->back_vertex_count);
        w_u32(w, s->back_triangle_count);
        w_u64(w, s->back_hash);
        w_u32(w, s->back_uvs ? BACK_HAS_UVS : 0u);
        w_u32(w, 0);
        at += 24;
    }
    uint8_t pad[HEADER_BYTES - 256];
    memset(pad, 0, sizeof pad);
    w_bytes(w, pad, HEADER_BYTES - at);
}

sss_result sss_sam_write(const char *path, const sss_sam *sam, sss_error *err)
{
    if (!path || !sam || (sam->vertex_count && (!sam->fan_area || !sam->links || !sam->form_factor || !sam->kprime)) ||
        (sam->back_vertex_count && (!sam->back_positions || !sam->back_normals || !sam->back_fan_area ||
                                    !sam->back_indices || sam->back_triangle_count == 0)))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sam: nothing to write");
    char tmp[4096];
    FILE *f = sss_atomic_open(path, tmp, sizeof tmp, err);
    if (!f) return err ? err->code : SSS_ERROR_IO;
    writer w = {f, 0xcbf29ce484222325ull, 0};
    put_header(&w, sam);
    size_t nv = sam->vertex_count, slots = nv * sam->n;
    w_f32s(&w, sam->fan_area, nv);
    for (size_t i = 0; i < slots; i++) w_u32(&w, sam->links[i]);
    w_f32s(&w, sam->form_factor, 3 * slots);
    w_f32s(&w, sam->kprime, 3 * slots);
    if (sam->back_vertex_count) {
        size_t bv = sam->back_vertex_count;
        w_f32s(&w, sam->back_positions, 3 * bv);
        w_f32s(&w, sam->back_normals, 3 * bv);
        if (sam->back_uvs) w_f32s(&w, sam->back_uvs, 2 * bv);
        w_f32s(&w, sam->back_fan_area, bv);
        for (size_t i = 0; i < 3 * (size_t)sam->back_triangle_count; i++) w_u32(&w, sam->back_indices[i]);
    }
    uint64_t h = w.hash;
    w_u64(&w, h);
    if (w.failed) {
        fclose(f);
        sss_discard_temp(tmp);
        return sss_error_set(err, SSS_ERROR_IO, "%s: write failed", path);
    }
    return sss_atomic_close(f, tmp, path, err);
}

/* The back-side mesh of a version-2 file (sizes already checked against the file's). */
static sss_result read_back(reader *b, const char *path, uint32_t flags, sss_sam *s, sss_error *err)
{
    size_t bv = s->back_vertex_count, bt = s->back_triangle_count;
    s->back_positions = malloc(sizeof(float) * 3 * bv);
    s->back_normals = malloc(sizeof(float) * 3 * bv);
    s->back_fan_area = malloc(sizeof(float) * bv);
    s->back_indices = malloc(sizeof(uint32_t) * 3 * bt);
    if (flags & BACK_HAS_UVS) s->back_uvs = malloc(sizeof(float) * 2 * bv);
    if (!s->back_positions || !s->back_normals || !s->back_fan_area || !s->back_indices ||
        ((flags & BACK_HAS_UVS) && !s->back_uvs))
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory (back-side mesh)", path);
    float *arrays[3] = {s->back_positions, s->back_normals, s->back_uvs};
    size_t sizes[3] = {3 * bv, 3 * bv, s->back_uvs ? 2 * bv : 0};
    for (int a = 0; a < 3; a++)
        for (size_t i = 0; i < sizes[a]; i++) {
            arrays[a][i] = r_f32(b);
            if (!isfinite(arrays[a][i]))
                return sss_error_set(err, SSS_ERROR_PARSE, "%s: back-side mesh: vertex %zu is not finite", path,
                                     i / (a == 2 ? 2 : 3));
        }
    for (size_t i = 0; i < bv; i++) {
        s->back_fan_area[i] = r_f32(b);
        if (!isfinite(s->back_fan_area[i]) || s->back_fan_area[i] < 0.0f)
            return sss_error_set(err, SSS_ERROR_PARSE, "%s: back-side mesh: vertex %zu: bad fan area", path, i);
    }
    for (size_t i = 0; i < 3 * bt; i++) {
        s->back_indices[i] = r_u32(b);
        if (s->back_indices[i] >= bv)
            return sss_error_set(err, SSS_ERROR_PARSE, "%s: back-side mesh: triangle %zu: index %u out of range", path,
                                 i / 3, s->back_indices[i]);
    }
    sss_mesh view;
    sss_sam_back_mesh(s, &view);
    if (sss_sam_mesh_hash(&view) != s->back_hash)
        return sss_error_set(err, SSS_ERROR_PARSE, "%s: the back-side mesh does not match its recorded hash", path);
    return SSS_OK;
}

/* The header's floats: finite and within what the writer's inputs allow (eta as sss/material.h, |g| < 1,
 * coefficients >= 0, the table's energy fraction in (0, 1]); a checksum is easy to repair, so a NaN
 * here must be caught before it reaches the renderer. */
static sss_result check_header_floats(const sss_sam *s, const char *name, sss_error *err)
{
    const sss_material *m = &s->material;
    if (!(s->energy > 0.0 && s->energy <= 1.0))
        return sss_error_set(err, SSS_ERROR_PARSE, "%s: header: energy %g is outside (0, 1]", name, s->energy);
    for (int c = 0; c < 3; c++)
        if (!(m->sigma_a[c] >= 0.0 && isfinite(m->sigma_a[c])) || !(m->sigma_s[c] >= 0.0 && isfinite(m->sigma_s[c])))
            return sss_error_set(err, SSS_ERROR_PARSE,
                                 "%s: header: sigma_a %g, sigma_s %g (channel %d) must be finite and >= 0", name,
                                 m->sigma_a[c], m->sigma_s[c], c);
    if (!(m->eta >= SSS_ETA_MIN && m->eta <= SSS_ETA_MAX))
        return sss_error_set(err, SSS_ERROR_PARSE, "%s: header: eta %g is outside [%g, %g]", name, m->eta, SSS_ETA_MIN,
                             SSS_ETA_MAX);
    if (!(m->g > -1.0 && m->g < 1.0))
        return sss_error_set(err, SSS_ERROR_PARSE, "%s: header: g %g is outside (-1, 1)", name, m->g);
    for (int i = 0; i < 16; i++)
        if (!isfinite(s->transform[i]))
            return sss_error_set(err, SSS_ERROR_PARSE, "%s: header: transform entry %d is %g", name, i,
                                 s->transform[i]);
    return SSS_OK;
}

/* The fixed header: counts, material, transform (into s) and the file size they imply (*expect).
 * head holds the first got bytes of the input. Nothing is allocated. */
static sss_result parse_header(const uint8_t *head, size_t got, const char *name, sss_sam *s, uint32_t *back_flags,
                               uint64_t *expect, sss_error *err)
{
    memset(s, 0, sizeof *s);
    *back_flags = 0;
    if (got < 16 || memcmp(head, MAGIC, 8) != 0)
        return sss_error_set(err, SSS_ERROR_PARSE, "%s: not a .sam file (bad magic)", name);
    reader r = {head, 8, got};
    uint32_t version = r_u32(&r), hbytes = r_u32(&r);
    if (version < 1 || version > SSS_SAM_FORMAT_VERSION || hbytes != HEADER_BYTES)
        return sss_error_set(err, SSS_ERROR_UNSUPPORTED,
                             "%s: .sam version %u (header %u bytes); this build reads versions 1 to %u", name, version,
                             hbytes, SSS_SAM_FORMAT_VERSION);
    if (got < HEADER_BYTES)
        return sss_error_set(err, SSS_ERROR_PARSE, "%s: truncated header (%zu of %d bytes)", name, got, HEADER_BYTES);
    s->vertex_count = r_u32(&r);
    s->triangle_count = r_u32(&r);
    s->n = r_u32(&r);
    s->samples = r_u32(&r);
    s->mesh_hash = r_u64(&r);
    s->seed = r_u64(&r);
    uint32_t model = r_u32(&r);
    (void)r_u32(&r);
    s->energy = r_f64(&r);
    for (int c = 0; c < 3; c++) s->material.sigma_a[c] = r_f64(&r);
    for (int c = 0; c < 3; c++) s->material.sigma_s[c] = r_f64(&r);
    s->material.eta = r_f64(&r);
    s->material.g = r_f64(&r);
    for (int i = 0; i < 16; i++) s->transform[i] = r_f64(&r);
    if (version >= 2) {
        s->back_vertex_count = r_u32(&r);
        s->back_triangle_count = r_u32(&r);
        s->back_hash = r_u64(&r);
        *back_flags = r_u32(&r);
        if (s->back_vertex_count == 0 || s->back_vertex_count > SSS_MESH_MAX_VERTICES || s->back_triangle_count == 0 ||
            s->back_triangle_count > SSS_MESH_MAX_TRIANGLES || (*back_flags & ~BACK_HAS_UVS) != 0)
            return sss_error_set(err, SSS_ERROR_PARSE,
                                 "%s: back-side mesh header out of range (%u vertices, %u triangles, flags %u)", name,
                                 s->back_vertex_count, s->back_triangle_count, *back_flags);
    }
    if (s->vertex_count == 0 || s->vertex_count > SSS_MESH_MAX_VERTICES || s->triangle_count == 0 ||
        s->triangle_count > SSS_MESH_MAX_TRIANGLES || s->n < 1 || s->n > SSS_SAM_MAX_N || s->samples < 1 ||
        s->samples > SSS_SAM_MAX_SAMPLES || model > (uint32_t)SSS_PROFILE_GAUSS6)
        return sss_error_set(err, SSS_ERROR_PARSE,
                             "%s: header out of range (%u vertices, %u triangles, n = %u, %u samples, model %u)", name,
                             s->vertex_count, s->triangle_count, s->n, s->samples, model);
    s->model = (sss_profile_model)model;
    sss_result res = check_header_floats(s, name, err);
    if (res != SSS_OK) return res;
    uint64_t nv = s->vertex_count, slots = nv * s->n;
    uint64_t bv = s->back_vertex_count, bt = s->back_triangle_count;
    uint64_t back_bytes = bv ? 4 * (7 * bv + ((*back_flags & BACK_HAS_UVS) ? 2 * bv : 0) + 3 * bt) : 0;
    *expect = HEADER_BYTES + 4 * nv + 4 * slots + 24 * slots + back_bytes + 8;
    return SSS_OK;
}

static sss_result size_error(const char *name, uint64_t size, uint64_t expect, sss_error *err)
{
    return sss_error_set(err, SSS_ERROR_PARSE, "%s: %s (%llu bytes; the header promises %llu)", name,
                         size < expect ? "truncated" : "trailing data", (unsigned long long)size,
                         (unsigned long long)expect);
}

sss_result sss_sam_decode(const void *bytes, size_t size, const char *name, sss_sam *out, sss_error *err)
{
    if (out) memset(out, 0, sizeof *out);
    if (!name) name = "<memory>";
    if ((!bytes && size) || !out) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sam: no input or output");
    const uint8_t *data = bytes;
    sss_sam s;
    uint32_t back_flags;
    uint64_t expect;
    sss_result res = parse_header(data, size < HEADER_BYTES ? size : HEADER_BYTES, name, &s, &back_flags, &expect, err);
    if (res != SSS_OK) return res;
    /* The input must hold exactly what the header promises (checked before allocating). */
    if ((uint64_t)size != expect) return size_error(name, size, expect, err);
    reader b = {data, (size_t)expect - 8, (size_t)expect};
    uint64_t stored = r_u64(&b);
    if (stored != fnv(data, (size_t)expect - 8))
        return sss_error_set(err, SSS_ERROR_PARSE, "%s: checksum mismatch (corrupted file)", name);
    uint64_t nv = s.vertex_count, slots = nv * s.n, bv = s.back_vertex_count;
    s.fan_area = malloc(sizeof(float) * nv);
    s.links = malloc(sizeof(uint32_t) * slots);
    s.form_factor = malloc(sizeof(float) * 3 * slots);
    s.kprime = malloc(sizeof(float) * 3 * slots);
    if (!s.fan_area || !s.links || !s.form_factor || !s.kprime)
        res = sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory", name);
    b.at = HEADER_BYTES;
    for (uint64_t i = 0; res == SSS_OK && i < nv; i++) {
        s.fan_area[i] = r_f32(&b);
        if (!isfinite(s.fan_area[i]) || s.fan_area[i] < 0.0f)
            res = sss_error_set(err, SSS_ERROR_PARSE, "%s: vertex %llu: bad fan area", name, (unsigned long long)i);
    }
    for (uint64_t i = 0; res == SSS_OK && i < slots; i++) {
        s.links[i] = r_u32(&b);
        /* links index the back-side mesh when there is one */
        if (s.links[i] != SSS_SAM_NONE && s.links[i] >= (bv ? s.back_vertex_count : s.vertex_count))
            res = sss_error_set(err, SSS_ERROR_PARSE, "%s: vertex %llu: link %u out of range", name,
                                (unsigned long long)(i / s.n), s.links[i]);
    }
    for (uint64_t i = 0; res == SSS_OK && i < 3 * slots; i++) {
        s.form_factor[i] = r_f32(&b);
        if (!isfinite(s.form_factor[i]) || s.form_factor[i] < 0.0f)
            res = sss_error_set(err, SSS_ERROR_PARSE, "%s: bad form factor", name);
    }
    for (uint64_t i = 0; res == SSS_OK && i < 3 * slots; i++) {
        s.kprime[i] = r_f32(&b);
        if (!isfinite(s.kprime[i]) || s.kprime[i] < 0.0f) res = sss_error_set(err, SSS_ERROR_PARSE, "%s: bad K'", name);
    }
    if (res == SSS_OK && bv) res = read_back(&b, name, back_flags, &s, err);
    if (res != SSS_OK) {
        sss_sam_free(&s);
        return res;
    }
    *out = s;
    return SSS_OK;
}

sss_result sss_sam_read(const char *path, sss_sam *out, sss_error *err)
{
    if (out) memset(out, 0, sizeof *out);
    if (!path || !out) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sam: no file or output");
    uint64_t size = 0;
    FILE *f = sss_fopen_input(path, SSS_FILE_ANY_SIZE, &size, err);
    if (!f) return err ? err->code : SSS_ERROR_IO;
    /* The header first: its sizes are checked against the file's before the body is allocated. */
    uint8_t head[HEADER_BYTES];
    size_t got = fread(head, 1, sizeof head, f);
    sss_sam probe;
    uint32_t back_flags;
    uint64_t expect;
    sss_result res = parse_header(head, got, path, &probe, &back_flags, &expect, err);
    if (res != SSS_OK) {
        fclose(f);
        return res;
    }
    if (size != expect) {
        fclose(f);
        return size_error(path, size, expect, err);
    }
    uint8_t *data = malloc((size_t)expect);
    if (!data) {
        fclose(f);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory (%llu bytes)", path,
                             (unsigned long long)expect);
    }
    rewind(f);
    size_t n = fread(data, 1, (size_t)expect, f);
    fclose(f);
    if (n != expect) {
        free(data);
        return sss_error_set(err, SSS_ERROR_IO, "%s: read failed", path);
    }
    res = sss_sam_decode(data, (size_t)expect, path, out, err);
    free(data);
    return res;
}

sss_result sss_sam_check(const sss_sam *sam, const sss_mesh *mesh, const sss_material *material,
                         sss_profile_model model, const double *transform, const char *name, sss_error *err)
{
    if (!name) name = "sam";
    if (!sam || !mesh) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "%s: no map or mesh", name);
    uint64_t h = sss_sam_mesh_hash(mesh);
    if (sam->vertex_count != mesh->vertex_count || sam->triangle_count != mesh->triangle_count || sam->mesh_hash != h)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                             "%s: built for a different mesh (%u vertices, %u triangles, hash %016llx; this mesh has "
                             "%u, %u, hash %016llx)",
                             name, sam->vertex_count, sam->triangle_count, (unsigned long long)sam->mesh_hash,
                             mesh->vertex_count, mesh->triangle_count, (unsigned long long)h);
    if (material) {
        const sss_material *m = &sam->material;
        int same = m->eta == material->eta && m->g == material->g;
        for (int c = 0; c < 3; c++) same = same && m->sigma_a[c] == material->sigma_a[c] && m->sigma_s[c] == material->sigma_s[c];
        if (!same)
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                                 "%s: built for a different material (sigma_a %g %g %g, sigma_s %g %g %g, eta %g per "
                                 "scene unit; expected sigma_a %g %g %g, sigma_s %g %g %g, eta %g)",
                                 name, m->sigma_a[0], m->sigma_a[1], m->sigma_a[2], m->sigma_s[0], m->sigma_s[1],
                                 m->sigma_s[2], m->eta, material->sigma_a[0], material->sigma_a[1],
                                 material->sigma_a[2], material->sigma_s[0], material->sigma_s[1],
                                 material->sigma_s[2], material->eta);
        if (sam->model != model)
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "%s: built for profile model %d, expected %d", name,
                                 (int)sam->model, (int)model);
    }
    for (int i = 0; i < 16; i++) {
        double t = transform ? transform[i] : (i % 5 == 0 ? 1.0 : 0.0);
        if (fabs(sam->transform[i] - t) > 1e-9 * (1.0 + fabs(t)))
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                                 "%s: built for a different object transform (entry %d: %g, expected %g)", name, i,
                                 sam->transform[i], t);
    }
    return SSS_OK;
}
