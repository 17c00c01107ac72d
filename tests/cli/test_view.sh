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
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fails=0
fail() {
    echo "FAIL: $*"
    fails=$((fails + 1))
}
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
# view NAME ARGS...: a viewer run under Xvfb writing $T/NAME.png
view() {
    local name=$1
    shift
    xvfb-run -a "$SSS" view "$@" --screenshot "$T/$name.png" >"$T/$name.log" 2>&1 ||
        fail "sss view $* failed: $(head -c 400 "$T/$name.log")"
}
# same NAME SCENE [render args]: the viewer's NAME.png equals `sss render` of SCENE
same() {
    local name=$1 scene=$2
    shift 2
    "$SSS" render "$scene" -o "$T/$name.render.png" "$@" 2>"$T/$name.render.err" ||
        { fail "sss render for $name failed: $(head -c 300 "$T/$name.render.err")"; return; }
    local d
    d=$(dssim "$T/$name.png" "$T/$name.render.png")
    echo "$name: DSSIM viewer vs sss render = $d"
    below "$d" 0.01 || fail "$name: the viewer's screenshot differs from sss render (DSSIM $d)"
}
# edit OUT PYTHON: writes the scene with the statement applied to the dict s
edit() {
    "$PY" - "$SC" "$1" "$2" <<'EOF'
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
view main "$SC" --frames 10 --width 128 --height 128
same main "$SC" --width 128 --height 128

# 2. the keys and the mouse, each checked against an independently edited scene (64 x 64)
S=(--width 64 --height 64)
view orbit "$SC" --frames 2 "${S[@]}" --input "orbit:100:0" # 100 px left drag: camera -30 degrees about y
edit "$T/orbit.json" 's["camera"]["position"] = rot_y(s["camera"]["position"], -30.0)'
same orbit "$T/orbit.json" "${S[@]}"
view light "$SC" --frames 3 "${S[@]}" --input "l,shift+l,l" # net +15 degrees about y through look_at
edit "$T/light.json" 'L = s["lights"][0]; L["center"] = rot_y(L["center"], 15); L["u"] = rot_y(L["u"], 15); L["v"] = rot_y(L["v"], 15)'
same light "$T/light.json" "${S[@]}"
"$SSS" render "$SC" -o "$T/original.png" "${S[@]}" || fail "sss render of the original scene failed"
for name in orbit light; do # and they are not the original view
    d=$(dssim "$T/$name.png" "$T/original.png")
    below "$d" 0.002 && fail "$name: the input changed nothing (DSSIM $d against the original view)"
done
view medium "$SC" --frames 2 "${S[@]}" --input "m"
name=$(sed -n 's/.*medium \([A-Za-z0-9]*\), scale x1$/\1/p' "$T/medium.log" | head -n 1)
[ -n "$name" ] || fail "the medium key did not report a medium: $(cat "$T/medium.log")"
edit "$T/medium.json" "m = s['objects'][0]['material']; m['medium'] = '$name'"
same medium "$T/medium.json" "${S[@]}"
view scale "$SC" --frames 3 "${S[@]}" --input "+,+"
edit "$T/scale.json" 's["objects"][0]["material"]["scale"] *= 4'
same scale "$T/scale.json" "${S[@]}"
view part2 "$SC" --frames 2 "${S[@]}" --input "2"
same part2 "$SC" "${S[@]}" --param screen_space=0
view part3 "$SC" --frames 2 "${S[@]}" --input "3"
same part3 "$SC" "${S[@]}" --param translucency=0
second=$("$SSS" techniques | sed -n '2s/ .*//p')
if [ -n "$second" ]; then
    view tab "$SC" --frames 2 "${S[@]}" --input "tab"
    same tab "$SC" "${S[@]}" --technique "$second"
fi

# 3. the DSSIM of the reference key: the CPU reference of this view, compared as sss compare does
edit "$T/small.json" 's["camera"]["width"] = 64; s["camera"]["height"] = 64'
xvfb-run -a "$SSS" view "$T/small.json" --frames 2 --reference >"$T/ref.log" 2>&1 || fail "--reference failed: $(cat "$T/ref.log")"
got=$(sed -n 's/.*DSSIM of the last frame vs the final reference: \([0-9.]*\).*/\1/p' "$T/ref.log")
"$SSS" render "$T/small.json" -o "$T/small.png" && "$SSS" reference "$T/small.json" -o "$T/small_ref.png" --quiet ||
    fail "render/reference of the small scene failed"
want=$(dssim "$T/small.png" "$T/small_ref.png")
echo "reference key: viewer DSSIM $got, sss compare $want"
[ -n "$got" ] && [ "$got" = "$want" ] || fail "the viewer's DSSIM ($got) differs from sss compare ($want)"

[ "$fails" -eq 0 ] || exit 1
echo "all view tests passed"
