#!/usr/bin/env bash
# JSON strings holding a NUL character (the escape \u0000) are refused with an error naming the JSON
# path, not cut at the NUL (cJSON keeps C strings): "Marble\u0000junk" is not the medium Marble, and a
# mesh path "box.ply\u0000/../.." is not box.ply. "\\u0000" (a backslash, then "u0000") is no NUL.
# Usage: bash test_json_nul.sh <sss-binary> <repo-root>
SSS=$1; ROOT=$2
fail=0
err() { echo "FAIL: $*"; fail=1; }
dir=$(mktemp -d); trap 'rm -rf "$dir"' EXIT
cp "$ROOT/tests/data/meshes/box_ascii.ply" "$dir/box.ply"
cp "$ROOT/tests/data/meshes/box_ascii.ply" "$dir/box\\u0000.ply" # a file name with a backslash in it

scene() { # $1 = the mesh field's JSON text, $2 = the medium's
    printf '{"camera": {"position": [0, 0.5, 3], "look_at": [0, 0, 0], "width": 8, "height": 8},
 "objects": [{"mesh": "%s", "material": {"type": "subsurface", "medium": "%s", "scale": 10}}],
 "lights": [{"type": "point", "position": [0, 2, 2], "intensity": [1, 1, 1]}]}' "$1" "$2"
}
# EXPECT | NAME | MESH | MEDIUM | PATTERN of the message
while IFS='|' read -r expect name mesh medium pattern; do
    scene "$mesh" "$medium" >"$dir/$name.json"
    mkdir -p "$dir/out_$name"
    "$SSS" export pbrt "$dir/$name.json" -o "$dir/out_$name/o.pbrt" >/dev/null 2>"$dir/stderr"; code=$?
    msg=$(cat "$dir/stderr")
    if [ "$expect" = fail ]; then
        [ $code = 1 ] || err "$name: exit $code, expected 1 ($msg)"
        grep -Eq "$pattern" "$dir/stderr" || err "$name: message '$msg' does not match '$pattern'"
        [ -z "$(ls "$dir/out_$name")" ] || err "$name: output left behind"
    else
        [ $code = 0 ] || err "$name: exit $code, expected 0 ($msg)"
    fi
done <<'CASES'
fail|medium_nul|box.ply|Marble\u0000junk|medium_nul\.json: objects\[0\]\.material\.medium: .*NUL
fail|mesh_nul|box.ply\u0000/../..|Marble|mesh_nul\.json: objects\[0\]\.mesh: .*NUL
fail|key_nul|box.ply|Marble", "x\u0000": "1|key_nul\.json: objects\[0\]\.material\.x\\u0000: .*NUL
ok|escaped_backslash|box\\u0000.ply|Marble|
CASES
exit $fail
