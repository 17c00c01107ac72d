#!/usr/bin/env bash
# Values that used to fall back to a default or to be written wrongly are refused: sentinels given on
# the command line (kernel --range 0 / -1, --taps 0, --extent 0, sam build --object -1, --threads 0),
# frame patterns that put every frame in one file or overflow the width, outputs whose extension
# names another format (PLY bytes in a .obj, a map in a .ply), and a .sam whose eta is NaN behind a
# repaired checksum (docs/sam_format.md: every float is checked).
# Usage: bash test_invalid_values.sh <sss-binary> <repo-root>
SSS=$1; ROOT=$2
fail=0
err() { echo "FAIL: $*"; fail=1; }
dir=$(mktemp -d); trap 'rm -rf "$dir"' EXIT
BOX=$ROOT/tests/data/meshes/box_ascii.ply
SCENE=$ROOT/tests/data/bad/scene_valid.json

# expect CODE PATTERN ARGS...: exit status CODE, stderr matching PATTERN, nothing left in $dir/out.
expect() {
    local want=$1 pattern=$2
    shift 2
    rm -rf "$dir/out"; mkdir "$dir/out"
    "$SSS" "$@" >/dev/null 2>"$dir/stderr"; local code=$?
    [ $code = "$want" ] || err "sss $*: exit $code, expected $want ($(head -c 200 "$dir/stderr"))"
    grep -Eq -- "$pattern" "$dir/stderr" || err "sss $*: message '$(head -c 200 "$dir/stderr")' lacks '$pattern'"
    [ -z "$(ls -A "$dir/out")" ] || err "sss $*: left $(ls -A "$dir/out")"
}

expect 2 "--range must be a number > 0, got '-1'" kernel Skin1 --range -1
expect 2 "--range must be a number > 0, got '0'" kernel Skin1 --range 0
expect 2 "--taps must be in 1\.\." kernel Skin1 --taps 0
expect 2 "--taps must be in 1\.\." kernel --artist production --taps 0
expect 2 "--extent must be a number > 0" kernel Skin1 --method svd --extent 0
"$SSS" kernel Skin1 --range 2 --taps 5 >/dev/null || err "kernel --range 2 --taps 5 refused"

expect 2 "--object must be in 0\.\." sam build "$SCENE" --object -1 -o "$dir/out/x.sam"
expect 2 "--object must be in 0\.\." sam info "$dir/none.sam" --object -1
expect 2 "--threads must be in 1\.\." sam build "$BOX" --medium Marble --threads 0 -o "$dir/out/x.sam"
expect 2 "x\.ply.*must end in \.sam" sam build "$BOX" --medium Marble -o "$dir/out/x.ply"
expect 2 "x\.obj.*must end in \.ply" mesh convert "$BOX" -o "$dir/out/x.obj"
expect 2 "y\.obj.*must end in \.ply" mesh simplify "$BOX" --triangles 4 -o "$dir/out/y.obj"

expect 2 "exactly one %d" render "$SCENE" --frames 2 --animate -o "$dir/out/f%%.png"
expect 2 "exactly one %d" render "$SCENE" --frames 2 --animate -o "$dir/out/f_%2147483648d.png"
expect 2 "exactly one %d" render "$SCENE" --frames 2 --animate -o "$dir/out/f_%33d.png"
expect 2 "exactly one %d" render "$SCENE" --frames 2 --animate -o "$dir/out/f_%d_%d.png"
expect 2 "--exr holds a %d pattern" render "$SCENE" -o "$dir/out/a.png" --exr "$dir/out/f_%d.exr"

# A .sam with eta = NaN and the checksum (FNV-1a 64 of every byte before it) recomputed.
"$SSS" sam build "$BOX" --medium Marble -n 1 --samples 1 -o "$dir/box.sam" >/dev/null || err "sam build failed"
python3 - "$dir/box.sam" "$dir/nan_eta.sam" <<'PY' || err "could not write nan_eta.sam"
import struct, sys
data = bytearray(open(sys.argv[1], "rb").read())
data[112:120] = struct.pack("<d", float("nan"))  # eta, docs/sam_format.md
h = 0xcbf29ce484222325
for b in data[:-8]:
    h = ((h ^ b) * 0x100000001b3) & 0xffffffffffffffff
data[-8:] = struct.pack("<Q", h)
open(sys.argv[2], "wb").write(data)
PY
"$SSS" sam info "$dir/box.sam" >/dev/null || err "the unmodified map is refused"
expect 1 "nan_eta\.sam: header: eta nan" sam info "$dir/nan_eta.sam"
exit $fail
