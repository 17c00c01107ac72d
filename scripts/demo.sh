#!/usr/bin/env bash
# make demo: renders the default scene (scenes/default.json: a Marble bunny lit from behind and to
# the side) with the main real-time technique and with the CPU ground truth, compares them, and
# prints the material's profile and kernel-LUT summary. Everything lands in out/demo/.
set -euo pipefail
BUILD=${1:-build}
SSS="$BUILD/sss"
SCENE=scenes/default.json
OUT=out/demo
mkdir -p "$OUT"

# The default scene's material (keep in step with scenes/default.json).
MEDIUM=Marble
SCALE=1.5
echo "== sss demo: $SCENE ($MEDIUM, scale $SCALE mm per scene unit)"
echo
echo "-- diffusion profile S_r(r) per scene unit^2 (PBRT-v3 photon beam diffusion)"
"$SSS" profile "$MEDIUM" --scale "$SCALE" --r 0:4:9
echo
echo "-- disc-integrated kernel LUT R'_d(r, A) (seed 000, 512 x 512 x RGB)"
"$SSS" lut "$MEDIUM" --scale "$SCALE" -o "$OUT/lut.exr"
echo
echo "-- real time: maisch2020 on OpenGL (headless; llvmpipe without a GPU)"
"$SSS" render "$SCENE" -o "$OUT/maisch2020.png" --exr "$OUT/maisch2020.exr" --timings
echo
echo "-- ground truth: sss reference (CPU, Embree)"
"$SSS" reference "$SCENE" -o "$OUT/reference.png" --exr "$OUT/reference.exr"
echo
echo "-- maisch2020 against the ground truth"
"$SSS" compare "$OUT/reference.png" "$OUT/maisch2020.png" --map "$OUT/dssim.png"
echo
echo "wrote $OUT/: maisch2020.png, reference.png, dssim.png (DSSIM map), lut.exr"
