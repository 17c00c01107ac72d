#!/usr/bin/env python3
"""Writes the glTF test assets of tests/scene/test_gltf.c (small, committed; rerun to regenerate):

  scatter.gltf     the test scene, buffers as a base64 data: URI
  scatter.glb      the same scene as binary glTF (JSON chunk + BIN chunk)
  external.gltf    a triangle whose buffer is the external file "external data.bin" (URI with %20)
  textured.gltf    the cube, subsurface, baseColorTexture = the external albedo.png (2x2)
  textured_embedded.glb   the same with albedo.png's bytes in a bufferView of the BIN chunk
  textured_datauri.gltf   the same with albedo.png as a data:image/png URI
  textured_jpeg.glb       the same with tests/data/images/two_colours.jpg (libjpeg-turbo) in a bufferView
  (exported.glb: written by `sss export gltf exported_source.json -o exported.glb`)
  bad/truncated.glb        scatter.glb cut inside its BIN chunk
  bad/accessor_range.gltf  an accessor reaching past its buffer view
  bad/missing_buffer.gltf  a buffer URI naming a file that does not exist
  bad/required_ext.gltf    extensionsRequired lists an extension sss does not implement
  bad/index_range.gltf     an index beyond the vertex count
  bad/image_mime.glb       an embedded image whose mimeType is image/gif
  bad/image_corrupt.glb    an embedded "image/png" whose bytes are not a PNG

Usage: python3 make_assets.py [OUT_DIR]   (default: this script's folder)
"""
import base64
import json
import math
import os
import struct
import sys

OUT = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))


def cube():
    """A unit cube centred at the origin: 24 vertices (normals and UVs per face), 36 indices,
    counter-clockwise seen from outside."""
    faces = [((1, 0, 0), (0, 1, 0)), ((-1, 0, 0), (0, 1, 0)), ((0, 1, 0), (0, 0, 1)),
             ((0, -1, 0), (0, 0, 1)), ((0, 0, 1), (0, 1, 0)), ((0, 0, -1), (0, 1, 0))]
    pos, nrm, uv, idx = [], [], [], []
    for n, up in faces:
        # right = up x n, so that (right, up) is counter-clockwise seen along -n (from outside)
        r = (up[1] * n[2] - up[2] * n[1], up[2] * n[0] - up[0] * n[2], up[0] * n[1] - up[1] * n[0])
        base = len(pos)
        for su, sv in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
            pos.append(tuple(0.5 * n[k] + 0.5 * su * r[k] + 0.5 * sv * up[k] for k in range(3)))
            nrm.append(n)
            uv.append((0.5 + 0.5 * su, 0.5 - 0.5 * sv))
        idx += [base, base + 1, base + 2, base, base + 2, base + 3]
    return pos, nrm, uv, idx


def quat(axis, degrees):
    length = math.sqrt(sum(a * a for a in axis))
    h = math.radians(degrees) / 2
    return [axis[0] / length * math.sin(h), axis[1] / length * math.sin(h), axis[2] / length * math.sin(h), math.cos(h)]


def pack_cube():
    pos, nrm, uv, idx = cube()
    blob = b"".join(struct.pack("<3f", *p) for p in pos)
    blob += b"".join(struct.pack("<3f", *n) for n in nrm)
    blob += b"".join(struct.pack("<2f", *t) for t in uv)
    blob += struct.pack("<%dH" % len(idx), *idx)
    blob += b"\0" * (-len(blob) % 4)
    n = len(pos)
    views = [{"buffer": 0, "byteOffset": 0, "byteLength": 12 * n},
             {"buffer": 0, "byteOffset": 12 * n, "byteLength": 12 * n},
             {"buffer": 0, "byteOffset": 24 * n, "byteLength": 8 * n},
             {"buffer": 0, "byteOffset": 32 * n, "byteLength": 2 * len(idx)}]
    lo = [min(p[k] for p in pos) for k in range(3)]
    hi = [max(p[k] for p in pos) for k in range(3)]
    accessors = [{"bufferView": 0, "componentType": 5126, "count": n, "type": "VEC3", "min": lo, "max": hi},
                 {"bufferView": 1, "componentType": 5126, "count": n, "type": "VEC3"},
                 {"bufferView": 2, "componentType": 5126, "count": n, "type": "VEC2"},
                 {"bufferView": 3, "componentType": 5123, "count": len(idx), "type": "SCALAR"}]
    return blob, views, accessors


