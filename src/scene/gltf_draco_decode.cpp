// Draco's decoder (Debian's libdraco-dev 1.5.5) behind the C interface of scene/gltf_draco.h. The stream's
// header was checked by the caller (gltf_draco.c: its triangle count within the limits and the decoding
// budget); here the mesh is decoded, each requested attribute looked up by its unique id and converted
// to floats (Draco checks every address it converts from), and the faces copied. No exception leaves
// this file: std::bad_alloc and anything else Draco or the standard library throws become messages.
#include "scene/gltf_draco.h"

#include <draco/compression/decode.h>

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <new>

namespace {

void release(gltf_draco_attribute *attrs, int count, gltf_draco_mesh *out)
{
    for (int i = 0; i < count; i++) {
        std::free(attrs[i].values);
        attrs[i].values = nullptr;
    }
    std::free(out->indices);
    out->indices = nullptr;
}

// attrs[i].values: the attribute's value at every point, as floats; false with a message on failure.
bool take_attribute(const draco::Mesh &mesh, gltf_draco_attribute *a, char *msg, size_t cap)
{
    const draco::PointAttribute *att = mesh.GetAttributeByUniqueId(a->unique_id);
    if (!att) {
        std::snprintf(msg, cap, "no attribute with the unique id %u in the Draco data", (unsigned)a->unique_id);
        return false;
    }
    if (att->num_components() != a->components) {
        std::snprintf(msg, cap, "the Draco attribute %u has %d components, %d expected", (unsigned)a->unique_id,
                      (int)att->num_components(), a->components);
        return false;
    }
    size_t n = mesh.num_points(), k = static_cast<size_t>(a->components);
    a->values = static_cast<float *>(std::malloc(n * k * sizeof(float) + 1));
    if (!a->values) {
        std::snprintf(msg, cap, "out of memory");
        return false;
    }
    if (!att->is_mapping_identity() && att->indices_map_size() < n) {
        std::snprintf(msg, cap, "the Draco attribute %u maps %zu of %zu points", (unsigned)a->unique_id,
                      att->indices_map_size(), n);
        return false;
    }
    for (size_t p = 0; p < n; p++) {
        draco::AttributeValueIndex v = att->mapped_index(draco::PointIndex(static_cast<uint32_t>(p)));
        if (v.value() >= att->size() || !att->ConvertValue<float>(v, a->components, a->values + p * k)) {
            std::snprintf(msg, cap, "the Draco attribute %u has no value for point %zu", (unsigned)a->unique_id, p);
            return false;
        }
    }
    return true;
}

bool decode(const unsigned char *data, size_t size, gltf_draco_attribute *attrs, int count, gltf_draco_mesh *out,
            char *msg, size_t cap)
{
    draco::DecoderBuffer buffer;
    buffer.Init(reinterpret_cast<const char *>(data), size);
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
    if (!decoded.ok()) {
        std::snprintf(msg, cap, "the Draco data does not decode: %s", decoded.status().error_msg());
        return false;
    }
    std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
    out->point_count = mesh->num_points();
    out->face_count = mesh->num_faces();
    out->indices = static_cast<uint32_t *>(std::malloc(3 * static_cast<size_t>(out->face_count) * sizeof(uint32_t) + 1));
    if (!out->indices) {
        std::snprintf(msg, cap, "out of memory");
        return false;
    }
    for (uint32_t f = 0; f < out->face_count; f++) {
        const draco::Mesh::Face &face = mesh->face(draco::FaceIndex(f));
        for (int k = 0; k < 3; k++) out->indices[3 * static_cast<size_t>(f) + k] = face[k].value();
    }
    for (int i = 0; i < count; i++)
        if (!take_attribute(*mesh, &attrs[i], msg, cap)) return false;
    return true;
}

} // namespace

extern "C" int gltf_draco_decode(const unsigned char *data, size_t size, gltf_draco_attribute *attrs, int count,
                                 gltf_draco_mesh *out, char *msg, size_t cap)
{
    out->point_count = out->face_count = 0;
    out->indices = nullptr;
    for (int i = 0; i < count; i++) attrs[i].values = nullptr;
    bool ok = false;
    try {
        ok = decode(data, size, attrs, count, out, msg, cap);
    } catch (const std::bad_alloc &) {
        std::snprintf(msg, cap, "out of memory decoding the Draco data");
    } catch (...) {
        std::snprintf(msg, cap, "the Draco decoder failed");
    }
    if (!ok) release(attrs, count, out);
    return ok ? 0 : -1;
}
