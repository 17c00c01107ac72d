#!/usr/bin/env bash
# sss eval on two tiny scenes (64x64; one animated, evaluated at t = 0.5) with two working technique
# specs and two that must fail (an unknown name, a parameter out of range): every output file is
# written, results.json validates against docs/results.schema.json (a small JSON Schema validator in
# python3 below), failures are reported and not dropped, the metrics equal `sss compare` of an
# independent `sss render` against the saved reference, the CSV matches the JSON, cached references
# are used (and a stale one is re-rendered), and usage errors exit 2.
# Usage: bash test_eval.sh <sss-binary> <repo-root>
set -u
SSS=$1
ROOT=$2
. "$(dirname "${BASH_SOURCE[0]}")/harness.sh"
find_python "json, csv"

mkdir -p "$T/scenes"
write_ball_scene "$T/scenes/ball.json" 0.5
cat >"$T/scenes/knot.json" <<'EOF'
{
  "camera": {"position": [0, 0, 4], "look_at": [0, 0, 0], "fov": 40, "width": 64, "height": 48},
  "objects": [
    {"procedural": {"shape": "trefoil", "radius": 1.2, "tube": 0.18, "segments": 96},
     "material": {"type": "subsurface", "medium": "Skimmilk", "scale": 15.0},
     "animation": {"type": "twist", "amplitude": 60, "period": 2}}
  ],
  "lights": [{"type": "point", "position": [2, 2, 3], "intensity": [8, 8, 8]}]
}
EOF

OUT=$T/out
TECHS="maisch2020,local,nosuch,maisch2020:layers=999"
"$SSS" eval "$T/scenes/ball.json" "$T/scenes/knot.json@0.5" --techniques "$TECHS" --frames 1 --warmup 0 \
    --timing-resolutions 96x64 --out "$OUT" --progress >"$T/stdout" 2>"$T/stderr"
rc=$?
[ "$rc" -eq 0 ] || fail "sss eval exited $rc: $(head -c 600 "$T/stderr")"
for f in results.json results.csv report.html sheet_ball.png sheet_knot_t0.5.png plot_dssim.png plot_flip.png \
    plot_passes.png plot_resolution.png crops_ball_0.png crops_knot_t0.5_1.png references/ball_64x64.exr \
    references/ball_64x64.json references/knot_64x48_t0.5.exr references/knot_64x48_t0.5.json; do
    [ -s "$OUT/$f" ] || fail "missing output $f"
