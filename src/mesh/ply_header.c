/* mesh/ply_header.c — the PLY header: format, elements, properties, and the roles the reader gives
 * them (positions, normals, UVs, face indices). Validates the counts against the limits and against
 * the bytes the file holds before the body reader allocates anything. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mesh/ply_internal.h"

static const struct {
    const char *name;
    ply_type type;
} type_names[] = {
    {"char", PLY_I8},    {"int8", PLY_I8},     {"uchar", PLY_U8},  {"uint8", PLY_U8},   {"short", PLY_I16},
    {"int16", PLY_I16},  {"ushort", PLY_U16},  {"uint16", PLY_U16}, {"int", PLY_I32},   {"int32", PLY_I32},
    {"uint", PLY_U32},   {"uint32", PLY_U32},  {"float", PLY_F32}, {"float32", PLY_F32}, {"double", PLY_F64},
    {"float64", PLY_F64},
};

const int ply_type_size[] = {0, 1, 1, 2, 2, 4, 4, 4, 8};

static ply_type parse_type(const char *s)
{
    for (size_t i = 0; i < sizeof type_names / sizeof type_names[0]; i++)
        if (strcmp(type_names[i].name, s) == 0) return type_names[i].type;
    return PLY_NONE;
}

#define MAX_TOKENS 8

/* Splits a header line (copied into buf) into at most MAX_TOKENS tokens; returns the count, or -1
 * when the line has more. */
static int split(char *buf, char **tok)
{
    int n = 0;
    char *p = buf;
    for (;;) {
        while (*p == ' ' || *p == '\t') p++;
        if (!*p) return n;
        if (n == MAX_TOKENS) return -1;
        tok[n++] = p;
        while (*p && *p != ' ' && *p != '\t') p++;
        if (*p) *p++ = '\0';
    }
}

static int copy_name(char *dst, const char *src)
{
    size_t n = strlen(src);
    if (n >= PLY_NAME) return 0;
    memcpy(dst, src, n + 1);
    return 1;
}

static int parse_count(const char *s, uint64_t *out)
{
    if (!*s) return 0;
    uint64_t v = 0;
    for (const char *p = s; *p; p++) {
        if (*p < '0' || *p > '9') return 0;
        v = v * 10 + (uint64_t)(*p - '0');
        if (v > UINT32_MAX) return 0;
    }
    *out = v;
    return 1;
}

static ply_prop *find_prop(ply_element *e, const char *name)
{
    for (int i = 0; i < e->prop_count; i++)
        if (strcmp(e->props[i].name, name) == 0) return &e->props[i];
    return NULL;
}

/* Gives the vertex element's properties their roles; x, y and z are required. */
static sss_result assign_vertex_roles(ply_header *h, const char *name, sss_error *err)
{
    ply_element *e = &h->elements[h->vertex];
    static const char *const xyz[3] = {"x", "y", "z"};
    for (int k = 0; k < 3; k++) {
        ply_prop *p = find_prop(e, xyz[k]);
        if (!p)
            return sss_error_set(err, SSS_ERROR_PARSE, "%s: line %zu: vertex element has no '%s' property", name,
                                 e->line, xyz[k]);
        if (p->count_type != PLY_NONE)
            return sss_error_set(err, SSS_ERROR_PARSE, "%s: line %zu: vertex property '%s' is a list", name,
                                 e->line, xyz[k]);
        p->role = ROLE_X + k;
    }
    /* Normals and UVs are used only when complete and scalar; otherwise skipped like any extra. */
    static const char *const nxyz[3] = {"nx", "ny", "nz"};
    ply_prop *n[3];
    int ok = 1;
    for (int k = 0; k < 3; k++) {
        n[k] = find_prop(e, nxyz[k]);
        if (!n[k] || n[k]->count_type != PLY_NONE) ok = 0;
    }
    if (ok) {
        for (int k = 0; k < 3; k++) n[k]->role = ROLE_NX + k;
        h->has_normals = 1;
    }
    static const char *const uv_names[4][2] = {{"u", "v"}, {"s", "t"}, {"texture_u", "texture_v"}, {"texture_s", "texture_t"}};
    for (int i = 0; i < 4; i++) {
        ply_prop *u = find_prop(e, uv_names[i][0]), *v = find_prop(e, uv_names[i][1]);
        if (u && v && u->count_type == PLY_NONE && v->count_type == PLY_NONE) {
            u->role = ROLE_U;
            v->role = ROLE_V;
            h->has_uvs = 1;
            break;
        }
    }
    return SSS_OK;
}

