#!/usr/bin/env bash
# sss eval --both-truths: every entry is scored against the full transport (the default truth) and the
# single-event truth (bounces 1: light from the lights only), side by side, on a Marble ball over a
# bright floor at 64 px (draft references):
# - results.json, the CSV (its last columns), the summary and report.html carry the second scores;
#   the single-event truth is saved as references/<scene>_bounces1_<W>x<H>.exr with a sidecar saying
#   bounces 1.
# - Light between surfaces only adds light (every bounce adds energy): the full transport is brighter than
#   the single event in every channel, so any image's mean R/G/B over the full truth is below its ratio
#   over the single event.
# - The single-event reference EXR itself, fed back as an external image (--images), scores DSSIM 0,
#   FLIP 0, PSNR infinite and mean ratios 1 against the single-event truth, and not against the full
#   truth (the floor lit by the ball and the ball by the floor); the full-transport EXR the other way round.
# - A cached <scene>_bounces1_ reference whose sidecar says another bounce count (here the full
#   transport's file copied under that name) is not used: the run says so and renders the right one.
# - --both-truths with --reference-bounces 1 (both truths the same) is a usage error that writes nothing.
# Usage: bash test_eval_truths.sh <sss-binary> <repo-root>
set -u
SSS=$1
ROOT=$2
. "$(dirname "${BASH_SOURCE[0]}")/harness.sh"
find_python "json, csv"

mkdir -p "$T/scenes"
write_ball_scene "$T/scenes/ball.json" 0.8 '{"exposure": 0.5}'
RUN=(--techniques local --frames 1 --warmup 0 --reference-quality draft --both-truths)

# 1. both truths rendered, scored and written
"$SSS" eval "$T/scenes/ball.json" "${RUN[@]}" --out "$T/o1" >"$T/stdout1" 2>"$T/stderr1" ||
    fail "eval --both-truths failed: $(head -c 400 "$T/stderr1")"
R=$T/o1/references
[ -s "$R/ball_64x64.exr" ] && [ -s "$R/ball_bounces1_64x64.exr" ] || fail "references saved: $(ls "$R" 2>&1)"
grep -q '"bounces": 1,' "$R/ball_bounces1_64x64.json" || fail "the single-event sidecar lacks bounces 1"
grep -q '"bounces": 0,' "$R/ball_64x64.json" || fail "the full-transport sidecar lacks bounces 0"
grep -q "vs full transport" "$T/stdout1" && grep -q "vs single event" "$T/stdout1" ||
    fail "the summary does not name both truths: $(cat "$T/stdout1")"
for s in "vs full transport" "vs single event" "Two truths" "light between surfaces" "single-event truth 64x64" \
    "Summary: DSSIM against the single event"; do
    grep -q "$s" "$T/o1/report.html" || fail "report.html lacks '$s'"
done

if [ -z "$PY" ]; then
    echo "note: python3 with json and csv unavailable; the result checks are skipped"
else
    "$PY" - "$T/o1" <<'EOF' || fail "results of the two truths"
import csv, json, sys
out = sys.argv[1]
doc = json.load(open(out + "/results.json"))
assert doc["settings"]["both_truths"] is True and doc["settings"]["reference_bounces"] == 0, doc["settings"]
sc = doc["scenes"][0]
assert [r["bounces"] for r in sc["references"]] == [0], sc["references"]
se = sc["single_event_reference"]
assert se["bounces"] == 1 and se["source"] == "rendered" and se["path"].endswith("ball_bounces1_64x64.exr"), se
(e,) = [r for r in doc["results"] if r["kind"] == "quality"]
one = e["single_event"]
assert one is not None and 0 < one["dssim"] < 1 and 0 < one["flip"] < 1 and one["psnr_infinite"] is False, e
# interreflection only adds light: the full truth is brighter in every channel, so the same image's
# mean over it is a smaller fraction than over the single event
for c in range(3):
    assert 0 < e["mean_ratio"][c] < one["mean_ratio"][c], (c, e["mean_ratio"], one["mean_ratio"])
# the CSV's last columns hold the same numbers
(row,) = [r for r in csv.DictReader(open(out + "/results.csv")) if r["kind"] == "quality"]
header = open(out + "/results.csv").readline().strip().split(",")
assert header[-11:] == ["mean_ratio_r", "mean_ratio_g", "mean_ratio_b", "single_event_dssim", "single_event_flip",
                        "single_event_psnr", "single_event_rmse", "single_event_max_abs", "single_event_ratio_r",
                        "single_event_ratio_g", "single_event_ratio_b"], header
