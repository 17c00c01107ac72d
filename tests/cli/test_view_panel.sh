#!/usr/bin/env bash
# `sss view --script`: the panel's actions from a file, under Xvfb. Screenshots after scripted actions
# are checked for properties, each against an image made independently: the panel is docked beside
# the image (the window widened by its width, the image `sss render`'s at the scene's size, the panel
# in its own columns) and, hidden, leaves the window to the image (`sss render` at the window's size);
# `panel width` gives the image the rest of the window; `panel scroll SECTION` opens the section and
# brings it into view (the Lights section's colour swatch appears in the panel); a material edit
# changes the image and equals `sss render` of the scene edited here, and so does a light edit; a
# parameter set in the panel equals `sss render --param`; a split view holds the left half of one
# technique and the right half of the other (or of `sss reference`), a divider at the cut and each
# side's name; the error map is of the frame against the reference (its DSSIM is `sss compare`'s),
# over the range the script set, and holds the colour bar with its ticks. Errors: a bad script line
# (exit 1, file and line named, before any window), --script with --frames (exit 2).
# Usage: bash test_view_panel.sh <sss-binary> <repo-root>
set -u
SSS=$1
ROOT=$2
. "$(dirname "${BASH_SOURCE[0]}")/harness.sh"
PY=python3
[ -x /usr/bin/python3 ] && PY=/usr/bin/python3
W=128
H=96

# --- errors that need no display ----------------------------------------------------------------
printf 'frames 1\n# fine so far\nmaterial 0 shine 2\n' >"$T/bad.txt"
env -u DISPLAY -u WAYLAND_DISPLAY "$SSS" view "$ROOT/scenes/gl_area.json" --script "$T/bad.txt" >"$T/out" 2>"$T/err"
rc=$?
[ "$rc" -eq 1 ] && grep -q "bad.txt:3: material: unknown field 'shine'" "$T/err" ||
    fail "bad script line: exit $rc, $(cat "$T/err")"
"$SSS" view "$ROOT/scenes/gl_area.json" --script "$T/missing.txt" >"$T/out" 2>"$T/err"
[ $? -eq 1 ] && grep -q "missing.txt" "$T/err" || fail "missing script: $(cat "$T/err")"
"$SSS" view "$ROOT/scenes/gl_area.json" --script "$T/bad.txt" --frames 2 >"$T/out" 2>"$T/err"
[ $? -eq 2 ] || fail "--script with --frames is not a usage error"

if ! command -v xvfb-run >/dev/null 2>&1; then
    echo "skipped: xvfb-run not installed"
    [ "$fails" -eq 0 ] || exit 1
    exit 0
fi

# edit IN OUT PYTHON: the scene IN with the statement applied to the dict s, as OUT
edit() {
    "$PY" - "$1" "$2" "$3" <<'PYEOF'
import json, sys
s = json.load(open(sys.argv[1]))
exec(sys.argv[3])
json.dump(s, open(sys.argv[2], "w"))
PYEOF
}
SC=$T/scene.json
edit "$ROOT/scenes/gl_area.json" "$SC" "s['camera']['width'] = $W; s['camera']['height'] = $H"
# view LOG SCRIPT-TEXT [ARGS...]: runs the script on $SC (or $SCENE) under Xvfb in $T (in sanitizer
# builds Mesa's few leaked bytes per window do not fail the run; tests/cli/test_view.sh bounds the
# viewer's leaks)
view() {
    local log=$1 text=$2
    shift 2
    printf '%s\n' "$text" >"$log.txt"
    (cd "$T" && xvfb-run -a env LSAN_OPTIONS=exitcode=0 "$SSS" view "${SCENE:-$SC}" --script "$log.txt" "$@") \
        >"$log" 2>&1 || fail "sss view --script ($text) failed: $(head -c 400 "$log")"
}
# $T/png.py: an 8-bit PNG reader (the screenshots), and the measures the checks need:
#   columns A B X0 X1 [Y0 Y1]  the mean absolute difference (8-bit codes) of two PNGs over columns
#                              [X0, X1) (and rows [Y0, Y1))
#   bar A W                    exit 0 when the bottom row's first W pixels rise in brightness
#   size A                     width and height
#   count A X0 X1 Y0 Y1 KIND   pixels of KIND (white: all channels >= 250, black: all <= 5, magenta:
#                              red and blue >= 200, green <= 60) in columns [X0, X1), rows [Y0, Y1)
cat >"$T/png.py" <<'PYEOF'
import struct, sys, zlib
def png(path):
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    at, idat = 8, b""
    while at < len(data):
        n, kind = struct.unpack(">I4s", data[at:at + 8])
        body = data[at + 8:at + 8 + n]
        if kind == b"IHDR":
            w, h, depth, ctype = struct.unpack(">IIBB", body[:10])
            assert depth == 8 and ctype in (2, 6)
            bpp = 3 if ctype == 2 else 4
        elif kind == b"IDAT":
            idat += body
        at += 12 + n
    raw, rows, prev, stride = zlib.decompress(idat), [], bytearray(w * bpp), w * bpp
    for y in range(h):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b, c = prev[i], prev[i - bpp] if i >= bpp else 0
            if f == 1: line[i] = (line[i] + a) & 255
            elif f == 2: line[i] = (line[i] + b) & 255
            elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append([tuple(line[x * bpp:x * bpp + 3]) for x in range(w)])
        prev = line
    return rows
