/* sss_export_gltf: a scene as one binary glTF 2.0 file (docs/gltf.md, "Export"), the reverse of the
 * importer (src/scene/gltf_*.c): world-space meshes, subsurface materials as KHR_materials_volume +
 * KHR_materials_volume_scatter (+ _ior, _diffuse_transmission) or KHR_materials_scatter (+ _ior,
 * _transmission) with their albedo textures as embedded
 * PNG baseColorTextures, the camera, KHR_lights_punctual. */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/file_util.h"
#include "sss/export.h"

typedef struct glb {
    unsigned char *bin;
    size_t size, cap;
    cJSON *root, *views, *accessors, *nodes, *scene_nodes;
    int ok;
} glb;

static void append(glb *g, const void *data, size_t bytes)
{
    size_t need = g->size + bytes + 3;
    if (!g->ok) return;
    if (need > g->cap) {
        size_t cap = g->cap ? g->cap : 1 << 16;
        while (cap < need) cap *= 2;
        unsigned char *grown = realloc(g->bin, cap);
        if (!grown) {
            g->ok = 0;
            return;
        }
        g->bin = grown;
        g->cap = cap;
    }
    memcpy(g->bin + g->size, data, bytes);
    g->size += bytes;
    while (g->size % 4) g->bin[g->size++] = 0; /* accessors of 4-byte components stay aligned */
}

static cJSON *add_object(glb *g, cJSON *array)
{
    cJSON *o = cJSON_CreateObject();
    if (!o || !cJSON_AddItemToArray(array, o)) {
        cJSON_Delete(o);
        g->ok = 0;
        return NULL;
    }
    return o;
}

static void add_number(glb *g, cJSON *obj, const char *key, double v)
{
    if (!obj || !cJSON_AddNumberToObject(obj, key, v)) g->ok = 0;
}

static void add_vec(glb *g, cJSON *obj, const char *key, const double *v, int n)
{
    cJSON *a = cJSON_CreateDoubleArray(v, n);
    if (!obj || !a || !cJSON_AddItemToObject(obj, key, a)) {
        cJSON_Delete(a);
        g->ok = 0;
    }
}

static cJSON *add_child(glb *g, cJSON *obj, const char *key)
{
    cJSON *c = obj ? cJSON_AddObjectToObject(obj, key) : NULL;
    if (!c) g->ok = 0;
    return c;
}

/* A buffer view over the bytes just appended, and an accessor on it; returns the accessor's index. */
static int add_accessor(glb *g, const void *data, size_t count, int components, int ctype, const char *type,
                        const double *lo, const double *hi)
{
    size_t offset = g->size, bytes = count * (size_t)components * 4;
    append(g, data, bytes);
    cJSON *view = add_object(g, g->views);
    add_number(g, view, "buffer", 0);
    add_number(g, view, "byteOffset", (double)offset);
    add_number(g, view, "byteLength", (double)bytes);
    add_number(g, view, "target", components == 1 ? 34963 : 34962); /* ELEMENT_ARRAY_BUFFER or ARRAY_BUFFER */
    cJSON *acc = add_object(g, g->accessors);
    add_number(g, acc, "bufferView", cJSON_GetArraySize(g->views) - 1);
    add_number(g, acc, "componentType", ctype);
    add_number(g, acc, "count", (double)count);
    if (acc && !cJSON_AddStringToObject(acc, "type", type)) g->ok = 0;
    if (lo) add_vec(g, acc, "min", lo, components);
    if (hi) add_vec(g, acc, "max", hi, components);
    return cJSON_GetArraySize(g->accessors) - 1;
}

/* The scene's albedo textures as images[k] (embedded PNG) and textures[k], k = index in scene->textures:
 * 8-bit sRGB, so a texture decoded from a PNG goes back to its exact bytes (HDR values clip at 1). */
static void add_textures(glb *g, const sss_scene *s, sss_error *err)
{
    if (s->texture_count == 0) return;
    cJSON *images = cJSON_AddArrayToObject(g->root, "images"), *textures = cJSON_AddArrayToObject(g->root, "textures");
    if (!images || !textures) g->ok = 0;
    for (size_t k = 0; g->ok == 1 && k < s->texture_count; k++) {
        unsigned char *png = NULL;
        size_t bytes = 0;
        if (sss_image_encode_png(&s->textures[k].image, 0.0, &png, &bytes, err) != SSS_OK) {
            sss_error_prefix(err, s->textures[k].path);
            g->ok = -1; /* err is set */
            return;
        }
        size_t offset = g->size;
        append(g, png, bytes);
        free(png);
        cJSON *view = add_object(g, g->views);
        add_number(g, view, "buffer", 0);
        add_number(g, view, "byteOffset", (double)offset);
        add_number(g, view, "byteLength", (double)bytes);
        cJSON *image = add_object(g, images);
        add_number(g, image, "bufferView", cJSON_GetArraySize(g->views) - 1);
        if (image && !cJSON_AddStringToObject(image, "mimeType", "image/png")) g->ok = 0;
        add_number(g, add_object(g, textures), "source", (double)k);
    }
}

