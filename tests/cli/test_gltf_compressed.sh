#!/usr/bin/env bash
# Compressed glTF (issue 30): the bunny as Draco (edgebreaker, sequential), EXT_meshopt_compression +
# KHR_mesh_quantization and KHR_mesh_quantization alone (tests/data/gltf/make_compressed.sh, written by
# @gltf-transform/cli) imports and renders like the bunny itself; before, each was refused
# ('extensionsRequired[0]: "KHR_draco_mesh_compression" is not supported'). Malformed compressed data
# is refused with exit 1, the file and the JSON path named, nothing written: counts and offsets that do
# not fit, a Draco header claiming more triangles than the accessors (or than the decoding budget), a
# meshopt stream that does not decode; and every single-byte corruption of the Draco and meshopt
# streams either imports or is refused cleanly (no crash: exit 0 or 1 only).
# Usage: bash test_gltf_compressed.sh <sss-binary> <repo-root>
SSS=$1; ROOT=$(cd "$2" && pwd)
fail=0
err() { echo "FAIL: $*"; fail=1; }
dir=$(mktemp -d); trap 'rm -rf "$dir"' EXIT
data=$ROOT/tests/data/gltf
mkdir "$dir/out"

for a in bunny_draco bunny_draco_sequential bunny_meshopt bunny_quantized; do
    "$SSS" import "$data/$a.glb" -o "$dir/$a/s.json" >/dev/null 2>"$dir/stderr" || err "$a: $(head -c 300 "$dir/stderr")"
    [ -s "$dir/$a/s_obj0.ply" ] || err "$a: no mesh written"
done
# The Draco bunny renders as the uncompressed one (positions within half a 14-bit step).
cat >"$dir/ply.json" <<JSON
{"camera": {"position": [0, 5, 25], "look_at": [0, 5, 0], "fov": 35, "width": 64, "height": 64},
 "objects": [{"mesh": "$ROOT/assets/bunny.ply", "material": {"type": "subsurface", "medium": "marble", "scale": 1}}],
 "lights": [{"type": "point", "position": [5, 10, 10], "intensity": [300, 300, 300]}]}
JSON
sed "s|$ROOT/assets/bunny.ply|$dir/bunny_draco/s_obj0.ply|" "$dir/ply.json" >"$dir/draco.json"
"$SSS" render "$dir/ply.json" -o "$dir/a.png" -q && "$SSS" render "$dir/draco.json" -o "$dir/b.png" -q || err "render failed"
case $("$SSS" compare "$dir/a.png" "$dir/b.png") in "dssim=0.00"*) ;; *) err "the Draco bunny renders differently: $("$SSS" compare "$dir/a.png" "$dir/b.png")";; esac

# variant SRC NAME PYTHON: the .glb SRC with its JSON (j) and BIN chunk (b, a bytearray) changed by the
# Python statements, written as NAME.glb.
variant() {
    python3 - "$data/$1.glb" "$dir/$2.glb" "$3" <<'PY' || err "could not write $2.glb"
import json, struct, sys
d = open(sys.argv[1], "rb").read()
n = struct.unpack_from("<I", d, 12)[0]
j = json.loads(d[20:20 + n])
b = bytearray(d[28 + n:])
exec(sys.argv[3])
t = json.dumps(j).encode()
t += b" " * (-len(t) % 4)
b += b"\0" * (-len(b) % 4)
open(sys.argv[2], "wb").write(struct.pack("<4sII", b"glTF", 2, 28 + len(t) + len(b)) +
                              struct.pack("<I4s", len(t), b"JSON") + t + struct.pack("<I4s", len(b), b"BIN\0") + b)
PY
}

# refused NAME PATTERN [CODE]: import exits CODE (1), stderr matches PATTERN, $dir/out stays empty.
refused() {
    "$SSS" import "$dir/$1.glb" -o "$dir/out/s.json" >/dev/null 2>"$dir/stderr"; local code=$?
    [ $code = "${3:-1}" ] || err "$1: exit $code, expected ${3:-1} ($(head -c 300 "$dir/stderr"))"
    grep -Eq -- "$1\.glb: $2" "$dir/stderr" || err "$1: message '$(head -c 300 "$dir/stderr")' lacks '$2'"
    [ -z "$(ls -A "$dir/out")" ] || err "$1: left $(ls -A "$dir/out")"
}