kinds = {"white": lambda p: min(p) >= 250, "black": lambda p: max(p) <= 5,
         "magenta": lambda p: p[0] >= 200 and p[1] <= 60 and p[2] >= 200}
if sys.argv[1] == "columns":
    a, b = png(sys.argv[2]), png(sys.argv[3])
    x0, x1 = int(sys.argv[4]), int(sys.argv[5])
    y0, y1 = (int(sys.argv[6]), int(sys.argv[7])) if len(sys.argv) > 7 else (0, len(a))
    d = [abs(p - q) for ra, rb in zip(a[y0:y1], b[y0:y1]) for pa, pb in zip(ra[x0:x1], rb[x0:x1]) for p, q in zip(pa, pb)]
    print("%.3f" % (sum(d) / max(1, len(d))))
elif sys.argv[1] == "size":
    a = png(sys.argv[2])
    print(len(a[0]), len(a))
elif sys.argv[1] == "count":
    a, (x0, x1, y0, y1), kind = png(sys.argv[2]), map(int, sys.argv[3:7]), kinds[sys.argv[7]]
    print(sum(1 for row in a[y0:y1] for p in row[x0:x1] if kind(p)))
else:
    row = png(sys.argv[2])[-1][:int(sys.argv[3])]
    steps = [sum(row[round(k * (len(row) - 1) / 4)]) for k in range(5)]
    print("bottom row brightness at 0, 1/4, ..., 1:", steps)
    sys.exit(0 if all(p < q for p, q in zip(steps, steps[1:])) else 1)
