/* scene/gltf_draco.h — the Draco decoder (Debian's libdraco-dev, a C++ library) behind a C interface,
 * implemented in gltf_draco_decode.cpp as src/view/panel_imgui.cpp wraps Dear ImGui (internal). */
#ifndef SSS_SCENE_GLTF_DRACO_H
#define SSS_SCENE_GLTF_DRACO_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* An attribute to take from the decoded mesh: in, its unique id in the stream and the number of
 * components it must have; out, its values per point as floats (malloc'd; normalized integers mapped
 * to [0, 1] or [-1, 1]). */
typedef struct gltf_draco_attribute {
    uint32_t unique_id;
    int components;
    float *values;
} gltf_draco_attribute;

/* The decoded mesh: its points and triangles (3 indices each, malloc'd). */
typedef struct gltf_draco_mesh {
    uint32_t point_count, face_count;
    uint32_t *indices;
} gltf_draco_mesh;

/* Decodes the Draco mesh stream data[0..size) and takes attrs[0..count). Returns 0, or -1 with a message
 * in msg (cap bytes) and nothing allocated; no exception leaves it. */
int gltf_draco_decode(const unsigned char *data, size_t size, gltf_draco_attribute *attrs, int count,
                      gltf_draco_mesh *out, char *msg, size_t cap);

#ifdef __cplusplus
}
#endif
#endif
