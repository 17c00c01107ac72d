#!/usr/bin/env bash
# A second renderer through `sss eval --images`: Blender's Cycles renders a small scene (a Marble ball
# on a diffuse floor under a point light) with tools/blender/render_scene.py, and sss eval scores it
# against the CPU reference as an external entry. Cycles' random walk traces the medium's own sigma_a,
# sigma_s (the script inverts Cycles' parameter mapping), so the two transports agree on the light the
# ball and the floor send to the camera: the mean of each channel over the lit pixels within 15%
# (measured 1-6% at 96 x 96; the boundaries differ: Cycles' walk enters and leaves through its own
# interface model). The script refuses what it does not map (an area light), naming it.
# Skips (exit 0) when blender is not installed (scripts/install-deps.sh --ci installs it).
# Usage: bash test_blender.sh <sss-binary> <repo-root>
set -u
SSS=$1
ROOT=$2
if ! command -v blender >/dev/null 2>&1; then
    echo "skipped: blender not installed (scripts/install-deps.sh --ci installs it)"
    exit 0
fi
. "$(dirname "${BASH_SOURCE[0]}")/harness.sh"
find_python "json"
SCRIPT=$ROOT/tools/blender/render_scene.py
blend() { # SCENE OUT ENGINE: the script, headless
    blender -b --factory-startup --python-exit-code 1 --python "$SCRIPT" -- "$1" --engine "$3" -o "$2" \
        --samples 32 --sss "$SSS" >"$T/blender.log" 2>&1
}

mkdir -p "$T/scenes" "$T/ext"
cat >"$T/scenes/ball.json" <<'EOF'
{
  "camera": {"position": [0, 1.2, 4], "look_at": [0, 0.4, 0], "fov": 35, "width": 64, "height": 48},
  "objects": [
    {"procedural": {"shape": "sphere", "radius": 0.6, "subdivisions": 4},
     "transform": {"translate": [0, 0.6, 0]},
     "material": {"type": "subsurface", "medium": "Marble", "scale": 20.0, "eta": 1.33}},
    {"procedural": {"shape": "plane", "size": 8}, "material": {"type": "diffuse", "reflectance": [0.5, 0.5, 0.5]}}
  ],
  "lights": [{"type": "point", "position": [1.5, 3, 1.5], "intensity": [6, 6, 6]}]
}
EOF
blend "$T/scenes/ball.json" "$T/ext/ball_cycles.exr" cycles || fail "render_scene.py (cycles) failed: $(tail -5 "$T/blender.log")"
[ -s "$T/ext/ball_cycles.exr" ] || fail "no Cycles image"

OUT=$T/out
"$SSS" eval "$T/scenes/ball.json" --techniques local --frames 1 --warmup 0 --reference-quality draft \
    --images "blender-cycles=$T/ext/{scene}_cycles.exr" --out "$OUT" -q >"$T/stdout" 2>"$T/stderr" ||
    fail "sss eval --images exited $?: $(head -c 400 "$T/stderr")"
grep -Eq "blender-cycles +ok" "$T/stdout" || fail "the summary does not list the Cycles image: $(cat "$T/stdout")"

if [ -n "$PY" ] && PYTHONPATH="$(dirname "$SSS")/python" "$PY" -c 'import sss' 2>/dev/null; then
    PYTHONPATH="$(dirname "$SSS")/python" "$PY" - "$OUT" "$T/ext/ball_cycles.exr" <<'EOF' || fail "Cycles against the reference"
import json, sys
import numpy as np
import sss
out, cycles = sys.argv[1], sys.argv[2]
doc = json.load(open(out + "/results.json"))
r = [e for e in doc["results"] if e["label"] == "blender-cycles"][0]
assert r["external"] and r["status"] == "ok" and 0 <= r["dssim"] < 0.5, r
ref = sss.read_image(out + "/references/ball_64x48.exr")
img = sss.read_image(cycles)
lit = ref.sum(axis=2) > 0.05 * ref.sum(axis=2).max()
ratio = img[lit].mean(axis=0) / ref[lit].mean(axis=0)
print("Cycles / reference, mean over the lit pixels:", np.round(ratio, 3), "DSSIM", r["dssim"])
assert np.all(np.abs(ratio - 1) < 0.15), ratio
EOF
else
    echo "note: the sss Python module is not built; the Cycles/reference ratio is not checked"
fi

# what the script does not map is refused, with its name, and no image is written
sed 's/"lights": \[/"lights": [{"type": "area", "center": [0, 3, 0], "u": [0.5, 0, 0], "v": [0, 0, 0.5], "radiance": [1, 1, 1]}, /' \
    "$T/scenes/ball.json" >"$T/scenes/area.json"
if blend "$T/scenes/area.json" "$T/ext/area.exr" cycles; then fail "an area light was not refused"; fi
grep -q "lights\[0\]: area lights are not mapped" "$T/blender.log" || fail "no message naming the area light: $(tail -3 "$T/blender.log")"
[ -e "$T/ext/area.exr" ] && fail "an image was written for a refused scene"

[ "$fails" -eq 0 ] && echo "test_blender: ok"
[ "$fails" -eq 0 ]