done
# no SAM sweep ran (sam is not among the techniques): no empty plot of it
[ -e "$OUT/plot_sam_rmse.png" ] && fail "plot_sam_rmse.png written without a SAM sweep"
for f in "$OUT"/*.png; do
    head -c 8 "$f" | od -An -tx1 | grep -q "89 50 4e 47" || fail "$f is not a PNG"
done
grep -q "nosuch" "$T/stdout" || fail "summary does not list the failing technique: $(cat "$T/stdout")"
grep -Eq "FAILED" "$T/stdout" || fail "summary does not mark failures"
grep -q "report.html" "$T/stdout" || fail "summary does not say where the report is"
# plain progress lines (stderr is not a terminal here: --progress), no carriage returns
grep -q "reference" "$T/stderr" || fail "no progress lines on stderr"
if grep -q $'\r' "$T/stderr"; then fail "progress bar escapes on a non-terminal"; fi

if [ -z "$PY" ]; then
    echo "note: python3 with json unavailable; schema checks skipped"
else
    "$PY" - "$ROOT/docs/results.schema.json" "$OUT" <<'EOF' || fail "results.json / results.csv checks failed"
import csv, json, math, sys

schema = json.load(open(sys.argv[1]))
out = sys.argv[2]
doc = json.load(open(out + "/results.json"))

# A JSON Schema (draft 2020-12) subset: type, const, enum, required, properties, additionalProperties,
# items, minItems, minimum, maximum, $ref to #/$defs/..., anyOf; keywords apply to the types they constrain.
def is_type(v, t):
    if t == "null": return v is None
    if t == "boolean": return isinstance(v, bool)
    if t == "integer": return isinstance(v, int) and not isinstance(v, bool) or (isinstance(v, float) and v.is_integer())
    if t == "number": return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)
    if t == "string": return isinstance(v, str)
    if t == "array": return isinstance(v, list)
    if t == "object": return isinstance(v, dict)
    raise ValueError("unknown type " + t)

errors = []
def check(v, s, path):
    if "$ref" in s:
        name = s["$ref"].split("/")[-1]
        return check(v, schema["$defs"][name], path)
    if "anyOf" in s:  # valid when one alternative leaves no errors
        before = len(errors)
        for alt in s["anyOf"]:
            del errors[before:]
            check(v, alt, path)
            if len(errors) == before: return
        return
    if "type" in s:
        ts = s["type"] if isinstance(s["type"], list) else [s["type"]]
        if not any(is_type(v, t) for t in ts):
            errors.append("%s: %r is not %s" % (path, v, ts)); return
    if "const" in s and v != s["const"]: errors.append("%s: %r != %r" % (path, v, s["const"]))
    if "enum" in s and v not in s["enum"]: errors.append("%s: %r not in %s" % (path, v, s["enum"]))
    if isinstance(v, (int, float)) and not isinstance(v, bool):
        if not math.isfinite(v): errors.append("%s: non-finite" % path)
        if "minimum" in s and v < s["minimum"]: errors.append("%s: %r < %r" % (path, v, s["minimum"]))
        if "maximum" in s and v > s["maximum"]: errors.append("%s: %r > %r" % (path, v, s["maximum"]))
    if isinstance(v, dict):
        for k in s.get("required", []):
            if k not in v: errors.append("%s: missing %s" % (path, k))
        props = s.get("properties", {})
        for k, val in v.items():
            if k in props: check(val, props[k], path + "." + k)
            elif s.get("additionalProperties") is False: errors.append("%s: unexpected %s" % (path, k))
            elif isinstance(s.get("additionalProperties"), dict): check(val, s["additionalProperties"], path + "." + k)
    if isinstance(v, list):
        if len(v) < s.get("minItems", 0): errors.append("%s: fewer than %d items" % (path, s["minItems"]))
        if "items" in s:
            for i, item in enumerate(v): check(item, s["items"], "%s[%d]" % (path, i))

# the validator itself must reject what the schema forbids
bad = json.loads(json.dumps(doc)); bad["results"][0]["status"] = "maybe"; del bad["gl"]
check(bad, schema, "$")
assert len(errors) >= 2, "validator accepted an invalid document"
errors = []
check(doc, schema, "$")
assert not errors, "schema violations:\n" + "\n".join(errors[:20])

techs = ["maisch2020", "local", "nosuch", "maisch2020:layers=999"]
assert doc["settings"]["techniques"] == techs, doc["settings"]["techniques"]
assert doc["settings"]["frames"] == 1 and doc["settings"]["warmup_frames"] == 0, doc["settings"]
assert [s["name"] for s in doc["scenes"]] == ["ball", "knot@0.5"], [s["name"] for s in doc["scenes"]]
assert doc["scenes"][1]["time"] == 0.5
quality = [r for r in doc["results"] if r["kind"] == "quality"]
timing = [r for r in doc["results"] if r["kind"] == "timing"]
# every scene x technique is there, failures included (not dropped)
assert sorted((r["scene"], r["label"]) for r in quality) == sorted((s, t) for s in ["ball", "knot@0.5"] for t in techs), quality
assert sorted((r["scene"], r["label"]) for r in timing) == sorted((s, t) for s in ["ball", "knot@0.5"] for t in techs)
for r in doc["results"]:
    if r["label"] in ("nosuch", "maisch2020:layers=999"):
        assert r["status"] == "failed" and r["error"], r
        assert r["dssim"] is None and r["flip"] is None and r["ms_total"] is None
        assert ("nosuch" in r["error"]) if r["label"] == "nosuch" else ("layers" in r["error"]), r["error"]
    else:
        assert r["status"] == "ok" and r["error"] is None, r
        assert r["passes"] and r["ms_total"] > 0 and r["precompute_ms"] > 0, r
        # one frame: the total is the sum of the passes
        assert abs(sum(p["ms"] for p in r["passes"]) - r["ms_total"]) <= 1e-6 * r["ms_total"] + 1e-9, r
        assert r["memory"]["gpu_bytes"] == r["memory"]["texture_bytes"] + r["memory"]["buffer_bytes"] > 0
        if r["kind"] == "quality":
            assert 0 < r["dssim"] < 1 and 0 < r["flip"] < 1 and r["rmse"] > 0 and r["psnr"] > 0, r
            assert (r["width"], r["height"]) == ((64, 64) if r["scene"] == "ball" else (64, 48))
        else:
            assert r["dssim"] is None and r["flip"] is None and (r["width"], r["height"]) == (96, 64)
assert doc["results"][0]["params"] == {} and [r for r in quality if r["label"] == "maisch2020:layers=999"][0]["params"] == {"layers": 999}
for s in doc["scenes"]:
    assert [(x["source"], x["quality"]) for x in s["references"]] == [("rendered", "final")], s
    assert s["references"][0]["path"].endswith(".exr")
if doc["sam_sweep"]["available"] is False:
    assert doc["sam_sweep"]["points"] == [] and doc["sam_sweep"]["ran"] is False

# the CSV holds the same rows
rows = list(csv.DictReader(open(out + "/results.csv")))
entries = doc["results"] + doc["sam_sweep"]["points"]
assert len(rows) == len(entries), (len(rows), len(entries))
for row, r in zip(rows, entries):
    assert row["label"] == r["label"] and row["status"] == r["status"] and row["kind"] == r["kind"], (row, r)
    for m in ("dssim", "flip"):
        if r[m] is not None: assert abs(float(row[m]) - r[m]) <= 1e-5 * max(1, r[m]), (m, row, r)
        else: assert row[m] == ""
    if r["status"] == "failed": assert row["error"] == r["error"]
# a file for the shell: the DSSIM of the two checks below
d = {(r["scene"], r["label"]): r["dssim"] for r in quality}
open(out + "/dssim.txt", "w").write("%.6f %.6f\n" % (d[("ball", "local")], d[("knot@0.5", "maisch2020")]))
EOF
fi

# The metrics are those of the technique's own image against the saved reference (same time, same
# size): render independently with `sss render` and compare with `sss compare`.
if [ -s "$OUT/dssim.txt" ]; then
    read -r d_ball d_knot <"$OUT/dssim.txt"
    "$SSS" render "$T/scenes/ball.json" --technique local -o "$T/ball_local.exr" 2>/dev/null || fail "sss render ball"
    "$SSS" render "$T/scenes/knot.json" --time 0.5 -o "$T/knot_m.exr" 2>/dev/null || fail "sss render knot"
    c1=$("$SSS" compare "$OUT/references/ball_64x64.exr" "$T/ball_local.exr" | sed 's/^dssim=\([^ ]*\).*/\1/')
    c2=$("$SSS" compare "$OUT/references/knot_64x48_t0.5.exr" "$T/knot_m.exr" | sed 's/^dssim=\([^ ]*\).*/\1/')
    # the saved reference is half-float, the run compared the float image: allow half's rounding
    awk -v a="$d_ball" -v b="$c1" 'BEGIN { exit !(a - b < 2e-3 && b - a < 2e-3) }' ||
        fail "ball/local DSSIM $d_ball differs from sss compare $c1"
    awk -v a="$d_knot" -v b="$c2" 'BEGIN { exit !(a - b < 2e-3 && b - a < 2e-3) }' ||
        fail "knot@0.5/maisch2020 DSSIM $d_knot differs from sss compare $c2"
    # ... and the time matters: the twisted knot at t = 0 is another image
    "$SSS" render "$T/scenes/knot.json" --time 0 -o "$T/knot_0.exr" 2>/dev/null
    c0=$("$SSS" compare "$T/knot_0.exr" "$T/knot_m.exr" | sed 's/^dssim=\([^ ]*\).*/\1/')
    awk -v a="$c0" 'BEGIN { exit !(a > 0.001) }' || fail "the twist at t = 0.5 does not change the image ($c0)"
