#!/usr/bin/env bash
# CLI test of `sss sam`: build from a mesh + medium (the bunny) and from a scene object, the printed
# counts equal the mesh's (`sss mesh info`), n links per vertex, the search visits a fraction of the
# pairs; `sss sam info` reads the file back and accepts the right mesh but rejects another mesh and a
# truncated file with clear messages; --brute-force gives the same file; `sss render --technique sam
# --data FILE` uses it and rejects another mesh's file; a back-side mesh (--backside-triangles, -mesh,
# -splat) gives a version-2 file of the documented size that renders as the map built at creation;
# usage errors exit 2 and write nothing.
# Usage: bash test_sam.sh <sss-binary> <repo-root>
set -u
SSS=$1
ROOT=$2
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fail=0
err() { echo "FAIL: $*" >&2; fail=1; }
val() { printf '%s\n' "$1" | awk -v k="$2" '$1 == k {print $2; exit}'; }

BUNNY="$ROOT/assets/bunny.ply"
out=$("$SSS" sam build "$BUNNY" --medium Marble --scale 2.5 -n 4 --samples 16 -o "$T/b.sam") || err "build: exit $?"
[ -s "$T/b.sam" ] || err "no .sam written"
head -c 8 "$T/b.sam" | grep -q "SSSSAM1" || err "b.sam lacks the magic"
info=$("$SSS" mesh info "$BUNNY")
[ "$(val "$out" vertices)" = "$(printf '%s\n' "$info" | awk '/vertices/ {for (i = 1; i <= NF; i++) if ($i ~ /^[0-9]+$/) {print $i; exit}}')" ] ||
    err "vertex count differs from sss mesh info: $(val "$out" vertices)"
[ "$(val "$out" n)" = 4 ] || err "n is not 4: $out"
[ "$(val "$out" linked_vertices)" = "$(val "$out" vertices)" ] || err "not every vertex is linked: $out"
pct=$(printf '%s\n' "$out" | awk '$1 == "vertices_tested" {gsub(/[(%]/, "", $3); print $3}')
awk -v p="$pct" 'BEGIN {exit !(p > 0 && p < 50)}' || err "the search tested $pct% of the pairs"
# the file's size: header 320 + V (4) + V n (4 + 24) + checksum 8
V=$(val "$out" vertices)
size=$(wc -c < "$T/b.sam")
[ "$size" -eq $((320 + 4 * V + 28 * V * 4 + 8)) ] || err "file size $size"

# brute force: the same links and form factors (the checksum covers everything)
"$SSS" sam build "$BUNNY" --medium Marble --scale 2.5 -n 4 --samples 16 --brute-force -o "$T/bf.sam" > /dev/null ||
    err "brute force: exit $?"
cmp -s "$T/b.sam" "$T/bf.sam" || err "tree and brute-force files differ"

# info: against the right mesh, another mesh, a truncated file
"$SSS" sam info "$T/b.sam" "$BUNNY" | grep -q "^matches" || err "info does not accept its mesh"
msg=$("$SSS" sam info "$T/b.sam" "$ROOT/assets/dragon_low.ply" 2>&1); rc=$?
[ $rc -eq 1 ] || err "info with another mesh: exit $rc"
printf '%s\n' "$msg" | grep -q "different mesh" || err "no clear message for another mesh: $msg"
head -c 1000 "$T/b.sam" > "$T/cut.sam"
msg=$("$SSS" sam info "$T/cut.sam" 2>&1); rc=$?
[ $rc -eq 1 ] || err "truncated file: exit $rc"
printf '%s\n' "$msg" | grep -q "truncated" || err "no clear message for a truncated file: $msg"

# a scene object, then the renderer uses its file and rejects the bunny's
cat > "$T/s.json" <<JSON
{"camera": {"position": [0, 0.6, 5], "look_at": [0, 0, 0], "fov": 30, "width": 32, "height": 32},
 "objects": [{"procedural": {"shape": "sphere", "radius": 1, "subdivisions": 2},
              "material": {"type": "subsurface", "medium": "Marble", "scale": 5, "eta": 1.33}}],
 "lights": [{"type": "point", "position": [0.8, 1.2, -4], "intensity": [300, 300, 300]}]}
JSON
out=$("$SSS" sam build "$T/s.json" -n 10 -o "$T/s.sam") || err "scene build: exit $?"
[ "$(val "$out" vertices)" = 162 ] || err "sphere with 2 subdivisions has 162 vertices: $out"
"$SSS" sam info "$T/s.sam" "$T/s.json" | grep -q "^matches" || err "info does not accept the scene object"
"$SSS" render "$T/s.json" --technique sam --data "$T/s.sam" -o "$T/a.png" || err "render with --data: exit $?"
"$SSS" render "$T/s.json" --technique sam --param n=10 -o "$T/b.png" || err "render built at creation: exit $?"
cmp -s "$T/a.png" "$T/b.png" || err "the file's map and the one built at creation render differently"
msg=$("$SSS" render "$T/s.json" --technique sam --data "$T/b.sam" -o "$T/c.png" 2>&1); rc=$?
[ $rc -eq 1 ] || err "render with another mesh's file: exit $rc"
printf '%s\n' "$msg" | grep -q "different mesh" || err "no clear message: $msg"
[ ! -e "$T/c.png" ] || err "an image was written despite the error"

