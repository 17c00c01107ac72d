/* mesh/ply_read.c — the PLY body (ascii, binary little and big endian) into an sss_mesh.
 *
 * Every value is read through one function per encoding, so the three formats share the element
 * walk: vertex properties with a role are stored, face index lists are fan-triangulated, anything
 * else (other properties, other elements, lists included) is parsed and dropped. Ascii is read one
 * element per line, so wrong counts in the header show up as lines with too many or too few values.
 */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mesh/mesh_internal.h"
#include "mesh/ply_internal.h"

enum { RV_OK = 0, RV_EOL, RV_TRUNCATED, RV_BAD, RV_RANGE };

typedef struct cursor {
    const unsigned char *p, *end;
    int format;
    size_t line;
    const char *name;
    const char *element; /* current element, for messages */
    uint64_t index;
    char token[48];      /* last ascii token, for messages */
    sss_error *err;
} cursor;

static sss_result fail(const cursor *c, sss_result code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

static sss_result fail(const cursor *c, sss_result code, const char *fmt, ...)
{
    char msg[320];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    if (c->format == PLY_ASCII)
        return sss_error_set(c->err, code, "%s: line %zu: %s %llu: %s", c->name, c->line, c->element,
                             (unsigned long long)c->index, msg);
    return sss_error_set(c->err, code, "%s: %s %llu: %s", c->name, c->element, (unsigned long long)c->index, msg);
}

static int is_space(unsigned char ch) { return ch == ' ' || ch == '\t' || ch == '\r' || ch == '\v' || ch == '\f'; }

static int in_range(ply_type t, long long v)
{
    switch (t) {
    case PLY_I8: return v >= -128 && v <= 127;
    case PLY_U8: return v >= 0 && v <= 255;
    case PLY_I16: return v >= -32768 && v <= 32767;
    case PLY_U16: return v >= 0 && v <= 65535;
    case PLY_I32: return v >= -2147483648LL && v <= 2147483647LL;
    case PLY_U32: return v >= 0 && v <= 4294967295LL;
    default: return 1;
    }
}

static int read_ascii(cursor *c, ply_type t, double *out)
{
    while (c->p < c->end && is_space(*c->p)) c->p++;
    if (c->p >= c->end || *c->p == '\n') return RV_EOL;
    size_t n = 0;
    int long_token = 0;
    while (c->p < c->end && !is_space(*c->p) && *c->p != '\n') {
        if (n + 1 < sizeof c->token) c->token[n++] = (char)*c->p;
        else long_token = 1;
        c->p++;
    }
    c->token[n] = '\0';
    if (long_token) return RV_BAD;
    char *e = NULL;
    errno = 0;
    if (t == PLY_F32 || t == PLY_F64) {
        double v = strtod(c->token, &e);
        if (e == c->token || *e) return RV_BAD;
        *out = v; /* overflow gives +-HUGE_VAL: the finiteness checks of used values reject it */
        return RV_OK;
    }
    long long v = strtoll(c->token, &e, 10);
    if (e == c->token || *e) return RV_BAD;
    if (errno == ERANGE || !in_range(t, v)) return RV_RANGE;
    *out = (double)v;
    return RV_OK;
}

static int read_binary(cursor *c, ply_type t, double *out)
{
    size_t size = (size_t)ply_type_size[t];
    if ((size_t)(c->end - c->p) < size) return RV_TRUNCATED;
    uint64_t u = 0;
    if (c->format == PLY_BINARY_BE)
        for (size_t i = 0; i < size; i++) u = u << 8 | c->p[i];
    else
        for (size_t i = 0; i < size; i++) u |= (uint64_t)c->p[i] << (8 * i);
    c->p += size;
    switch (t) {
    case PLY_I8: *out = u >= 0x80u ? (double)u - 256.0 : (double)u; break;
    case PLY_I16: *out = u >= 0x8000u ? (double)u - 65536.0 : (double)u; break;
    case PLY_I32: *out = u >= 0x80000000u ? (double)u - 4294967296.0 : (double)u; break;
    case PLY_F32: {
        uint32_t w = (uint32_t)u;
        float f;
        memcpy(&f, &w, sizeof f);
        *out = f;
        break;
    }
    case PLY_F64: {
        double d;
        memcpy(&d, &u, sizeof d);
        *out = d;
        break;
    }
    default: *out = (double)u; break; /* unsigned types */
    }
    return RV_OK;
}

static int read_value(cursor *c, ply_type t, double *out)
{
    return c->format == PLY_ASCII ? read_ascii(c, t, out) : read_binary(c, t, out);
}

/* Turns a read status into an error naming the place. */
static sss_result value_error(const cursor *c, int rv, const char *what)
{
    switch (rv) {
    case RV_EOL: return fail(c, SSS_ERROR_PARSE, "fewer values than the header declares (missing %s)", what);
    case RV_TRUNCATED: return fail(c, SSS_ERROR_PARSE, "data ends early reading %s (truncated file)", what);
    case RV_RANGE: return fail(c, SSS_ERROR_PARSE, "%s '%s' is out of range for its type", what, c->token);
    default: return fail(c, SSS_ERROR_PARSE, "%s '%s' is not a number", what, c->token);
    }
}

typedef struct body {
    sss_mesh *m;
    size_t index_cap;
    uint64_t triangles;
} body;

/* Reads one face index list (count already read) and appends its fan triangulation. */
static sss_result read_face(cursor *c, const ply_prop *p, double count_value, body *b)
{
    if (count_value < 3)
        return fail(c, SSS_ERROR_PARSE, "face has %.0f vertices (at least 3 needed)", count_value);
    uint64_t count = (uint64_t)count_value;
    /* each index takes at least its binary size, or a digit and a separator in ascii */
    uint64_t room = (uint64_t)(c->end - c->p);
    uint64_t fits = c->format == PLY_ASCII ? room / 2 + 1 : room / (uint64_t)ply_type_size[p->type];
    if (fits < count)
        return fail(c, SSS_ERROR_PARSE, "%llu indices announced but the file ends sooner (truncated file?)",
                    (unsigned long long)count);
    b->triangles += count - 2;
    if (b->triangles > SSS_MESH_MAX_TRIANGLES)
        return fail(c, SSS_ERROR_LIMIT, "more than %u triangles after splitting polygons", SSS_MESH_MAX_TRIANGLES);
    void *idx = b->m->indices;
    if (!mesh_grow(&idx, &b->index_cap, (size_t)b->triangles * 3, sizeof(uint32_t)))
        return fail(c, SSS_ERROR_OUT_OF_MEMORY, "out of memory for %llu triangles", (unsigned long long)b->triangles);
    b->m->indices = idx;
    uint32_t first = 0, prev = 0, nv = b->m->vertex_count;
    for (uint64_t k = 0; k < count; k++) {
        double v;
        int rv = read_value(c, p->type, &v);
        if (rv != RV_OK) return value_error(c, rv, "a vertex index");
        if (v != floor(v)) return fail(c, SSS_ERROR_PARSE, "vertex index %.17g is not an integer", v);
        if (v < 0 || v >= (double)nv)
            return fail(c, SSS_ERROR_PARSE, "vertex index %.17g out of range (%u vertices)", v, nv);
        uint32_t i = (uint32_t)v;
        if (k >= 2) { /* fan around the first corner keeps the polygon's winding */
            uint32_t *t = b->m->indices + 3 * (size_t)b->m->triangle_count++;
            t[0] = first;
            t[1] = prev;
            t[2] = i;
        }
        if (k == 0) first = i;
        prev = i;
    }
    return SSS_OK;
}

static sss_result skip_list(cursor *c, const ply_prop *p, double count_value)
{
    uint64_t count = (uint64_t)count_value;
    if (c->format != PLY_ASCII) {
        if ((uint64_t)(c->end - c->p) / (uint64_t)ply_type_size[p->type] < count)
            return fail(c, SSS_ERROR_PARSE, "data ends early in list '%s' (truncated file)", p->name);
        c->p += count * (uint64_t)ply_type_size[p->type];
        return SSS_OK;
    }
    for (uint64_t k = 0; k < count; k++) {
        double v;
        int rv = read_value(c, p->type, &v);
        if (rv != RV_OK) return value_error(c, rv, p->name);
    }
    return SSS_OK;
}

static sss_result store_vertex_value(cursor *c, const ply_prop *p, double v, sss_mesh *m)
{
    float f = (float)v;
    if (!isfinite(f))
        return fail(c, SSS_ERROR_PARSE, "property '%s' is %s", p->name, isnan(v) ? "NaN" : "infinite or too large");
    size_t i = (size_t)c->index;
    if (p->role <= ROLE_Z) m->positions[3 * i + (size_t)(p->role - ROLE_X)] = f;
    else if (p->role <= ROLE_NZ) m->normals[3 * i + (size_t)(p->role - ROLE_NX)] = f;
    else m->uvs[2 * i + (size_t)(p->role - ROLE_U)] = f;
    return SSS_OK;
}

static sss_result read_element(cursor *c, const ply_header *h, int e_index, body *b)
{
    const ply_element *e = &h->elements[e_index];
    int is_vertex = e_index == h->vertex;
    c->element = e->name;
    for (uint64_t i = 0; i < e->count; i++) {
        c->index = i;
        if (c->format == PLY_ASCII) { /* blank lines between elements are harmless */
            for (;;) {
                while (c->p < c->end && is_space(*c->p)) c->p++;
                if (c->p < c->end && *c->p == '\n') {
                    c->p++;
                    c->line++;
                } else break;
            }
            if (c->p >= c->end)
                return fail(c, SSS_ERROR_PARSE, "file ends after %llu of %llu '%s' elements", (unsigned long long)i,
                            (unsigned long long)e->count, e->name);
        }
        for (int k = 0; k < e->prop_count; k++) {
            const ply_prop *p = &e->props[k];
            double v;
            int rv = read_value(c, p->count_type != PLY_NONE ? p->count_type : p->type, &v);
            if (rv != RV_OK) return value_error(c, rv, p->name);
            sss_result r = SSS_OK;
            if (p->count_type != PLY_NONE) {
                if (v < 0) return fail(c, SSS_ERROR_PARSE, "negative list count in '%s'", p->name);
                r = p->role == ROLE_INDICES ? read_face(c, p, v, b) : skip_list(c, p, v);
            } else if (is_vertex && p->role != ROLE_NONE) {
                r = store_vertex_value(c, p, v, b->m);
            }
            if (r != SSS_OK) return r;
        }
        if (c->format == PLY_ASCII) {
            while (c->p < c->end && is_space(*c->p)) c->p++;
            if (c->p < c->end && *c->p != '\n')
                return fail(c, SSS_ERROR_PARSE, "more values than the header declares for '%s' (wrong counts?)", e->name);
            if (c->p < c->end) {
                c->p++;
                c->line++;
            }
        }
    }
    return SSS_OK;
}

sss_result sss_mesh_parse_ply(const void *data, size_t size, const char *name, sss_mesh *out, sss_error *err)
{
    memset(out, 0, sizeof *out);
    if (!name) name = "<ply>";
    ply_header *h = malloc(sizeof *h);
    if (!h) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory", name);
    sss_result r = ply_parse_header(data, size, name, h, err);
    if (r != SSS_OK) {
        free(h);
        return r;
    }
    /* The header check bounded every count by the bytes present, so these sizes follow the file. */
    uint32_t nv = (uint32_t)h->elements[h->vertex].count;
    uint64_t nf = h->elements[h->face].count;
    sss_mesh *m = out;
    body b = {m, (size_t)nf * 3, 0};
    m->vertex_count = nv;
    m->positions = malloc(((size_t)nv * 3 + 1) * sizeof(float));
    m->normals = h->has_normals ? malloc(((size_t)nv * 3 + 1) * sizeof(float)) : NULL;
    m->uvs = h->has_uvs ? malloc(((size_t)nv * 2 + 1) * sizeof(float)) : NULL;
    m->indices = malloc(b.index_cap * sizeof(uint32_t));
    if (!m->positions || (h->has_normals && !m->normals) || (h->has_uvs && !m->uvs) || !m->indices) {
        sss_mesh_free(m);
        free(h);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory for %u vertices", name, nv);
    }
    cursor c = {(const unsigned char *)data + h->body, (const unsigned char *)data + size, h->format, h->body_line,
                name, "", 0, "", err};
    for (int e = 0; e < h->element_count && r == SSS_OK; e++) r = read_element(&c, h, e, &b);
    if (r == SSS_OK) {
        if (c.format == PLY_ASCII) {
            while (c.p < c.end && (is_space(*c.p) || *c.p == '\n')) {
                if (*c.p == '\n') c.line++;
                c.p++;
            }
            if (c.p < c.end)
                r = sss_error_set(err, SSS_ERROR_PARSE,
                                  "%s: line %zu: data after the last element (the header's counts are too small?)",
                                  name, c.line);
        } else if (c.p < c.end) {
            r = sss_error_set(err, SSS_ERROR_PARSE,
                              "%s: %zu bytes after the last element (the header's counts are too small?)", name,
                              (size_t)(c.end - c.p));
        }
    }
    if (r == SSS_OK) r = mesh_finish(m, h->has_normals, h->has_uvs, name, err);
    free(h);
    if (r != SSS_OK) sss_mesh_free(m);
    return r;
}