fi

# report.html: self-contained (every image a data URI, nothing fetched)
n_img=$(grep -o '<img ' "$OUT/report.html" | wc -l)
n_data=$(grep -o '<img alt="[^"]*" src="data:image/png;base64,' "$OUT/report.html" | wc -l)
[ "$n_img" -ge 6 ] && [ "$n_img" -eq "$n_data" ] || fail "report images: $n_img <img>, $n_data data URIs"
if grep -Eq '(src|href)="(https?:|file:|//)' "$OUT/report.html"; then fail "report.html references external files"; fi
grep -q "maisch2020:layers=999" "$OUT/report.html" || fail "report lacks the failing technique"

# Cached references: the second run reads them (no rendering) and gets the same numbers.
"$SSS" eval "$T/scenes/ball.json" "$T/scenes/knot.json@0.5" --techniques maisch2020,local --frames 1 --warmup 0 \
    --cached-reference --reference-dir "$OUT/references" --out "$T/out2" >"$T/stdout2" 2>"$T/stderr2" ||
    fail "cached run failed: $(head -c 400 "$T/stderr2")"
if [ -n "$PY" ]; then
    "$PY" - "$OUT/results.json" "$T/out2/results.json" <<'EOF' || fail "cached run differs"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
assert all(r["source"] == "cached" for s in b["scenes"] for r in s["references"]), b["scenes"]
da = {(r["scene"], r["label"]): r["dssim"] for r in a["results"] if r["kind"] == "quality" and r["status"] == "ok"}
db = {(r["scene"], r["label"]): r["dssim"] for r in b["results"] if r["kind"] == "quality"}
assert set(db) == set(da), (db, da)
for k in db: assert abs(db[k] - da[k]) < 2e-3, (k, db[k], da[k])
EOF
fi
[ ! -d "$T/out2/references" ] || [ -z "$(ls "$T/out2/references")" ] || fail "cached run rendered references"
# a scene that changed since its reference was rendered is re-rendered, and the user is told
echo " " >>"$T/scenes/ball.json"
"$SSS" eval "$T/scenes/ball.json" --techniques local --frames 1 --warmup 0 --cached-reference \
    --reference-dir "$OUT/references" --out "$T/out3" >/dev/null 2>"$T/stderr3" || fail "stale run failed"
