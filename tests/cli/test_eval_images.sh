#!/usr/bin/env bash
# sss eval --images NAME=PATTERN: images of another program scored against the same truth as the
# techniques. The "other program" here is `sss render` itself, so that the scores are known: a PNG of
# technique local scores exactly local's DSSIM, FLIP, PSNR and RMSE (the metrics work on the tone-mapped
# 8-bit images, and a PNG written at the scene's exposure decodes and maps back to its own bytes), and
# a float PFM of it (linear radiance) too. The entries are marked external (no timings: ms_total
# null, technique "external", the file named) in results.json, the CSV, the summary, the sheet's
# caption and the report. Errors stop the run before any work and write nothing: a missing file, a
# file of the wrong size (both named), a pattern without {scene} for several scenes, a name that is
# also a technique of the run, NAME=PATTERN without one of its halves (usage error, exit 2).
# Usage: bash test_eval_images.sh <sss-binary> <repo-root>
set -u
SSS=$1
ROOT=$2
. "$(dirname "${BASH_SOURCE[0]}")/harness.sh"
find_python "json, csv"

mkdir -p "$T/scenes" "$T/ext"
cat >"$T/scenes/ball.json" <<'EOF'
{
  "camera": {"position": [0, 1.2, 4], "look_at": [0, 0.4, 0], "fov": 35, "width": 48, "height": 48},
  "objects": [
    {"procedural": {"shape": "sphere", "radius": 0.6, "subdivisions": 3},
     "transform": {"translate": [0, 0.6, 0]},
     "material": {"type": "subsurface", "medium": "Marble", "scale": 20.0}},
    {"procedural": {"shape": "plane", "size": 8}, "material": {"type": "diffuse", "reflectance": [0.5, 0.5, 0.5]}}
  ],
  "lights": [{"type": "point", "position": [1.5, 3, -1.5], "intensity": [6, 6, 6]}],
  "render": {"exposure": 0.5}
}
EOF
cat >"$T/scenes/knot.json" <<'EOF'
{
  "camera": {"position": [0, 0, 4], "look_at": [0, 0, 0], "fov": 40, "width": 48, "height": 36},
  "objects": [
    {"procedural": {"shape": "trefoil", "radius": 1.2, "tube": 0.18, "segments": 96},
     "material": {"type": "subsurface", "medium": "Skimmilk", "scale": 15.0}}
  ],
  "lights": [{"type": "point", "position": [2, 2, 3], "intensity": [8, 8, 8]}]
}
EOF
for s in ball knot; do
    "$SSS" render "$T/scenes/$s.json" --technique local -o "$T/ext/${s}_local.png" -q || fail "render $s png"
    "$SSS" render "$T/scenes/$s.json" --technique local -o "$T/ext/${s}_local.pfm" -q || fail "render $s pfm"
done

OUT=$T/out
"$SSS" eval "$T/scenes/ball.json" "$T/scenes/knot.json" --techniques local --frames 1 --warmup 0 \
    --reference-quality draft --images "other-png=$T/ext/{scene}_local.png" --images "other-pfm=$T/ext/{scene}_local.pfm" \
    --out "$OUT" -q >"$T/stdout" 2>"$T/stderr"
rc=$?
[ "$rc" -eq 0 ] || fail "sss eval --images exited $rc: $(head -c 600 "$T/stderr")"
for f in results.json results.csv report.html sheet_ball.png sheet_knot.png plot_dssim.png plot_passes.png \
    crops_ball_1.png crops_knot_2.png; do
    [ -s "$OUT/$f" ] || fail "missing output $f"
done
grep -Eq "other-png +ok .* external" "$T/stdout" || fail "the summary does not mark the external image: $(cat "$T/stdout")"
grep -q "external image: " "$OUT/report.html" || fail "the report does not mark the external images"
grep -q "0 frames" "$OUT/report.html" && fail "the report gives an external image a frame count (it has no timings)"

if [ -n "$PY" ]; then
    "$PY" - "$OUT" "$T/ext" <<'EOF' || fail "results.json / results.csv checks failed"
import csv, json, sys
out, ext = sys.argv[1], sys.argv[2]
doc = json.load(open(out + "/results.json"))
assert doc["settings"]["techniques"] == ["local"], doc["settings"]
names = [i["name"] for i in doc["settings"]["images"]]
assert names == ["other-png", "other-pfm"], names
res = {(r["scene"], r["label"]): r for r in doc["results"]}
for scene in ("ball", "knot"):
    local = res[(scene, "local")]
    assert local["external"] is False and local["file"] is None and local["ms_total"] > 0, local
    for name, suffix in (("other-png", ".png"), ("other-pfm", ".pfm")):
        r = res[(scene, name)]
        assert r["external"] is True and r["technique"] == "external" and r["status"] == "ok", r
        assert r["ms_total"] is None and r["passes"] == [] and r["memory"] is None, r
        assert r["file"] == ext + "/" + scene + "_local" + suffix, r["file"]
        for key in ("dssim", "flip", "psnr", "rmse", "max_abs"):
            assert r[key] == local[key], (scene, name, key, r[key], local[key])
rows = list(csv.DictReader(open(out + "/results.csv")))
ext_rows = [r for r in rows if r["external"] == "1"]
assert len(ext_rows) == 4 and all(r["ms_total"] == "" and r["file"] for r in ext_rows), ext_rows
EOF
fi

# errors: nothing is written, the message names the problem
expect_error() { # EXPECTED-STATUS MESSAGE-REGEX ARGS...
    local want=$1 re=$2
    shift 2
    rm -rf "$T/bad"
    "$SSS" eval "$@" --techniques local --frames 1 --warmup 0 --reference-quality draft --out "$T/bad" -q \
        >"$T/o" 2>"$T/e"
    local rc=$?
    [ "$rc" -eq "$want" ] || fail "$* exited $rc, expected $want: $(head -c 300 "$T/e")"
    grep -Eq "$re" "$T/e" || fail "$*: message does not match '$re': $(head -c 300 "$T/e")"
    [ -e "$T/bad/results.json" ] && fail "$*: results written after an error"
}
expect_error 1 "missing_ball\.png: cannot open" "$T/scenes/ball.json" "$T/scenes/knot.json" --images "x=$T/ext/missing_{scene}.png"
cp "$T/ext/ball_local.png" "$T/ext/wrong_knot.png"
cp "$T/ext/ball_local.png" "$T/ext/wrong_ball.png"
expect_error 1 "wrong_knot\.png is 48x48, the scene knot is compared at 48x36" "$T/scenes/ball.json" "$T/scenes/knot.json" \
    --images "x=$T/ext/wrong_{scene}.png"
expect_error 1 "has no \{scene\}" "$T/scenes/ball.json" "$T/scenes/knot.json" --images "x=$T/ext/ball_local.png"
expect_error 1 "also a technique" "$T/scenes/ball.json" --images "local=$T/ext/{scene}_local.png"
expect_error 2 "NAME=PATTERN" "$T/scenes/ball.json" --images "=$T/ext/{scene}_local.png"
expect_error 2 "NAME=PATTERN" "$T/scenes/ball.json" --images "x"

[ "$fails" -eq 0 ] && echo "test_eval_images: ok"
[ "$fails" -eq 0 ]
