/* glTF containers: .glb chunks (glTF 2.0 spec, section 4.4 "Binary glTF Layout"), the JSON root,
 * buffers (the BIN chunk, data: URIs in base64, external files through sss_read_file). */
#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/file_util.h"
#include "scene/gltf_internal.h"
#include "scene/json_reader.h"

#define GLB_MAGIC 0x46546C67u      /* "glTF" */
#define GLB_CHUNK_JSON 0x4E4F534Au /* "JSON" */
#define GLB_CHUNK_BIN 0x004E4942u  /* "BIN\0" */

sss_result gltf_fail(gltf_ctx *c, sss_result code, const char *fmt, ...)
{
    char msg[SSS_ERROR_MESSAGE_SIZE];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return sss_error_set(c->err, code, "%s: %s", c->name, msg);
}

const cJSON *gltf_get(const cJSON *obj, const char *key)
{
    return cJSON_IsObject(obj) ? cJSON_GetObjectItemCaseSensitive(obj, key) : NULL;
}

sss_result gltf_int(gltf_ctx *c, const cJSON *obj, const char *path, const char *key, int required, long def,
                    long min, long max, long *out)
{
    const cJSON *item = gltf_get(obj, key);
    if (!item) {
        if (required) return gltf_fail(c, SSS_ERROR_PARSE, "%s.%s: required field missing", path, key);
        *out = def;
        return SSS_OK;
    }
    double v = item->valuedouble;
    if (!cJSON_IsNumber(item) || !isfinite(v) || floor(v) != v)
        return gltf_fail(c, SSS_ERROR_PARSE, "%s.%s: expected an integer", path, key);
    if (v < (double)min || v > (double)max)
        return gltf_fail(c, SSS_ERROR_INVALID_ARGUMENT, "%s.%s: %.17g is out of range %ld..%ld", path, key, v,
                         min, max);
    *out = (long)v;
    return SSS_OK;
}

sss_result gltf_number(gltf_ctx *c, const cJSON *obj, const char *path, const char *key, double def,
                       double *out)
{
    const cJSON *item = gltf_get(obj, key);
    if (!item) {
        *out = def;
        return SSS_OK;
    }
    if (!cJSON_IsNumber(item) || !isfinite(item->valuedouble))
        return gltf_fail(c, SSS_ERROR_PARSE, "%s.%s: expected a finite number", path, key);
    *out = item->valuedouble;
    return SSS_OK;
}

sss_result gltf_vec(gltf_ctx *c, const cJSON *obj, const char *path, const char *key, int n, const double *def,
                    double *out)
{
    const cJSON *item = gltf_get(obj, key);
    if (!item) {
        if (def) memcpy(out, def, (size_t)n * sizeof *out);
        return SSS_OK;
    }
    if (!cJSON_IsArray(item) || cJSON_GetArraySize(item) != n)
        return gltf_fail(c, SSS_ERROR_PARSE, "%s.%s: expected an array of %d numbers", path, key, n);
    int i = 0;
    for (const cJSON *e = item->child; e; e = e->next, i++) {
        if (!cJSON_IsNumber(e) || !isfinite(e->valuedouble))
            return gltf_fail(c, SSS_ERROR_PARSE, "%s.%s[%d]: expected a finite number", path, key, i);
        out[i] = e->valuedouble;
    }
    return SSS_OK;
}

sss_result gltf_object(gltf_ctx *c, const cJSON *obj, const char *path)
{
    if (obj && !cJSON_IsObject(obj)) return gltf_fail(c, SSS_ERROR_PARSE, "%s: expected an object", path);
    return SSS_OK;
}

const cJSON *gltf_item(const gltf_ctx *c, int list, long index)
{
    const gltf_list *l = &c->lists[list];
    return index >= 0 && (size_t)index < l->count ? l->items[index] : NULL;
}

size_t gltf_count(const gltf_ctx *c, int list)
{
    return c->lists[list].count;
}

