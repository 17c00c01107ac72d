/* scene/gltf_internal.h — the parts of the glTF importer shared between its files (internal).
 * Errors are "<file>: <JSON path>: <problem>"; the path is written by the caller into the message. */
#ifndef SSS_SCENE_GLTF_INTERNAL_H
#define SSS_SCENE_GLTF_INTERNAL_H

#include <cjson/cJSON.h>
#include <stdint.h>

#include "sss/gltf.h"

typedef struct gltf_buffer {
    unsigned char *owned;      /* decoded data: URI or external file (freed), or NULL */
    const unsigned char *data; /* owned, or the .glb's BIN chunk */
    size_t size;
    int loaded;
} gltf_buffer;

/* The top-level arrays whose elements the asset refers to by index (glTF 2.0 spec, section 3.3). */
enum {
    GLTF_NODES, GLTF_SCENES, GLTF_MESHES, GLTF_ACCESSORS, GLTF_BUFFER_VIEWS, GLTF_BUFFERS, GLTF_MATERIALS,
    GLTF_TEXTURES, GLTF_IMAGES, GLTF_CAMERAS, GLTF_LIGHTS, /* extensions.KHR_lights_punctual.lights */
    GLTF_LIST_COUNT
};

/* One of them indexed once into a C array: cJSON keeps arrays as linked lists, and a walk per
 * reference (cJSON_GetArrayItem) made the import quadratic (100,000 nodes: 35 s). */
typedef struct gltf_list {
    const cJSON **items;
    size_t count;
} gltf_list;

typedef struct gltf_ctx {
    const char *name;     /* the asset's file name, for messages */
    const char *base_dir; /* folder of external URIs */
    sss_error *err;
    cJSON *root;
    gltf_list lists[GLTF_LIST_COUNT];
    const unsigned char *glb_bin; /* the .glb's BIN chunk, or NULL */
    size_t glb_bin_size;
    gltf_buffer *buffers;
    size_t buffer_count;
    sss_gltf_desc desc;
    sss_gltf_scene *out;  /* where decoded embedded images go (out->images, one slot per images[k]) */
    int quantization;     /* KHR_mesh_quantization is used: integer positions, normals and UVs allowed */
    unsigned char **decoded_views; /* per bufferViews[k]: its EXT_meshopt_compression data decoded, or NULL */
    size_t decoded_bytes; /* meshopt views and Draco meshes decoded so far (SSS_GLTF_MAX_DECODED_SIZE) */
} gltf_ctx;

/* A validated accessor: element i, component k is at base + i * stride + k * component size. */
typedef struct gltf_accessor {
    const unsigned char *base;
    size_t count, stride;
    int components;     /* 1 (SCALAR), 2 (VEC2), 3 (VEC3), 4 (VEC4), 16 (MAT4) */
    int component_type; /* 5120..5126 */
    int normalized;
} gltf_accessor;

