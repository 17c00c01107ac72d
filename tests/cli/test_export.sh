#!/usr/bin/env bash
# sss export pbrt: writes the .pbrt and one PLY per object; bad input fails cleanly with no output.
SSS=$1; ROOT=$2
fail=0
err() { echo "FAIL: $*"; fail=1; }
dir=$(mktemp -d); trap 'rm -rf "$dir"' EXIT

"$SSS" export pbrt "$ROOT/scenes/default.json" -o "$dir/d.pbrt" >/dev/null || err "export of the default scene failed"
[ -s "$dir/d.pbrt" ] || err "no .pbrt written"
n_obj=$(grep -c '"plymesh"' "$dir/d.pbrt")
n_ply=$(ls "$dir"/d_obj*.ply 2>/dev/null | wc -l)
[ "$n_obj" -ge 1 ] && [ "$n_obj" = "$n_ply" ] || err "plymesh statements ($n_obj) and PLY files ($n_ply) differ"
for p in "$dir"/d_obj*.ply; do "$SSS" mesh info "$p" >/dev/null || err "$p does not read back"; done
grep -q '^WorldEnd' "$dir/d.pbrt" || err "file not complete"
# The depth: the default matches sss reference's default transport, --maxdepth 1 its --bounces 1.
grep -q 'Integrator "path" "integer maxdepth" \[16\]' "$dir/d.pbrt" || err "default maxdepth is not 16"
"$SSS" export pbrt "$ROOT/scenes/default.json" -o "$dir/d1.pbrt" --maxdepth 1 >/dev/null || err "--maxdepth 1 failed"
grep -q 'Integrator "path" "integer maxdepth" \[1\]' "$dir/d1.pbrt" || err "--maxdepth 1 not written"
"$SSS" export pbrt "$ROOT/scenes/default.json" -o "$dir/d0.pbrt" --maxdepth 0 >/dev/null 2>&1; [ $? = 2 ] || err "--maxdepth 0 is not a usage error"
[ -e "$dir/d0.pbrt" ] && err "--maxdepth 0 left output"

# A broken scene: exit 1, the file named, nothing written.
printf '{"camera": {"position": [0,0,1], "look_at": [0,0,0]}, "objects": [], "bogus": 1}' > "$dir/bad.json"
out=$("$SSS" export pbrt "$dir/bad.json" -o "$dir/bad.pbrt" 2>&1); code=$?
[ $code = 1 ] || err "bad scene: exit $code"
case "$out" in *bad.json*) ;; *) err "bad scene: message does not name the file: $out";; esac
ls "$dir"/bad* | grep -q pbrt && err "bad scene left output"
# Usage errors: exit 2.
"$SSS" export pbrt "$ROOT/scenes/default.json" >/dev/null 2>&1; [ $? = 2 ] || err "missing -o is not a usage error"
"$SSS" export obj "$ROOT/scenes/default.json" -o x >/dev/null 2>&1; [ $? = 2 ] || err "unknown format is not a usage error"
exit $fail
