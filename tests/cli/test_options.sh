#!/usr/bin/env bash
# The command line as one tool (cli.h option tables): --width/--height wherever a scene is rendered,
# --threads, --quiet/--progress, -o/--output, "--name=value", "did you mean" for commands, options,
# subcommands and technique names, and `sss completion bash` (COMPREPLY for a command, an option, a
# technique name and a subcommand's option). Image sizes are read from the PNG header (IHDR), not by sss.
# Usage: bash test_options.sh <sss-binary> <repo-root>
set -u
SSS=$1
ROOT=$2
. "$(dirname "${BASH_SOURCE[0]}")/harness.sh"

cat >"$T/ball.json" <<'JSON'
{
  "camera": {"position": [0, 1, 4], "look_at": [0, 0.5, 0], "fov": 40, "width": 20, "height": 20},
  "objects": [
    {"procedural": {"shape": "sphere", "radius": 0.8, "subdivisions": 2},
     "transform": {"translate": [0, 0.8, 0]},
     "material": {"type": "subsurface", "medium": "Marble", "scale": 2.0}},
    {"procedural": {"shape": "plane", "size": 6}, "material": {"type": "diffuse", "reflectance": [0.5, 0.5, 0.5]}}
  ],
  "lights": [{"type": "point", "position": [1, 3, -2], "intensity": [8, 8, 8]}]
}
JSON

# "W H" of a PNG from its IHDR chunk (bytes 16..23, big-endian).
png_size() { od -An -tu1 -j16 -N8 "$1" | awk '{print $1*16777216+$2*65536+$3*256+$4, $5*16777216+$6*65536+$7*256+$8}'; }
# expect CODE PATTERN ARGS...: sss ARGS exits CODE and stderr matches PATTERN (grep -E).
expect() {
    local code=$1 pattern=$2
    shift 2
    "$SSS" "$@" >"$T/out.txt" 2>"$T/err.txt"
    local rc=$?
    [ "$rc" -eq "$code" ] || fail "sss $*: exit $rc, want $code: $(head -c 300 "$T/err.txt")"
    grep -Eq -- "$pattern" "$T/err.txt" || fail "sss $*: stderr lacks /$pattern/: $(head -c 300 "$T/err.txt")"
}

# --width/--height: reference (new), render, and export pbrt (the film of the exported scene).
"$SSS" reference "$T/ball.json" -o "$T/ref.png" --width 32 --height 24 --quality draft --quiet || fail "reference --width"
[ "$(png_size "$T/ref.png")" = "32 24" ] || fail "reference --width 32 --height 24 gave $(png_size "$T/ref.png")"
"$SSS" reference "$T/ball.json" --output="$T/ref_h.png" --height=16 --quality draft --quiet || fail "reference --height="
[ "$(png_size "$T/ref_h.png")" = "20 16" ] || fail "reference --height 16 gave $(png_size "$T/ref_h.png") (width: the camera's)"
"$SSS" render "$T/ball.json" -o "$T/gl.png" --width 36 --height 28 --quiet || fail "render --width"
[ "$(png_size "$T/gl.png")" = "36 28" ] || fail "render --width 36 --height 28 gave $(png_size "$T/gl.png")"
"$SSS" export pbrt "$T/ball.json" --output "$T/ball.pbrt" --width 40 --height 30 >/dev/null || fail "export pbrt --width"
grep -q '"integer xresolution" \[40\] "integer yresolution" \[30\]' "$T/ball.pbrt" || fail "export pbrt: no 40x30 film"
expect 2 "--width must be in 1\.\.16384, got 0" reference "$T/ball.json" -o "$T/x.png" --width 0
expect 2 "--height must be in 1\.\.16384" export pbrt "$T/ball.json" -o "$T/x.pbrt" --height 99999
expect 2 "--supersample must be in 1\.\.4" render "$T/ball.json" -o "$T/x.png" --supersample 5
[ ! -e "$T/x.png" ] && [ ! -e "$T/x.pbrt" ] || fail "a usage error wrote an output"

# eval: --width/--height (one size for every scene), --threads and its old spelling, --output.
# (eval's plots use cairo, whose fontconfig keeps its caches: no leak report in ASan builds.)
LSAN_OPTIONS=detect_leaks=0 "$SSS" eval "$T/ball.json" --techniques local --frames 1 --warmup 0 --reference-quality draft --width 24 --height 16 \
    --threads 1 --no-sam-sweep --output "$T/ev" --quiet >/dev/null 2>"$T/ev.err" || fail "eval --width: $(head -c 300 "$T/ev.err")"
