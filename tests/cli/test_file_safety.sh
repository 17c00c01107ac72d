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

# ---- Two outputs of one command that are one file: refused before the work (a transaction renames
# both, and the last one wins: `-o o.png --timings-json o.png` used to leave the JSON and no image)
O=$T/twice
mkdir -p "$O"
expect 1 "o\.png: is the same file as the output" -- render "$I/s.json" -o "$O/o.png" --timings-json "$O/./o.png" \
    --width 8 --height 8
expect 1 "r\.exr: is the same file as the output" -- reference "$I/s.json" -o "$O/r.exr" --exr "$O/../twice/r.exr" \
    --quality draft --spp 1 -q
empty "$O" "two outputs in one file"

# ---- import and export pbrt write side files (<stem>_objN.ply, <stem>_imgK.png): none of them, nor
# the scene, may be a file the asset or scene is made of. Every spelling of the buffer, a symlink and a
# hard link to it, a mesh or image side file named like a buffer, and a scene mesh named like an
# export's side file are refused before anything is written; the inputs stay as they were.
G=$T/gltf
mkdir -p "$G"
cp "$ROOT/tests/data/gltf/external.gltf" "$ROOT/tests/data/gltf/external data.bin" "$G/"
ln -s "external data.bin" "$G/link.json"
ln "$G/external data.bin" "$G/hard.json"
sed 's/external%20data\.bin/s_obj0.ply/' "$G/external.gltf" >"$G/obj.gltf"
cp "$G/external data.bin" "$G/s_obj0.ply"
"${PY:-python3}" - "$ROOT/tests/data/gltf/textured_datauri.gltf" "$G/img.gltf" "$G/t_img0.png" <<'PYEOF' ||
import base64, json, sys
a = json.load(open(sys.argv[1]))
b = a["buffers"][0]
open(sys.argv[3], "wb").write(base64.b64decode(b["uri"].split(",", 1)[1]))
b["uri"] = "t_img0.png"  # the buffer, in the file import writes the embedded image to for -o t.json
json.dump(a, open(sys.argv[2], "w"))
PYEOF
    fail "could not write the external-buffer asset"
scene a.png m_obj0.ply >"$G/mesh.json"
cp "$I/a.png" "$I/m.ply" "$G/"
cp "$I/m.ply" "$G/m_obj0.ply"
gsums() { (cd "$G" && cksum "external data.bin" s_obj0.ply t_img0.png m_obj0.ply obj.gltf img.gltf mesh.json); }
before=$(gsums)
listing=$(ls -A "$G")
expect 1 "external data\.bin: is the same file as the input" -- import "$G/external.gltf" -o "$G/external data.bin"
expect 1 "same file as the input" -- import "$G/external.gltf" -o "$G/./external data.bin"
expect 1 "link\.json: is the same file as the input" -- import "$G/external.gltf" -o "$G/link.json"
expect 1 "hard\.json: is the same file as the input" -- import "$G/external.gltf" -o "$G/hard.json"
expect 1 "s_obj0\.ply: is the same file as the input" -- import "$G/obj.gltf" -o "$G/s.json"
expect 1 "t_img0\.png: is the same file as the input" -- import "$G/img.gltf" -o "$G/t.json"
expect 1 "m_obj0\.ply: is the same file as the input" -- export pbrt "$G/mesh.json" -o "$G/m.pbrt"
# a .gltf given as a scene: its buffer is an input of render too
expect 1 "hard\.json: is the same file as the input" -- render "$G/external.gltf" -o "$G/x.png" \
    --timings-json "$G/hard.json" --width 8 --height 8
[ "$(gsums)" = "$before" ] || fail "import/export changed an input"
[ "$(ls -A "$G")" = "$listing" ] || fail "refused imports/exports left files: $(ls -A "$G")"
mkdir -p "$G/fine"
"$SSS" import "$G/obj.gltf" -o "$G/fine/s.json" >/dev/null 2>"$T/err.txt" && [ -s "$G/fine/s_obj0.ply" ] ||
    fail "import to another folder failed: $(head -c 300 "$T/err.txt")"

# ---- The viewer writes through the same rules: a --screenshot or a script's screenshot line that is
# an input (the scene's texture, the scene, the script itself) or another screenshot of the script is
# refused, naming the line and the file, before the window opens; nothing is written.
if command -v xvfb-run >/dev/null 2>&1; then
    V=$T/view
    mkdir -p "$V"
    cp "$I/a.png" "$I/s.json" "$V/"
    printf 'frames 1\nscreenshot a.png\n' >"$V/texture.txt"
    printf 'frames 1\nscreenshot self.png\n' >"$V/self.png"
    printf 'frames 1\nscreenshot x.png\nframes 1\nscreenshot ./x.png\n' >"$V/twice.txt"
    vsums() { (cd "$V" && cksum a.png s.json self.png texture.txt twice.txt); }
    before=$(vsums)
    vexpect() { # vexpect PATTERN ARGS: sss view ARGS in $V under Xvfb exits 1 with PATTERN on stderr
        local pattern=$1
        shift
        (cd "$V" && timeout 60 xvfb-run -a "$SSS" view "$@") >"$T/out.txt" 2>"$T/err.txt"
        local got=$?
        [ "$got" -eq 1 ] || fail "sss view $* exited $got, expected 1 ($(head -c 300 "$T/err.txt"))"
        grep -Eq -e "$pattern" "$T/err.txt" || fail "sss view $* stderr lacks /$pattern/: $(head -c 300 "$T/err.txt")"
    }
    vexpect "texture\.txt:2: screenshot: a\.png: is the same file as the input" s.json --script texture.txt
    vexpect "self\.png:2: screenshot: self\.png: is the same file as the input" s.json --script self.png
    vexpect "twice\.txt:4: screenshot: \./x\.png: is the same file as the output x\.png" s.json --script twice.txt
    vexpect "a\.png: is the same file as the input" s.json --frames 1 --screenshot "$V/../view/a.png"
    [ "$(vsums)" = "$before" ] || fail "sss view changed an input"
    [ "$(ls -A "$V" | wc -l)" -eq 5 ] || fail "refused viewer runs left files: $(ls -A "$V")"
else
    echo "note: xvfb-run not installed; the viewer's output checks are skipped"
fi

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