# back side on a lower-tessellation mesh (Maisch & Ropinski 2017, 4.4): version 2 with the coarse mesh in the file
out=$("$SSS" sam build "$BUNNY" --medium Marble --scale 2.5 -n 4 --samples 16 --backside-triangles 600 -o "$T/c.sam") ||
    err "backside build: exit $?"
[ "$(od -An -tu4 -j8 -N4 "$T/c.sam" | tr -d ' ')" = 2 ] || err "c.sam is not version 2"
BV=$(val "$out" backside_vertices); BT=$(val "$out" backside_triangles)
[ -n "$BV" ] && [ "$BT" -le 600 ] && [ "$BV" -lt "$V" ] || err "back-side counts: $out"
[ "$(val "$out" linked_vertices)" = "$V" ] || err "not every vertex linked to the back-side mesh: $out"
size=$(wc -c < "$T/c.sam")
[ "$size" -eq $((320 + 4 * V + 28 * V * 4 + 4 * (7 * BV + 3 * BT) + 8)) ] || err "version-2 file size $size"
"$SSS" sam info "$T/c.sam" "$BUNNY" | grep -q "^backside_vertices $BV" || err "info does not show the back-side mesh"
msg=$("$SSS" sam info "$T/c.sam" "$ROOT/assets/dragon_low.ply" 2>&1); rc=$?
[ $rc -eq 1 ] && printf '%s
' "$msg" | grep -q "c.sam: built for a different mesh" || err "v2 file, other mesh: $rc $msg"
# a given coarse mesh: the simplification written out by sss mesh simplify gives the same links
"$SSS" mesh simplify "$BUNNY" --triangles 600 -o "$T/low.ply" > /dev/null || err "mesh simplify: exit $?"
"$SSS" sam build "$BUNNY" --medium Marble --scale 2.5 -n 4 --samples 16 --backside-mesh "$T/low.ply" -o "$T/c2.sam" \
    > /dev/null || err "--backside-mesh: exit $?"
[ "$(val "$("$SSS" sam info "$T/c2.sam")" backside_vertices)" = "$BV" ] || err "--backside-mesh: other vertex count"
msg=$("$SSS" sam build "$BUNNY" --medium Marble --backside-mesh "$T/none.ply" -o "$T/u.sam" 2>&1); rc=$?
[ $rc -eq 1 ] && printf '%s
' "$msg" | grep -q "none.ply" || err "missing back-side mesh: $rc $msg"
# a scene object's splat mesh (docs/scene-format.md splat_triangles), rendered from the file
sed 's/"subdivisions": 2}/"subdivisions": 3}, "splat_triangles": 80/' "$T/s.json" > "$T/sp.json"
out=$("$SSS" sam build "$T/sp.json" -n 10 --backside-splat -o "$T/sp.sam") || err "--backside-splat: exit $?"
[ "$(val "$out" backside_triangles)" -le 80 ] && [ "$(val "$out" vertices)" = 642 ] || err "--backside-splat: $out"
"$SSS" render "$T/sp.json" --technique sam --data "$T/sp.sam" -o "$T/sp.png" || err "render a version-2 file: exit $?"
"$SSS" render "$T/sp.json" --technique sam --param n=10 --param backside_splat=1 -o "$T/sp2.png" ||
    err "render with backside_splat: exit $?"
cmp -s "$T/sp.png" "$T/sp2.png" || err "the file's coarse map and the one built at creation render differently"
msg=$("$SSS" sam build "$T/s.json" --backside-splat -o "$T/u.sam" 2>&1); rc=$?
[ $rc -eq 1 ] && printf '%s
' "$msg" | grep -q "splat_mesh" || err "--backside-splat without a splat mesh: $rc $msg"

# usage errors: exit 2, nothing written
for args in "build" "build $BUNNY -o $T/u.sam" "build $BUNNY --medium Marble" "build $BUNNY --medium Marble -n 0 -o $T/u.sam" \
    "build $T/s.json --medium Marble -o $T/u.sam" "frobnicate" \
    "build $BUNNY --medium Marble --backside-triangles 0 -o $T/u.sam" \
    "build $BUNNY --medium Marble --backside-splat -o $T/u.sam" \
    "build $T/s.json --backside-triangles 50 --backside-splat -o $T/u.sam"; do
    "$SSS" sam $args > /dev/null 2>&1; rc=$?
    [ $rc -eq 2 ] || err "sss sam $args: exit $rc, expected 2"
done
"$SSS" sam build "$BUNNY" --medium Unobtainium -o "$T/u.sam" > /dev/null 2>&1; rc=$?
[ $rc -eq 1 ] || err "unknown medium: exit $rc"
[ ! -e "$T/u.sam" ] || err "a file was written on error"
"$SSS" sam --help | grep -q "usage: sss sam build" || err "no help"
exit $fail