/* The array at path (the member key of parent; absent: empty) into l, one walk of its list. */
static sss_result index_list(gltf_ctx *c, const cJSON *parent, const char *key, const char *path, gltf_list *l)
{
    const cJSON *arr = gltf_get(parent, key);
    if (!arr) return SSS_OK;
    if (!cJSON_IsArray(arr)) return gltf_fail(c, SSS_ERROR_PARSE, "%s: expected an array", path);
    size_t n = 0;
    for (const cJSON *e = arr->child; e; e = e->next) n++;
    if (n && !(l->items = malloc(n * sizeof *l->items)))
        return gltf_fail(c, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    for (const cJSON *e = arr->child; e; e = e->next) l->items[l->count++] = e;
    return SSS_OK;
}

static sss_result index_lists(gltf_ctx *c)
{
    static const char *const keys[GLTF_LIST_COUNT] = {
        [GLTF_NODES] = "nodes",         [GLTF_SCENES] = "scenes",   [GLTF_MESHES] = "meshes",
        [GLTF_ACCESSORS] = "accessors", [GLTF_BUFFER_VIEWS] = "bufferViews", [GLTF_BUFFERS] = "buffers",
        [GLTF_MATERIALS] = "materials", [GLTF_TEXTURES] = "textures", [GLTF_IMAGES] = "images",
        [GLTF_CAMERAS] = "cameras",     [GLTF_LIGHTS] = "extensions.KHR_lights_punctual.lights"};
    sss_result res = SSS_OK;
    for (int i = 0; i < GLTF_LIGHTS && res == SSS_OK; i++) res = index_list(c, c->root, keys[i], keys[i], &c->lists[i]);
    const cJSON *punctual = gltf_get(gltf_get(c->root, "extensions"), "KHR_lights_punctual");
    if (res == SSS_OK) res = index_list(c, punctual, "lights", keys[GLTF_LIGHTS], &c->lists[GLTF_LIGHTS]);
    return res;
}

static uint32_t read_u32(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

/* glTF 2.0 spec 4.4: a 12-byte header (magic, version 2, length), then chunks of (length, type,
 * data): the first is JSON, an optional second one BIN. */
static sss_result split_glb(gltf_ctx *c, const unsigned char *data, size_t size, const char **json,
                            size_t *json_size)
{
    if (size < 12) return gltf_fail(c, SSS_ERROR_PARSE, "truncated .glb: %zu bytes, less than its 12-byte header", size);
    uint32_t version = read_u32(data + 4), length = read_u32(data + 8);
    if (version != 2) return gltf_fail(c, SSS_ERROR_UNSUPPORTED, ".glb version %u (only 2 is supported)", version);
    if (length > size)
        return gltf_fail(c, SSS_ERROR_PARSE, "truncated .glb: the header gives %u bytes, the file has %zu", length, size);
    size_t pos = 12;
    for (int chunk = 0; pos < length; chunk++) {
        if (length - pos < 8)
            return gltf_fail(c, SSS_ERROR_PARSE, "truncated .glb: chunk %d header at byte %zu", chunk, pos);
        uint32_t chunk_len = read_u32(data + pos), type = read_u32(data + pos + 4);
        pos += 8;
        if (chunk_len > length - pos)
            return gltf_fail(c, SSS_ERROR_PARSE, "truncated .glb: chunk %d claims %u bytes, %zu remain", chunk,
                             chunk_len, length - pos);
        if (chunk == 0) {
            if (type != GLB_CHUNK_JSON)
                return gltf_fail(c, SSS_ERROR_PARSE, ".glb: the first chunk is not JSON (type 0x%08x)", type);
            *json = (const char *)data + pos;
            *json_size = chunk_len;
            /* The chunk is padded to 4 bytes with spaces (4.4.3.1); some writers pad with zeros, which
             * would be text after the JSON value: up to 3 of them are taken as padding. */
            for (int pad = 0; pad < 3 && *json_size > 0 && (*json)[*json_size - 1] == '\0'; pad++) (*json_size)--;
        } else if (chunk == 1 && type == GLB_CHUNK_BIN) {
            c->glb_bin = data + pos;
            c->glb_bin_size = chunk_len;
        } /* other chunks: ignored, as the spec asks */
        pos += chunk_len;
    }
    if (!*json) return gltf_fail(c, SSS_ERROR_PARSE, "truncated .glb: no JSON chunk");
    return SSS_OK;
}

/* Extensions whose meaning this importer knows (or may safely ignore when only used). */
static int extension_supported(const char *name)
{
    static const char *const known[] = {"KHR_materials_volume", "KHR_materials_volume_scatter",
                                        "KHR_materials_scatter", "KHR_materials_ior",
                                        "KHR_materials_diffuse_transmission", "KHR_lights_punctual",
                                        "KHR_draco_mesh_compression", "EXT_meshopt_compression",
                                        "KHR_mesh_quantization"};
    for (size_t i = 0; i < sizeof known / sizeof known[0]; i++)
        if (strcmp(name, known[i]) == 0) return 1;
    return 0;
}

static sss_result check_root(gltf_ctx *c)
{
    if (!cJSON_IsObject(c->root)) return gltf_fail(c, SSS_ERROR_PARSE, "expected a JSON object at the top level");
    const cJSON *asset = gltf_get(c->root, "asset");
    if (!asset) return gltf_fail(c, SSS_ERROR_PARSE, "asset: required field missing");
    const cJSON *version = gltf_get(asset, "version");
    if (!cJSON_IsString(version)) return gltf_fail(c, SSS_ERROR_PARSE, "asset.version: expected a string");
    if (strncmp(version->valuestring, "2.", 2) != 0)
        return gltf_fail(c, SSS_ERROR_UNSUPPORTED, "asset.version: \"%s\" (only glTF 2.x is supported)",
                         version->valuestring);
    const cJSON *required = gltf_get(c->root, "extensionsRequired"), *used = gltf_get(c->root, "extensionsUsed");
    if (required && !cJSON_IsArray(required))
        return gltf_fail(c, SSS_ERROR_PARSE, "extensionsRequired: expected an array");
    int i = 0;
    for (const cJSON *e = required ? required->child : NULL; e; e = e->next, i++) {
        if (!cJSON_IsString(e)) return gltf_fail(c, SSS_ERROR_PARSE, "extensionsRequired[%d]: expected a string", i);
        if (!extension_supported(e->valuestring))
            return gltf_fail(c, SSS_ERROR_UNSUPPORTED, "extensionsRequired[%d]: \"%s\" is not supported", i,
                             e->valuestring);
        c->quantization |= strcmp(e->valuestring, "KHR_mesh_quantization") == 0;
    }
    /* KHR_mesh_quantization must be required where used; an asset that only lists it as used is read
     * as meant all the same */
    for (const cJSON *e = cJSON_IsArray(used) ? used->child : NULL; e; e = e->next)
        c->quantization |= cJSON_IsString(e) && strcmp(e->valuestring, "KHR_mesh_quantization") == 0;
    return SSS_OK;
}

sss_result gltf_open(gltf_ctx *c, const unsigned char *data, size_t size)
{
    const char *json = (const char *)data;
    size_t json_size = size;
    sss_result res;
    if (size >= 4 && read_u32(data) == GLB_MAGIC && (res = split_glb(c, data, size, &json, &json_size)) != SSS_OK)
        return res;
    if (json_size > SSS_GLTF_MAX_JSON_SIZE)
        return gltf_fail(c, SSS_ERROR_LIMIT, "JSON of %zu bytes, more than the %u accepted", json_size,
                         (unsigned)SSS_GLTF_MAX_JSON_SIZE);
    jr r;
    jr_init(&r, c->name, c->err);
    if ((res = jr_parse(&r, json, json_size, &c->root)) != SSS_OK) return res;
    if ((res = check_root(c)) != SSS_OK || (res = index_lists(c)) != SSS_OK) return res;
    c->buffer_count = gltf_count(c, GLTF_BUFFERS);
    if (c->buffer_count && !(c->buffers = calloc(c->buffer_count, sizeof *c->buffers)))
        return gltf_fail(c, SSS_ERROR_OUT_OF_MEMORY, "out of memory");
    return SSS_OK;
}

void gltf_close(gltf_ctx *c)
{
    for (size_t i = 0; c->decoded_views && i < gltf_count(c, GLTF_BUFFER_VIEWS); i++) free(c->decoded_views[i]);
    free(c->decoded_views);
    c->decoded_views = NULL;
    for (size_t i = 0; i < c->buffer_count; i++) free(c->buffers[i].owned);
    free(c->buffers);
    for (int i = 0; i < GLTF_LIST_COUNT; i++) free(c->lists[i].items);
    memset(c->lists, 0, sizeof c->lists);
    cJSON_Delete(c->root);
    c->buffers = NULL;
    c->buffer_count = 0;
    c->root = NULL;
}

static int base64_value(int ch)
{
    if (ch >= 'A' && ch <= 'Z') return ch - 'A';
    if (ch >= 'a' && ch <= 'z') return ch - 'a' + 26;
    if (ch >= '0' && ch <= '9') return ch - '0' + 52;
    if (ch == '+' || ch == '-') return 62;
    if (ch == '/' || ch == '_') return 63;
    return -1;
}

/* RFC 4648 base64 (padding optional); returns 0 on a character outside the alphabet. */
static int base64_decode(const char *text, unsigned char *out, size_t *out_size)
{
    size_t n = 0;
    uint32_t acc = 0;
    int bits = 0;
    for (const char *p = text; *p && *p != '='; p++) {
        int v = base64_value((unsigned char)*p);
        if (v < 0) return 0;
        acc = (acc << 6) | (uint32_t)v;
        bits += 6;
        if (bits >= 8) {
            bits -= 8;
            out[n++] = (unsigned char)(acc >> bits);
        }
    }
    *out_size = n;
    return 1;
}

sss_result gltf_data_uri(gltf_ctx *c, const char *uri, const char *path, unsigned char **owned, size_t *size)
{
    *owned = NULL;
    *size = 0;
    const char *comma = strstr(uri, ";base64,");
    if (!comma) return gltf_fail(c, SSS_ERROR_UNSUPPORTED, "%s: a data URI that is not base64", path);
    const char *text = comma + 8;
    if (!(*owned = malloc(strlen(text) / 4 * 3 + 3))) return gltf_fail(c, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    if (!base64_decode(text, *owned, size)) return gltf_fail(c, SSS_ERROR_PARSE, "%s: invalid base64", path);
    return SSS_OK;
}

static int hex_value(int ch)
{
    if (ch >= '0' && ch <= '9') return ch - '0';
    ch = tolower(ch);
    return ch >= 'a' && ch <= 'f' ? ch - 'a' + 10 : -1;
}

/* base_dir + "/" + the percent-decoded relative URI (glTF URIs are RFC 3986 references), or NULL when
 * the URI is absolute (has a scheme or starts with '/') or malformed. */
char *gltf_resolve_uri(const char *base_dir, const char *uri)
{
    if (uri[0] == '/' || strchr(uri, ':')) return NULL;
    size_t nb = base_dir ? strlen(base_dir) : 0, nu = strlen(uri);
    char *path = malloc(nb + nu + 2);
    if (!path) return NULL;
    size_t n = 0;
    if (nb) {
        memcpy(path, base_dir, nb);
        n = nb;
        if (path[n - 1] != '/') path[n++] = '/';
    }
    for (size_t i = 0; i < nu; i++) {
        if (uri[i] == '%') {
            int hi = i + 2 < nu ? hex_value((unsigned char)uri[i + 1]) : -1;
            int lo = hi >= 0 ? hex_value((unsigned char)uri[i + 2]) : -1;
            if (lo < 0 || (hi == 0 && lo == 0)) {
                free(path);
                return NULL;
            }
            path[n++] = (char)(hi * 16 + lo);
            i += 2;
        } else {
            path[n++] = uri[i];
        }
    }
    path[n] = '\0';
    return path;
}

static sss_result load_buffer(gltf_ctx *c, long index, gltf_buffer *b)
{
    const cJSON *def = gltf_item(c, GLTF_BUFFERS, index);
    char path[64];
    snprintf(path, sizeof path, "buffers[%ld]", index);
    sss_result res;
    long byte_length = 0;
    if ((res = gltf_object(c, def, path)) != SSS_OK) return res;
    if ((res = gltf_int(c, def, path, "byteLength", 1, 0, 1, (long)SSS_GLTF_MAX_FILE_SIZE, &byte_length)) != SSS_OK)
        return res;
    const cJSON *uri = gltf_get(def, "uri");
    if (!uri) {
        if (index != 0 || !c->glb_bin)
            return gltf_fail(c, SSS_ERROR_PARSE, "%s: no uri, and it is not the BIN chunk of a .glb", path);
        b->data = c->glb_bin;
        b->size = c->glb_bin_size;
    } else if (!cJSON_IsString(uri)) {
        return gltf_fail(c, SSS_ERROR_PARSE, "%s.uri: expected a string", path);
    } else if (strncmp(uri->valuestring, "data:", 5) == 0) {
        char uri_path[80];
        snprintf(uri_path, sizeof uri_path, "%s.uri", path);
        if ((res = gltf_data_uri(c, uri->valuestring, uri_path, &b->owned, &b->size)) != SSS_OK) return res;
        b->data = b->owned;
    } else {
        char *file = gltf_resolve_uri(c->base_dir, uri->valuestring);
        if (!file)
            return gltf_fail(c, SSS_ERROR_UNSUPPORTED, "%s.uri: \"%s\" is not a relative file reference", path,
                             uri->valuestring);
        char *bytes = NULL;
        sss_error inner = {0};
        res = sss_read_file(file, SSS_GLTF_MAX_FILE_SIZE, &bytes, &b->size, &inner);
        free(file);
        if (res != SSS_OK) return gltf_fail(c, res, "%s.uri: %s", path, inner.message);
        b->owned = (unsigned char *)bytes;
        b->data = b->owned;
    }
    if (b->size < (size_t)byte_length)
        return gltf_fail(c, SSS_ERROR_PARSE, "%s: byteLength is %ld but the data holds %zu bytes", path, byte_length,
                         b->size);
    b->size = (size_t)byte_length;
    b->loaded = 1;
    return SSS_OK;
}

sss_result gltf_buffer_data(gltf_ctx *c, long index, const char *path, const unsigned char **data,
                            size_t *size)
{
    if (index < 0 || (size_t)index >= c->buffer_count)
        return gltf_fail(c, SSS_ERROR_PARSE, "%s: buffer %ld does not exist (%zu buffers)", path, index,
                         c->buffer_count);
    gltf_buffer *b = &c->buffers[index];
    if (!b->loaded) {
        sss_result res = load_buffer(c, index, b);
        if (res != SSS_OK) {
            free(b->owned);
            memset(b, 0, sizeof *b);
            return res;
        }
    }
    *data = b->data;
    *size = b->size;
    return SSS_OK;
}

/* ---- The files an asset reads --------------------------------------------------------------------- */

sss_result gltf_add_file(sss_gltf_scene *out, const char *path)
{
    char **grown = realloc(out->files, (out->file_count + 1) * sizeof *grown);
    char *copy = grown ? malloc(strlen(path) + 1) : NULL;
    if (grown) out->files = grown;
    if (!copy) return SSS_ERROR_OUT_OF_MEMORY;
    strcpy(copy, path);
    out->files[out->file_count++] = copy;
    return SSS_OK;
}

/* The external files of the root array key ("buffers", "images"): every string uri that is not a data:
 * URI and resolves to a relative file (the others are refused where they are used). */
static sss_result list_uris(gltf_ctx *c, const char *key, sss_gltf_scene *out)
{
    const cJSON *arr = gltf_get(c->root, key);
    for (const cJSON *e = cJSON_IsArray(arr) ? arr->child : NULL; e; e = e->next) {
        const cJSON *uri = gltf_get(e, "uri");
        if (!cJSON_IsString(uri) || strncmp(uri->valuestring, "data:", 5) == 0) continue;
        char *file = gltf_resolve_uri(c->base_dir, uri->valuestring);
        sss_result res = file ? gltf_add_file(out, file) : SSS_OK;
        free(file);
        if (res != SSS_OK) return gltf_fail(c, res, "%s: out of memory", key);
    }
    return SSS_OK;
}

sss_result gltf_list_files(gltf_ctx *c, sss_gltf_scene *out)
{
    sss_result res = list_uris(c, "buffers", out);
    return res == SSS_OK ? list_uris(c, "images", out) : res;
}