def scatter_doc():
    blob, views, accessors = pack_cube()
    prim = {"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3}
    materials = [
        {"name": "scatter", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.6, 0.5, 1]},
         "extensions": {
             "KHR_materials_volume": {"thicknessFactor": 1, "attenuationDistance": 0.25,
                                      "attenuationColor": [0.5, 0.25, 0.125]},
             "KHR_materials_volume_scatter": {"multiscatterColor": [0.9, 0.6, 0.3], "scatterAnisotropy": 0.3},
             "KHR_materials_ior": {"ior": 1.4},
             "KHR_materials_diffuse_transmission": {"diffuseTransmissionFactor": 1}}},
        {"name": "diffuse", "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.4, 0.6, 1]}},
        {"name": "absorbing glass", "pbrMetallicRoughness": {"baseColorFactor": [0.7, 0.7, 0.7, 1]},
         "extensions": {"KHR_materials_volume": {"thicknessFactor": 1, "attenuationDistance": 1,
                                                 "attenuationColor": [0.5, 0.5, 0.5]}}},
        {"name": "scatter defaults",
         "extensions": {"KHR_materials_volume": {"thicknessFactor": 0.5, "attenuationDistance": 2,
                                                 "attenuationColor": [0.1, 0.2, 0.4]},
                        "KHR_materials_volume_scatter": {"multiscatterColor": [0.95, 0.5, 0.05]}}},
    ]
    meshes = [{"primitives": [dict(prim, material=i)]} for i in range(4)]
    c30, s30 = math.cos(math.radians(30)), math.sin(math.radians(30))
    # rotation about +y by 30 degrees, uniform scale 1.5, translation (-2, 0, 0); column-major
    matrix = [1.5 * c30, 0, -1.5 * s30, 0, 0, 1.5, 0, 0, 1.5 * s30, 0, 1.5 * c30, 0, -2, 0, 0, 1]
    nodes = [
        {"name": "parent", "translation": [1, 0, 0], "children": [1]},
        {"name": "child", "mesh": 0, "translation": [0, 0.5, 0], "rotation": quat((1, 1, 0), 60),
         "scale": [2, 1, 0.5]},
        {"name": "matrix", "mesh": 1, "matrix": matrix},
        {"name": "glass", "mesh": 2, "translation": [0, 0, -3]},
        {"name": "defaults", "mesh": 3, "translation": [0, 0, 3]},
        {"name": "camera0", "camera": 0, "translation": [0, 1, 8], "rotation": quat((1, 0, 0), -7)},
        {"name": "camera1", "camera": 1, "translation": [8, 0, 0], "rotation": quat((0, 1, 0), 90)},
        {"name": "point", "translation": [2, 3, 4], "extensions": {"KHR_lights_punctual": {"light": 0}}},
        {"name": "spot", "translation": [0, 4, 0], "rotation": quat((1, 0, 0), -90),
         "extensions": {"KHR_lights_punctual": {"light": 1}}},
        {"name": "sun", "rotation": quat((1, 0, 0), -45), "extensions": {"KHR_lights_punctual": {"light": 2}}},
        {"name": "local", "mesh": 0},
        {"name": "mirror", "mesh": 1, "scale": [-1, 1, 1], "translation": [0, -3, 0]},
    ]
    doc = {
        "asset": {"version": "2.0", "generator": "sss tests/data/gltf/make_assets.py"},
        "extensionsUsed": ["KHR_materials_volume", "KHR_materials_volume_scatter", "KHR_materials_ior",
                           "KHR_materials_diffuse_transmission", "KHR_lights_punctual"],
        "extensionsRequired": ["KHR_materials_volume"],
        "scene": 0,
        "scenes": [{"nodes": [0, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11]}],
        "nodes": nodes,
        "meshes": meshes,
        "materials": materials,
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.6, "aspectRatio": 1.5, "znear": 0.1}},
                    {"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"type": "point", "color": [1, 0.5, 0.25], "intensity": 20},
            {"type": "spot", "intensity": 30, "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.5}},
            {"type": "directional", "intensity": 3}]}},
        "buffers": [{"byteLength": len(blob)}],
        "bufferViews": views,
        "accessors": accessors,
    }
    return doc, blob


def write_gltf(path, doc, blob):
    doc = json.loads(json.dumps(doc))
    doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64.b64encode(blob).decode()
    with open(path, "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")