/* A node at the end of nodes[], listed in the scene; matrix is row-major (glTF's is column-major). */
static cJSON *add_node(glb *g, const double m[16])
{
    cJSON *node = add_object(g, g->nodes);
    if (m) {
        double cm[16];
        for (int r = 0; r < 4; r++)
            for (int c = 0; c < 4; c++) cm[4 * c + r] = m[4 * r + c];
        add_vec(g, node, "matrix", cm, 16);
    }
    cJSON *index = cJSON_CreateNumber(cJSON_GetArraySize(g->nodes) - 1);
    if (!index || !cJSON_AddItemToArray(g->scene_nodes, index)) {
        cJSON_Delete(index);
        g->ok = 0;
    }
    return node;
}

/* The multiple-scattering albedo of the single-scattering albedo alpha, the importer's inversion
 * reversed (src/scene/gltf_material.c, Kulla & Conty 2017): rho = (1 - s)(1 - 0.139 s) / (1 + 1.17 s)
 * with s^2 = 1 - alpha (KHR_materials_volume_scatter) or (1 - alpha) / (1 - g alpha) (KHR_materials_scatter). */
static double multiscatter_albedo(double alpha, double g, int with_g)
{
    double s = sqrt(with_g ? (1 - alpha) / (1 - g * alpha) : 1 - alpha);
    return (1 - s) * (1 - 0.139 * s) / (1 + 1.17 * s);
}

/* The scattering extension(s) of a subsurface material: rho as the multiple-scattering albedo. */
static void add_scattering(glb *g, cJSON *ext, const double rho[3], double aniso, sss_export_gltf_scatter which)
{
    if (which == SSS_EXPORT_GLTF_SCATTER) {
        cJSON *scatter = add_child(g, ext, "KHR_materials_scatter");
        add_number(g, scatter, "scatterStrengthFactor", 1);
        add_vec(g, scatter, "multiscatterColorFactor", rho, 3);
        add_number(g, scatter, "scatterAnisotropy", aniso);
        /* the draft: no effect without transmission, which lets the light into the volume */
        add_number(g, add_child(g, ext, "KHR_materials_transmission"), "transmissionFactor", 1);
        return;
    }
    cJSON *scatter = add_child(g, ext, "KHR_materials_volume_scatter");
    add_vec(g, scatter, "multiscatterColor", rho, 3);
    add_number(g, scatter, "scatterAnisotropy", aniso);
    add_number(g, add_child(g, ext, "KHR_materials_diffuse_transmission"), "diffuseTransmissionFactor", 1);
}

/* Subsurface: sigma_t = sigma_a + sigma_s per scene unit as attenuationColor c = exp(-sigma_t d) at
 * d = 1 / max(sigma_t) (c in [1/e, 1), well resolved), alpha = sigma_s / sigma_t as the multiple-
 * scattering albedo of the chosen extension. */
static void add_material(glb *g, cJSON *materials, const sss_scene *s, const sss_scene_material *m,
                         sss_export_gltf_scatter which)
{
    cJSON *mat = add_object(g, materials), *pbr = add_child(g, mat, "pbrMetallicRoughness");
    for (size_t k = 0; m->texture_image && k < s->texture_count; k++)
        if (&s->textures[k].image == m->texture_image)
            add_number(g, add_child(g, pbr, "baseColorTexture"), "index", (double)k);
    double base[4] = {m->albedo[0], m->albedo[1], m->albedo[2], 1};
    for (int k = 0; k < 3; k++) base[k] = base[k] < 0 ? 0 : base[k] > 1 ? 1 : base[k];
    add_vec(g, pbr, "baseColorFactor", base, 4);
    add_number(g, pbr, "metallicFactor", 0);
    add_number(g, pbr, "roughnessFactor", m->has_specular ? m->roughness : 1);
    if (m->type != SSS_SCENE_MATERIAL_SUBSURFACE) return;
    const sss_material *o = &m->optical;
    double sigma_t[3], max_t = 0, color[3], rho[3];
    for (int k = 0; k < 3; k++) {
        sigma_t[k] = o->sigma_a[k] + o->sigma_s[k];
        max_t = fmax(max_t, sigma_t[k]);
    }
    for (int k = 0; k < 3; k++) {
        color[k] = exp(-sigma_t[k] / max_t);
        rho[k] = multiscatter_albedo(o->sigma_s[k] / sigma_t[k], o->g, which == SSS_EXPORT_GLTF_SCATTER);
    }
    cJSON *ext = add_child(g, mat, "extensions");
    cJSON *volume = add_child(g, ext, "KHR_materials_volume");
    add_number(g, volume, "thicknessFactor", 1);
    add_number(g, volume, "attenuationDistance", 1 / max_t);
    add_vec(g, volume, "attenuationColor", color, 3);
    add_scattering(g, ext, rho, o->g, which);
    add_number(g, add_child(g, ext, "KHR_materials_ior"), "ior", o->eta);
}

