#!/usr/bin/env bash
# `sss view --script`: the panel's actions from a file, under Xvfb. Screenshots after scripted actions
# are checked for properties, each against an image made independently: the panel is drawn where it
# is (pixels differ there and nowhere else) and absent when hidden; with the panel hidden the window
# equals `sss render`; a material edit changes the image and equals `sss render` of the scene edited
# here, and so does a light edit; a parameter set in the panel equals `sss render --param`; a split
# view holds the left half of one technique and the right half of the other (or of `sss reference`);
# the error map is of the frame against the reference (its DSSIM is `sss compare`'s) and holds the
# colour bar. Errors: a bad script line (exit 1, file and line named, before any window), --script
# with --frames (exit 2).
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
# view LOG SCRIPT-TEXT [ARGS...]: runs the script under Xvfb in $T (in sanitizer builds Mesa's few
# leaked bytes per window do not fail the run; tests/cli/test_view.sh bounds the viewer's leaks)
view() {
    local log=$1 text=$2
    shift 2
    printf '%s\n' "$text" >"$log.txt"
    (cd "$T" && xvfb-run -a env LSAN_OPTIONS=exitcode=0 "$SSS" view "$SC" --script "$log.txt" "$@") >"$log" 2>&1 ||
        fail "sss view --script ($text) failed: $(head -c 400 "$log")"
}
# $T/png.py: an 8-bit PNG reader (the screenshots), and the two measures the checks need:
#   columns A B X0 X1  the mean absolute difference (8-bit codes) of two PNGs over columns [X0, X1)
#   bar A              exit 0 when the bottom row rises in brightness from left to right
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
if sys.argv[1] == "columns":
    a, b = png(sys.argv[2]), png(sys.argv[3])
    x0, x1 = int(sys.argv[4]), int(sys.argv[5])
    d = [abs(p - q) for ra, rb in zip(a, b) for pa, pb in zip(ra[x0:x1], rb[x0:x1]) for p, q in zip(pa, pb)]
    print("%.3f" % (sum(d) / max(1, len(d))))
else:
    row = png(sys.argv[2])[-1]
    steps = [sum(row[round(k * (len(row) - 1) / 4)]) for k in range(5)]
    print("bottom row brightness at 0, 1/4, ..., 1:", steps)
    sys.exit(0 if all(p < q for p, q in zip(steps, steps[1:])) else 1)
