#!/usr/bin/env bash
# How sss opens inputs and writes outputs (issue 12): a FIFO anywhere fails at once as "not a regular
# file"; a symlink planted at a temporary or output name is never followed; a command with several
# outputs leaves all of them or none (and no temporary file); an output that is the same file as an
# input (any spelling, a hard link) is refused before the work; a PNG's size is checked against the
# pixel budget from its header (and `compare` compares sizes before decoding); PNG chunk CRCs are
# verified; a texture render refuses (empty, corrupt) is refused by reference and export too.
# Usage: bash test_file_safety.sh <sss-binary> <repo-root>
set -u
SSS=$1
ROOT=$2
DATA=$ROOT/tests/data
. "$(dirname "${BASH_SOURCE[0]}")/harness.sh"
# expect CODE PATTERN -- ARGS: exit status CODE within 10 s (a hang is a failure), stderr matching
# PATTERN (extended regex, case-insensitive).
expect() {
    local code=$1 pattern=$2
    shift 3
    timeout 10 "$SSS" "$@" >"$T/out.txt" 2>"$T/err.txt"
    local got=$?
    [ "$got" -eq "$code" ] || fail "sss $* exited $got, expected $code ($(head -c 300 "$T/err.txt"))"
    [ -z "$pattern" ] || grep -Eqi -e "$pattern" "$T/err.txt" || fail "sss $* stderr lacks /$pattern/: $(head -c 300 "$T/err.txt")"
}
# empty DIR WHAT: DIR holds nothing at all (no output, no temporary file)
empty() { [ -z "$(ls -A "$1")" ] || fail "$2 left: $(ls -A "$1")"; }

# A small scene with a textured subsurface plane; $1 = texture file, $2 = mesh field (or none).
scene() {
    local mesh=${2:+"{\"mesh\": \"$2\", \"material\": {\"type\": \"diffuse\", \"reflectance\": [0.5, 0.5, 0.5]}},"}
    cat <<EOF
{"camera": {"position": [0, 0.5, 3], "look_at": [0, 0, 0], "width": 32, "height": 24},
 "objects": [$mesh
  {"procedural": {"shape": "plane", "size": 4},
   "material": {"type": "subsurface", "medium": "Marble", "scale": 10, "texture": "$1"}}],
 "lights": [{"type": "point", "position": [0, 2, 2], "intensity": [1, 1, 1]}]}
EOF
}
I=$T/in
mkdir -p "$I"
cp "$DATA/images/base.png" "$I/a.png"
cp "$DATA/images/blur.png" "$I/b.png"
cp "$DATA/meshes/box_ascii.ply" "$I/m.ply"
scene a.png >"$I/s.json"

# ---- FIFOs: refused at once wherever an input is named (the open does not wait for a writer)
F=$T/fifo
mkdir -p "$F/o"
mkfifo "$F/p.json" "$F/p.ply" "$F/p.sam" "$F/p.png"
cp "$I/a.png" "$F/a.png"
scene a.png p.ply >"$F/mesh_in_scene.json"
scene p.png >"$F/texture_fifo.json"
expect 1 "p\.json: not a regular file" -- render "$F/p.json" -o "$F/o/x.png"
expect 1 "p\.json: not a regular file" -- reference "$F/p.json" -o "$F/o/x.png"
expect 1 "p\.ply: not a regular file" -- mesh info "$F/p.ply"
expect 1 "objects\[0\]\.mesh: p\.ply: not a regular file" -- export pbrt "$F/mesh_in_scene.json" -o "$F/o/x.pbrt"
expect 1 "texture: p\.png: not a regular file" -- reference "$F/texture_fifo.json" -o "$F/o/x.png"
expect 1 "p\.sam: not a regular file" -- sam info "$F/p.sam"
expect 1 "p\.sam: not a regular file" -- render "$ROOT/scenes/gl_area.json" --technique sam --data "$F/p.sam" \
    -o "$F/o/x.png" --width 8 --height 8
expect 1 "p\.png: not a regular file" -- compare "$F/p.png" "$I/a.png"
expect 1 "p\.png: not a regular file" -- compare "$I/a.png" "$F/p.png"
empty "$F/o" "FIFO inputs"

