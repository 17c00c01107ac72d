#!/usr/bin/env bash
# sss import: a .glb becomes a scene + PLYs that `sss export pbrt` (any scene consumer) loads; bad
# input exits 1 naming the file and leaves nothing; usage errors exit 2. A .glb given directly as a
# scene (imported in memory) exports to the same PBRT scene as its imported scene file.
SSS=$1; ROOT=$2
fail=0
err() { echo "FAIL: $*"; fail=1; }
dir=$(mktemp -d); trap 'rm -rf "$dir"' EXIT
data="$ROOT/tests/data/gltf"

"$SSS" import "$data/scatter.glb" -o "$dir/s.json" >/dev/null || err "import failed"
n_ply=$(ls "$dir"/s_obj*.ply 2>/dev/null | wc -l)
[ "$n_ply" = 6 ] || err "expected 6 PLY files, got $n_ply"
grep -q '"subsurface"' "$dir/s.json" || err "no subsurface material"

# The same scene, through the import and directly: identical PBRT scenes and meshes.
mkdir "$dir/a" "$dir/b"
"$SSS" export pbrt "$dir/s.json" -o "$dir/a/x.pbrt" >/dev/null || err "the imported scene does not load"
"$SSS" export pbrt "$data/scatter.glb" -o "$dir/b/x.pbrt" >/dev/null || err "the .glb does not load as a scene"
# (line 1 names the input)
diff <(sed 1d "$dir/a/x.pbrt") <(sed 1d "$dir/b/x.pbrt") >/dev/null || err "the .glb and its imported scene export differently"
for i in 0 1 2 3 4 5; do cmp -s "$dir/a/x_obj$i.ply" "$dir/b/x_obj$i.ply" || err "object $i differs"; done

# Embedded textures (a .glb bufferView, a data: URI) render exactly like the external PNG they were
# made from, and the texture is visible (the same asset without it renders differently).
render() { "$SSS" render "$1" -o "$2" --width 48 --height 48 >/dev/null || err "render $1 failed"; }
render "$data/textured.gltf" "$dir/t_ext.png"
sed -z 's/"baseColorTexture": {[^}]*}//' "$data/textured.gltf" >"$dir/untextured.gltf"
render "$dir/untextured.gltf" "$dir/t_none.png"
for asset in textured_embedded.glb textured_datauri.gltf; do
    render "$data/$asset" "$dir/t_emb.png"
    case $("$SSS" compare "$dir/t_ext.png" "$dir/t_emb.png") in *"max=0"*) ;; *) err "$asset renders unlike textured.gltf";; esac
done
case $("$SSS" compare "$dir/t_ext.png" "$dir/t_none.png") in *"max=0"*) err "the texture does not show";; esac
rm -f "$dir"/t_*.png

# Bad inputs: exit 1, the file and the JSON path named, nothing written.
for bad in truncated.glb accessor_range.gltf missing_buffer.gltf required_ext.gltf index_range.gltf image_mime.glb \
           image_corrupt.glb; do
    out=$("$SSS" import "$data/bad/$bad" -o "$dir/bad.json" 2>&1); code=$?
    [ $code = 1 ] || err "$bad: exit $code"
    case "$out" in *"$bad"*) ;; *) err "$bad: message does not name the file: $out";; esac