D='meshes\[0\]\.primitives\[0\]\.extensions\.KHR_draco_mesh_compression'
E='j["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]'
variant bunny_draco d_view "j['bufferViews'][0]['byteLength'] += 8"
refused d_view 'bufferViews\[0\]: bytes 0\.\.[0-9]+ are beyond buffers\[0\]'
variant bunny_draco d_trunc "j['bufferViews'][0]['byteLength'] = 40"
refused d_trunc "$D: the Draco data does not decode"
variant bunny_draco d_magic "b[0:5] = b'DRACP'"
refused d_magic "$D: the buffer view does not hold a Draco stream"
variant bunny_draco d_count "j['accessors'][0]['count'] = 3000"
refused d_count "$D: the Draco stream holds 3674 triangles, accessors\[0\] 3000 indices"
variant bunny_draco d_points "j['accessors'][1]['count'] = 1000; j['accessors'][2]['count'] = 1000"
refused d_points "$D: the Draco stream decodes to 1839 points, the POSITION accessor has 1000"
variant bunny_draco d_id "$E['attributes']['NORMAL'] = 7"
refused d_id "$D: no attribute with the unique id 7"
variant bunny_draco d_noattr "del $E['attributes']['POSITION']"
refused d_noattr "$D\.attributes\.POSITION: required field missing"
variant bunny_draco d_strip "j['meshes'][0]['primitives'][0]['mode'] = 5"
refused d_strip "$D: mode 5 with Draco"
# A header that claims 100 million triangles (the edgebreaker's face count rewritten as a 4-byte
# varint) with indices to match: refused by the budget before the decoder allocates for them.
variant bunny_draco d_huge "
import struct
v = 100_000_000
p = 11 + 1 + 2  # header, traversal type, encoded vertices (1839: a 2-byte varint)
assert b[p - 2:p] == bytes([1839 & 0x7f | 0x80, 1839 >> 7]) and b[p:p + 2] == bytes([3674 & 0x7f | 0x80, 3674 >> 7])
b[p:p + 2] = bytes([v & 0x7f | 0x80, v >> 7 & 0x7f | 0x80, v >> 14 & 0x7f | 0x80, v >> 21])
j['bufferViews'][0]['byteLength'] += 2
j['buffers'][0]['byteLength'] += 2
j['accessors'][0]['count'] = 3 * v"
refused d_huge "$D: decodes to [0-9]+ bytes, beyond the 1073741824 of compressed data decoded per asset"

M='bufferViews\[2\]\.extensions\.EXT_meshopt_compression'
X='j["bufferViews"][2]["extensions"]["EXT_meshopt_compression"]'
variant bunny_meshopt m_range "$X['byteLength'] += 100000"
refused m_range "$M: bytes [0-9]+\.\.[0-9]+ are beyond buffers\[0\]"
variant bunny_meshopt m_count "$X['count'] -= 1"
refused m_count "$M: count 1838 x byteStride 8 = 14704 bytes, the buffer view's byteLength is 14712"
variant bunny_meshopt m_stride "$X['byteStride'] = 6; j['bufferViews'][2]['byteStride'] = 6"
refused m_stride '(bufferViews\[2\]\.byteStride: 6 is not a multiple of 4|byteStride: 6)'
variant bunny_meshopt m_mode "$X['mode'] = 'VERTICES'"
refused m_mode "$M\.mode: expected ATTRIBUTES, TRIANGLES, INDICES"
variant bunny_meshopt m_data "o = $X['byteOffset']; b[o] ^= 0xff"
refused m_data "$M: the ATTRIBUTES data does not decode \(meshoptimizer error"
variant bunny_meshopt m_huge "$X['count'] = 1 << 28; j['bufferViews'][2]['byteLength'] = 8 << 28"
refused m_huge "$M: decodes to 2147483648 bytes, beyond the 1073741824"
variant bunny_quantized q_undeclared "del j['extensionsUsed']; del j['extensionsRequired']"
refused q_undeclared 'meshes\[0\]\.primitives\[0\]\.attributes\.POSITION: accessors\[1\] has componentType 5122 \(normalized\), not allowed without KHR_mesh_quantization'

# Bytes of the Draco and meshopt streams flipped, one at a time (96 spread over each stream, the headers'
# first 16 among them): exit 0 or 1 only, and a refusal names the file.
python3 - "$data" "$dir" <<'PY' || err "could not write the corrupted streams"
import json, struct, sys
src, out = sys.argv[1:]
for name, view in (("bunny_draco", 0), ("bunny_meshopt", 2)):
    d = bytearray(open(f"{src}/{name}.glb", "rb").read())
    n = struct.unpack_from("<I", d, 12)[0]
    j = json.loads(d[20:20 + n])
    bv = j["bufferViews"][view]
    ext = bv.get("extensions", {}).get("EXT_meshopt_compression", bv)
    start = 28 + n + ext.get("byteOffset", 0)
    length = ext["byteLength"]
    for k, pos in enumerate(sorted(set(list(range(16)) + list(range(0, length, max(1, length // 80)))))):
        pos += start
        c = bytearray(d)
        c[pos] ^= 0x5a
        open(f"{out}/flip_{name}_{k}.glb", "wb").write(c)
PY
crashes=0
for f in "$dir"/flip_*.glb; do
    "$SSS" import "$f" -o "$dir/flip/s.json" >/dev/null 2>"$dir/stderr"; code=$?
    if [ $code != 0 ] && [ $code != 1 ]; then crashes=$((crashes + 1)); err "$(basename "$f"): exit $code"; fi
    [ $code = 1 ] && ! grep -q "$(basename "$f")" "$dir/stderr" && err "$(basename "$f"): $(head -c 200 "$dir/stderr")"
    rm -rf "$dir/flip" "$f"
done
exit $fail
