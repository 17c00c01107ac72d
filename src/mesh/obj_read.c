/* mesh/obj_read.c — Wavefront OBJ (v, vt, vn, f) into an sss_mesh.
 *
 * OBJ indexes positions, UVs and normals separately; a GPU-style mesh has one index per vertex, so
 * every distinct (v, vt, vn) corner becomes one output vertex (a hash map finds repeats). Indices
 * may be negative (relative to the vertices defined so far) and must refer to data defined earlier
 * in the file. Polygons are fan-triangulated. Grouping, material and line statements are ignored.
 */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mesh/mesh_internal.h"

typedef struct vec_array {
    float *data;
    size_t count, cap; /* in elements of `width` floats */
    int width;
} vec_array;

typedef struct corner_map {
    uint32_t *slots; /* unified vertex id, or UINT32_MAX */
    size_t cap;      /* power of two */
    int32_t *keys;   /* 3 per unified vertex: v, vt, vn (-1 when absent) */
    size_t count, key_cap;
} corner_map;

typedef struct obj_state {
    const char *name;
    size_t line;
    sss_error *err;
    vec_array v, vt, vn;
    corner_map map;
    uint32_t *indices;
    size_t index_count, index_cap;
    int any_vt, any_vn;
} obj_state;

static const char *const ignored[] = {"o",     "g",     "s",        "usemtl", "mtllib",  "l",         "p",
                                      "vp",    "cstype", "deg",     "bmat",   "step",    "curv",      "curv2",
                                      "surf",  "parm",  "trim",     "hole",   "scrv",    "sp",        "end",
                                      "con",   "mg",    "bevel",    "c_interp", "d_interp", "lod",    "usemap",
                                      "maplib", "shadow_obj", "trace_obj", "ctech", "stech", NULL};

static int is_blank(char ch) { return ch == ' ' || ch == '\t' || ch == '\r' || ch == '\v' || ch == '\f'; }

/* Next whitespace-separated token in [*s, e); returns its length (0 at the end). */
static size_t next_token(const char **s, const char *e, const char **tok)
{
    const char *p = *s;
    while (p < e && is_blank(*p)) p++;
    *tok = p;
    while (p < e && !is_blank(*p)) p++;
    *s = p;
    return (size_t)(p - *tok);
}

static int token_is(const char *tok, size_t len, const char *word)
{
    return strlen(word) == len && memcmp(tok, word, len) == 0;
}

static int parse_float(const char *tok, size_t len, float *out)
{
    char buf[64];
    if (len == 0 || len >= sizeof buf) return 0;
    memcpy(buf, tok, len);
    buf[len] = '\0';
    char *end = NULL;
    double v = strtod(buf, &end);
    if (end != buf + len) return 0;
    *out = (float)v;
    return isfinite(*out); /* NaN, Inf and values beyond float range are all rejected */
}

/* An OBJ index (1-based, or negative relative to count) into a 0-based index; -1 when out of range,
 * -2 when not an integer. */
static long long resolve_index(const char *tok, size_t len, size_t count)
{
    char buf[24];
    if (len == 0 || len >= sizeof buf) return -2;
    memcpy(buf, tok, len);
    buf[len] = '\0';
    char *end = NULL;
    errno = 0;
    long long i = strtoll(buf, &end, 10);
    if (end != buf + len) return -2;
    if (errno == ERANGE || i == 0) return -1;
    long long r = i > 0 ? i - 1 : (long long)count + i;
    return r >= 0 && r < (long long)count ? r : -1;
}

static sss_result obj_fail(obj_state *s, sss_result code, const char *what)
{
    return sss_error_set(s->err, code, "%s: line %zu: %s", s->name, s->line, what);
}

static sss_result read_vector(obj_state *s, vec_array *a, const char *p, const char *e, int min, int max)
{
    float vals[7];
    int n = 0;
    const char *tok;
    size_t len;
    while ((len = next_token(&p, e, &tok)) > 0) {
        if (n == max) return obj_fail(s, SSS_ERROR_PARSE, "too many numbers");
        if (!parse_float(tok, len, &vals[n]))
            return sss_error_set(s->err, SSS_ERROR_PARSE, "%s: line %zu: '%.*s' is not a finite number", s->name,
                                 s->line, (int)(len > 40 ? 40 : len), tok);
        n++;
    }
    if (n < min) return obj_fail(s, SSS_ERROR_PARSE, "too few numbers");
    if (a->count >= SSS_MESH_MAX_VERTICES) return obj_fail(s, SSS_ERROR_LIMIT, "too many vertices (limit reached)");
    void *d = a->data;
    if (!mesh_grow(&d, &a->cap, (a->count + 1) * (size_t)a->width, sizeof(float)))
        return obj_fail(s, SSS_ERROR_OUT_OF_MEMORY, "out of memory");
    a->data = d;
    float *dst = a->data + a->count * (size_t)a->width;
    for (int k = 0; k < a->width; k++) dst[k] = k < n ? vals[k] : 0.0f; /* a missing vt 'v' is 0 */
    a->count++;
    return SSS_OK;
}