done
out=$("$SSS" render "$data/bad/accessor_range.gltf" -o "$dir/bad.png" 2>&1); code=$?
[ $code = 1 ] || err "render of a bad .gltf: exit $code"
case "$out" in *"accessors[0]"*) ;; *) err "render: message does not name the accessor: $out";; esac
ls "$dir" | grep -q '^bad' && err "a bad input left output"
# A .gltf loaded directly goes through the scene loader's checks like a scene's mesh files: a node
# scaled beyond the 1e18 world range is refused by the reference too (it used to render it).
sed 's/"mesh": 0/"mesh": 0, "scale": [1e20, 1e20, 1e20]/' "$data/external.gltf" >"$dir/huge.gltf"
cp "$data/external data.bin" "$dir/"
out=$("$SSS" reference "$dir/huge.gltf" -o "$dir/huge.png" --quality draft -q 2>&1); code=$?
[ $code = 1 ] || err "reference of a .gltf beyond the world range: exit $code"
case "$out" in *"huge.gltf: nodes[0] places"*"beyond 1e+18"*) ;; *) err "reference: message does not name the node: $out";; esac
# export gltf, then import: the default scene comes back with its subsurface material.
"$SSS" export gltf "$ROOT/scenes/default.json" -o "$dir/d.glb" >/dev/null || err "export gltf failed"
"$SSS" import "$dir/d.glb" -o "$dir/d.json" >/dev/null || err "import of the export failed"
grep -q '"subsurface"' "$dir/d.json" || err "the export lost the subsurface material"
# The round trip renders as the original (the export holds world meshes bit for bit and coefficients
# within 1e-9), and reference, eval and view take the .glb directly.
# The interreflection stage's sources are the meshes simplified in object space, which the export
# moved to world space (other chords): bit for bit without it, within DSSIM 0.001 with it.
"$SSS" render "$ROOT/scenes/default.json" -o "$dir/rt_a.png" --width 64 --height 64 -q --param interreflection=0 || err "render of default.json failed"
"$SSS" render "$dir/d.glb" -o "$dir/rt_b.png" --width 64 --height 64 -q --param interreflection=0 || err "render of its export failed"
rt=$("$SSS" compare "$dir/rt_a.png" "$dir/rt_b.png")
case "$rt" in "dssim=0.000000 "*) ;; *) err "the exported scene renders differently: $rt";; esac
"$SSS" render "$ROOT/scenes/default.json" -o "$dir/rt_c.png" --width 64 --height 64 -q || err "render of default.json failed"
"$SSS" render "$dir/d.glb" -o "$dir/rt_d.png" --width 64 --height 64 -q || err "render of its export failed"
rt=$("$SSS" compare "$dir/rt_c.png" "$dir/rt_d.png")
case "$rt" in "dssim=0.000"*) ;; *) err "the exported scene renders differently with interreflection: $rt";; esac
"$SSS" reference "$dir/d.glb" -o "$dir/rt_ref.png" --width 16 --height 16 --quality draft -q || err "reference of a .glb failed"
[ -s "$dir/rt_ref.png" ] || err "reference of a .glb wrote nothing"
LSAN_OPTIONS=detect_leaks=0 "$SSS" eval "$dir/d.glb" --techniques local --frames 1 --warmup 0 --reference-quality draft \
    --width 16 --height 16 --no-sam-sweep -o "$dir/ev" -q >"$dir/ev.txt" 2>&1 || err "eval of a .glb failed: $(head -c 300 "$dir/ev.txt")"
grep -q "^d  *local  *ok" "$dir/ev.txt" || err "eval of a .glb: no result row: $(head -c 300 "$dir/ev.txt")"
if command -v xvfb-run >/dev/null 2>&1; then
    xvfb-run -a env LSAN_OPTIONS=exitcode=0 "$SSS" view "$dir/d.glb" --frames 1 --screenshot "$dir/rt_view.png" \
        --width 64 --height 64 --no-overlay >"$dir/view.txt" 2>&1 || err "view of a .glb failed: $(head -c 300 "$dir/view.txt")"
    case $("$SSS" compare "$dir/rt_d.png" "$dir/rt_view.png") in "dssim=0.00"*) ;; *) err "view of a .glb differs from render";; esac