static sss_result assign_face_roles(ply_header *h, const char *name, sss_error *err)
{
    ply_element *e = &h->elements[h->face];
    ply_prop *p = find_prop(e, "vertex_indices");
    if (!p) p = find_prop(e, "vertex_index");
    if (!p)
        return sss_error_set(err, SSS_ERROR_PARSE,
                             "%s: line %zu: face element has no 'vertex_indices' (or 'vertex_index') list", name,
                             e->line);
    if (p->count_type == PLY_NONE)
        return sss_error_set(err, SSS_ERROR_PARSE, "%s: line %zu: face property '%s' is not a list", name, e->line,
                             p->name);
    p->role = ROLE_INDICES;
    return SSS_OK;
}

/* The fewest bytes one instance of e can take: binary, the scalars plus each list's count (an
 * index list holds at least three indices); ascii, one digit and one separator per value. */
static uint64_t min_element_bytes(const ply_element *e, int ascii)
{
    uint64_t bytes = 0;
    for (int i = 0; i < e->prop_count; i++) {
        const ply_prop *p = &e->props[i];
        uint64_t items = p->role == ROLE_INDICES ? 3 : 0;
        if (ascii) bytes += 2 * (1 + (p->count_type != PLY_NONE ? items : 0));
        else if (p->count_type == PLY_NONE) bytes += (uint64_t)ply_type_size[p->type];
        else bytes += (uint64_t)ply_type_size[p->count_type] + items * (uint64_t)ply_type_size[p->type];
    }
    return bytes;
}

static sss_result check_header(ply_header *h, size_t body_bytes, const char *name, sss_error *err)
{
    if (h->vertex < 0) return sss_error_set(err, SSS_ERROR_PARSE, "%s: no 'vertex' element in the header", name);
    if (h->face < 0)
        return sss_error_set(err, SSS_ERROR_PARSE, "%s: no 'face' element in the header (a point cloud is not a mesh)",
                             name);
    sss_result r = assign_vertex_roles(h, name, err);
    if (r == SSS_OK) r = assign_face_roles(h, name, err);
    if (r != SSS_OK) return r;
    const ply_element *v = &h->elements[h->vertex], *f = &h->elements[h->face];
    if (v->count == 0) return sss_error_set(err, SSS_ERROR_PARSE, "%s: line %zu: mesh has no vertices", name, v->line);
    if (f->count == 0) return sss_error_set(err, SSS_ERROR_PARSE, "%s: line %zu: mesh has no faces", name, f->line);
    if (v->count > SSS_MESH_MAX_VERTICES)
        return sss_error_set(err, SSS_ERROR_LIMIT, "%s: line %zu: %llu vertices, more than the %u accepted", name,
                             v->line, (unsigned long long)v->count, SSS_MESH_MAX_VERTICES);
    if (f->count > SSS_MESH_MAX_TRIANGLES)
        return sss_error_set(err, SSS_ERROR_LIMIT, "%s: line %zu: %llu faces, more than the %u triangles accepted",
                             name, f->line, (unsigned long long)f->count, SSS_MESH_MAX_TRIANGLES);
    /* counts < 2^32 and element sizes < 2^12 keep every product and the sum far below 2^64 */
    uint64_t need = 0;
    for (int i = 0; i < h->element_count; i++)
        need += h->elements[i].count * min_element_bytes(&h->elements[i], h->format == PLY_ASCII);
    /* ascii: the last value needs no separator after it */
    uint64_t have = (uint64_t)body_bytes + (h->format == PLY_ASCII ? 1 : 0);
    if (need > have)
        return sss_error_set(err, SSS_ERROR_PARSE,
                             "%s: header claims at least %llu bytes of data but the file holds %llu after the header "
                             "(truncated file or wrong counts)",
                             name, (unsigned long long)need, (unsigned long long)body_bytes);
    return SSS_OK;
}

