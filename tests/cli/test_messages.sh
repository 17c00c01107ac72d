#!/usr/bin/env bash
# Messages on stderr: control characters from data (scene strings, file names, arguments) are printed
# escaped (\x1b), never raw, so a scene cannot drive the terminal; a message with a very long path
# keeps its cause (the path loses its middle, within the 511-character message limit).
# Usage: bash test_messages.sh <sss-binary> <repo-root>
SSS=$1; ROOT=$2
fail=0
err() { echo "FAIL: $*"; fail=1; }
dir=$(mktemp -d); trap 'rm -rf "$dir"' EXIT
BOX=$ROOT/tests/data/meshes/box_ascii.ply

# no_raw_controls NAME FILE: no C0 control byte but the newlines ending lines, no DEL
no_raw_controls() {
    if LC_ALL=C grep -q $'[\x01-\x09\x0b-\x1f\x7f]' "$2"; then err "$1: raw control characters on stderr: $(cat -v "$2" | head -c 300)"; fi
}

# A scene string with a terminal escape (clear screen, set the window title, bell).
printf '{"camera": {"position": [0, 0.5, 3], "look_at": [0, 0, 0], "width": 8, "height": 8},
 "objects": [{"mesh": "%s", "material": {"type": "subsurface", "medium": "\\u001b[2J\\u001b]0;pwned\\u0007", "scale": 10}}]}' \
    "$BOX" >"$dir/esc.json"
"$SSS" export pbrt "$dir/esc.json" -o "$dir/o.pbrt" >/dev/null 2>"$dir/e1"; code=$?
[ $code = 1 ] || err "scene string: exit $code"
no_raw_controls "scene string" "$dir/e1"
grep -q 'objects\[0\]\.material\.medium: unknown medium "\\x1b\[2J\\x1b\]0;pwned\\x07"' "$dir/e1" ||
    err "scene string: the medium is not shown escaped: $(cat -v "$dir/e1")"

# A file name and arguments with escapes (library errors, usage errors, unknown commands).
"$SSS" mesh info "$dir/"$'\e[31mred\r.ply' >/dev/null 2>"$dir/e2"; [ $? = 1 ] || err "file name: exit not 1"
no_raw_controls "file name" "$dir/e2"
grep -q '\\x1b\[31mred\\r\.ply: ' "$dir/e2" || err "file name not shown escaped: $(cat -v "$dir/e2")"
"$SSS" render $'--\e[5mblink' >/dev/null 2>"$dir/e3"; [ $? = 2 ] || err "unknown option: exit not 2"
no_raw_controls "unknown option" "$dir/e3"
"$SSS" $'\e[5mblink' >/dev/null 2>"$dir/e4"; [ $? = 2 ] || err "unknown command: exit not 2"
no_raw_controls "unknown command" "$dir/e4"

# A 5000-character output path: the message fits the limit and still ends with its cause.
long="$dir/$(printf 'd%.0s' $(seq 4990))/x.ply"
"$SSS" mesh convert "$BOX" -o "$long" >/dev/null 2>"$dir/e5"; [ $? = 1 ] || err "long path: exit not 1"
line=$(head -n 1 "$dir/e5")
[ ${#line} -le $((511 + 11)) ] || err "long path: message of ${#line} characters"
case "$line" in
"sss mesh: $dir/ddd"*"...ddd"*"/x.ply: path too long") ;;
*) err "long path: the message lost its cause or the path's ends: ${line:0:80}...${line: -80}" ;;
esac

# A NaN pixel in an environment map: every command that reads the map names the scene, the light and
# the file (the real-time renderer used to turn it into black silently).
python3 - "$dir/nan.pfm" <<'PY'
import struct, sys
w, h = 8, 4
px = [1.0] * (w * h * 3)
px[3 * (3 * w + 1) + 2] = float("nan")  # pixel (1, 3), blue; PFM rows run bottom to top
open(sys.argv[1], "wb").write(b"PF\n%d %d\n-1.0\n" % (w, h) + struct.pack("<%df" % len(px), *px))
PY
printf '{"camera": {"position": [0, 0.5, 3], "look_at": [0, 0, 0], "width": 8, "height": 8},
 "objects": [{"mesh": "%s", "material": {"type": "subsurface", "medium": "Marble", "scale": 10}}],
 "lights": [{"type": "environment", "file": "nan.pfm"}]}' "$BOX" >"$dir/nanenv.json"
"$SSS" render "$dir/nanenv.json" -o "$dir/o_render.png" >/dev/null 2>"$dir/e7"; code=$?
[ $code = 1 ] || err "NaN map, render: exit $code"
"$SSS" reference "$dir/nanenv.json" -o "$dir/o_ref.png" --quiet >/dev/null 2>"$dir/e8"; code=$?
[ $code = 1 ] || err "NaN map, reference: exit $code"
for e in e7 e8; do
    grep -q "nanenv\.json: lights\[0\]\.file: .*nan\.pfm: pixel (1, [03]) is nan" "$dir/$e" ||
        err "NaN map: message does not name scene, light, file and pixel: $(cat "$dir/$e")"
done
[ ! -e "$dir/o_render.png" ] && [ ! -e "$dir/o_ref.png" ] || err "NaN map: an image was written"

# A transform scale of 1e18 on the box (bounds 0..1, 0..2, 0..3): world positions up to 3e18, beyond the
# single-precision range of the real-time renderer: refused at load, naming the object's transform,
# by every command (it used to end in "technique maisch2020 produced NaN/Inf values").
sed 's/"scale": 10}}\]/"scale": 10}, "transform": {"scale": 1e18}}]/' "$dir/nanenv.json" |
    sed 's/"environment", "file": "nan.pfm"/"point", "position": [0, 2, 2], "intensity": [1, 1, 1]/' >"$dir/huge.json"
for args in "export pbrt $dir/huge.json -o $dir/h.pbrt" "render $dir/huge.json -o $dir/h.png" \
    "reference $dir/huge.json -o $dir/h.exr --quiet"; do
    "$SSS" $args >/dev/null 2>"$dir/e9"; code=$?
    [ $code = 1 ] || err "scale 1e18 ($args): exit $code"
    grep -q "huge\.json: objects\[0\]\.transform: world-space positions reach 3e+18, beyond 1e+18" "$dir/e9" ||
        err "scale 1e18 ($args): $(cat "$dir/e9")"
done
exit $fail