fi
rm -rf "$dir"/rt_* "$dir/ev" "$dir/ev.txt" "$dir/view.txt"
"$SSS" export gltf "$ROOT/scenes/default.json" >/dev/null 2>&1; [ $? = 2 ] || err "export gltf without -o is not a usage error"
# --scatter-extension scatter writes the draft KHR_materials_scatter, which imports to the same medium.
"$SSS" export gltf "$ROOT/scenes/default.json" -o "$dir/ks.glb" --scatter-extension scatter >/dev/null || err "export --scatter-extension scatter failed"
grep -aq '"KHR_materials_scatter"' "$dir/ks.glb" || err "--scatter-extension scatter wrote no KHR_materials_scatter"
"$SSS" import "$dir/ks.glb" -o "$dir/ks.json" >/dev/null || err "import of the KHR_materials_scatter export failed"
"$SSS" import "$dir/d.glb" -o "$dir/d2.json" >/dev/null
python3 - "$dir/d2.json" "$dir/ks.json" <<'PY' || err "the two scatter extensions import to different media"
import json, sys
a, b = (json.load(open(p))["objects"][0]["material"] for p in sys.argv[1:])
assert a["type"] == b["type"] == "subsurface"
for key in ("sigma_a", "sigma_s"):
    assert all(abs(x - y) <= 1e-9 * abs(x) for x, y in zip(a[key], b[key])), (key, a[key], b[key])
PY
out=$("$SSS" export gltf "$ROOT/scenes/default.json" -o "$dir/x.glb" --scatter-extension scater 2>&1); code=$?
[ $code = 2 ] || err "--scatter-extension scater: exit $code"
case "$out" in *"did you mean 'scatter'"*) ;; *) err "--scatter-extension scater: $out";; esac
rm -f "$dir"/ks.* "$dir"/ks_* "$dir"/d2*
# A volume with diffuse transmission and no scattering extension (gltf_transform.glb) imports as a
# subsurface material, with a warning that says so (it was a plain diffuse material, silently).
"$SSS" import "$data/gltf_transform.glb" -o "$dir/gt.json" >/dev/null 2>"$dir/stderr" || err "import of gltf_transform.glb failed"
grep -q '"subsurface"' "$dir/gt.json" || err "gltf_transform.glb: the volume + diffuse transmission is not subsurface"
grep -q "warning: .*gltf_transform.glb: materials\[0\]: KHR_materials_volume + KHR_materials_diffuse_transmission" "$dir/stderr" ||
    err "gltf_transform.glb: no warning: $(cat "$dir/stderr")"
"$SSS" import "$data/gltf_transform.glb" -o "$dir/gt.json" -q >/dev/null 2>"$dir/stderr"
[ -s "$dir/stderr" ] && err "-q still warns: $(cat "$dir/stderr")"
rm -f "$dir"/gt*
# An output onto the asset itself is refused before the work, the asset unchanged.
cp "$data/external.gltf" "$data/external data.bin" "$dir/"
"$SSS" import "$dir/external.gltf" -o "$dir/external.gltf" >/dev/null 2>&1; [ $? = 1 ] || err "import onto its input not refused"
cmp -s "$dir/external.gltf" "$data/external.gltf" || err "import overwrote its input"
# -o into folders that do not exist: created (the import used to fail: "cannot write: No such file or
# directory"); a refused import creates none.
"$SSS" import "$data/scatter.glb" -o "$dir/new/sub/s.json" >/dev/null 2>"$dir/stderr" || err "import into a new folder: $(cat "$dir/stderr")"
[ -s "$dir/new/sub/s.json" ] && [ -s "$dir/new/sub/s_obj5.ply" ] || err "import into a new folder wrote $(ls -R "$dir/new")"
"$SSS" import "$data/bad/index_range.gltf" -o "$dir/none/s.json" >/dev/null 2>&1; [ $? = 1 ] || err "bad import into a new folder"
[ -e "$dir/none" ] && err "a refused import left the folder it would have written into"
# Usage errors: exit 2.
"$SSS" import "$data/scatter.glb" >/dev/null 2>&1; [ $? = 2 ] || err "missing -o is not a usage error"
"$SSS" import "$data/scatter.glb" -o "$dir/x.json" --light-scale 0 >/dev/null 2>&1; [ $? = 2 ] || err "--light-scale 0 is not a usage error"
"$SSS" import "$data/scatter.glb" -o "$dir/x.json" --camera -1 >/dev/null 2>&1; [ $? = 2 ] || err "--camera -1 is not a usage error"
exit $fail