[ -s "$T/ev/references/ball_24x16.exr" ] || fail "eval --width 24 --height 16: no 24x16 reference: $(ls "$T/ev/references" 2>&1)"
[ ! -s "$T/ev.err" ] || fail "eval --quiet wrote to stderr: $(head -c 300 "$T/ev.err")"
expect 2 "--width and --height go together" eval "$T/ball.json" --width 24
expect 2 "exclude each other" eval "$T/ball.json" --width 24 --height 16 --resolutions 32x32
expect 2 "--reference-threads must be in 1\.\.4096" eval "$T/ball.json" --reference-threads 0
"$SSS" eval --help | grep -q -- "--threads N" || fail "eval --help lacks --threads"

# Progress: render --frames on stderr only with --progress (stderr is not a terminal here), never with --quiet.
"$SSS" render "$T/ball.json" -o "$T/f.png" --frames 3 2>"$T/p0.txt" || fail "render --frames 3"
[ ! -s "$T/p0.txt" ] || fail "render printed progress to a non-terminal without --progress: $(cat "$T/p0.txt")"
"$SSS" render "$T/ball.json" -o "$T/f.png" --frames 3 --progress 2>"$T/p1.txt" || fail "render --frames 3 --progress"
grep -qx "100%" "$T/p1.txt" || fail "render --frames 3 --progress: no '100%' line: $(cat "$T/p1.txt")"
"$SSS" render "$T/ball.json" -o "$T/a.png" --frames 2 --animate --progress --quiet 2>"$T/p2.txt" || fail "render --animate"
[ ! -s "$T/p2.txt" ] || fail "--quiet --progress printed: $(cat "$T/p2.txt")"
[ -s "$T/a_0000.png" ] && [ -s "$T/a_0001.png" ] || fail "render --animate wrote no sequence"
"$SSS" reference "$T/ball.json" -o "$T/r.png" --quality draft 2>"$T/p3.txt" || fail "reference"
[ ! -s "$T/p3.txt" ] || fail "reference printed progress to a non-terminal without --progress"

# Every command's --help lists the common options (from the tables), and every command takes --quiet.
for c in profile lut kernel compare "mesh info" reference render techniques version eval view "export pbrt" import \
    "sam build" completion; do
    # shellcheck disable=SC2086
    "$SSS" $c --help >"$T/help.txt" || fail "sss $c --help"
    for o in "-q, --quiet" "--progress" "-h, --help"; do
        grep -q -- "$o" "$T/help.txt" || fail "sss $c --help lacks $o"
    done
    # The usage lines name every option the command documents (the common ones and aliases,
    # "the same as X", aside): both come from the one table, so none can be left out of the synopsis.
    usage=$(awk '/^$/ {exit} {print}' "$T/help.txt")
    awk '/^options:/ {on = 1; next} on && /^$/ {exit} on && /^  -/ {print}' "$T/help.txt" |
        grep -v -e "the same as" -e "--quiet" -e "--progress" -e "--help" | while read -r names _; do
        long=$(printf '%s\n' "$names" | grep -oE -- '--[a-z0-9-]+' | head -n 1)
        short=$(printf '%s\n' "$names" | grep -oE -- '^-[a-z]' | head -n 1)
        printf '%s\n' "$usage" | grep -qE -- "(^|[[ ])(${long}${short:+|$short})([] ]|\$)" ||
            echo "FAIL: sss $c --help: the usage lines lack ${long}" >&2
    done 2>>"$T/usage_fails.txt"
done
[ ! -s "$T/usage_fails.txt" ] || fail "$(cat "$T/usage_fails.txt")"
"$SSS" techniques --quiet >/dev/null || fail "techniques --quiet"
"$SSS" profile Marble --r 0:1:2 --quiet >/dev/null || fail "profile --quiet"
"$SSS" version -q >/dev/null || fail "version -q"

# -o/--output wherever an output is written.
"$SSS" compare "$T/gl.png" "$T/gl.png" --output "$T/map.png" >/dev/null || fail "compare --output"
[ -s "$T/map.png" ] || fail "compare --output wrote no map"
"$SSS" lut Marble --output "$T/lut.pfm" --size 4 >/dev/null || fail "lut --output"
"$SSS" mesh convert "$ROOT/tests/data/meshes/box_ascii.ply" --output "$T/m.ply" >/dev/null || fail "mesh convert --output"
[ -s "$T/m.ply" ] || fail "mesh convert --output wrote nothing"
"$SSS" export gltf "$T/ball.json" --output "$T/ball.glb" >/dev/null || fail "export gltf --output"
"$SSS" import "$T/ball.glb" --output "$T/imported.json" >/dev/null || fail "import --output"
[ -s "$T/imported.json" ] || fail "import --output wrote nothing"
"$SSS" view --help | grep -q -- "-o, --output FILE" || fail "view --help lacks -o/--output"