sss_result ply_parse_header(const char *data, size_t size, const char *name, ply_header *h, sss_error *err)
{
    memset(h, 0, sizeof *h);
    h->vertex = h->face = -1;
    h->format = -1;
    size_t pos = 0, line = 0;
    char buf[1024];
    for (;;) {
        line++;
        if (pos >= size) {
            if (line == 1) return sss_error_set(err, SSS_ERROR_PARSE, "%s: empty file", name);
            return sss_error_set(err, SSS_ERROR_PARSE, "%s: line %zu: header ends without 'end_header'", name, line);
        }
        const char *nl = memchr(data + pos, '\n', size - pos);
        size_t len = nl ? (size_t)(nl - (data + pos)) : size - pos;
        size_t next = nl ? pos + len + 1 : size;
        if (len > 0 && data[pos + len - 1] == '\r') len--;
        if (len >= sizeof buf)
            return sss_error_set(err, SSS_ERROR_PARSE, "%s: line %zu: header line too long", name, line);
        memcpy(buf, data + pos, len);
        buf[len] = '\0';
        if (memchr(buf, '\0', len))
            return sss_error_set(err, SSS_ERROR_PARSE, "%s: line %zu: NUL byte in the header", name, line);
        pos = next;
        if (line == 1) {
            if (strcmp(buf, "ply") != 0)
                return sss_error_set(err, SSS_ERROR_PARSE, "%s: line 1: not a PLY file (no 'ply' magic)", name);
            continue;
        }
        char *tok[MAX_TOKENS];
        int n;
        if (strncmp(buf, "comment", 7) == 0 && (buf[7] == '\0' || buf[7] == ' ' || buf[7] == '\t')) continue;
        if (strncmp(buf, "obj_info", 8) == 0 && (buf[8] == '\0' || buf[8] == ' ' || buf[8] == '\t')) continue;
        n = split(buf, tok);
        if (n == 0) continue;
        if (n < 0) return sss_error_set(err, SSS_ERROR_PARSE, "%s: line %zu: too many words in a header line", name, line);
        if (strcmp(tok[0], "format") == 0) {
            if (n != 3 || h->format != -1)
                return sss_error_set(err, SSS_ERROR_PARSE, "%s: line %zu: malformed or repeated 'format' line", name, line);
            if (strcmp(tok[1], "ascii") == 0) h->format = PLY_ASCII;
            else if (strcmp(tok[1], "binary_little_endian") == 0) h->format = PLY_BINARY_LE;
            else if (strcmp(tok[1], "binary_big_endian") == 0) h->format = PLY_BINARY_BE;
            else return sss_error_set(err, SSS_ERROR_UNSUPPORTED, "%s: line %zu: unknown format '%s'", name, line, tok[1]);
            if (strcmp(tok[2], "1.0") != 0 && strcmp(tok[2], "1") != 0)
                return sss_error_set(err, SSS_ERROR_UNSUPPORTED, "%s: line %zu: PLY version '%s' (1.0 expected)", name,
                                     line, tok[2]);
        } else if (strcmp(tok[0], "element") == 0) {
            if (h->format == -1)
                return sss_error_set(err, SSS_ERROR_PARSE, "%s: line %zu: 'element' before 'format'", name, line);
            if (n != 3) return sss_error_set(err, SSS_ERROR_PARSE, "%s: line %zu: expected 'element NAME COUNT'", name, line);
            if (h->element_count == PLY_MAX_ELEMENTS)
                return sss_error_set(err, SSS_ERROR_UNSUPPORTED, "%s: line %zu: more than %d elements", name, line,
                                     PLY_MAX_ELEMENTS);
            ply_element *e = &h->elements[h->element_count];
            if (!copy_name(e->name, tok[1]))
                return sss_error_set(err, SSS_ERROR_PARSE, "%s: line %zu: element name too long", name, line);
            if (!parse_count(tok[2], &e->count))
                return sss_error_set(err, SSS_ERROR_PARSE, "%s: line %zu: bad element count '%s'", name, line, tok[2]);
            e->line = line;
            int *slot = strcmp(e->name, "vertex") == 0 ? &h->vertex : strcmp(e->name, "face") == 0 ? &h->face : NULL;
            if (slot) {
                if (*slot >= 0)
                    return sss_error_set(err, SSS_ERROR_PARSE, "%s: line %zu: second '%s' element", name, line, e->name);
                *slot = h->element_count;
            }
            h->element_count++;
        } else if (strcmp(tok[0], "property") == 0) {
            if (h->element_count == 0)
                return sss_error_set(err, SSS_ERROR_PARSE, "%s: line %zu: 'property' before any 'element'", name, line);
            ply_element *e = &h->elements[h->element_count - 1];
            if (e->prop_count == PLY_MAX_PROPS)
                return sss_error_set(err, SSS_ERROR_UNSUPPORTED, "%s: line %zu: more than %d properties in '%s'", name,
                                     line, PLY_MAX_PROPS, e->name);
            ply_prop *p = &e->props[e->prop_count];
            memset(p, 0, sizeof *p);
            const char *pname;
            if (n == 5 && strcmp(tok[1], "list") == 0) {
                p->count_type = parse_type(tok[2]);
                p->type = parse_type(tok[3]);
                pname = tok[4];
                if (p->count_type == PLY_NONE || p->type == PLY_NONE)
                    return sss_error_set(err, SSS_ERROR_PARSE, "%s: line %zu: unknown type in list property", name, line);
                if (p->count_type == PLY_F32 || p->count_type == PLY_F64)
                    return sss_error_set(err, SSS_ERROR_PARSE, "%s: line %zu: list count type must be an integer type",
                                         name, line);
            } else if (n == 3) {
                p->type = parse_type(tok[1]);
                pname = tok[2];
                if (p->type == PLY_NONE)
                    return sss_error_set(err, SSS_ERROR_PARSE, "%s: line %zu: unknown property type '%s'", name, line,
                                         tok[1]);
            } else {
                return sss_error_set(err, SSS_ERROR_PARSE,
                                     "%s: line %zu: expected 'property TYPE NAME' or 'property list TYPE TYPE NAME'",
                                     name, line);
            }
            if (!copy_name(p->name, pname))
                return sss_error_set(err, SSS_ERROR_PARSE, "%s: line %zu: property name too long", name, line);
            if (find_prop(e, p->name))
                return sss_error_set(err, SSS_ERROR_PARSE, "%s: line %zu: repeated property '%s'", name, line, p->name);
            e->prop_count++;
        } else if (strcmp(tok[0], "end_header") == 0) {
            if (n != 1) return sss_error_set(err, SSS_ERROR_PARSE, "%s: line %zu: text after 'end_header'", name, line);
            if (h->format == -1) return sss_error_set(err, SSS_ERROR_PARSE, "%s: no 'format' line in the header", name);
            h->body = pos;
            h->body_line = line + 1;
            return check_header(h, size - pos, name, err);
        } else {
            return sss_error_set(err, SSS_ERROR_PARSE, "%s: line %zu: unknown header keyword '%.40s'", name, line, tok[0]);
        }
    }
}
