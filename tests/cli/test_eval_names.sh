#!/usr/bin/env bash
# sss eval names every scene's outputs apart (docs/eval.md "Scene names"): two scenes with one file
# stem (d1/s.json, d2/s.json) get their folders' names (s-d1, s-d2), and each sheet, crops file and
# saved reference belongs to its scene (copied next to that scene, --cached-reference takes it: the
# lookup checks the sidecar's hash of the scene file, and renders again on a mismatch); the same
# file given twice at one time is refused before any work. A scene file name holding ESC, CR and a
# byte that is not UTF-8 is shown escaped on stdout, in results.json (valid UTF-8 JSON), the CSV and
# the HTML, and the run succeeds (cairo refuses text that is not UTF-8).
# Usage: bash test_eval_names.sh <sss-binary> <repo-root>
set -u
SSS=$1
. "$(dirname "${BASH_SOURCE[0]}")/harness.sh"
PY=python3
command -v "$PY" >/dev/null 2>&1 || { echo "skipped: python3 not installed"; exit 0; }

mkdir -p "$T/d1" "$T/d2"
cat >"$T/d1/s.json" <<'EOF'
{"camera": {"position": [0, 0.5, 3], "look_at": [0, 0, 0], "width": 16, "height": 16},
 "objects": [{"procedural": {"shape": "sphere", "radius": 0.6, "subdivisions": 2},
   "material": {"type": "subsurface", "medium": "Marble", "scale": 10}}],
 "lights": [{"type": "point", "position": [0, 2, 2], "intensity": [1, 1, 1]}]}
EOF
sed 's/"radius": 0.6/"radius": 0.3/' "$T/d1/s.json" >"$T/d2/s.json"
HOSTILE=$(printf 'h\033[31m\rx\377')
ARGS=(--techniques local --frames 1 --warmup 0 --reference-quality draft --quiet)

# ---- one stem, two folders
cd "$T" || exit 1
"$SSS" eval d1/s.json d2/s.json "${ARGS[@]}" --out "$T/o" >"$T/stdout" 2>"$T/stderr" ||
    fail "eval of d1/s.json d2/s.json failed: $(head -c 400 "$T/stderr")"
for f in sheet_s-d1.png sheet_s-d2.png crops_s-d1_0.png crops_s-d2_0.png references/s-d1_16x16.exr \
    references/s-d2_16x16.exr references/s-d1_16x16.json references/s-d2_16x16.json; do
    [ -s "$T/o/$f" ] || fail "missing output $f (have: $(ls "$T/o" "$T/o/references" | tr '\n' ' '))"
done
cmp -s "$T/o/sheet_s-d1.png" "$T/o/sheet_s-d2.png" && fail "the two scenes' sheets are the same file content"
"$PY" - "$T" <<'EOF' || fail "results.json / sidecars do not tell the scenes apart"
import json, sys
t = sys.argv[1]
doc = json.load(open(t + "/o/results.json"))
names = [(s["name"], s["path"]) for s in doc["scenes"]]
assert names == [("s-d1", "d1/s.json"), ("s-d2", "d2/s.json")], names
assert sorted(r["scene"] for r in doc["results"] if r["kind"] == "quality") == ["s-d1", "s-d2"], doc["results"]
hashes = [json.load(open("%s/o/references/s-%s_16x16.json" % (t, d)))["scene_fnv1a64"] for d in ("d1", "d2")]
assert hashes[0] != hashes[1], hashes
EOF
# each saved reference, committed next to its scene under the file's own stem, is what --cached-reference
# uses there (a reference of the other scene would fail the sidecar's hash and be rendered again)
for d in d1 d2; do
    mkdir -p "$T/$d/references"
    cp "$T/o/references/s-${d}_16x16.exr" "$T/$d/references/s_16x16.exr"
    cp "$T/o/references/s-${d}_16x16.json" "$T/$d/references/s_16x16.json"
done
"$SSS" eval d1/s.json d2/s.json "${ARGS[@]}" --cached-reference --out "$T/c" >/dev/null 2>"$T/stderr" ||
    fail "eval --cached-reference failed: $(head -c 400 "$T/stderr")"
"$PY" -c 'import json, sys
doc = json.load(open(sys.argv[1]))
src = [s["references"][0]["source"] for s in doc["scenes"]]
assert src == ["cached", "cached"], src' "$T/c/results.json" || fail "the cached references next to the scenes were not used"

# ---- the same file twice at one time: refused before any work, nothing written
"$SSS" eval d1/s.json ./d1/../d1/s.json "${ARGS[@]}" --out "$T/twice" >/dev/null 2>"$T/stderr"
rc=$?
[ "$rc" -eq 1 ] || fail "the same scene twice: exit $rc"
grep -q "d1/s.json and ./d1/../d1/s.json would write the same output files" "$T/stderr" ||
    fail "the same scene twice: $(head -c 400 "$T/stderr")"
[ -e "$T/twice" ] && fail "the refused run wrote $(ls -R "$T/twice")"

# ---- hostile file names (ESC and CR, valid UTF-8; and with a 0xFF byte): escaped wherever shown
for name in "$(printf 'h\033[31m\rx')" "$HOSTILE"; do
    rm -rf "$T/h"
    cp "$T/d1/s.json" "$T/$name.json"
    "$SSS" eval "$name.json" "${ARGS[@]}" --out "$T/h" >"$T/stdout" 2>"$T/stderr" ||
        fail "eval of a scene named with control characters failed: $(head -c 400 "$T/stderr")"
    for f in "$T/stdout" "$T/stderr" "$T/h/results.csv" "$T/h/report.html" "$T/h/results.json"; do
        [ -e "$f" ] || { fail "missing $f"; continue; }
        if LC_ALL=C grep -q $'\033\|\r\|\377' "$f"; then fail "$(basename "$f") holds a raw ESC, CR or 0xFF byte"; fi
    done
    grep -Fq 'h\x1b[31m\rx' "$T/stdout" || fail "stdout does not show the escaped name: $(head -c 400 "$T/stdout")"
    "$PY" -c 'import json, sys
doc = json.loads(open(sys.argv[1], "rb").read().decode("utf-8"))
assert doc["scenes"][0]["name"].startswith("h\\x1b[31m\\rx"), doc["scenes"][0]["name"]' "$T/h/results.json" ||
        fail "results.json is not UTF-8 JSON holding the escaped name"
done

if [ "$fails" -ne 0 ]; then
    echo "$fails failure(s)"
    exit 1
fi
echo "eval names checks passed"
