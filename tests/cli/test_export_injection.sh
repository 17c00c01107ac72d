#!/usr/bin/env bash
# sss export pbrt with names that hold PBRT syntax: an environment map and a texture whose file names
# hold a quote and newlines followed by directives, and an -o path with a quote. The .pbrt must
# tokenize under PBRT-v3's lexical rules (src/core/parser.cpp of PBRT-v3: a string ends at an
# unescaped quote and may not hold a raw newline; escapes \b \f \n \r \t \\ \' \"; a comment runs to
# the end of the line) into exactly the directives of the scene, with every string decoding to the
# original name.
# Usage: bash test_export_injection.sh <sss-binary> <repo-root>
SSS=$1; ROOT=$2
fail=0
err() { echo "FAIL: $*"; fail=1; }
dir=$(mktemp -d); trap 'rm -rf "$dir"' EXIT
command -v python3 >/dev/null || { echo "python3 missing"; exit 1; }

env_name=$'sky"]\nLightSource "point" "rgb I" [9 9 9]\n#.hdr'
tex_name=$'tex\nShape "sphere"\n.png'
out_name='o"ut.pbrt'
cp "$ROOT/scenes/gl_sky.hdr" "$dir/$env_name"
cp "$ROOT/tests/data/images/base.png" "$dir/$tex_name"
python3 - "$dir/scene.json" "$env_name" "$tex_name" "$ROOT/tests/data/meshes/tetra_normals_uv.ply" <<'PY'
import json, sys
scene = {
    "camera": {"position": [0, 0.5, 3], "look_at": [0, 0, 0], "fov": 40, "width": 16, "height": 16},
    "objects": [{"mesh": sys.argv[4],
                 "material": {"type": "subsurface", "medium": "Marble", "scale": 10, "texture": sys.argv[3]}}],
    "lights": [{"type": "environment", "file": sys.argv[2]}],
}
json.dump(scene, open(sys.argv[1], "w"))
PY

"$SSS" export pbrt "$dir/scene.json" -o "$dir/$out_name" >/dev/null 2>"$dir/stderr" || err "export failed: $(cat "$dir/stderr")"
python3 - "$dir/$out_name" "$dir/$env_name" "$tex_name" "${out_name%.pbrt}" <<'PY' || err "the .pbrt does not tokenize to the scene's directives"
import os, sys
path, env_path, tex_name, stem = sys.argv[1:]
text = open(path, "rb").read().decode("latin-1")
ESC = {"b": "\b", "f": "\f", "n": "\n", "r": "\r", "t": "\t", "\\": "\\", "'": "'", '"': '"'}

def tokens(s):
    """PBRT-v3's lexical rules, written from its documented behaviour: (kind, value) pairs."""
    i, n = 0, len(s)
    while i < n:
        c = s[i]
        if c in " \n\t\r":
            i += 1
        elif c == '"':
            i += 1
            out = []
            while True:
                if i >= n: raise SystemExit("premature end of file in a string")
                c = s[i]
                if c == '"': break
                if c == "\n": raise SystemExit("unterminated string (raw newline)")
                if c == "\\":
                    i += 1
                    if i >= n or s[i] not in ESC: raise SystemExit("bad escape")
                    out.append(ESC[s[i]])
                else:
                    out.append(c)
                i += 1
            i += 1
            yield "string", "".join(out)
        elif c in "[]":
            i += 1
            yield "bracket", c
        elif c == "#":
            j = i
            while j < n and s[j] not in "\n\r": j += 1
            yield "comment", s[i:j]
            i = j
        else:
            j = i
            while j < n and s[j] not in ' \n\t\r"[]': j += 1
            yield "word", s[i:j]
            i = j

toks = list(tokens(text))
directives = [v for k, v in toks if k == "word" and v[:1].isalpha()]
expected = ["Scale", "LookAt", "Camera", "Film", "Sampler", "Integrator", "WorldBegin",
            "AttributeBegin", "Transform", "LightSource", "AttributeEnd",
            "AttributeBegin", "Material", "Shape", "AttributeEnd", "WorldEnd"]
if directives != expected:
    raise SystemExit("directives %r, expected %r" % (directives, expected))
strings = [v for k, v in toks if k == "string"]
want = [os.path.realpath(env_path), stem + ".exr", stem + "_obj0.ply"]
for w in want:
    if w not in strings: raise SystemExit("no string decoding to %r in %r" % (w, strings))
comments = [v for k, v in toks if k == "comment"]
if not any("tex" in c and "not exported" in c for c in comments):
    raise SystemExit("the texture's comment is missing or was cut: %r" % comments)
PY
[ -f "$dir/${out_name%.pbrt}_obj0.ply" ] || err "the mesh beside the .pbrt is missing"
exit $fail