PYEOF
columns() { "$PY" "$T/png.py" columns "$@"; }
pngsize() { "$PY" "$T/png.py" size "$1"; }
count() { "$PY" "$T/png.py" count "$@"; }
below() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a != "" && a + 0 < b + 0) }'; }
near() { awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN { d = a - b; exit !(a != "" && b != "" && d < t && -d < t) }'; }
render() { "$SSS" render "$@" 2>"$T/render.err" || fail "sss render $*: $(head -c 300 "$T/render.err")"; }
dssim() { "$SSS" compare "$1" "$2" | sed -n 's/^dssim=\([0-9.e+-]*\).*/\1/p'; }

# 1. the panel docked beside the image: the window is widened by the panel's width (logged), the
#    image keeps the scene's size and is `sss render`'s image (nothing of it under the panel), the
#    panel is drawn in its own columns; hidden, the image fills the window and is `sss render` at
#    the window's size (the view recentred)
view "$T/panel.log" "frames 2
screenshot panel.png
panel off
screenshot hidden.png"
render "$SC" -o "$T/render.png"
P=$(sed -n 's/.*image [0-9]*x[0-9]*, panel \([0-9]*\) px.*/\1/p' "$T/panel.log" | head -n 1)
P=${P:-0}
WIN=$((W + P))
size=$(pngsize "$T/panel.png")
echo "panel $P px beside the ${W}x$H image: screenshot $size"
[ "$P" -ge 160 ] && [ "$size" = "$WIN $H" ] || fail "the window is not widened by the panel (panel $P px, $size)"
image=$(columns "$T/panel.png" "$T/render.png" 0 "$W")
echo "the image beside the panel vs sss render: mean |difference| $image"
below "$image" 0.5 || fail "the image beside the panel differs from sss render ($image): the panel covers it"
render "$SC" -o "$T/render_wide.png" --width "$WIN" --height "$H"
d=$(dssim "$T/hidden.png" "$T/render_wide.png")
below "$d" 0.01 || fail "hidden panel: the window differs from sss render at its size, ${WIN}x$H (DSSIM $d)"
panel=$(columns "$T/panel.png" "$T/hidden.png" $((W + 2)) "$WIN")
below 5 "$panel" || fail "the panel is not drawn in its columns (mean difference $panel)"
view "$T/noov.log" "screenshot noov.png" --no-overlay
d=$(dssim "$T/noov.png" "$T/render.png")
below "$d" 0.01 || fail "--no-overlay: the window differs from sss render (DSSIM $d)"

# 1b. sections and width (a taller window, a magenta light): `panel scroll Lights` opens the Lights
#     section and brings it into view, its colour swatch appearing in the panel's columns (none
#     there before: the section starts closed); `panel width 200` leaves the image the rest of the
#     window, rendered at that size (`sss render` of it)
TH=240
edit "$SC" "$T/tall.json" "s['camera']['height'] = $TH; s['lights'][0]['radiance'] = [6, 0, 6]"
SCENE=$T/tall.json view "$T/sections.log" "frames 1
screenshot closed.png
panel scroll Lights
screenshot lights.png
panel width 200
screenshot narrow.png"
before=$(count "$T/closed.png" "$W" "$WIN" 0 "$TH" magenta)
after=$(count "$T/lights.png" "$W" "$WIN" 0 "$TH" magenta)
echo "magenta pixels in the panel: $before with Lights closed, $after after 'panel scroll Lights'"
[ "$before" = 0 ] && [ "${after:-0}" -ge 50 ] || fail "panel scroll Lights: no colour swatch in view ($before, $after)"
grep -q "panel scroll Lights: open, header at y [0-9]* of [0-9]* (in view)" "$T/sections.log" ||
    fail "panel scroll Lights: $(grep 'panel scroll' "$T/sections.log")"
NW=$((WIN - 200))
grep -q "image ${NW}x$TH, panel 200 px" "$T/sections.log" || fail "panel width 200: $(grep 'image' "$T/sections.log")"
render "$T/tall.json" -o "$T/narrow_render.png" --width "$NW" --height "$TH"
image=$(columns "$T/narrow.png" "$T/narrow_render.png" 0 "$NW")
echo "panel width 200: the ${NW}x$TH image vs sss render: mean |difference| $image"
below "$image" 0.5 || fail "panel width 200: the image differs from sss render at ${NW}x$TH ($image)"

# 2. material edits (a preset, then its scale): the image changes and equals `sss render` of the
#    scene edited here
view "$T/mat.log" "material 0 medium Ketchup
material 0 scale 0.5
screenshot mat.png" --no-overlay
edit "$SC" "$T/mat.json" "m = s['objects'][0]['material']; m.update(medium='Ketchup', scale=0.5)"
render "$T/mat.json" -o "$T/mat_render.png"
d=$(dssim "$T/mat.png" "$T/mat_render.png")
changed=$(dssim "$T/mat.png" "$T/render.png")
echo "material Ketchup x0.5: DSSIM vs sss render of the edited scene $d, vs the unedited scene $changed"
below "$d" 0.01 || fail "material edit: differs from sss render of the edited scene (DSSIM $d)"
below 0.02 "$changed" || fail "material edit: the image did not change (DSSIM $changed)"
grep -q "rebuilt in" "$T/mat.log" || fail "material edit: no rebuild time reported"

# 2a. the window is not frozen by a material edit: with the worker held back 3 s
#     (SSS_VIEW_BUILD_DELAY_MS, a test hook), the window draws frames while the build runs (`wait`
#     counts them), a second edit made during the build replaces the one waiting (the first build is
#     dropped), and the image is the second edit's: `sss render` of it, not of the first
SSS_VIEW_BUILD_DELAY_MS=3000 view "$T/async.log" "material 0 scale 2
frames 1
material 0 scale 0.5
wait
screenshot async.png" --no-overlay
edit "$SC" "$T/half.json" "s['objects'][0]['material']['scale'] = 0.5"
edit "$SC" "$T/double.json" "s['objects'][0]['material']['scale'] = 2"
render "$T/half.json" -o "$T/half.png"
render "$T/double.json" -o "$T/double.png"
waited=$(sed -n 's/.*wait: \([0-9]*\) frames drawn.*/\1/p' "$T/async.log" | tail -n 1)
during=$(sed -n 's/.*while \([0-9]*\) frames were drawn.*/\1/p' "$T/async.log" | tail -n 1)
dropped=$(sed -n 's/.* \([0-9]*\) older edits dropped.*/\1/p' "$T/async.log" | tail -n 1)
d=$(dssim "$T/async.png" "$T/half.png")
first=$(dssim "$T/async.png" "$T/double.png")
echo "edits in the background: $waited frames drawn while waiting, $during during the last build, $dropped dropped;" \
    "DSSIM vs the second edit $d, vs the first $first"
[ -n "$waited" ] && [ "$waited" -gt 0 ] && [ -n "$during" ] && [ "$during" -gt 0 ] ||
    fail "the window drew no frames while the material was rebuilt: $(grep -E 'wait|rebuilt' "$T/async.log")"
[ "$dropped" = "1" ] || fail "the first build was not dropped for the second edit ($dropped)"
below "$d" 0.01 || fail "edit during a build: differs from sss render of the second edit (DSSIM $d)"
below 0.02 "$first" || fail "edit during a build: looks like the first edit (DSSIM $first)"
# a value the loader refuses fails in the worker: the script stops naming the edit's line, exit 1
printf 'panel off\nmaterial 0 eta 9\nframes 1\n' >"$T/bad_eta.txt"
# sss view's own exit status, written by a shell inside xvfb-run: xvfb-run itself exits 5 when it
# cannot clean up its temporary folder, a race with the X server's exit that is not the viewer's
(cd "$T" && xvfb-run -a sh -c 'LSAN_OPTIONS=exitcode=0 "$0" view "$1" --script bad_eta.txt; echo $? >bad_eta.rc' \
    "$SSS" "$SC") >"$T/bad_eta.log" 2>&1
rc=$(cat "$T/bad_eta.rc" 2>/dev/null || echo none)
[ "$rc" = 1 ] && grep -q "bad_eta.txt:2: .*eta" "$T/bad_eta.log" ||
    fail "a refused edit: exit $rc, $(tail -n 2 "$T/bad_eta.log")"

# 2b. light edits (moved in place, no rebuild): equal `sss render` of the scene edited here
view "$T/light.log" "light 0 position -0.5 1.5 0.8
light 0 intensity 3
light 0 colour 1 0.5 0.25
screenshot light.png" --no-overlay
edit "$SC" "$T/light.json" "l = s['lights'][0]; l.update(center=[-0.5, 1.5, 0.8], radiance=[3, 1.5, 0.75])"
render "$T/light.json" -o "$T/light_render.png"
d=$(dssim "$T/light.png" "$T/light_render.png")
changed=$(dssim "$T/light.png" "$T/render.png")
echo "light moved, dimmed, coloured: DSSIM vs sss render of the edited scene $d, vs the unedited scene $changed"
below "$d" 0.01 || fail "light edit: differs from sss render of the edited scene (DSSIM $d)"
below 0.02 "$changed" || fail "light edit: the image did not change (DSSIM $changed)"

# 3. a parameter set by the panel equals `sss render --param`
view "$T/param.log" "param maisch2020.brightening 0
screenshot param.png" --technique maisch2020 --no-overlay
render "$SC" -o "$T/param_render.png" --technique maisch2020 --param brightening=0
d=$(dssim "$T/param.png" "$T/param_render.png")
below "$d" 0.01 || fail "param: differs from sss render --param (DSSIM $d)"

# 3b. the buffer selector: an intermediate buffer replaces the image, and `final` brings back the
#     image `sss render` writes
view "$T/buffer.log" "buffer irradiance
screenshot buffer_irr.png
buffer final
screenshot buffer_final.png" --no-overlay
irr=$(dssim "$T/buffer_irr.png" "$T/render.png")
d=$(dssim "$T/buffer_final.png" "$T/render.png")
echo "buffer irradiance vs final: DSSIM $irr; back to final: $d"
below 0.02 "$irr" || fail "buffer irradiance: the image did not change (DSSIM $irr)"
below "$d" 0.01 || fail "buffer final: differs from sss render (DSSIM $d)"

# 4. split between two techniques, the panel beside it: left of one, right of the other (below the
#    labels' rows, 2 columns around the cut left out); the divider's white core on the 2 columns at
#    the cut, edged in black, the whole height; each side's name in white in its top corner (the
#    renders hold no white there)
view "$T/split.log" "technique maisch2020
split ssss
screenshot split.png"
render "$SC" -o "$T/left.png" --technique maisch2020
render "$SC" -o "$T/right.png" --technique ssss
LABELS=28
L=$(columns "$T/split.png" "$T/left.png" 0 $((W / 2 - 2)) "$LABELS" "$H")
R=$(columns "$T/split.png" "$T/right.png" $((W / 2 + 2)) "$W" "$LABELS" "$H")
LR=$(columns "$T/left.png" "$T/right.png" 0 "$W")
echo "split maisch2020 | ssss: left half vs maisch2020 $L, right half vs ssss $R (the two differ by $LR)"
below "$L" 0.5 && below "$R" 0.5 || fail "split view: halves differ from their techniques ($L, $R)"
below 0.5 "$LR" || fail "split view: the two techniques look alike here ($LR): the test checks nothing"
core=$(count "$T/split.png" $((W / 2 - 1)) $((W / 2 + 1)) 0 "$H" white)
edges=$(($(count "$T/split.png" $((W / 2 - 2)) $((W / 2 - 1)) 0 "$H" black) +
    $(count "$T/split.png" $((W / 2 + 1)) $((W / 2 + 2)) 0 "$H" black)))
echo "divider: $core white pixels in its core (of $((2 * H))), $edges black on its edges (of $((2 * H)))"
[ "$core" = $((2 * H)) ] && [ "$edges" = $((2 * H)) ] || fail "split view: no divider at the cut ($core, $edges)"
lw=$(count "$T/split.png" 0 $((W / 2 - 2)) 0 "$LABELS" white)
rw=$(count "$T/split.png" $((W / 2 + 2)) "$W" 0 "$LABELS" white)
l0=$(count "$T/left.png" 0 $((W / 2 - 2)) 0 "$LABELS" white)
r0=$(count "$T/right.png" $((W / 2 + 2)) "$W" 0 "$LABELS" white)
echo "labels: $lw white pixels top left, $rw top right (the renders: $l0, $r0)"
[ "$lw" -ge 20 ] && [ "$rw" -ge 20 ] && [ "$l0" = 0 ] && [ "$r0" = 0 ] || fail "split view: labels missing ($lw, $rw)"

# 5. split against the reference and the error map (64x64, the CPU reference at final quality), its
#    colour bar over the range the script set, with tick marks over the black rule at both ends
edit "$SC" "$T/small.json" "s['camera']['width'] = 64; s['camera']['height'] = 64"
SC=$T/small.json
view "$T/ref.log" "split reference
screenshot ref_split.png
split off
errormap on 0.1
screenshot errormap.png" --no-overlay
render "$SC" -o "$T/small.png"
"$SSS" reference "$SC" -o "$T/small_ref.png" --quiet || fail "sss reference failed"
L=$(columns "$T/ref_split.png" "$T/small.png" 0 30)
R=$(columns "$T/ref_split.png" "$T/small_ref.png" 34 64)
echo "split reference: left vs sss render $L, right vs sss reference $R"
below "$L" 0.5 && below "$R" 0.5 || fail "split reference: halves differ ($L, $R)"
# the error map is of this frame against this reference: its DSSIM is what sss compare says
got=$(sed -n 's/.*error map: DSSIM \([0-9.]*\), colour bar.*/\1/p' "$T/ref.log" | tail -n 1)
want=$(dssim "$T/small.png" "$T/small_ref.png")
echo "error map: DSSIM $got, sss compare $want"
# equal up to the run-to-run noise of maisch2020's additive splat blending (order varies: ~1e-6 DSSIM)
near "$got" "$want" 2e-5 || fail "error map: DSSIM $got, sss compare says $want"
grep -q "error map: DSSIM [0-9.]*, colour bar from 0 (left) to 0.1 (right)" "$T/ref.log" ||
    fail "error map: not over the range set (0.1): $(grep 'error map' "$T/ref.log")"
# the colour bar: its bottom row runs from dark (left) to bright (right); the rule above it is black
# but for the ticks at its two ends (64 pixels hold no more labels side by side)
"$PY" "$T/png.py" bar "$T/errormap.png" 64 || fail "error map: no colour bar along the bottom"
RULE=$((64 - 9))
ticks="$(count "$T/errormap.png" 0 1 "$RULE" $((RULE + 1)) white) $(count "$T/errormap.png" 63 64 "$RULE" $((RULE + 1)) white)"
black=$(count "$T/errormap.png" 1 63 "$RULE" $((RULE + 1)) black)
echo "colour bar rule: ticks at its ends $ticks, black between: $black of 62"
[ "$ticks" = "1 1" ] && [ "$black" = 62 ] || fail "error map: no ticks on the colour bar ($ticks, $black)"
[ "$fails" -eq 0 ] || exit 1
echo "all view panel tests passed"
