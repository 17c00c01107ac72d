#!/usr/bin/env bash
# Every real-time technique renders scenes out to the world range (1e18, docs/limits.md), not only small
# ones. Radiative transfer has no length scale of its own: the same scene with every length times s,
# the coefficients times 1/s and the intensities times s^2 has the same radiance, so the image at
# s = 1e13 must be the image at s = 1. It was not: |dp/dx x dp/dy| and the cross products of triangle
# edges hold squared lengths, and length() squares them again, overflowing float from edges of ~1.4e9
# on: maisch2020 produced NaN ("technique maisch2020 produced 648 NaN/Inf values"), and the pixels of
# every screen-space technique left the kernel sum (their area Inf, taken as grazing), a dark object.
# A sphere scaled 1e17 (near the world range, coefficients fixed) renders with each technique.
# Usage: bash test_world_scale.sh <sss-binary> <repo-root>
SSS=$1; ROOT=$2
fail=0
err() { echo "FAIL: $*"; fail=1; }
dir=$(mktemp -d); trap 'rm -rf "$dir"' EXIT

# scene S MATERIAL_SCALE INTENSITY: a Marble sphere on a plane, lit by a point light, all lengths times S.
scene() {
    local s=$1 ms=$2 i=$3
    cat <<EOF
{"camera": {"position": [0, $(awk "BEGIN{print 0.5*$s}"), $(awk "BEGIN{print 3*$s}")], "look_at": [0, 0, 0],
            "fov": 30, "width": 48, "height": 48},
 "objects": [{"procedural": {"shape": "sphere", "radius": 0.5}, "transform": {"scale": $s},
              "material": {"type": "subsurface", "medium": "Marble", "scale": $ms}},
             {"procedural": {"shape": "plane", "size": 4}, "transform": {"scale": $s, "translate": [0, $(awk "BEGIN{print -0.5*$s}"), 0]},
              "material": {"type": "diffuse", "reflectance": [0.5, 0.5, 0.5]}}],
 "lights": [{"type": "point", "position": [$(awk "BEGIN{print 0.5*$s}"), $(awk "BEGIN{print 2*$s}"), $(awk "BEGIN{print 2*$s}")],
             "intensity": [$i, $i, $i]}]}
EOF
}
scene 1 10 10 >"$dir/s1.json"
scene 1e13 1e-12 1e27 >"$dir/s13.json"
scene 1e17 10 1e29 >"$dir/s17.json"

render() { # SCENE TECHNIQUE OUT [--data MAP]
    local scene=$1 t=$2 out=$3
    shift 3
    "$SSS" render "$dir/$scene.json" --technique "$t" -o "$dir/$out" -q "$@" 2>"$dir/stderr" ||
        err "$scene $t: $(head -c 300 "$dir/stderr")"
}
for t in local maisch2020 screen ssss mertens2003 dss chen2012 sam; do
    data=()
    [ $t = chen2012 ] && data=(--param buffer_size=256) # 2048^2 light-view buffers: 30 s per image
    if [ $t = sam ]; then
        for s in s1 s13 s17; do
            "$SSS" sam build "$dir/$s.json" -o "$dir/$s.sam" -q >/dev/null 2>&1 || err "sam build $s failed"
        done
    fi
    [ $t = sam ] && data=(--data "$dir/s1.sam")
    render s1 $t a.exr "${data[@]}"
    [ $t = sam ] && data=(--data "$dir/s13.sam")
    render s13 $t b.exr "${data[@]}"
    # the same image (up to rounding: the scaled scene's floats round differently)
    m=$("$SSS" compare "$dir/a.exr" "$dir/b.exr")
    d=${m#dssim=}; d=${d%% *}
    awk "BEGIN{exit !($d <= 0.001)}" || err "$t: s = 1e13 renders unlike s = 1: $m"
    [ $t = sam ] && data=(--data "$dir/s17.sam")
    render s17 $t c.exr "${data[@]}"
    rm -f "$dir"/[abc].exr
done
exit $fail