static void add_mesh(glb *g, cJSON *meshes, const sss_mesh *w, int material)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < 3 * (size_t)w->vertex_count; i++) {
        lo[i % 3] = fmin(lo[i % 3], w->positions[i]);
        hi[i % 3] = fmax(hi[i % 3], w->positions[i]);
    }
    cJSON *prim = add_object(g, cJSON_AddArrayToObject(add_object(g, meshes), "primitives"));
    cJSON *attr = add_child(g, prim, "attributes");
    add_number(g, attr, "POSITION", add_accessor(g, w->positions, w->vertex_count, 3, 5126, "VEC3", lo, hi));
    add_number(g, attr, "NORMAL", add_accessor(g, w->normals, w->vertex_count, 3, 5126, "VEC3", NULL, NULL));
    if (w->uvs) {
        float *uv = malloc(2 * sizeof *uv * w->vertex_count);
        if (!uv) g->ok = 0;
        for (uint32_t i = 0; uv && i < w->vertex_count; i++) {
            uv[2 * i] = w->uvs[2 * i];
            uv[2 * i + 1] = 1.0f - w->uvs[2 * i + 1]; /* glTF's v runs down the image */
        }
        if (uv) add_number(g, attr, "TEXCOORD_0", add_accessor(g, uv, w->vertex_count, 2, 5126, "VEC2", NULL, NULL));
        free(uv);
    }
    add_number(g, prim, "indices", add_accessor(g, w->indices, 3 * (size_t)w->triangle_count, 1, 5125, "SCALAR", NULL, NULL));
    add_number(g, prim, "material", material);
}

/* A row-major matrix whose -z axis is dir (unit) and whose origin is at. */
static void frame_along(const double dir[3], const double at[3], double m[16])
{
    double z[3] = {-dir[0], -dir[1], -dir[2]}, helper[3] = {0, 1, 0}, x[3], y[3];
    if (fabs(z[1]) > 0.9) helper[1] = 0, helper[0] = 1;
    x[0] = helper[1] * z[2] - helper[2] * z[1], x[1] = helper[2] * z[0] - helper[0] * z[2], x[2] = helper[0] * z[1] - helper[1] * z[0];
    double len = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    for (int k = 0; k < 3; k++) x[k] /= len;
    y[0] = z[1] * x[2] - z[2] * x[1], y[1] = z[2] * x[0] - z[0] * x[2], y[2] = z[0] * x[1] - z[1] * x[0];
    for (int r = 0; r < 3; r++) {
        m[4 * r] = x[r], m[4 * r + 1] = y[r], m[4 * r + 2] = z[r], m[4 * r + 3] = at[r];
        m[12 + r] = 0;
    }
    m[15] = 1;
}

static void add_camera(glb *g, const sss_scene *s)
{
    const sss_camera_basis *b = &s->basis;
    double m[16] = {0}, aspect = (double)b->width / b->height;
    for (int r = 0; r < 3; r++) {
        m[4 * r] = b->right[r], m[4 * r + 1] = b->up[r], m[4 * r + 2] = -b->forward[r], m[4 * r + 3] = b->origin[r];
    }
    m[15] = 1;
    add_number(g, add_node(g, m), "camera", 0);
    cJSON *camera = add_object(g, cJSON_AddArrayToObject(g->root, "cameras"));
    if (camera && !cJSON_AddStringToObject(camera, "type", "perspective")) g->ok = 0;
    cJSON *persp = add_child(g, camera, "perspective");
    add_number(g, persp, "yfov", 2 * atan(b->tan_half[1])); /* tan_half[1]: the vertical half extent */
    add_number(g, persp, "aspectRatio", aspect);
    add_number(g, persp, "znear", 1e-3);
}

