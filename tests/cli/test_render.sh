#!/usr/bin/env bash
# `sss render` and `sss techniques`: outputs (PNG, EXR, numbered animation frames), timings as a table
# and as JSON, technique parameters, and errors (exit 1 for bad inputs, 2 for usage) that write nothing.
# Usage: bash test_render.sh <sss-binary> <repo-root>
set -u
SSS=$1
ROOT=$2
. "$(dirname "${BASH_SOURCE[0]}")/harness.sh"
# expect CODE PATTERN -- ARGS: exit status CODE, stderr matching PATTERN (extended regex, case-insensitive)
expect() {
    local code=$1 pattern=$2
    shift 3
    "$SSS" "$@" >"$T/out.txt" 2>"$T/err.txt"
    local got=$?
    [ "$got" -eq "$code" ] || fail "sss $* exited $got, expected $code ($(head -c 300 "$T/err.txt"))"
    [ -z "$pattern" ] || grep -Eqi -e "$pattern" "$T/err.txt" || fail "sss $* stderr lacks /$pattern/: $(head -c 300 "$T/err.txt")"
}
SC=$ROOT/scenes

# techniques: one line each, parameters on request
"$SSS" techniques >"$T/tech.txt" || fail "sss techniques failed"
grep -q '^maisch2020 ' "$T/tech.txt" || fail "maisch2020 not listed"
grep -q '^local ' "$T/tech.txt" || fail "local not listed"
"$SSS" techniques --params >"$T/params.txt" || fail "sss techniques --params failed"
for p in n_l layers brightening grazing_cutoff translucency_divisor lut_size shadow_size; do
    grep -q " $p " "$T/params.txt" || fail "parameter $p not listed"
done
expect 2 "unknown option" -- techniques --bogus

# a render with PNG + EXR, timings table and JSON
mkdir -p "$T/o"
"$SSS" render "$SC/gl_area.json" -o "$T/o/a.png" --exr "$T/o/a.exr" --width 48 --height 40 --timings \
    --timings-json "$T/o/t.json" >"$T/timings.txt" 2>"$T/err.txt" || fail "render failed: $(cat "$T/err.txt")"
[ -s "$T/o/a.png" ] && [ -s "$T/o/a.exr" ] || fail "render wrote no images"
head -c 8 "$T/o/a.png" | od -An -tx1 | grep -q "89 50 4e 47" || fail "a.png is not a PNG"
for pass in gbuffer shadows illumination mipmaps splat_cull translucency upsample screen_space combine total; do
    grep -q "^$pass " "$T/timings.txt" || fail "timings table lacks $pass"
done
grep -Eq "glFinish|GL_TIME_ELAPSED" "$T/timings.txt" || fail "timings do not name the method"
grep -q "median of 5 frames after 2 warm-up" "$T/timings.txt" || fail "timings do not say what they are: $(head -1 "$T/timings.txt")"
"$SSS" render "$SC/gl_area.json" -o "$T/o/b.png" --width 16 --height 16 --timings --frames 1 --warmup 0 >"$T/t1.txt" ||
    fail "render --frames 1 --warmup 0 failed"
grep -q "median of 1 frame after 0 warm-up" "$T/t1.txt" || fail "--frames/--warmup not honoured: $(head -1 "$T/t1.txt")"
if command -v python3 >/dev/null; then
    python3 - "$T/o/t.json" <<'EOF' || fail "timings JSON malformed"
import json, sys
d = json.load(open(sys.argv[1]))
# timed by default: 5 frames after 2 warm-up frames (sss_gl_timing_series)
assert d["technique"] == "maisch2020" and d["width"] == 48 and d["height"] == 40
assert d["frames"] == 5 and d["warmup_frames"] == 2, (d["frames"], d["warmup_frames"])
names = [p["name"] for p in d["passes"]]
assert "screen_space" in names and "translucency" in names, names
assert all(p["median_ms"] >= 0 for p in d["passes"]) and d["total_median_ms"] > 0
assert d["method"] in ("glFinish + monotonic clock", "GL_TIME_ELAPSED queries")
EOF
fi
# the PNG is the EXR tone-mapped with the scene's exposure (sss compare: identical 8-bit images)
if "$SSS" compare "$T/o/a.png" "$T/o/a.exr" >"$T/cmp.txt" 2>&1; then
    grep -Eqi "psnr[^0-9]*inf|dssim[^0-9]*0(\.0+)?([^0-9]|$)" "$T/cmp.txt" || fail "PNG and EXR differ: $(cat "$T/cmp.txt")"
fi