def glb_bytes(doc, blob):
    text = json.dumps(doc, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    blob += b"\0" * (-len(blob) % 4)
    total = 12 + 8 + len(text) + 8 + len(blob)
    return (struct.pack("<4sII", b"glTF", 2, total) + struct.pack("<I4s", len(text), b"JSON") + text +
            struct.pack("<I4s", len(blob), b"BIN\0") + blob)


def triangle_doc(uri):
    blob = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
    return {"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
            "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
            "buffers": [{"uri": uri, "byteLength": len(blob)}],
            "bufferViews": [{"buffer": 0, "byteLength": len(blob)}],
            "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                           "min": [0, 0, 0], "max": [1, 1, 0]}]}, blob  # min/max: required for POSITION


def png_2x2(path):
    """A 2x2 RGB PNG: red, green / blue, white (top row first)."""
    import zlib
    rows = b"\0\xff\0\0\0\xff\0" + b"\0\0\0\xff\xff\xff\xff"
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xffffffff)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", 2, 2, 8, 2, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b""))


def textured_doc():
    """The cube with a subsurface material whose baseColorTexture is the external albedo.png, lit by a
    directional light (so that renders show the texture)."""
    blob, views, accessors = pack_cube()
    doc = {"asset": {"version": "2.0"}, "scenes": [{"nodes": [0, 1]}],
           "nodes": [{"mesh": 0}, {"rotation": list(quat((1, 0, 0), -20)),
                                   "extensions": {"KHR_lights_punctual": {"light": 0}}}],
           "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_volume", "KHR_materials_volume_scatter"],
           "extensions": {"KHR_lights_punctual": {"lights": [{"type": "directional", "intensity": 3}]}},
           "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3,
                                       "material": 0}]}],
           "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}},
                          "extensions": {"KHR_materials_volume": {"thicknessFactor": 1, "attenuationDistance": 1,
                                                                  "attenuationColor": [0.5, 0.5, 0.5]},
                                         "KHR_materials_volume_scatter": {"multiscatterColor": [0.8, 0.8, 0.8]}}}],
           "textures": [{"source": 0}], "images": [{"uri": "albedo.png"}],
           "buffers": [{"byteLength": len(blob)}], "bufferViews": views, "accessors": accessors}
    return doc, blob


def embed_image(doc, blob, data, mime):
    """doc's images[0] as data appended to blob in a new bufferView (returns the new blob)."""
    doc = json.loads(json.dumps(doc))
    blob += b"\0" * (-len(blob) % 4)
    doc["bufferViews"].append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data)})
    doc["images"] = [{"bufferView": len(doc["bufferViews"]) - 1, "mimeType": mime}]
    blob += data
    doc["buffers"][0]["byteLength"] = len(blob)
    return doc, blob


def dump(path, doc):
    with open(path, "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")


def main():
    os.makedirs(os.path.join(OUT, "bad"), exist_ok=True)
    doc, blob = scatter_doc()
    write_gltf(os.path.join(OUT, "scatter.gltf"), doc, blob)
    glb = glb_bytes(doc, blob)
    with open(os.path.join(OUT, "scatter.glb"), "wb") as f:
        f.write(glb)

    doc, blob = textured_doc()
    write_gltf(os.path.join(OUT, "textured.gltf"), doc, blob)
    png_2x2(os.path.join(OUT, "albedo.png"))

    with open(os.path.join(OUT, "albedo.png"), "rb") as f:
        png = f.read()
    with open(os.path.join(OUT, "..", "images", "two_colours.jpg"), "rb") as f:
        jpeg = f.read()
    for name, data, mime in (("textured_embedded.glb", png, "image/png"), ("textured_jpeg.glb", jpeg, "image/jpeg"),
                             (os.path.join("bad", "image_mime.glb"), png, "image/gif"),
                             (os.path.join("bad", "image_corrupt.glb"), b"\x89PNG not a png at all", "image/png")):
        d, b = embed_image(doc, blob, data, mime)
        with open(os.path.join(OUT, name), "wb") as f:
            f.write(glb_bytes(d, b))
    d = json.loads(json.dumps(doc))
    d["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(png).decode()}]
    write_gltf(os.path.join(OUT, "textured_datauri.gltf"), d, blob)

    tri, tri_blob = triangle_doc("external%20data.bin")
    dump(os.path.join(OUT, "external.gltf"), tri)
    with open(os.path.join(OUT, "external data.bin"), "wb") as f:
        f.write(tri_blob)

    with open(os.path.join(OUT, "bad", "truncated.glb"), "wb") as f:
        f.write(glb[: len(glb) - 100])

    tri, tri_blob = triangle_doc("data:application/octet-stream;base64," + base64.b64encode(tri_blob).decode())
    tri["accessors"][0]["count"] = 4  # 48 bytes from a 36-byte buffer view
    dump(os.path.join(OUT, "bad", "accessor_range.gltf"), tri)

    tri, _ = triangle_doc("missing.bin")
    dump(os.path.join(OUT, "bad", "missing_buffer.gltf"), tri)

    tri, _ = triangle_doc("data:application/octet-stream;base64," + base64.b64encode(tri_blob).decode())
    tri["extensionsUsed"] = tri["extensionsRequired"] = ["KHR_materials_volume", "KHR_texture_basisu"]
    dump(os.path.join(OUT, "bad", "required_ext.gltf"), tri)

    tri, _ = triangle_doc("data:application/octet-stream;base64," +
                          base64.b64encode(tri_blob + struct.pack("<3H", 0, 1, 3) + b"\0\0").decode())
    tri["buffers"][0]["byteLength"] = len(tri_blob) + 8
    tri["bufferViews"].append({"buffer": 0, "byteOffset": len(tri_blob), "byteLength": 6})
    tri["accessors"].append({"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"})
    tri["meshes"][0]["primitives"][0]["indices"] = 1
    dump(os.path.join(OUT, "bad", "index_range.gltf"), tri)


if __name__ == "__main__":
    main()