/* "<file>: " + the formatted rest; returns code. */
sss_result gltf_fail(gltf_ctx *c, sss_result code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* Typed members (path names the object for messages; absent and not required -> def). */
const cJSON *gltf_get(const cJSON *obj, const char *key);
sss_result gltf_int(gltf_ctx *c, const cJSON *obj, const char *path, const char *key, int required, long def,
                    long min, long max, long *out);
sss_result gltf_number(gltf_ctx *c, const cJSON *obj, const char *path, const char *key, double def,
                       double *out);
/* An array of exactly n finite numbers (absent -> def, which may be NULL to leave out untouched). */
sss_result gltf_vec(gltf_ctx *c, const cJSON *obj, const char *path, const char *key, int n, const double *def,
                    double *out);
/* obj must be a JSON object (or absent when optional). */
sss_result gltf_object(gltf_ctx *c, const cJSON *obj, const char *path);
/* Element index of the top-level array list (GLTF_NODES, ...), or NULL when there is no such element. */
const cJSON *gltf_item(const gltf_ctx *c, int list, long index);
/* How many elements the top-level array list has (0 when absent). */
size_t gltf_count(const gltf_ctx *c, int list);

/* gltf_file.c: the container. Splits a .glb (or takes the text of a .gltf), parses the JSON into
 * c->root (through the scene reader's jr_parse, as every JSON), checks asset.version and
 * extensionsRequired and indexes the top-level arrays (c->lists). */
sss_result gltf_open(gltf_ctx *c, const unsigned char *data, size_t size);
void gltf_close(gltf_ctx *c);
/* base_dir + "/" + a percent-decoded relative URI (malloc'd), or NULL when the URI is absolute or
 * malformed. */
char *gltf_resolve_uri(const char *base_dir, const char *uri);
/* The bytes of buffers[index] (loaded on first use: BIN chunk, data: URI or external file). */
sss_result gltf_buffer_data(gltf_ctx *c, long index, const char *path, const unsigned char **data,
                            size_t *size);

/* Appends a copy of path to out->files (SSS_ERROR_OUT_OF_MEMORY without a message). */
sss_result gltf_add_file(sss_gltf_scene *out, const char *path);
/* The asset's external files into out->files: buffers[].uri and images[].uri that are files (used or
 * not: they belong to the asset), resolved against c->base_dir. */
sss_result gltf_list_files(gltf_ctx *c, sss_gltf_scene *out);

/* The bytes of a data: URI with base64 content (malloc'd into *owned); path names the URI's JSON member. */
sss_result gltf_data_uri(gltf_ctx *c, const char *uri, const char *path, unsigned char **owned, size_t *size);

/* gltf_accessor.c. accessors[index]'s type, count and normalization into a (base NULL) and its
 * bufferView (-1: none) and byteOffset; use and components as for gltf_accessor_get. */
sss_result gltf_accessor_meta(gltf_ctx *c, long index, const char *use, int components, gltf_accessor *a,
                              long *view, long *offset);
/* The bytes of bufferViews[index] (use names the referrer in messages). */
sss_result gltf_buffer_view(gltf_ctx *c, long index, const char *use, const unsigned char **start, size_t *length);
/* accessors[index], used as `use` (a JSON path for messages, e.g.
 * "meshes[0].primitives[1].attributes.POSITION"); components: the required element size. */
sss_result gltf_accessor_get(gltf_ctx *c, long index, const char *use, int components, gltf_accessor *a);
/* Component k of element i as a float (normalized integers mapped to [0, 1] or [-1, 1]). */
double gltf_accessor_float(const gltf_accessor *a, size_t i, int k);
/* Element i of an unsigned integer accessor (indices). */
uint32_t gltf_accessor_uint(const gltf_accessor *a, size_t i);

/* gltf_meshopt.c: bufferViews[index] whose EXT_meshopt_compression object is ext (stride: the view's
 * byteStride, 0 when absent; *length: its byteLength), decoded once (meshoptimizer) into
 * c->decoded_views[index]: *start points there. Every member is checked against the extension's rules
 * and the compressed bytes against their buffer before anything is decoded. */
sss_result gltf_meshopt_view(gltf_ctx *c, long index, const cJSON *ext, long stride, const unsigned char **start,
                             size_t *length);
/* Adds bytes to c->decoded_bytes, refusing (SSS_ERROR_LIMIT, naming path) beyond SSS_GLTF_MAX_DECODED_SIZE. */
sss_result gltf_decoded_budget(gltf_ctx *c, unsigned long long bytes, const char *path);

/* The vertex and index data of a primitive: accessors over the file's bytes, or over decoded Draco data
 * (owned, released by gltf_source_free). idx_accessor: the indices' accessor (-1: none; for messages). */
typedef struct gltf_source {
    gltf_accessor pos, nrm, uv, idx;
    int has_nrm, has_uv, has_idx;
    long idx_accessor;
    void *owned[4];
} gltf_source;
void gltf_source_free(gltf_source *src);
/* gltf_draco.c: the primitive's KHR_draco_mesh_compression object ext (path: the primitive's JSON path)
 * decoded into src (float attributes, 32-bit indices); its accessors give the counts the decoded data
 * must have. The stream's header is read here first: its triangle count must be the indices accessor's
 * and within the limits and the decoding budget before the decoder allocates anything. */
sss_result gltf_draco_source(gltf_ctx *c, const cJSON *primitive, const cJSON *ext, const char *path,
                             gltf_source *src);

/* gltf_material.c: materials[index] (index -1: the glTF default material). */
sss_result gltf_material(gltf_ctx *c, long index, sss_gltf_material *m);
void gltf_material_free(sss_gltf_material *m);

/* gltf_mesh.c: primitive `prim` of meshes[mesh_index] baked into world space with the row-major
 * matrix world (p' = world p) of nodes[node]. */
sss_result gltf_primitive_mesh(gltf_ctx *c, long node, long mesh_index, long prim, const cJSON *primitive,
                               const double world[16], sss_mesh *out, int *has_uvs);

/* gltf_import.c: sss_gltf_load, with check 0 leaving out the scene loader's checks (scene_load_gltf,
 * which loads the scene right after, makes them itself). */
sss_result gltf_load(const char *path, const sss_gltf_desc *desc, int check, sss_gltf_scene *out, sss_error *err);

/* scene_gltf.c: the scene loader's verdict on the imported scene g as sss_gltf_scene_json writes it,
 * its meshes and images lent (left in g): whatever the loader refuses is refused at import, not by every
 * command that reads the written scene. name: the asset (messages), dir: its folder. */
sss_result scene_check_gltf(const char *name, const char *dir, sss_gltf_scene *g, sss_error *err);

#endif
