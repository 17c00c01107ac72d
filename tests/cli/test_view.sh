#!/usr/bin/env bash
# `sss view` under Xvfb: the screenshot of N frames is the image `sss render` writes for the same view
# (overlay on: it must stay out of the screenshot); scripted input does what the keys promise, each
# checked against `sss render` of the scene edited independently here (orbit, light, medium, scale,
# technique, parts alone); the DSSIM of the reference key equals `sss compare` of `sss render` and
# `sss reference`; errors: no display (exit 1, suggests `sss render`), bad scene (exit 1, names it),
# usage (exit 2).
# Usage: bash test_view.sh <sss-binary> <repo-root>
set -u
SSS=$1
ROOT=$2
. "$(dirname "${BASH_SOURCE[0]}")/harness.sh"
SC=$ROOT/scenes/gl_area.json # procedural shapes only: edited copies need no asset paths
PY=python3
[ -x /usr/bin/python3 ] && PY=/usr/bin/python3

# --- errors that need no display ---------------------------------------------------------------
env -u DISPLAY -u WAYLAND_DISPLAY "$SSS" view "$SC" --frames 1 >"$T/out" 2>"$T/err"
rc=$?
[ "$rc" -eq 1 ] || fail "no display: exit $rc, expected 1"
grep -q "sss render" "$T/err" || fail "no display: the message does not suggest sss render: $(cat "$T/err")"
echo '{"camera": {"position": [0, 0, 1]}}' >"$T/bad_scene.json"
env -u DISPLAY -u WAYLAND_DISPLAY "$SSS" view "$T/bad_scene.json" --frames 1 >"$T/out" 2>"$T/err"
rc=$?
[ "$rc" -eq 1 ] || fail "bad scene: exit $rc, expected 1"
grep -q "bad_scene.json" "$T/err" || fail "bad scene: the message does not name the file: $(cat "$T/err")"
"$SSS" view "$T/missing.json" >"$T/out" 2>"$T/err"
[ $? -eq 1 ] && grep -q "missing.json" "$T/err" || fail "missing scene: $(cat "$T/err")"
for args in "" "$SC --screenshot $T/x.png" "$SC --frames 0" "$SC --frames 2 --screenshot $T/x.exr" "$SC --bogus" \
    "$SC --input tab"; do
    # shellcheck disable=SC2086
    "$SSS" view $args >"$T/out" 2>"$T/err"
    rc=$?
    [ "$rc" -eq 2 ] || fail "sss view $args: exit $rc, expected 2 (usage)"
done
for input in "l,l" "bogus" "orbit:1"; do # checked before a window opens
    env -u DISPLAY -u WAYLAND_DISPLAY "$SSS" view "$SC" --frames 1 --input "$input" >"$T/out" 2>"$T/err"
    rc=$?
    [ "$rc" -eq 1 ] && grep -q "input event" "$T/err" || fail "--input $input: exit $rc, $(cat "$T/err")"
done
"$SSS" view --help | grep -q "orbit" || fail "--help does not list the mouse bindings"

if ! command -v xvfb-run >/dev/null 2>&1; then
    echo "skipped: xvfb-run not installed"
    [ "$fails" -eq 0 ] || exit 1
    exit 0
fi