static size_t hash3(const int32_t *k)
{
    uint64_t h = (uint64_t)(uint32_t)k[0] * 0x9e3779b97f4a7c15ULL;
    h ^= (uint64_t)(uint32_t)k[1] * 0xc2b2ae3d27d4eb4fULL + (h << 6) + (h >> 2);
    h ^= (uint64_t)(uint32_t)k[2] * 0x165667b19e3779f9ULL + (h << 6) + (h >> 2);
    return (size_t)(h ^ (h >> 29));
}

static int map_rehash(corner_map *m)
{
    size_t cap = m->cap ? m->cap * 2 : 1024;
    uint32_t *slots = malloc(cap * sizeof *slots);
    if (!slots) return 0;
    memset(slots, 0xff, cap * sizeof *slots);
    for (size_t id = 0; id < m->count; id++) {
        size_t j = hash3(m->keys + 3 * id) & (cap - 1);
        while (slots[j] != UINT32_MAX) j = (j + 1) & (cap - 1);
        slots[j] = (uint32_t)id;
    }
    free(m->slots);
    m->slots = slots;
    m->cap = cap;
    return 1;
}

/* The unified vertex of a (v, vt, vn) corner, created on first use. */
static sss_result corner_id(obj_state *s, const int32_t key[3], uint32_t *id)
{
    corner_map *m = &s->map;
    if ((m->count + 1) * 2 > m->cap && !map_rehash(m)) return obj_fail(s, SSS_ERROR_OUT_OF_MEMORY, "out of memory");
    size_t j = hash3(key) & (m->cap - 1);
    while (m->slots[j] != UINT32_MAX) {
        const int32_t *k = m->keys + 3 * (size_t)m->slots[j];
        if (k[0] == key[0] && k[1] == key[1] && k[2] == key[2]) {
            *id = m->slots[j];
            return SSS_OK;
        }
        j = (j + 1) & (m->cap - 1);
    }
    if (m->count >= SSS_MESH_MAX_VERTICES) return obj_fail(s, SSS_ERROR_LIMIT, "too many distinct vertices");
    void *keys = m->keys;
    if (!mesh_grow(&keys, &m->key_cap, (m->count + 1) * 3, sizeof(int32_t)))
        return obj_fail(s, SSS_ERROR_OUT_OF_MEMORY, "out of memory");
    m->keys = keys;
    memcpy(m->keys + 3 * m->count, key, 3 * sizeof(int32_t));
    m->slots[j] = (uint32_t)m->count;
    *id = (uint32_t)m->count++;
    return SSS_OK;
}

static sss_result bad_corner(obj_state *s, const char *tok, size_t len)
{
    return sss_error_set(s->err, SSS_ERROR_PARSE, "%s: line %zu: malformed face corner '%.*s'", s->name, s->line,
                         (int)(len > 40 ? 40 : len), tok);
}

/* One face corner "v", "v/vt", "v//vn" or "v/vt/vn". */
static sss_result parse_corner(obj_state *s, const char *tok, size_t len, uint32_t *id)
{
    const char *part[3] = {tok, NULL, NULL};
    size_t plen[3] = {len, 0, 0};
    int parts = 1;
    for (size_t i = 0; i < len; i++) {
        if (tok[i] != '/') continue;
        if (parts == 3) return bad_corner(s, tok, len);
        plen[parts - 1] = (size_t)(tok + i - part[parts - 1]);
        part[parts] = tok + i + 1;
        plen[parts] = (size_t)(tok + len - part[parts]);
        parts++;
    }
    int32_t key[3] = {-1, -1, -1};
    const vec_array *arrays[3] = {&s->v, &s->vt, &s->vn};
    static const char *const what[3] = {"vertex", "texture coordinate", "normal"};
    for (int k = 0; k < parts; k++) {
        if (plen[k] == 0) {
            if (k == 1 && parts == 3) continue; /* "1//2" */
            return bad_corner(s, tok, len);     /* "/1", "1/", "1/2/" */
        }
        long long r = resolve_index(part[k], plen[k], arrays[k]->count);
        if (r == -2) return bad_corner(s, tok, len);
        if (r < 0)
            return sss_error_set(s->err, SSS_ERROR_PARSE,
                                 "%s: line %zu: %s index '%.*s' out of range (%zu defined so far)", s->name, s->line,
                                 what[k], (int)(plen[k] > 20 ? 20 : plen[k]), part[k], arrays[k]->count);
        key[k] = (int32_t)r;
    }
    if (key[1] >= 0) s->any_vt = 1;
    if (key[2] >= 0) s->any_vn = 1;
    return corner_id(s, key, id);
}