# ---- Symlinks: one planted at the temporary name the old writer used (.NAME.tmp-PID; the shell's
# pid becomes sss's through exec) and one at the output itself. Neither target may change, and the
# output must end up a regular file.
L=$T/link
mkdir -p "$L"
planted() { # planted NAME -- ARGS: runs sss ARGS with symlinks at L/.NAME.tmp-PID and at L/NAME
    local name=$1
    shift 2
    echo victim >"$L/victim_tmp"
    echo victim >"$L/victim_out"
    rm -f "$L/$name"
    ln -s "$L/victim_out" "$L/$name"
    bash -c 'ln -s "$1" "$2.tmp-$$"; shift 2; exec "$@"' _ "$L/victim_tmp" "$L/.$name" "$SSS" "$@" \
        >/dev/null 2>"$T/err.txt" || fail "sss $* failed: $(head -c 300 "$T/err.txt")"
    echo victim | cmp -s - "$L/victim_tmp" || fail "sss $* wrote through the symlink at the temporary name"
    echo victim | cmp -s - "$L/victim_out" || fail "sss $* wrote through the symlink at the output"
    [ -f "$L/$name" ] && [ ! -L "$L/$name" ] || fail "sss $*: $name is not a regular file"
    rm -f "$L"/.*.tmp-*
}
planted map.png -- compare "$I/a.png" "$I/b.png" --map "$L/map.png"
planted copy.ply -- mesh convert "$I/m.ply" -o "$L/copy.ply"
planted lut.exr -- lut Marble --size 8 -o "$L/lut.exr"

# ---- All outputs or none: the second output fails (a folder in its place, or a frame's name)
P=$T/partial
mkdir -p "$P"
partial() { # partial WHAT -- ARGS: exits 1 and leaves P holding only the folders it had
    local what=$1
    shift 2
    timeout 120 "$SSS" "$@" >/dev/null 2>"$T/err.txt"
    [ $? -eq 1 ] || fail "$what: exit status $? ($(head -c 300 "$T/err.txt"))"
    local left
    left=$(find "$P" -mindepth 1 -not -type d)
    [ -z "$left" ] || fail "$what left: $left"
}
mkdir -p "$P/dir.exr" "$P/dir.json" "$P/f_0002.png"
partial "render -o + --exr FOLDER" -- render "$ROOT/scenes/gl_area.json" -o "$P/o.png" --exr "$P/dir.exr" \
    --width 16 --height 16
partial "render -o + --timings-json FOLDER" -- render "$ROOT/scenes/gl_area.json" -o "$P/o.png" \
    --timings-json "$P/dir.json" --width 16 --height 16
partial "reference -o + --exr FOLDER" -- reference "$I/s.json" -o "$P/o.png" --exr "$P/dir.exr" --quality draft \
    --spp 1 -q
partial "render --animate, frame 2 unwritable" -- render "$ROOT/scenes/gl_twist.json" -o "$P/f.png" --frames 3 \
    --animate --width 16 --height 16
partial "render --animate, --exr frames unwritable" -- render "$ROOT/scenes/gl_twist.json" -o "$P/g.png" \
    --exr "$P/missing/g.exr" --frames 2 --animate --width 16 --height 16
mkdir -p "$P/ev/report.html"  # eval's last output cannot be written: none of its outputs may stay
partial "eval, report.html a folder" -- eval "$I/s.json" --techniques local --frames 1 --warmup 0 \
    --reference-quality draft --out "$P/ev" --quiet

