#!/usr/bin/env bash
# The CLI's smoke runs under valgrind memcheck: no invalid reads or writes, no uses of uninitialised
# values, no leaks ("definitely lost: 0", "indirectly lost: 0"), on success paths and on error paths
# (a malformed input must be refused without leaking what was allocated before the error).
# Skips (exit 0) when valgrind is not installed. About a minute on 2 cores.
# Usage: bash test_valgrind_smoke.sh <sss-binary> <repo-root>
set -u
SSS=$1
ROOT=$2
if ! command -v valgrind >/dev/null 2>&1; then
    echo "skipped: valgrind not installed"
    exit 0
fi
if ldd "$SSS" 2>/dev/null | grep -qE "libasan|libtsan|libubsan"; then
    echo "skipped: $SSS is built with sanitizers, which valgrind cannot run (the sanitizers check it instead)"
    exit 0
fi
D=$ROOT/tests/data
BAD=$D/bad
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fails=0 runs=0 skipped=0

# vg EXPECTED_EXIT ARGS...: one sss run under memcheck.
vg() {
    local want=$1
    shift
    if "$SSS" "$1" --help 2>&1 | grep -q "not built yet"; then
        echo "skipped (sss $1 not built yet): sss $*"
        skipped=$((skipped + 1))
        return
    fi
    runs=$((runs + 1))
    valgrind --error-exitcode=99 --leak-check=full --errors-for-leak-kinds=definite,indirect \
        --show-leak-kinds=definite,indirect --log-file="$T/vg.log" \
        "$SSS" "$@" >"$T/out" 2>"$T/err" </dev/null
    local rc=$?
    local label="sss $*"
    label=${label//$ROOT\//}
    label=${label//$T\//}
    local bad=""
    [ $rc -eq 99 ] && bad="memcheck errors"
    [ $rc -ne 99 ] && [ $rc -ne "$want" ] && bad="exit $rc, expected $want"
    grep -q "definitely lost: [1-9]" "$T/vg.log" && bad="${bad:+$bad; }definitely lost"
    grep -q "indirectly lost: [1-9]" "$T/vg.log" && bad="${bad:+$bad; }indirectly lost"
    if [ -n "$bad" ]; then
        echo "FAIL: $label: $bad" >&2
        grep -E "^==[0-9]+== (Invalid|Conditional|Use of|Syscall|Mismatched|[0-9,]+ bytes in|   (at|by) )" "$T/vg.log" |
            head -30 >&2
        fails=$((fails + 1))
    fi
}

# Success paths.
vg 0 profile Marble
vg 0 profile Skin1 --model dipole --scale 10 --eta 1.4 --r 0:2:9
vg 0 lut Marble --size 32 -o "$T/lut.exr"
vg 0 compare "$D/images/base.png" "$D/images/blur.png" --map "$T/map.png"
vg 0 compare "$ROOT/fuzz/corpus/exr/sss_zip_12x11.exr" "$ROOT/fuzz/corpus/exr/sss_zip_12x11.exr" --map "$T/map.exr"
vg 0 compare "$ROOT/fuzz/corpus/hdr/stb_rle_16x12.hdr" "$ROOT/fuzz/corpus/hdr/stb_rle_16x12.hdr" --map "$T/map.hdr"
vg 0 compare "$BAD/pfm_nan_pixels.pfm" "$BAD/pfm_nan_pixels.pfm" --map "$T/map.pfm"
vg 0 mesh info "$D/meshes/box_ascii.ply"
vg 0 mesh info "$D/meshes/cube_faces.obj"
vg 0 mesh info "$D/meshes/tetra_normals_uv.ply"
vg 0 mesh simplify "$ROOT/fuzz/fixtures/assets/dragon.ply" --triangles 4 -o "$T/s.ply"
vg 0 export pbrt "$BAD/scene_valid.json" -o "$T/scene.pbrt"
# Error paths: everything allocated before the error must be released.
vg 1 profile Unobtainium
vg 1 profile Marble --eta 0.5
vg 1 lut Marble --size 32 -o "$T/no_folder/lut.exr"
vg 1 compare "$BAD/png_truncated.png" "$D/images/base.png"
vg 1 compare "$D/images/base.png" "$BAD/hdr_bad_rle.hdr"
vg 1 compare "$D/images/base.png" "$BAD/exr_truncated.exr"
vg 1 compare "$BAD/pfm_truncated.pfm" "$D/images/base.png"
vg 1 compare "$D/images/base.png" "$D/images/small_a.png"
vg 1 compare "$D/images/base.png" "$D/images/blur.png" --map "$T/no_folder/map.png"
vg 1 mesh info "$BAD/ply_index_out_of_range.ply"
vg 1 mesh info "$BAD/ply_truncated_binary.ply"
vg 1 mesh info "$BAD/obj_forward_reference.obj"
vg 1 export pbrt "$BAD/scene_bad_mesh.json" -o "$T/bad.pbrt"
vg 1 export pbrt "$BAD/scene_unknown_medium.json" -o "$T/bad.pbrt"
vg 1 export pbrt "$BAD/scene_valid.json" -o "$T/no_folder/scene.pbrt"

echo "valgrind smoke: $runs runs, $fails with errors or leaks, $skipped skipped"
[ $fails -eq 0 ]