/* Point, spot and directional lights (color = value / its largest channel); others are counted. */
static void add_lights(glb *g, const sss_scene *s, int *skipped)
{
    cJSON *lights = NULL;
    for (size_t i = 0; i < s->light_count; i++) {
        const sss_light *l = &s->lights[i];
        if (l->type != SSS_LIGHT_POINT && l->type != SSS_LIGHT_SPOT && l->type != SSS_LIGHT_DIRECTIONAL) {
            (*skipped)++;
            continue;
        }
        if (!lights) {
            cJSON *ext = cJSON_GetObjectItemCaseSensitive(g->root, "extensions");
            if (!ext) ext = add_child(g, g->root, "extensions");
            lights = cJSON_AddArrayToObject(add_child(g, ext, "KHR_lights_punctual"), "lights");
        }
        const double *value = l->type == SSS_LIGHT_DIRECTIONAL ? l->radiance : l->intensity;
        double peak = fmax(value[0], fmax(value[1], value[2])), color[3], dir[3], m[16];
        for (int k = 0; k < 3; k++) color[k] = peak > 0 ? value[k] / peak : 1;
        cJSON *light = add_object(g, lights);
        const char *type = l->type == SSS_LIGHT_POINT ? "point" : l->type == SSS_LIGHT_SPOT ? "spot" : "directional";
        if (light && !cJSON_AddStringToObject(light, "type", type)) g->ok = 0;
        add_vec(g, light, "color", color, 3);
        add_number(g, light, "intensity", peak);
        if (l->type == SSS_LIGHT_DIRECTIONAL) {
            memcpy(dir, l->direction, sizeof dir);
        } else if (l->type == SSS_LIGHT_SPOT) {
            double len = 0;
            for (int k = 0; k < 3; k++) {
                dir[k] = l->look_at[k] - l->position[k];
                len += dir[k] * dir[k];
            }
            for (int k = 0; k < 3; k++) dir[k] /= sqrt(len);
        } else {
            dir[0] = dir[1] = 0, dir[2] = -1; /* a point light shines everywhere: any frame */
        }
        if (l->type == SSS_LIGHT_SPOT) {
            cJSON *spot = add_child(g, light, "spot");
            double outer = l->cone_angle * M_PI / 180, inner = (l->cone_angle - l->cone_delta) * M_PI / 180;
            add_number(g, spot, "outerConeAngle", outer);
            add_number(g, spot, "innerConeAngle", fmin(inner, nextafter(outer, 0))); /* glTF: inner < outer */
        }
        static const double origin[3] = {0, 0, 0};
        frame_along(dir, l->type == SSS_LIGHT_DIRECTIONAL ? origin : l->position, m);
        cJSON *lp = add_child(g, add_child(g, add_node(g, m), "extensions"), "KHR_lights_punctual");
        add_number(g, lp, "light", cJSON_GetArraySize(lights) - 1);
    }
}

static void put_u32(unsigned char *p, uint32_t v)
{
    for (int i = 0; i < 4; i++) p[i] = (unsigned char)(v >> (8 * i));
}

/* glTF 2.0 spec 4.4: header, JSON chunk (padded with spaces), BIN chunk (padded with zeros). */
static sss_result write_glb(const char *path, const char *json, const glb *g, sss_error *err)
{
    size_t json_len = strlen(json), json_padded = (json_len + 3) / 4 * 4;
    uint64_t total = 12 + 8 + json_padded + 8 + g->size;
    if (total > UINT32_MAX) return sss_error_set(err, SSS_ERROR_LIMIT, "%s: more than 4 GiB for a .glb", path);
    unsigned char header[20], bin_header[8];
    memcpy(header, "glTF", 4);
    put_u32(header + 4, 2);
    put_u32(header + 8, (uint32_t)total);
    put_u32(header + 12, (uint32_t)json_padded);
    memcpy(header + 16, "JSON", 4);
    put_u32(bin_header, (uint32_t)g->size);
    memcpy(bin_header + 4, "BIN", 4);
    char tmp[4096];
    FILE *f = sss_atomic_open(path, tmp, sizeof tmp, err);
    if (!f) return err ? err->code : SSS_ERROR_IO;
    fwrite(header, 1, sizeof header, f);
    fwrite(json, 1, json_len, f);
    for (size_t i = json_len; i < json_padded; i++) fputc(' ', f);
    fwrite(bin_header, 1, sizeof bin_header, f);
    if (g->size) fwrite(g->bin, 1, g->size, f);
    return sss_atomic_close(f, tmp, path, err);
}

