#!/usr/bin/env bash
# examples/engine_gbuffer: an engine with its own G-buffer, lighting and shadow maps running a technique
# through sss/gl_pass.h writes the image `sss render SCENE --technique T` writes, within DSSIM 0.002
# (the engines' shadow maps differ in resolution, bias and filtering; measured 0.0003 back-lit,
# 0.001 on gl_spot, where shadow edges on the floor dominate), on a back-lit scene and a front-lit one;
# usage errors exit 2, scenes outside the example's scope exit 1 with a message naming the problem.
# Usage: bash engine_gbuffer.sh <sss-binary> <repo-root> <engine_gbuffer-binary>
set -u
SSS=$1
ROOT=$2
ENGINE=$3
. "$(dirname "${BASH_SOURCE[0]}")/harness.sh"

check() { # scene technique [engine options]
    "$ENGINE" "$ROOT/scenes/$1" -o "$T/engine.png" --technique "$2" "${@:3}" 2>"$T/err.txt" ||
        { fail "engine_gbuffer $1 $2 failed: $(cat "$T/err.txt")"; return; }
    # the pass adds no light between surfaces (sss/gl_pass.h: the engine's own indirect light)
    "$SSS" render "$ROOT/scenes/$1" -o "$T/render.png" --technique "$2" --param interreflection=0 2>"$T/err.txt" ||
        { fail "sss render $1 $2 failed: $(cat "$T/err.txt")"; return; }
    local line
    line=$("$SSS" compare "$T/engine.png" "$T/render.png") || { fail "compare failed: $line"; return; }
    echo "$1 $2 ${*:3}: $line"
    awk -v l="$line" 'BEGIN { split(l, a, /[= ]/); exit !(a[2] + 0 <= 0.002) }' ||
        fail "$1 $2: engine_gbuffer differs from sss render: $line"
}
check gl_backlit.json maisch2020
check gl_spot.json ssss
# An engine that keeps depth, not world positions (sss_gl_pass_frame.depth): the pass reconstructs
# positions and pixel areas; the same bound.
check gl_backlit.json maisch2020 --depth-only
check gl_spot.json ssss --depth-only

"$ENGINE" "$ROOT/scenes/gl_spot.json" >/dev/null 2>&1
[ $? -eq 2 ] || fail "a missing -o is not a usage error (exit 2)"
"$ENGINE" "$ROOT/scenes/gl_area.json" -o "$T/x.png" 2>"$T/err.txt"
[ $? -eq 1 ] || fail "an area light is not refused with exit 1"
grep -q "lights\[" "$T/err.txt" || fail "the refusal does not name the light: $(cat "$T/err.txt")"
[ -e "$T/x.png" ] && fail "a refused scene left an output file"
[ "$fails" -eq 0 ]