grep -qi "stale" "$T/stderr3" || fail "no note about the stale reference: $(cat "$T/stderr3")"
[ -s "$T/out3/references/ball_64x64.exr" ] || fail "stale reference was not re-rendered"
# a reference cached by an older interreflection (sidecar transport_version) is stale too
mkdir -p "$T/oldrefs" && cp "$OUT"/references/knot_* "$T/oldrefs/"
sed -i 's/"transport_version": [0-9]*/"transport_version": 1/' "$T"/oldrefs/*.json
"$SSS" eval "$T/scenes/knot.json@0.5" --techniques local --frames 1 --warmup 0 --cached-reference \
    --reference-dir "$T/oldrefs" --out "$T/out5" >/dev/null 2>"$T/stderr5" || fail "old-transport run failed"
grep -qi "interreflection version 1" "$T/stderr5" || fail "no note about the old transport: $(cat "$T/stderr5")"
# a missing cached reference is rendered, with a note
"$SSS" eval "$T/scenes/ball.json" --techniques local --frames 1 --warmup 0 --cached-reference \
    --reference-dir "$T/nowhere" --out "$T/out4" >/dev/null 2>"$T/stderr4" || fail "uncached run failed"
grep -qi "no cached reference" "$T/stderr4" || fail "no note about the missing reference: $(cat "$T/stderr4")"

# usage errors (exit 2) and input errors (exit 1) write nothing
expect() {
    local code=$1 pattern=$2
    shift 2
    "$SSS" eval "$@" >/dev/null 2>"$T/err.txt"
    local got=$?
    [ "$got" -eq "$code" ] || fail "sss eval $* exited $got, expected $code"
    grep -Eqi -e "$pattern" "$T/err.txt" || fail "sss eval $*: stderr lacks /$pattern/: $(head -c 300 "$T/err.txt")"
}
expect 2 "at least one scene" --out "$T/x"
expect 2 "resolutions" "$T/scenes/ball.json" --resolutions 64by64 --out "$T/x"
expect 2 "resolutions" "$T/scenes/ball.json" --resolutions 8x8 --out "$T/x"
expect 2 "techniques" "$T/scenes/ball.json" --techniques "local:shadow_size" --out "$T/x"
expect 2 "frames" "$T/scenes/ball.json" --frames 0 --out "$T/x"
expect 2 "reference-quality" "$T/scenes/ball.json" --reference-quality best --out "$T/x"
expect 2 "unknown option" "$T/scenes/ball.json" --bogus
expect 1 "missing.json" "$T/scenes/missing.json" --out "$T/x"
[ ! -e "$T/x" ] || fail "a failed run wrote $T/x"
"$SSS" eval --help | grep -q "cached-reference" || fail "--help lacks --cached-reference"

if [ "$fails" -ne 0 ]; then
    echo "$fails failure(s)"
    exit 1
fi
echo "ok"