# ---- An output that is an input's file: refused before the work, the input unchanged
S=$T/same
mkdir -p "$S"
cp "$I"/* "$S/"
ln "$S/m.ply" "$S/hard.ply"
ln "$S/m.ply" "$S/hard.sam"  # a name sam build accepts for its output, the input's inode
sums() { (cd "$S" && cksum a.png b.png m.ply s.json); }
before=$(sums)
expect 1 "a\.png: is the same file as the input" -- compare "$S/a.png" "$S/b.png" --map "$S/a.png"
expect 1 "same file as the input" -- compare "$S/a.png" "$S/b.png" --map "$S/./b.png"
expect 1 "hard\.sam: is the same file as the input" -- sam build "$S/m.ply" --medium Marble -o "$S/hard.sam"
expect 1 "same file as the input" -- mesh convert "$S/m.ply" -o "$S/hard.ply"
expect 1 "a\.png: is the same file as the input" -- reference "$S/s.json" -o "$S/a.png" --quality draft --spp 1 -q
expect 1 "s\.json: is the same file as the input" -- render "$S/s.json" -o "$S/out.png" --timings-json "$S/s.json" \
    --width 8 --height 8
expect 1 "same file as the input" -- render "$S/s.json" -o "$S/a.png" --width 8 --height 8
expect 1 "same file as the input" -- export pbrt "$S/s.json" -o "$S/s.json"
[ "$(sums)" = "$before" ] || fail "an input changed"
[ "$(ls -A "$S" | wc -l)" -eq 6 ] || fail "refused commands left files: $(ls -A "$S")"

# ---- PNG decompression bomb: a valid all-black 16384^2 PNG (260 kB, 268 M pixels) is refused from
# its header, within 400 MB of address space; compare checks both sizes before decoding either (an
# 8192^2 PNG would need about 1 GB decoded).
B=$T/bomb
mkdir -p "$B"
gzip -dc "$DATA/bad/png_bomb_16384.png.gz" >"$B/bomb.png"
gzip -dc "$DATA/bad/png_black_8192.png.gz" >"$B/black.png"
bounded() { # runs sss ARGS within 400 MB of address space (unbounded for a sanitizer build, which
    # reserves terabytes of shadow memory up front)
    (ulimit -v 400000 && exec "$SSS" "$@") >/dev/null 2>"$T/err.txt"
    local got=$?
    grep -q ReserveShadowMemoryRange "$T/err.txt" || return $got
    "$SSS" "$@" >/dev/null 2>"$T/err.txt"
}
bounded compare "$B/bomb.png" "$B/bomb.png"
[ $? -eq 1 ] && grep -Eq "bomb\.png: .*16384x16384.*limit" "$T/err.txt" || fail "bomb: $(head -c 300 "$T/err.txt")"
bounded compare "$B/black.png" "$I/a.png"
[ $? -eq 1 ] && grep -Eq "sizes differ.*8192x8192" "$T/err.txt" || fail "8192^2 vs 64x48: $(head -c 300 "$T/err.txt")"

# ---- PNG CRCs: one bit flipped in the stored CRC of IHDR, then of the first IDAT
C=$T/crc
mkdir -p "$C/o"
flip() { # flip FILE OFFSET: inverts the lowest bit of the byte at OFFSET
    local b
    b=$(od -An -tu1 -j "$2" -N1 "$1" | tr -d ' ')
    printf "$(printf '\\%03o' $((b ^ 1)))" | dd of="$1" bs=1 seek="$2" conv=notrunc 2>/dev/null
}
cp "$I/a.png" "$C/ihdr.png"
flip "$C/ihdr.png" 29 # signature 8 + length and type 8 + IHDR data 13
idat=$(grep -obUa IDAT "$I/a.png" | head -1 | cut -d: -f1)
len=$(od -An -tu1 -j $((idat - 4)) -N4 "$I/a.png" | awk '{print $1 * 16777216 + $2 * 65536 + $3 * 256 + $4}')
cp "$I/a.png" "$C/idat.png"
flip "$C/idat.png" $((idat + 4 + len))
expect 1 "ihdr\.png: corrupt: chunk IHDR fails its CRC" -- compare "$C/ihdr.png" "$I/a.png"
expect 1 "idat\.png: corrupt: chunk IDAT fails its CRC" -- compare "$I/a.png" "$C/idat.png"
expect 1 "idat\.png: corrupt: chunk IDAT" -- compare "$C/idat.png" "$C/idat.png" --map "$C/o/m.png"
empty "$C/o" "bad CRC"

# ---- Textures: one that render refuses (empty, not an image) is refused by reference and export
X=$T/tex
mkdir -p "$X/o"
: >"$X/empty.png"
echo "not a png" >"$X/junk.png"
scene empty.png >"$X/empty.json"
scene junk.png >"$X/junk.json"
for s in empty junk; do
    expect 1 "texture: .*$s\.png" -- render "$X/$s.json" -o "$X/o/x.png" --width 8 --height 8
    expect 1 "texture: .*$s\.png" -- reference "$X/$s.json" -o "$X/o/x.png" -q
    expect 1 "texture: .*$s\.png" -- export pbrt "$X/$s.json" -o "$X/o/x.pbrt"
done
empty "$X/o" "refused textures"

if [ "$fails" -ne 0 ]; then
    echo "$fails failure(s)"
    exit 1
fi
echo "all file safety checks passed"