# technique and parameters
"$SSS" render "$SC/gl_area.json" -o "$T/o/l.png" --technique local --width 24 --height 24 || fail "local failed"
"$SSS" render "$SC/gl_area.json" -o "$T/o/p.png" --width 24 --height 24 --param layers=2 --param n=1 \
    --param area_samples=4 || fail "parameters rejected"

# an animation: numbered frames at t = T + k / fps
mkdir -p "$T/anim"
"$SSS" render "$SC/gl_twist.json" -o "$T/anim/f.png" --width 24 --height 24 --frames 3 --animate --fps 2 \
    --time 0 2>"$T/err.txt" || fail "animation failed: $(cat "$T/err.txt")"
for k in 0000 0001 0002; do [ -s "$T/anim/f_$k.png" ] || fail "frame f_$k.png missing"; done
[ "$(ls "$T/anim" | wc -l)" -eq 3 ] || fail "animation wrote $(ls "$T/anim")"
cmp -s "$T/anim/f_0000.png" "$T/anim/f_0002.png" && fail "animation frames 0 and 2 are identical"
"$SSS" render "$SC/gl_twist.json" -o "$T/anim/g_%02d.png" --width 16 --height 16 --frames 2 --animate || fail "pattern failed"
[ -s "$T/anim/g_00.png" ] && [ -s "$T/anim/g_01.png" ] || fail "printf-pattern frames missing"

# errors write nothing
mkdir -p "$T/e"
expect 1 "missing.json" -- render "$T/missing.json" -o "$T/e/x.png"
expect 1 "unknown technique 'nope'.*maisch2020" -- render "$SC/gl_area.json" -o "$T/e/x.png" --technique nope
expect 1 "no parameter 'bogus'" -- render "$SC/gl_area.json" -o "$T/e/x.png" --param bogus=1
expect 1 "layers" -- render "$SC/gl_area.json" -o "$T/e/x.png" --param layers=-3
expect 2 "NAME=VALUE" -- render "$SC/gl_area.json" -o "$T/e/x.png" --param layers
expect 2 "number" -- render "$SC/gl_area.json" -o "$T/e/x.png" --param layers=abc
expect 2 "layers: 'paper'" -- render "$SC/gl_area.json" -o "$T/e/x.png" --param layers=paper
"$SSS" render "$SC/gl_area.json" -o "$T/p.png" --width 24 --height 24 --param preset=paper 2>"$T/err.txt" ||
    fail "--param preset=paper refused: $(cat "$T/err.txt")"
expect 2 "missing -o" -- render "$SC/gl_area.json"
expect 2 "missing SCENE" -- render -o "$T/e/x.png"
expect 2 "--width" -- render "$SC/gl_area.json" -o "$T/e/x.png" --width 0
expect 2 "--animate needs --frames" -- render "$SC/gl_area.json" -o "$T/e/x.png" --animate
expect 2 "unknown image format" -- render "$SC/gl_area.json" -o "$T/e/x.bmp"
expect 2 "\.exr" -- render "$SC/gl_area.json" -o "$T/e/x.png" --exr "$T/e/x.png"
expect 2 "unknown option" -- render "$SC/gl_area.json" -o "$T/e/x.png" --bogus
expect 1 "" -- render "$SC/gl_area.json" -o "$T/no-such-folder/x.png" --width 8 --height 8
[ -z "$(ls -A "$T/e")" ] || fail "failed renders left files: $(ls -A "$T/e")"
# a window needs a display: the message says so and points to headless rendering
DISPLAY= WAYLAND_DISPLAY= "$SSS" render "$SC/gl_area.json" --window >"$T/out.txt" 2>"$T/err.txt"
[ $? -eq 1 ] || fail "--window without a display did not exit 1"
grep -q "DISPLAY" "$T/err.txt" && grep -q "sss render" "$T/err.txt" || fail "--window message: $(cat "$T/err.txt")"
"$SSS" render --help | grep -q "timings-json" || fail "help lacks --timings-json"
# with a display (Xvfb), a GLFW window shows the same image the headless context renders
if command -v xvfb-run >/dev/null; then
    mkdir -p "$T/w"
    "$SSS" render "$SC/gl_area.json" -o "$T/w/headless.png" --width 40 --height 32 || fail "headless render failed"
    timeout 120 xvfb-run -a "$SSS" render "$SC/gl_area.json" --window --frames 2 -o "$T/w/window.png" \
        --width 40 --height 32 2>"$T/err.txt" || fail "--window under xvfb-run failed: $(cat "$T/err.txt")"
    cmp -s "$T/w/headless.png" "$T/w/window.png" || fail "window and headless renders differ"
fi

if [ "$fails" -ne 0 ]; then
    echo "$fails failure(s)"
    exit 1
fi
echo "all render CLI checks passed"
