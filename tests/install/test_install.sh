#!/usr/bin/env bash
# sss as an installed library: `cmake --install` into a temporary prefix, then the examples (the copy
# installed in share/doc/sss/examples) built out of tree against that prefix four ways: find_package
# with sss::sss and with sss::sss_static, pkg-config, and pkg-config --static with libsss.a. Each
# program runs and its output is compared with the installed `sss` tool's for the same input and
# settings. Both call the same library functions on the same input (the reference is deterministic for
# a seed, llvmpipe for a scene), so the files must be identical: profile TSV, LUT EXR, render PNG,
# reference PNG.
# Usage: bash test_install.sh <build-dir> <repo-root>
set -u
BUILD=$1
ROOT=$2
. "$(dirname "${BASH_SOURCE[0]}")/../cli/harness.sh"
P=$T/prefix
cmake --install "$BUILD" --prefix "$P" >"$T/install.log" 2>&1 || { cat "$T/install.log"; echo "FAIL: cmake --install"; exit 1; }
pc=$(find "$P" -name sss.pc 2>/dev/null | head -1)
[ -n "$pc" ] || { echo "FAIL: cmake --install installed no sss.pc: $(find "$P" 2>/dev/null | head)"; exit 1; }
libdir=$(cd "$(dirname "$pc")/.." && pwd)  # lib or lib/<multiarch>
SSS=$P/bin/sss
EXAMPLES=$P/share/doc/sss/examples
export PKG_CONFIG_PATH=$libdir/pkgconfig

# The installed tree: headers (with the generated version.h), both libraries, the tool and its bash
# completion, the CMake package, sss.pc, the docs and examples.
for f in include/sss/sss.h include/sss/version.h bin/sss share/bash-completion/completions/sss share/doc/sss/limits.md \
    share/doc/sss/examples/CMakeLists.txt; do
    [ -f "$P/$f" ] || fail "not installed: $f"
done
for f in libsss.a libsss.so pkgconfig/sss.pc cmake/sss/sssConfig.cmake cmake/sss/sssConfigVersion.cmake; do
    [ -e "$libdir/$f" ] || fail "not installed: $(basename "$libdir")/$f"
done
major=$(sed -n 's/^#define SSS_VERSION_MAJOR \([0-9]*\)$/\1/p' "$P/include/sss/version.h")
[ -n "$major" ] && [ -e "$libdir/libsss.so.$major" ] || fail "no libsss.so.MAJOR (MAJOR '$major')"
readelf -d "$libdir/libsss.so" | grep -q "SONAME.*\[libsss.so.$major\]" || fail "libsss.so's SONAME is not libsss.so.$major"
# Nothing installed points back into the build tree (the tool must run with it gone).
for f in "$SSS" "$libdir"/libsss.so.*.*; do
    ! readelf -d "$f" | grep -Eq 'RPATH|RUNPATH' || fail "$f keeps a run path: $(readelf -d "$f" | grep -E 'RPATH|RUNPATH')"
done
# libsss.so exports exactly the functions and data the installed headers declare, all in sss_
# (internal helpers such as gl_check or sss_read_file must not clash with a program's symbols).
if command -v python3 >/dev/null; then
    python3 "$ROOT/tests/install/check_exports.py" "$libdir/libsss.so" "$P/include" >"$T/exports.txt" ||
        fail "installed libsss.so against the installed headers: $(cat "$T/exports.txt")"
else
    echo "note: no python3, the exported symbols are not checked"
fi
# The tool, the pkg-config file and the CMake package report the project's version (CMakeLists.txt).
project_version=$(sed -n 's/^project(sss VERSION \([0-9.]*\) .*/\1/p' "$ROOT/CMakeLists.txt")
[ "$("$SSS" --version)" = "sss $project_version" ] || fail "sss --version: '$("$SSS" --version)', project $project_version"
[ "$(pkg-config --modversion sss)" = "$project_version" ] || fail "sss.pc version $(pkg-config --modversion sss)"

# A small scene: a translucent sphere on a diffuse floor, 64 x 64.
cat >"$T/scene.json" <<'EOF'
{
  "camera": {"position": [0, 0.8, 3], "look_at": [0, 0, 0], "fov": 35, "width": 64, "height": 64},
  "objects": [
    {"procedural": {"shape": "sphere", "radius": 0.6, "subdivisions": 3},
     "material": {"type": "subsurface", "medium": "Marble", "scale": 10.0, "eta": 1.33}},
    {"procedural": {"shape": "plane", "size": 6}, "transform": {"translate": [0, -0.6, 0]},
     "material": {"type": "diffuse", "reflectance": [0.5, 0.5, 0.5]}}
  ],
  "lights": [{"type": "point", "position": [1.5, 2, -1.5], "intensity": [8, 8, 8]}],
  "render": {"technique": "maisch2020", "exposure": 0}
}
EOF
# What the installed tool makes of it.
mkdir -p "$T/tool"
"$SSS" profile Marble --r 0:2:5 >"$T/tool/profile.tsv" || fail "sss profile"
"$SSS" lut Marble --size 64 -o "$T/tool/lut.exr" >/dev/null || fail "sss lut"
"$SSS" render "$T/scene.json" --technique ssss -o "$T/tool/render.png" || fail "sss render"
"$SSS" reference "$T/scene.json" --quality draft --quiet -o "$T/tool/reference.png" || fail "sss reference"

