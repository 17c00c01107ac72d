#!/bin/bash
# sss mesh: info on the bundled bunny, exit 1 naming the file for malformed meshes, simplify writes a
# PLY with at most N triangles, usage errors exit 2 without writing anything.
# Usage: bash test_mesh.sh SSS_BINARY REPO_ROOT
set -u
SSS=$1
ROOT=$2
DATA="$ROOT/tests/data/meshes"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# --- info on an asset: counts of the npm 'bunny' package (1839 positions, 3674 cells), closed,
# positive signed volume (counter-clockwise outward)
if out=$("$SSS" mesh info "$ROOT/assets/bunny.ply"); then
    grep -qx 'vertices: 1839' <<<"$out" || fail "bunny vertices: $out"
    grep -qx 'triangles: 3674' <<<"$out" || fail "bunny triangles"
    grep -qx 'closed: yes' <<<"$out" || fail "bunny should be closed"
    vol=$(sed -n 's/^signed volume: \([^ ]*\).*/\1/p' <<<"$out")
    awk -v v="$vol" 'BEGIN { exit !(v > 0) }' || fail "bunny signed volume $vol not positive"
    grep -q '^surface area: ' <<<"$out" || fail "no surface area"
    grep -q '^bounds min: ' <<<"$out" || fail "no bounds"
    grep -qx 'degenerate triangles: 0' <<<"$out" || fail "bunny degenerate triangles"
    grep -qi 'nan\|inf' <<<"$out" && fail "non-finite number in: $out"
else
    fail "mesh info bunny exited $?"
fi

# an ascii box written by hand: 1 x 2 x 3, area 22, volume 6, normals not in the file
out=$("$SSS" mesh info "$DATA/box_ascii.ply") || fail "mesh info box exited $?"
grep -qx 'surface area: 22' <<<"$out" || fail "box area: $out"
grep -qx 'signed volume: 6' <<<"$out" || fail "box volume"
grep -q '^normals: computed' <<<"$out" || fail "box normals should be reported as computed"
out=$("$SSS" mesh info "$DATA/tetra_normals_uv.ply") || fail "mesh info tetra exited $?"
grep -qx 'normals: from file' <<<"$out" || fail "tetra normals from file"
grep -qx 'uvs: from file' <<<"$out" || fail "tetra uvs from file"

# --- malformed inputs: exit 1 and a message naming the file
for f in bad_index.ply bad_count.ply bad_nan.ply bad_huge_count.ply bad_empty.ply bad_header_only.ply \
         bad_index.obj bad_garbage.obj missing_file.ply; do
    "$SSS" mesh info "$DATA/$f" >"$tmp/out" 2>"$tmp/err"
    rc=$?
    [ $rc -eq 1 ] || fail "mesh info $f: exit $rc, expected 1"
    grep -q "$f" "$tmp/err" || fail "mesh info $f: message does not name the file: $(cat "$tmp/err")"
    [ -s "$tmp/out" ] && fail "mesh info $f: printed to stdout"
done
"$SSS" mesh simplify "$DATA/bad_nan.ply" --triangles 10 -o "$tmp/never.ply" 2>"$tmp/err"
[ $? -eq 1 ] || fail "simplify of a malformed file should exit 1"
[ -e "$tmp/never.ply" ] && fail "simplify of a malformed file wrote output"

# --- simplify: at most N triangles, counted from the written file's own header
out=$("$SSS" mesh simplify "$ROOT/assets/bunny.ply" --triangles 500 -o "$tmp/b500.ply") || fail "simplify exited $?"
n=$(head -c 400 "$tmp/b500.ply" | tr -d '\0' | sed -n 's/^element face \([0-9]*\).*/\1/p' | head -1)
[ -n "$n" ] && [ "$n" -le 500 ] && [ "$n" -gt 0 ] || fail "simplified file has '$n' faces"
grep -q "$n triangles" <<<"$out" || fail "simplify should print the achieved count ($n): $out"
head -c 40 "$tmp/b500.ply" | grep -q 'format binary_little_endian 1.0' || fail "not binary little-endian PLY"
out=$("$SSS" mesh info "$tmp/b500.ply") || fail "cannot read the simplified file back"
grep -qx "triangles: $n" <<<"$out" || fail "read-back triangle count differs"
ls -a "$tmp" | grep -q '\.tmp-' && fail "temporary file left behind"

# convert OBJ -> PLY keeps the triangles
"$SSS" mesh convert "$DATA/cube_faces.obj" -o "$tmp/cube.ply" >/dev/null || fail "convert exited $?"
"$SSS" mesh info "$tmp/cube.ply" | grep -qx 'triangles: 12' || fail "converted cube triangles"

# --- usage errors: exit 2, nothing written
expect_usage() {
    "$SSS" "$@" >/dev/null 2>&1
    rc=$?
    [ $rc -eq 2 ] || fail "sss $*: exit $rc, expected 2"
}
expect_usage mesh
expect_usage mesh frobnicate "$DATA/box_ascii.ply"
expect_usage mesh info
expect_usage mesh info "$DATA/box_ascii.ply" --bogus
expect_usage mesh simplify "$DATA/box_ascii.ply" --triangles 5
expect_usage mesh simplify "$DATA/box_ascii.ply" -o "$tmp/x.ply"
expect_usage mesh simplify "$DATA/box_ascii.ply" --triangles abc -o "$tmp/x.ply"
expect_usage mesh simplify "$DATA/box_ascii.ply" --triangles 0 -o "$tmp/x.ply"
expect_usage mesh simplify "$DATA/box_ascii.ply" --triangles 5 -o
expect_usage mesh convert "$DATA/box_ascii.ply"
[ -e "$tmp/x.ply" ] && fail "a usage error wrote output"
"$SSS" mesh --help >/dev/null || fail "mesh --help should exit 0"

if [ $failures -ne 0 ]; then
    echo "$failures failure(s)"
    exit 1
fi
echo "all mesh CLI checks passed"