# "did you mean": commands, options, subcommands, formats (exit 2); technique names (exit 1, as before).
expect 2 "unknown command 'rendr'; did you mean 'render'\?" rendr "$T/ball.json"
expect 2 "unknown command 'refrence'; did you mean 'reference'\?" help refrence
expect 2 "unknown option '--widht'; did you mean '--width'\?" render "$T/ball.json" -o "$T/x.png" --widht 8
expect 2 "unknown option '--qualty'; did you mean '--quality'\?" reference "$T/ball.json" -o "$T/x.png" --qualty=draft
expect 2 "unknown option '--tech'; did you mean '--techniques'\?" eval "$T/ball.json" --tech local
expect 2 "unknown subcommand 'simplfy'; did you mean 'simplify'\?" mesh simplfy x.ply
expect 2 "unknown format 'pbr'; did you mean 'pbrt'\?" export pbr "$T/ball.json"
expect 2 "unknown option '--frobnicate'\$" render "$T/ball.json" --frobnicate
expect 1 "unknown technique 'maisch202'; did you mean 'maisch2020'\?" render "$T/ball.json" -o "$T/x.png" --technique maisch202
LSAN_OPTIONS=detect_leaks=0 expect 0 "warning: unknown technique 'lcoal'; did you mean 'local'\?" eval "$T/ball.json" --techniques lcoal \
    --frames 1 --warmup 0 --reference-dir "$T/ev/references" --cached-reference --width 24 --height 16 \
    --no-sam-sweep -o "$T/ev2"
expect 2 "--width needs a value W" render "$T/ball.json" --width
expect 2 "sss render: --width must be in 1\.\.16384, got 0" render "$T/ball.json" -o "$T/x.png" --width=0
expect 2 "--animate takes no value" render "$T/ball.json" --animate=1
[ ! -e "$T/x.png" ] || fail "a usage error wrote an output"

# Bash completion, generated from the same tables: COMPREPLY for a command, an option, a technique
# name, a subcommand and its option, a choice.
"$SSS" completion bash >"$T/sss.bash" || fail "completion bash"
expect 2 "unknown shell 'bsh'; did you mean 'bash'\?" completion bsh
complete_words() { # the words of COMPREPLY for the command line "$@" (the last word is being completed)
    bash -c 'source "$1"; shift; COMP_WORDS=("$@"); COMP_CWORD=$(($# - 1)); _sss; printf "%s\n" "${COMPREPLY[@]}"' \
        _ "$T/sss.bash" "$@"
}
[ "$(complete_words sss ren)" = "render" ] || fail "completion of 'sss ren': $(complete_words sss ren)"
[ "$(complete_words sss render --tech)" = "--technique" ] || fail "completion of '--tech': $(complete_words sss render --tech)"
[ "$(complete_words sss render x.json --technique maisch)" = "maisch2020" ] ||
    fail "completion of '--technique maisch': $(complete_words sss render x.json --technique maisch)"
complete_words sss view --technique "" | grep -qx "local" || fail "completion of view --technique lacks local"
[ "$(complete_words sss eval x.json --techniques local,mais)" = "local,maisch2020" ] ||
    fail "completion of '--techniques local,mais': $(complete_words sss eval x.json --techniques local,mais)"
[ "$(complete_words sss mesh sim)" = "simplify" ] || fail "completion of 'sss mesh sim': $(complete_words sss mesh sim)"
[ "$(complete_words sss mesh simplify x.ply --tri)" = "--triangles" ] || fail "completion of mesh simplify --tri"
[ "$(complete_words sss reference x.json --quality d)" = "draft" ] || fail "completion of --quality d"
[ "$(complete_words sss profile Mar)" = "Marble" ] || fail "completion of a medium: $(complete_words sss profile Mar)"
complete_words sss reference --wid | grep -qx -- "--width" || fail "completion of reference --wid"
touch "$T/scene_a.json"
[ "$(complete_words sss render "$T/scene_")" = "$T/scene_a.json" ] || fail "completion of a scene file"

[ "$fails" -eq 0 ]