PYEOF
columns() { "$PY" "$T/png.py" columns "$@"; }
below() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a != "" && a + 0 < b + 0) }'; }
near() { awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN { d = a - b; exit !(a != "" && b != "" && d < t && -d < t) }'; }
render() { "$SSS" render "$@" 2>"$T/render.err" || fail "sss render $*: $(head -c 300 "$T/render.err")"; }
dssim() { "$SSS" compare "$1" "$2" | sed -n 's/^dssim=\([0-9.e+-]*\).*/\1/p'; }

# 1. the panel where it is drawn (the left 40% of the window at most), nothing of it elsewhere or
#    when hidden; the hidden-panel window is the image `sss render` writes
view "$T/panel.log" "frames 2
screenshot panel.png
panel off
screenshot hidden.png"
render "$SC" -o "$T/render.png"
PANEL_W=$((W * 2 / 5))
inside=$(columns "$T/panel.png" "$T/hidden.png" 0 "$PANEL_W")
outside=$(columns "$T/panel.png" "$T/hidden.png" $((PANEL_W + 2)) "$W")
echo "panel shown vs hidden: mean |difference| $inside inside the panel, $outside outside"
below 5 "$inside" || fail "the panel is not drawn (mean difference $inside in its columns)"
below "$outside" 0.5 || fail "the panel changes pixels outside its columns ($outside)"
d=$(dssim "$T/hidden.png" "$T/render.png")
below "$d" 0.01 || fail "hidden panel: the window differs from sss render (DSSIM $d)"
view "$T/noov.log" "screenshot noov.png" --no-overlay
d=$(dssim "$T/noov.png" "$T/render.png")
below "$d" 0.01 || fail "--no-overlay: the window differs from sss render (DSSIM $d)"

# 2. material edits (a preset, then its scale): the image changes and equals `sss render` of the
#    scene edited here
view "$T/mat.log" "panel off
material 0 medium Ketchup
material 0 scale 0.5
screenshot mat.png"
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
SSS_VIEW_BUILD_DELAY_MS=3000 view "$T/async.log" "panel off
material 0 scale 2
frames 1
material 0 scale 0.5
wait
screenshot async.png"
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
(cd "$T" && xvfb-run -a env LSAN_OPTIONS=exitcode=0 "$SSS" view "$SC" --script bad_eta.txt) >"$T/bad_eta.log" 2>&1
rc=$?
[ "$rc" -eq 1 ] && grep -q "bad_eta.txt:2: .*eta" "$T/bad_eta.log" ||
    fail "a refused edit: exit $rc, $(tail -n 2 "$T/bad_eta.log")"

# 2b. light edits (moved in place, no rebuild): equal `sss render` of the scene edited here
view "$T/light.log" "panel off
light 0 position -0.5 1.5 0.8
light 0 intensity 3
light 0 colour 1 0.5 0.25
screenshot light.png"
edit "$SC" "$T/light.json" "l = s['lights'][0]; l.update(center=[-0.5, 1.5, 0.8], radiance=[3, 1.5, 0.75])"
render "$T/light.json" -o "$T/light_render.png"
d=$(dssim "$T/light.png" "$T/light_render.png")
changed=$(dssim "$T/light.png" "$T/render.png")
echo "light moved, dimmed, coloured: DSSIM vs sss render of the edited scene $d, vs the unedited scene $changed"
below "$d" 0.01 || fail "light edit: differs from sss render of the edited scene (DSSIM $d)"
below 0.02 "$changed" || fail "light edit: the image did not change (DSSIM $changed)"

# 3. a parameter set by the panel equals `sss render --param`
view "$T/param.log" "panel off
param maisch2020.brightening 0
screenshot param.png" --technique maisch2020
render "$SC" -o "$T/param_render.png" --technique maisch2020 --param brightening=0
d=$(dssim "$T/param.png" "$T/param_render.png")
below "$d" 0.01 || fail "param: differs from sss render --param (DSSIM $d)"

# 3b. the buffer selector: an intermediate buffer replaces the image, and `final` brings back the
#     image `sss render` writes
view "$T/buffer.log" "panel off
buffer irradiance
screenshot buffer_irr.png
buffer final
screenshot buffer_final.png"
irr=$(dssim "$T/buffer_irr.png" "$T/render.png")
d=$(dssim "$T/buffer_final.png" "$T/render.png")
echo "buffer irradiance vs final: DSSIM $irr; back to final: $d"
below 0.02 "$irr" || fail "buffer irradiance: the image did not change (DSSIM $irr)"
below "$d" 0.01 || fail "buffer final: differs from sss render (DSSIM $d)"

# 4. split between two techniques: left of one, right of the other (2 columns around the cut left out)
view "$T/split.log" "panel off
technique maisch2020
split ssss
screenshot split.png"
render "$SC" -o "$T/left.png" --technique maisch2020
render "$SC" -o "$T/right.png" --technique ssss
L=$(columns "$T/split.png" "$T/left.png" 0 $((W / 2 - 2)))
R=$(columns "$T/split.png" "$T/right.png" $((W / 2 + 2)) "$W")
LR=$(columns "$T/left.png" "$T/right.png" 0 "$W")
echo "split maisch2020 | ssss: left half vs maisch2020 $L, right half vs ssss $R (the two differ by $LR)"
below "$L" 0.5 && below "$R" 0.5 || fail "split view: halves differ from their techniques ($L, $R)"
below 0.5 "$LR" || fail "split view: the two techniques look alike here ($LR): the test checks nothing"

# 5. split against the reference and the error map (64x64, the CPU reference at final quality)
edit "$SC" "$T/small.json" "s['camera']['width'] = 64; s['camera']['height'] = 64"
SC=$T/small.json
view "$T/ref.log" "panel off
split reference
screenshot ref_split.png
split off
errormap on
screenshot errormap.png"
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
# the colour bar: its bottom row runs from dark (left) to bright (right)
"$PY" "$T/png.py" bar "$T/errormap.png" || fail "error map: no colour bar along the bottom"
[ "$fails" -eq 0 ] || exit 1
echo "all view panel tests passed"
