#!/usr/bin/env bash
# make demo: shows the default scene's material end to end with what exists today.
# Until a renderer lands it prints the profile and kernel-LUT summary of the default material and
# writes the LUT as an image (out/demo/lut.exr, plus a log-scaled PNG to look at).
set -euo pipefail
BUILD=${1:-build}
SSS="$BUILD/sss"
OUT=out/demo
mkdir -p "$OUT"

MEDIUM=Marble
SCALE=10   # 10 mm per scene unit
echo "== sss demo: $MEDIUM, scale $SCALE (mm per scene unit)"
echo "-- diffusion profile S_r(r) (PBRT-v3 photon beam diffusion), per scene unit^2"
"$SSS" profile "$MEDIUM" --scale "$SCALE" --r 0:2:11
echo "-- disc-integrated kernel LUT (seed 000, 512 x 512 x RGB)"
"$SSS" lut "$MEDIUM" --scale "$SCALE" -o "$OUT/lut.exr" --png "$OUT/lut.png"
echo "wrote $OUT/lut.exr and $OUT/lut.png"