static void add_document(glb *g, const sss_scene *scene, sss_export_gltf_desc *d, sss_error *err)
{
    cJSON *asset = add_child(g, g->root, "asset");
    if (asset && (!cJSON_AddStringToObject(asset, "version", "2.0") ||
                  !cJSON_AddStringToObject(asset, "generator", "sss export gltf"))) g->ok = 0;
    add_number(g, g->root, "scene", 0);
    g->scene_nodes = cJSON_AddArrayToObject(add_object(g, cJSON_AddArrayToObject(g->root, "scenes")), "nodes");
    g->nodes = cJSON_AddArrayToObject(g->root, "nodes");
    cJSON *meshes = cJSON_AddArrayToObject(g->root, "meshes"), *materials = cJSON_AddArrayToObject(g->root, "materials");
    g->views = cJSON_AddArrayToObject(g->root, "bufferViews");
    g->accessors = cJSON_AddArrayToObject(g->root, "accessors");
    if (!g->scene_nodes || !g->nodes || !meshes || !materials || !g->views || !g->accessors) g->ok = 0;
    add_textures(g, scene, err);
    for (size_t i = 0; g->ok == 1 && i < scene->object_count; i++) {
        sss_mesh world = {0};
        if (sss_scene_object_world_mesh(&scene->objects[i], d->time, &world, err) != SSS_OK) {
            g->ok = -1; /* err is set */
            break;
        }
        add_material(g, materials, scene, &scene->objects[i].material, d->scatter_extension);
        add_mesh(g, meshes, &world, (int)i);
        add_number(g, add_node(g, NULL), "mesh", (double)i);
        sss_mesh_free(&world);
    }
    add_camera(g, scene);
    add_lights(g, scene, &d->skipped_lights);
    cJSON *buffer = add_object(g, cJSON_AddArrayToObject(g->root, "buffers"));
    add_number(g, buffer, "byteLength", (double)g->size);
    /* extensionsUsed: the extensions that appear */
    static const char *const names[2][4] = {
        {"KHR_materials_volume", "KHR_materials_volume_scatter", "KHR_materials_ior", "KHR_materials_diffuse_transmission"},
        {"KHR_materials_volume", "KHR_materials_scatter", "KHR_materials_ior", "KHR_materials_transmission"}};
    int subsurface = 0, lights = cJSON_GetObjectItemCaseSensitive(g->root, "extensions") != NULL;
    for (size_t i = 0; i < scene->object_count; i++)
        subsurface |= scene->objects[i].material.type == SSS_SCENE_MATERIAL_SUBSURFACE;
    cJSON *used = subsurface || lights ? cJSON_AddArrayToObject(g->root, "extensionsUsed") : NULL;
    int scatter = d->scatter_extension == SSS_EXPORT_GLTF_SCATTER;
    for (int i = 0; subsurface && i < 4; i++) g->ok &= cJSON_AddItemToArray(used, cJSON_CreateString(names[scatter][i]));
    if (lights) g->ok &= cJSON_AddItemToArray(used, cJSON_CreateString("KHR_lights_punctual"));
}

sss_result sss_export_gltf(const sss_scene *scene, sss_export_gltf_desc *desc, const char *out_path, sss_error *err)
{
    sss_export_gltf_desc d = desc ? *desc : (sss_export_gltf_desc){0};
    d.skipped_lights = 0;
    if (!isfinite(d.time)) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "%s: export time is not finite", out_path);
    if (d.scatter_extension != SSS_EXPORT_GLTF_VOLUME_SCATTER && d.scatter_extension != SSS_EXPORT_GLTF_SCATTER)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "%s: unknown scatter extension %d", out_path,
                             (int)d.scatter_extension);
    glb g = {.root = cJSON_CreateObject(), .ok = 1};
    if (!g.root) g.ok = 0;
    if (g.ok) add_document(&g, scene, &d, err);
    char *json = g.ok == 1 ? cJSON_PrintUnformatted(g.root) : NULL;
    sss_result res = SSS_OK;
    if (g.ok < 0) res = err ? err->code : SSS_ERROR_INVALID_ARGUMENT;
    else if (!json) res = sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory", out_path);
    else res = write_glb(out_path, json, &g, err);
    free(json);
    cJSON_Delete(g.root);
    free(g.bin);
    if (desc) desc->skipped_lights = d.skipped_lights;
    return res;
}