# dssim A B: the DSSIM that sss compare prints
dssim() { "$SSS" compare "$1" "$2" | sed -n 's/^dssim=\([0-9.e+-]*\).*/\1/p'; }
# below A LIMIT: A < LIMIT as numbers
below() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a != "" && a + 0 < b + 0) }'; }
near() { awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN { d = a - b; exit !(a != "" && b != "" && d < t && -d < t) }'; }
# Sanitizer builds: Mesa/GLX/xcb leak a few bytes whenever a window is opened (`sss render --window`
# too); a viewer run may leak no more than that baseline.
leaked() { sed -n 's/^SUMMARY: AddressSanitizer: \([0-9]*\) byte(s) leaked.*/\1/p' "$1" | head -n 1; }
xvfb-run -a env LSAN_OPTIONS=exitcode=0 "$SSS" render "$SC" --window --frames 1 --width 16 --height 16 \
    >"$T/baseline.log" 2>&1 || fail "sss render --window failed: $(head -c 300 "$T/baseline.log")"
baseline=$(leaked "$T/baseline.log")
baseline=${baseline:-0}
# view LOG ARGS...: a viewer run under Xvfb (in $T/shots, where the S key writes)
view() {
    local log=$1
    shift
    mkdir -p "$T/shots"
    (cd "$T/shots" && xvfb-run -a env LSAN_OPTIONS=exitcode=0 "$SSS" view "$@") >"$log" 2>&1 ||
        fail "sss view $* failed: $(head -c 400 "$log")"
    local l
    l=$(leaked "$log")
    [ -z "$l" ] || [ "$l" -le "$baseline" ] || fail "sss view $* leaked $l bytes (a window alone: $baseline)"
}
# same IMAGE SCENE [render args]: the viewer's IMAGE equals `sss render` of SCENE
same() {
    local img=$1 scene=$2
    shift 2
    "$SSS" render "$scene" -o "$img.render.png" "$@" 2>"$img.render.err" ||
        { fail "sss render for $img failed: $(head -c 300 "$img.render.err")"; return; }
    local d
    d=$(dssim "$img" "$img.render.png")
    echo "$(basename "$img"): DSSIM viewer vs sss render = $d"
    below "$d" 0.01 || fail "$img: the viewer's screenshot differs from sss render (DSSIM $d)"
}
# edit IN OUT PYTHON: writes the scene IN with the statement applied to the dict s as OUT
edit() {
    "$PY" - "$1" "$2" "$3" <<'EOF'
import json, math, sys
s = json.load(open(sys.argv[1]))
def rot_y(p, deg, pivot=(0.0, 0.0, 0.0)):  # right-handed about +y through pivot
    a = math.radians(deg); x, y, z = (p[0] - pivot[0], p[1] - pivot[1], p[2] - pivot[2])
    return [pivot[0] + x * math.cos(a) + z * math.sin(a), p[1], pivot[2] - x * math.sin(a) + z * math.cos(a)]
exec(sys.argv[3])
json.dump(s, open(sys.argv[2], "w"))
EOF
}

# 1. ten frames with the overlay on: the screenshot is sss render's image of the same view
view "$T/main.log" "$SC" --frames 10 --width 128 --height 128 --screenshot "$T/main.png"
same "$T/main.png" "$SC" --width 128 --height 128

# 2. the mouse and the keys in one run, one event per frame; after each step the S key saves
#    sss-view-NNNN.png, checked against `sss render` of the scene edited the same way here (64 x 64):
#    a 100 px left drag (the camera turns -30 degrees about y), the light +15 degrees net, the first
#    medium, scale x4, the translucency part alone, the screen-space part alone, all parts, next technique
S=(--width 64 --height 64)
view "$T/keys.log" "$SC" --frames 18 "${S[@]}" \
    --input "orbit:100:0,s,l,shift+l,l,s,m,s,+,+,s,2,s,3,s,1,tab,s"
P=$T/shots/sss-view
for k in 0000 0001 0002 0003 0004 0005 0006; do [ -s "$P-$k.png" ] || fail "screenshot sss-view-$k.png missing"; done
edit "$SC" "$T/orbit.json" 's["camera"]["position"] = rot_y(s["camera"]["position"], -30.0)'
same "$P-0000.png" "$T/orbit.json" "${S[@]}"
edit "$T/orbit.json" "$T/light.json" \
    'L = s["lights"][0]; L["center"] = rot_y(L["center"], 15); L["u"] = rot_y(L["u"], 15); L["v"] = rot_y(L["v"], 15)'
same "$P-0001.png" "$T/light.json" "${S[@]}"
"$SSS" render "$T/orbit.json" -o "$T/orbit_only.png" "${S[@]}" && "$SSS" render "$SC" -o "$T/original.png" "${S[@]}" ||
    fail "sss render of the original scene failed"
d=$(dssim "$P-0000.png" "$T/original.png")
below "$d" 0.002 && fail "the orbit changed nothing (DSSIM $d against the original view)"
d=$(dssim "$P-0001.png" "$T/orbit_only.png")
below "$d" 0.002 && fail "the light key changed nothing (DSSIM $d)"
name=$(sed -n 's/.*medium \([A-Za-z0-9]*\), scale x1$/\1/p' "$T/keys.log" | head -n 1)
[ -n "$name" ] || fail "the medium key did not report a medium: $(cat "$T/keys.log")"
edit "$T/light.json" "$T/medium.json" "s['objects'][0]['material']['medium'] = '$name'"
same "$P-0002.png" "$T/medium.json" "${S[@]}"
edit "$T/medium.json" "$T/scale.json" 's["objects"][0]["material"]["scale"] *= 4'
same "$P-0003.png" "$T/scale.json" "${S[@]}"
same "$P-0004.png" "$T/scale.json" "${S[@]}" --param screen_space=0
same "$P-0005.png" "$T/scale.json" "${S[@]}" --param translucency=0
second=$("$SSS" techniques | sed -n '2s/ .*//p')
if grep -q "technique $second failed" "$T/keys.log" ||
    ! "$SSS" render "$T/scale.json" -o "$T/second.png" "${S[@]}" --technique "$second" 2>/dev/null; then
    echo "note: technique $second cannot render this scene; the Tab check is skipped"
else
    same "$P-0006.png" "$T/scale.json" "${S[@]}" --technique "$second"
fi

# 3. the DSSIM of the reference key: the CPU reference of this view, compared as sss compare does
edit "$SC" "$T/small.json" 's["camera"]["width"] = 64; s["camera"]["height"] = 64'
view "$T/ref.log" "$T/small.json" --frames 2 --reference
got=$(sed -n 's/.*DSSIM of the last frame vs the final reference: \([0-9.]*\).*/\1/p' "$T/ref.log")
"$SSS" render "$T/small.json" -o "$T/small.png" && "$SSS" reference "$T/small.json" -o "$T/small_ref.png" --quiet ||
    fail "render/reference of the small scene failed"
want=$(dssim "$T/small.png" "$T/small_ref.png")
echo "reference key: viewer DSSIM $got, sss compare $want"
# equal up to the run-to-run noise of maisch2020's additive splat blending (order varies: ~1e-6 DSSIM)
near "$got" "$want" 2e-5 || fail "the viewer's DSSIM ($got) differs from sss compare ($want)"

[ "$fails" -eq 0 ] || exit 1
echo "all view tests passed"
