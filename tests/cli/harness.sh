# tests/cli/harness.sh — sourced by the shell tests (tests/cli/test_*.sh, tests/install/): a temporary
# folder $T removed on exit, and fail MESSAGE, which prints "FAIL: MESSAGE" and counts it in $fails.
# The test ends with: [ "$fails" -eq 0 ] (or its own summary of $fails).
# find_python MODULES: PY = the first of /usr/bin/python3, python3 that imports MODULES ("json, csv"),
# else empty (the test then skips what needs it).
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fails=0
fail() {
    echo "FAIL: $*"
    fails=$((fails + 1))
}
find_python() {
    PY=""
    local p
    for p in /usr/bin/python3 python3; do
        if command -v "$p" >/dev/null 2>&1 && "$p" -c "import $1" 2>/dev/null; then PY=$p; return; fi
    done
}

# write_ball_scene FILE REFLECTANCE [RENDER]: a Marble ball (64 x 64) on a diffuse floor of the given
# grey reflectance under a point light; RENDER, when given, is the scene's "render" object.
write_ball_scene() {
    local render=""
    [ $# -ge 3 ] && render=",
  \"render\": $3"
    cat >"$1" <<EOF
{
  "camera": {"position": [0, 1.2, 4], "look_at": [0, 0.4, 0], "fov": 35, "width": 64, "height": 64},
  "objects": [
    {"procedural": {"shape": "sphere", "radius": 0.6, "subdivisions": 3},
     "transform": {"translate": [0, 0.6, 0]},
     "material": {"type": "subsurface", "medium": "Marble", "scale": 20.0}},
    {"procedural": {"shape": "plane", "size": 8}, "material": {"type": "diffuse", "reflectance": [$2, $2, $2]}}
  ],
  "lights": [{"type": "point", "position": [1.5, 3, -1.5], "intensity": [6, 6, 6]}]$render
}
EOF
}