# Runs the three examples of directory $1 (a build) and compares their files with the tool's.
check_examples() {
    local bin=$1 name=$2 out=$T/out-$2
    mkdir -p "$out"
    for e in lut render reference; do
        [ -x "$bin/example_$e" ] || { fail "$name: example_$e was not built"; return; }
    done
    "$bin/example_lut" Marble "$out/lut.exr" 64 >"$out/profile.tsv" || fail "$name: example_lut failed"
    "$bin/example_render" "$T/scene.json" ssss "$out/render.png" || fail "$name: example_render failed"
    "$bin/example_reference" "$T/scene.json" "$out/reference.png" draft 2>/dev/null ||
        fail "$name: example_reference failed"
    for f in profile.tsv lut.exr render.png reference.png; do
        cmp -s "$T/tool/$f" "$out/$f" || fail "$name: $f differs from the sss tool's ($("$SSS" compare "$T/tool/$f" "$out/$f" 2>&1))"
    done
    # A bad input is an error naming it, not a crash.
    "$bin/example_render" "$T/missing.json" ssss "$out/x.png" 2>"$out/err.txt"
    [ $? -eq 1 ] && grep -q missing.json "$out/err.txt" || fail "$name: example_render on a missing scene: $(cat "$out/err.txt")"
    [ ! -e "$out/x.png" ] || fail "$name: example_render wrote an image for a missing scene"
}

# 1-2. CMake, find_package(sss CONFIG REQUIRED): sss::sss (libsss.so), then sss::sss_static (libsss.a).
for variant in shared static; do
    static=OFF
    [ $variant = static ] && static=ON
    b=$T/cmake-$variant
    if cmake -S "$EXAMPLES" -B "$b" -DCMAKE_PREFIX_PATH="$P" -DSSS_EXAMPLES_STATIC=$static >"$T/cmake-$variant.log" 2>&1 &&
        cmake --build "$b" >>"$T/cmake-$variant.log" 2>&1; then
        check_examples "$b" "find_package $variant"
    else
        fail "find_package $variant: the examples did not build: $(tail -20 "$T/cmake-$variant.log")"
    fi
done
readelf -d "$T/cmake-shared/example_lut" | grep -q 'NEEDED.*libsss\.so' || fail "sss::sss does not link libsss.so"
! readelf -d "$T/cmake-static/example_lut" | grep -q 'NEEDED.*libsss\.so' || fail "sss::sss_static links libsss.so"

# 3. pkg-config --cflags --libs sss: libsss.so, with a strict C11 compiler that the public headers pass.
CFLAGS="-std=c11 -Wall -Wextra -Wpedantic -Werror"
b=$T/pc-shared
mkdir -p "$b"
for e in lut render reference; do
    # shellcheck disable=SC2046,SC2086
    cc $CFLAGS "$EXAMPLES/$e.c" -o "$b/example_$e" $(pkg-config --cflags --libs sss) -Wl,-rpath,"$libdir" \
        2>"$b/$e.log" || fail "pkg-config: example_$e did not build: $(cat "$b/$e.log")"
done
check_examples "$b" "pkg-config"

# 4. pkg-config --static: libsss.a (found first, in a directory that holds only it) with the
# dependencies of Requires.private and Libs.private.
b=$T/pc-static
mkdir -p "$b/lib"
ln -s "$libdir/libsss.a" "$b/lib/libsss.a"
for e in lut render reference; do
    # shellcheck disable=SC2046,SC2086
    cc $CFLAGS "$EXAMPLES/$e.c" -o "$b/example_$e" -L"$b/lib" $(pkg-config --static --cflags --libs sss) \
        2>"$b/$e.log" || fail "pkg-config --static: example_$e did not build: $(cat "$b/$e.log")"
done
! readelf -d "$b/example_lut" 2>/dev/null | grep -q 'NEEDED.*libsss\.so' || fail "pkg-config --static: linked libsss.so"
check_examples "$b" "pkg-config --static"

[ $fails -eq 0 ] || { echo "$fails failure(s)"; exit 1; }
echo "install: OK"
