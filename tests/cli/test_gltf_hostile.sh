#!/usr/bin/env bash
# Hostile glTF assets (issue 25): each is refused by `sss import` with exit 1, a message naming the file
# and the JSON path, and nothing written; before, each was imported (a NUL cut the buffer's URI, an
# out-of-range albedo was clamped, aspectRatio 0 was "absent", a scene was written that every other
# command refused, a light beyond the float range made every technique produce NaN). And a 300,000-node
# asset (3 MB) imports within a generous timeout: one list walk per node reference made the import
# quadratic (100,000 nodes: 35 s on the 2-core test machine, 300,000 about 9 times that; now 0.3 s).
# Usage: bash test_gltf_hostile.sh <sss-binary> <repo-root>
SSS=$1; ROOT=$2
fail=0
err() { echo "FAIL: $*"; fail=1; }
dir=$(mktemp -d); trap 'rm -rf "$dir"' EXIT
data=$ROOT/tests/data/gltf
cp "$data/external.gltf" "$data/external data.bin" "$dir/"
mkdir "$dir/out"

# variant NAME PYTHON: external.gltf (one triangle) as g, changed by the Python statements, as NAME.gltf.
variant() {
    python3 - "$dir/external.gltf" "$dir/$1.gltf" "$2" <<'PY' || err "could not write $1.gltf"
import json, sys
g = json.load(open(sys.argv[1]))
exec(sys.argv[3])
json.dump(g, open(sys.argv[2], "w"))
PY
}

# refused CODE FILE PATTERN [OPTIONS]: import exits CODE, stderr matches PATTERN, $dir/out stays empty.
refused() {
    local want=$1 file=$2 pattern=$3
    shift 3
    "$SSS" import "$dir/$file" -o "$dir/out/s.json" "$@" >/dev/null 2>"$dir/stderr"; local code=$?
    [ $code = "$want" ] || err "$file $*: exit $code, expected $want ($(head -c 300 "$dir/stderr"))"
    grep -Eq -- "$pattern" "$dir/stderr" || err "$file $*: message '$(head -c 300 "$dir/stderr")' lacks '$pattern'"
    [ -z "$(ls -A "$dir/out")" ] || err "$file $*: left $(ls -A "$dir/out")"
}

# 3. NUL in a string: the escape in a .gltf, a raw 0 byte in a .glb's JSON chunk.
variant nul_uri 'g["buffers"][0]["uri"] += "\u0000../../etc/passwd"'
refused 1 nul_uri.gltf 'nul_uri\.gltf: buffers\[0\]\.uri: a string holds a NUL character'
python3 - "$dir/external.gltf" "$dir/nul.glb" <<'PY' || err "could not write nul.glb"
import json, struct, sys
g = json.load(open(sys.argv[1]))
g["buffers"][0]["uri"] = "external%20data.bin#../../etc/passwd"
text = json.dumps(g).encode().replace(b"#", b"\0")
text += b" " * (-len(text) % 4)
open(sys.argv[2], "wb").write(struct.pack("<4sII", b"glTF", 2, 20 + len(text)) +
                              struct.pack("<I4s", len(text), b"JSON") + text)
PY
refused 1 nul.glb 'nul\.glb: buffers\[0\]\.uri: a string holds a NUL character'

# 5. multiscatterColor outside [0, 1] (it was clamped to sigma_a = 0 or sigma_s = 0).
for rho in '[1.5, 0.5, 0.5]' '[0.5, -0.1, 0.5]'; do
    variant scatter "g['materials'] = [{'extensions': {'KHR_materials_volume': {'thicknessFactor': 1,
        'attenuationDistance': 1, 'attenuationColor': [0.5, 0.5, 0.5]},
        'KHR_materials_volume_scatter': {'multiscatterColor': $rho}}}]
g['meshes'][0]['primitives'][0]['material'] = 0"
    refused 1 scatter.gltf 'scatter\.gltf: materials\[0\]\.extensions\.KHR_materials_volume_scatter\.multiscatterColor\[[01]\]: (1\.5|-0\.1) is outside \[0, 1\]'
done

# 6. An explicit aspectRatio of 0 (it was taken as absent).
variant aspect "g['cameras'] = [{'type': 'perspective', 'perspective': {'yfov': 0.5, 'znear': 0.1, 'aspectRatio': 0}}]
g['nodes'][0]['camera'] = 0"
refused 1 aspect.gltf 'aspect\.gltf: cameras\[0\]\.perspective\.aspectRatio: 0 is outside'

# 7./8. A node scaled to 1e30 (the scene was written, then refused by every command), lights beyond
# the largest value sss renders (every technique produced NaN).
variant huge 'g["nodes"][0]["scale"] = [1e30, 1e30, 1e30]'
refused 1 huge.gltf 'huge\.gltf: nodes\[0\] places meshes\[0\]\.primitives\[0\] vertex 1 at 1e\+30, beyond 1e\+18'
variant light 'g["extensions"] = {"KHR_lights_punctual": {"lights": [{"type": "point", "intensity": 1e39}]}}
g["nodes"][0]["extensions"] = {"KHR_lights_punctual": {"light": 0}}'
refused 1 light.gltf 'light\.gltf: extensions\.KHR_lights_punctual\.lights\[0\]\.intensity: 1e\+39 x color\[0\] 1 x light scale 1 = 1e\+39, beyond'
refused 2 external.gltf '--light-scale must be in \(0, 1e\+30\]' --light-scale 1e300
# 7. What only the scene loader checks: an external texture that does not decode.
cp "$data/textured.gltf" "$dir/"
echo "not a PNG" >"$dir/albedo.png"
refused 1 textured.gltf 'textured\.gltf: objects\[0\]\.material\.texture: .*albedo\.png: not a PNG file'

# 4. 300,000 nodes, the first with the mesh: in seconds at most.
python3 - "$dir/external.gltf" "$dir/many.gltf" <<'PY' || err "could not write many.gltf"
import json, sys
n = 300000
g = json.load(open(sys.argv[1]))
g["nodes"] = [{"mesh": 0}] + [{} for _ in range(n - 1)]
g["scenes"][0]["nodes"] = list(range(n))
open(sys.argv[2], "w").write(json.dumps(g, separators=(",", ":")))
PY
timeout 20 "$SSS" import "$dir/many.gltf" -o "$dir/many.json" >/dev/null 2>"$dir/stderr"; code=$?
[ $code = 0 ] || err "300,000 nodes: exit $code (124: over 20 s) $(head -c 300 "$dir/stderr")"
exit $fail
