#!/usr/bin/env bash
# sss reference: a tiny scene renders to PNG + EXR + PFM with plain progress lines; bad scenes fail with
# the loader's message naming the field and write nothing; usage errors exit 2.
# usage: bash test_reference.sh SSS_BINARY REPO_ROOT
set -u
SSS="$1"
ROOT="$2"
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
fail=0
check() { # description, condition exit status
    if [ "$2" -ne 0 ]; then echo "FAIL: $1"; fail=1; else echo "ok: $1"; fi
}

cat > "$TMP/good.json" <<'EOF'
{
  "camera": { "position": [0, 1, 4], "look_at": [0, 0.5, 0], "fov": 40, "width": 24, "height": 20 },
  "objects": [
    { "procedural": { "shape": "sphere", "radius": 0.8, "subdivisions": 3 },
      "transform": { "translate": [0, 0.8, 0] },
      "material": { "type": "subsurface", "medium": "Marble", "scale": 2.0 } },
    { "procedural": { "shape": "plane", "size": 6 },
      "material": { "type": "diffuse", "reflectance": [0.5, 0.5, 0.5] } }
  ],
  "lights": [ { "type": "point", "position": [1, 3, -2], "intensity": [8, 8, 8] } ],
  "render": { "exposure": 0.5 }
}
EOF

# --help
"$SSS" reference --help > "$TMP/help.txt"
check "--help exits 0" $?
grep -q "usage: sss reference" "$TMP/help.txt"
check "--help prints the usage" $?

# A good scene: all outputs, plain progress lines (stderr is not a terminal here: --progress), stats.
"$SSS" reference "$TMP/good.json" -o "$TMP/out.png" --exr "$TMP/out.exr" --pfm "$TMP/out.pfm" \
    --quality draft --threads 2 --seed 7 --stats --progress > "$TMP/stats.txt" 2> "$TMP/progress.txt"
check "good scene renders (exit 0)" $?
for f in out.png out.exr out.pfm; do
    [ -s "$TMP/$f" ]
    check "writes $f" $?
done
grep -qx "100%" "$TMP/progress.txt"
check "plain progress ends with a '100%' line" $?
grep -q "surface_samples=" "$TMP/stats.txt"
check "--stats prints the sample count" $?
# EXR and PFM hold the same linear image.
"$SSS" compare "$TMP/out.exr" "$TMP/out.pfm" > "$TMP/cmp2.txt" 2>&1
grep -q "dssim=0.000000" "$TMP/cmp2.txt"
check "EXR and PFM hold the same image" $?
# Same seed, other thread count: the same image.
"$SSS" reference "$TMP/good.json" -o "$TMP/one.pfm" --quality draft --threads 1 --seed 7 --quiet 2> "$TMP/quiet.txt"
check "renders with 1 thread" $?
cmp -s "$TMP/out.pfm" "$TMP/one.pfm"
check "1 and 2 threads give identical files" $?
[ ! -s "$TMP/quiet.txt" ]
check "--quiet prints nothing" $?
# Interreflection: the default bounces (the sphere lights the floor and back), --stats times each.
grep -q "^bounce 2: seconds=" "$TMP/stats.txt"
check "--stats prints the time of bounce 2" $?
"$SSS" reference "$TMP/good.json" -o "$TMP/b1.pfm" --quality draft --seed 7 --bounces 1 --stats > "$TMP/b1.txt" 2> /dev/null
check "--bounces 1 renders" $?
grep -q "^bounces=1 " "$TMP/b1.txt"
check "--bounces 1 computes one bounce" $?
cmp -s "$TMP/out.pfm" "$TMP/b1.pfm"
[ $? -ne 0 ]
check "--bounces 1 differs from the default" $?

# Bad scenes: exit 1, the message names the field, and no output file appears.
bad_scene() { # name, sed expression, expected text
    sed "$2" "$TMP/good.json" > "$TMP/$1.json"
    "$SSS" reference "$TMP/$1.json" -o "$TMP/$1.png" --exr "$TMP/$1.exr" --quality draft 2> "$TMP/$1.err"
    local status=$?
    [ $status -eq 1 ]
    check "$1: exit 1" $?
    grep -qF "$3" "$TMP/$1.err"
    check "$1: message names '$3'" $?
    [ ! -e "$TMP/$1.png" ] && [ ! -e "$TMP/$1.exr" ]
    check "$1: no output file" $?
}
bad_scene unknown_field 's/"fov": 40/"fov": 40, "colour": 1/' "camera.colour"
bad_scene missing_mesh 's/{ "procedural": { "shape": "sphere", "radius": 0.8, "subdivisions": 3 },/{ "mesh": "nothere.ply",/' "objects[0].mesh"
bad_scene unknown_medium 's/"medium": "Marble"/"medium": "Jelly"/' "objects[0].material.medium"
bad_scene negative_coefficient 's/"medium": "Marble", "scale": 2.0/"sigma_a": [0.1, -0.2, 0.1], "sigma_s": [1, 1, 1]/' "sigma_a"
bad_scene zero_width 's/"width": 24/"width": 0/' "camera.width"
bad_scene not_json 's/"camera"/camera/' "not_json.json"

# Usage errors: exit 2, nothing written.
usage() { # description, args...
    local d="$1"
    shift
    "$SSS" reference "$@" 2> /dev/null
    local status=$?
    [ $status -eq 2 ]
    check "usage: $d (exit 2)" $?
}
usage "no output" "$TMP/good.json"
usage "no scene" -o "$TMP/x.png"
usage "bad quality" "$TMP/good.json" -o "$TMP/x.png" --quality best
usage "bad spp" "$TMP/good.json" -o "$TMP/x.png" --spp 0
usage "bad threads" "$TMP/good.json" -o "$TMP/x.png" --threads -1
usage "bad seed" "$TMP/good.json" -o "$TMP/x.png" --seed -3
usage "bad output extension" "$TMP/good.json" -o "$TMP/x.jpg"
usage "--exr needs .exr" "$TMP/good.json" -o "$TMP/x.png" --exr "$TMP/x.png2"
usage "unknown option" "$TMP/good.json" -o "$TMP/x.png" --fast
usage "bounces 0" "$TMP/good.json" -o "$TMP/x.png" --bounces 0
usage "bounces 17" "$TMP/good.json" -o "$TMP/x.png" --bounces 17
[ ! -e "$TMP/x.png" ] && [ ! -e "$TMP/x.jpg" ]
check "usage errors write nothing" $?

exit $fail
