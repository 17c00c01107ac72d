#!/usr/bin/env bash
# Writes the compressed glTF test assets of tests/scene/test_gltf.c and tests/cli/test_gltf_compressed.sh
# (small, committed; rerun to regenerate) from assets/bunny.ply (1,839 vertices, 3,674 triangles, with
# normals) through an independent writer, the npm package @gltf-transform/cli 4.5.1 (Draco by its
# draco3dgltf, meshopt by meshoptimizer's JavaScript encoder):
#   bunny_draco.glb            KHR_draco_mesh_compression, edgebreaker (reorders vertices and triangles)
#   bunny_draco_sequential.glb KHR_draco_mesh_compression, sequential
#   bunny_meshopt.glb          EXT_meshopt_compression + KHR_mesh_quantization (gltf-transform's defaults)
#   bunny_quantized.glb        KHR_mesh_quantization alone (16-bit positions, 8-bit normals)
# Each holds the bunny world-space as `sss export gltf` writes it (positions, normals, 32-bit indices).
# And fuzz seeds (fuzz/corpus/gltf, under the fuzzer's 16 KiB): scatter.glb (six cubes) as draco.glb,
# meshopt.glb and quantized.glb, and meshopt_huge.glb (a view claiming 2 GiB decoded).
# Usage: bash make_compressed.sh SSS_BINARY   (npx fetches @gltf-transform/cli@4.5.1 on first use)
set -euo pipefail
SSS=$1
here=$(cd "$(dirname "$0")" && pwd)
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
cat >"$tmp/bunny.json" <<JSON
{"camera": {"position": [0, 5, 25], "look_at": [0, 5, 0], "fov": 35, "width": 64, "height": 64},
 "objects": [{"mesh": "$here/../../../assets/bunny.ply", "material": {"type": "diffuse", "reflectance": [0.8, 0.8, 0.8]}}]}
JSON
"$SSS" export gltf "$tmp/bunny.json" -o "$tmp/bunny.glb"
gt() { npx --yes @gltf-transform/cli@4.5.1 "$@"; }
gt draco "$tmp/bunny.glb" "$here/bunny_draco.glb"
gt draco "$tmp/bunny.glb" "$here/bunny_draco_sequential.glb" --method sequential
gt meshopt "$tmp/bunny.glb" "$here/bunny_meshopt.glb"
gt quantize "$tmp/bunny.glb" "$here/bunny_quantized.glb"
seeds=$here/../../../fuzz/corpus/gltf
gt draco "$here/scatter.glb" "$seeds/draco.glb"
gt meshopt "$here/scatter.glb" "$seeds/meshopt.glb"
gt quantize "$here/scatter.glb" "$seeds/quantized.glb"
python3 - "$seeds/meshopt.glb" "$seeds/meshopt_huge.glb" <<'PY'
import json, struct, sys
d = open(sys.argv[1], "rb").read()
n = struct.unpack_from("<I", d, 12)[0]
j = json.loads(d[20:20 + n])
view = next(v for v in j["bufferViews"] if v.get("extensions", {}).get("EXT_meshopt_compression", {}).get("mode") == "ATTRIBUTES")
ext = view["extensions"]["EXT_meshopt_compression"]
ext["count"] = 1 << 28
view["byteLength"] = ext["byteStride"] << 28
t = json.dumps(j).encode()
t += b" " * (-len(t) % 4)
rest = d[20 + n:]
open(sys.argv[2], "wb").write(struct.pack("<4sII", b"glTF", 2, 20 + len(t) + len(rest)) + struct.pack("<I4s", len(t), b"JSON") + t + rest)
PY