for key, v in [("single_event_dssim", one["dssim"]), ("single_event_flip", one["flip"]),
               ("single_event_ratio_b", one["mean_ratio"][2]), ("mean_ratio_r", e["mean_ratio"][0])]:
    assert abs(float(row[key]) - v) <= 1e-5 * max(1, v), (key, row[key], v)
EOF
fi

# 2. the truths themselves as external images, both references read from the cache of run 1
"$SSS" eval "$T/scenes/ball.json" "${RUN[@]}" --cached-reference --reference-dir "$R" \
    --images "single=$R/{scene}_bounces1_64x64.exr" --images "full=$R/{scene}_64x64.exr" --out "$T/o2" \
    >"$T/stdout2" 2>"$T/stderr2" || fail "eval with the truths as images failed: $(head -c 400 "$T/stderr2")"
if [ -n "$PY" ]; then
    "$PY" - "$T/o2/results.json" <<'EOF' || fail "the truths scored against themselves"
import json, sys
doc = json.load(open(sys.argv[1]))
sc = doc["scenes"][0]
assert sc["references"][0]["source"] == "cached" and sc["single_event_reference"]["source"] == "cached", sc
e = {r["label"]: r for r in doc["results"] if r["kind"] == "quality"}
def same(m):  # the image is the truth: nothing lost, the same light
    return m["dssim"] == 0 and m["flip"] == 0 and m["psnr_infinite"] and all(abs(x - 1) < 1e-12 for x in m["mean_ratio"])
s, f = e["single"], e["full"]
assert same(s["single_event"]), s
assert same(f), f
# a scene with a floor: the truths differ where light travels between the surfaces
assert s["dssim"] > 0.005 and s["flip"] > 0.005 and all(x < 0.999 for x in s["mean_ratio"]), s
assert f["single_event"]["dssim"] > 0.005 and all(x > 1.001 for x in f["single_event"]["mean_ratio"]), f
EOF
fi

# 3. a cached single-event reference with the wrong bounces (the full transport under its name) is not used
mkdir -p "$T/wrong"
cp "$R/ball_64x64.exr" "$R/ball_64x64.json" "$T/wrong/"
cp "$R/ball_64x64.exr" "$T/wrong/ball_bounces1_64x64.exr"
cp "$R/ball_64x64.json" "$T/wrong/ball_bounces1_64x64.json"
"$SSS" eval "$T/scenes/ball.json" "${RUN[@]}" --cached-reference --reference-dir "$T/wrong" --out "$T/o3" \
    >/dev/null 2>"$T/stderr3" || fail "eval with a wrong cached truth failed: $(head -c 400 "$T/stderr3")"
grep -q "ball_bounces1_64x64.exr has bounces 0 (0: full transport), not 1; rendering it" "$T/stderr3" ||
    fail "no note about the wrong bounces: $(cat "$T/stderr3")"
grep -q '"bounces": 1,' "$T/o3/references/ball_bounces1_64x64.json" 2>/dev/null ||
    fail "the single-event truth was not rendered again"
[ ! -e "$T/o3/references/ball_64x64.exr" ] || fail "the right cached full-transport reference was rendered again"
if [ -n "$PY" ]; then
    "$PY" - "$T/o1/results.json" "$T/o3/results.json" <<'EOF' || fail "the re-rendered single-event truth"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
assert b["scenes"][0]["single_event_reference"]["source"] == "rendered", b["scenes"][0]
ea, eb = ([r for r in d["results"] if r["kind"] == "quality"][0] for d in (a, b))
# the same truth as run 1 (which compared the float image, this one too): the same scores
assert abs(ea["single_event"]["dssim"] - eb["single_event"]["dssim"]) < 2e-3, (ea["single_event"], eb["single_event"])
EOF
fi

# 4. both truths the same: refused, nothing written
"$SSS" eval "$T/scenes/ball.json" "${RUN[@]}" --reference-bounces 1 --out "$T/o4" >/dev/null 2>"$T/stderr4"
code=$?
[ "$code" -eq 2 ] || fail "--both-truths --reference-bounces 1 exited $code, expected 2"
grep -q -- "--both-truths" "$T/stderr4" || fail "the usage error does not name --both-truths: $(cat "$T/stderr4")"
[ ! -e "$T/o4" ] || fail "a refused run wrote $T/o4"
"$SSS" eval --help | grep -q -- "--both-truths" || fail "sss eval --help lacks --both-truths"

if [ "$fails" -ne 0 ]; then
    echo "$fails failure(s)"
    exit 1
fi
echo "ok"