static sss_result read_face(obj_state *s, const char *p, const char *e)
{
    const char *tok;
    size_t len, n = 0;
    uint32_t first = 0, prev = 0;
    while ((len = next_token(&p, e, &tok)) > 0) {
        uint32_t id = 0;
        sss_result r = parse_corner(s, tok, len, &id);
        if (r != SSS_OK) return r;
        if (n >= 2) { /* fan around the first corner keeps the polygon's winding */
            if (s->index_count / 3 >= SSS_MESH_MAX_TRIANGLES) return obj_fail(s, SSS_ERROR_LIMIT, "too many triangles");
            void *idx = s->indices;
            if (!mesh_grow(&idx, &s->index_cap, s->index_count + 3, sizeof(uint32_t)))
                return obj_fail(s, SSS_ERROR_OUT_OF_MEMORY, "out of memory");
            s->indices = idx;
            s->indices[s->index_count++] = first;
            s->indices[s->index_count++] = prev;
            s->indices[s->index_count++] = id;
        }
        if (n == 0) first = id;
        prev = id;
        n++;
    }
    if (n < 3) return obj_fail(s, SSS_ERROR_PARSE, "face with fewer than 3 vertices");
    return SSS_OK;
}

static sss_result read_line(obj_state *s, const char *p, const char *e)
{
    const char *hash = memchr(p, '#', (size_t)(e - p));
    if (hash) e = hash;
    const char *kw;
    size_t len = next_token(&p, e, &kw);
    if (len == 0) return SSS_OK;
    if (token_is(kw, len, "v")) return read_vector(s, &s->v, p, e, 3, 7); /* x y z [w] or x y z r g b */
    if (token_is(kw, len, "vn")) return read_vector(s, &s->vn, p, e, 3, 3);
    if (token_is(kw, len, "vt")) return read_vector(s, &s->vt, p, e, 1, 3);
    if (token_is(kw, len, "f")) return read_face(s, p, e);
    for (int i = 0; ignored[i]; i++)
        if (token_is(kw, len, ignored[i])) return SSS_OK;
    return sss_error_set(s->err, SSS_ERROR_PARSE, "%s: line %zu: unknown statement '%.*s'", s->name, s->line,
                         (int)(len > 40 ? 40 : len), kw);
}

static sss_result build_mesh(obj_state *s, sss_mesh *out)
{
    if (s->v.count == 0) return sss_error_set(s->err, SSS_ERROR_PARSE, "%s: mesh has no vertices", s->name);
    if (s->index_count == 0) return sss_error_set(s->err, SSS_ERROR_PARSE, "%s: mesh has no faces", s->name);
    uint32_t nv = (uint32_t)s->map.count;
    sss_result r = mesh_alloc(out, nv, (uint32_t)(s->index_count / 3), s->any_vn, s->any_vt, s->name, s->err);
    if (r != SSS_OK) return r;
    for (uint32_t i = 0; i < nv; i++) {
        const int32_t *k = s->map.keys + 3 * (size_t)i;
        memcpy(out->positions + 3 * (size_t)i, s->v.data + 3 * (size_t)k[0], 3 * sizeof(float));
        /* corners without vn get a zero normal, which mesh_finish replaces by the computed one */
        if (out->normals && k[2] >= 0) memcpy(out->normals + 3 * (size_t)i, s->vn.data + 3 * (size_t)k[2], 3 * sizeof(float));
        if (out->uvs && k[1] >= 0) memcpy(out->uvs + 2 * (size_t)i, s->vt.data + 3 * (size_t)k[1], 2 * sizeof(float));
    }
    memcpy(out->indices, s->indices, s->index_count * sizeof(uint32_t));
    return mesh_finish(out, s->any_vn, s->any_vt, s->name, s->err);
}

sss_result sss_mesh_parse_obj(const void *data, size_t size, const char *name, sss_mesh *out, sss_error *err)
{
    memset(out, 0, sizeof *out);
    obj_state s;
    memset(&s, 0, sizeof s);
    s.name = name ? name : "<obj>";
    s.err = err;
    s.v.width = 3;
    s.vn.width = 3;
    s.vt.width = 3;
    const char *p = data, *end = p + size;
    sss_result r = SSS_OK;
    while (p < end && r == SSS_OK) {
        s.line++;
        const char *nl = memchr(p, '\n', (size_t)(end - p));
        const char *e = nl ? nl : end;
        if (memchr(p, '\0', (size_t)(e - p))) r = obj_fail(&s, SSS_ERROR_PARSE, "NUL byte (binary data?)");
        else r = read_line(&s, p, e);
        p = nl ? nl + 1 : end;
    }
    if (r == SSS_OK) r = build_mesh(&s, out);
    free(s.v.data);
    free(s.vt.data);
    free(s.vn.data);
    free(s.map.slots);
    free(s.map.keys);
    free(s.indices);
    if (r != SSS_OK) sss_mesh_free(out);
    return r;
}
