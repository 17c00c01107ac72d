/* mesh/ply_internal.h — the PLY header as the body reader sees it (not public). */
#ifndef SSS_MESH_PLY_INTERNAL_H
#define SSS_MESH_PLY_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "sss/common.h"
#include "sss/mesh.h"

typedef enum ply_type { PLY_NONE = 0, PLY_I8, PLY_U8, PLY_I16, PLY_U16, PLY_I32, PLY_U32, PLY_F32, PLY_F64 } ply_type;
extern const int ply_type_size[]; /* bytes, indexed by ply_type */

enum { PLY_ASCII = 0, PLY_BINARY_LE = 1, PLY_BINARY_BE = 2 };

/* What the reader does with a property; ROLE_NONE ones are skipped. */
enum { ROLE_NONE = 0, ROLE_X, ROLE_Y, ROLE_Z, ROLE_NX, ROLE_NY, ROLE_NZ, ROLE_U, ROLE_V, ROLE_INDICES };

#define PLY_MAX_ELEMENTS 32
#define PLY_MAX_PROPS 64
#define PLY_NAME 64

typedef struct ply_prop {
    char name[PLY_NAME];
    ply_type type;       /* scalar type, or the item type of a list */
    ply_type count_type; /* PLY_NONE for scalars */
    int role;
} ply_prop;

typedef struct ply_element {
    char name[PLY_NAME];
    uint64_t count;
    size_t line; /* header line that declared it */
    int prop_count;
    ply_prop props[PLY_MAX_PROPS];
} ply_element;

typedef struct ply_header {
    int format;
    int element_count;
    ply_element elements[PLY_MAX_ELEMENTS];
    int vertex, face;           /* element indices (validated >= 0 after a successful parse) */
    int has_normals, has_uvs;
    size_t body;      /* byte offset of the data */
    size_t body_line; /* line number of the first data line (ascii) */
} ply_header;

/* Parses and validates the header (roles, limits, and data size against what the file holds). */
sss_result ply_parse_header(const char *data, size_t size, const char *name, ply_header *h, sss_error *err);

#endif
