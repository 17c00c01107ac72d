#!/usr/bin/env bash
# bench/gpu/run.sh — frame times and GPU memory of every technique on a machine with a GPU
# (docs/performance.md says how to run it there and what it measures).
#
#   bench/gpu/run.sh bundle BUILD_DIR BUNDLE_DIR       here: what must travel, in one folder
#   bench/gpu/run.sh run BUNDLE_DIR OUT_DIR [--small]  there (or here with --small, on llvmpipe)
#   bench/gpu/run.sh check OUT_DIR [--small]           the outputs complete and well-formed
#
# bundle: bench_techniques (linked to libsss.a: no Embree), the shared libraries `ldd` lists for it
# except glibc and the GL loaders (libEGL, libGL, libOpenGL, libGLX, libGLdispatch, libGLES: they come
# with the target's driver, or from .gl/ as the device tool's README says), the two evaluation scenes
# and the meshes they name, this script and a MANIFEST. Shaders are embedded in the binary. Fails when
# the folder, or the folder together with the checkout's files that travel with it, exceeds 64 MiB.
# run: every technique on scenes/eval_front.json (front-lit Skin1 head) and scenes/eval_backlit.json
# (back-lit Skimmilk dragon) at 960x540, 1920x1080 and 3840x2160: 10 warm-up frames, then up to 50
# timed frames or 2 s of them (at least 3), medians per pass (GL_TIME_ELAPSED on a GPU) and of the wall
# clock; writes OUT_DIR/bench.tsv, bench.json, bench.log, env.txt and images.tar (each technique at
# 960x540, to compare with llvmpipe's), then checks them. The bench is stopped after 420 s (the files
# hold every row finished by then). --small: one scene, 96x54, 1 warm-up and 2 timed frames.
set -u -o pipefail

LIMIT=$((64 * 1024 * 1024))
SCENES="scenes/eval_front.json scenes/eval_backlit.json"
SMALL_SCENES="scenes/eval_front.json"
SIZES="960x540 1920x1080 3840x2160"
SMALL_SIZES="96x54"
BENCH_SECONDS=420
MARKER=.sss-gpu-bundle
SELF=$(realpath "$0")

die() {
    echo "run.sh: $*" >&2
    exit 1
}

usage() {
    sed -n '5,7p' "$SELF" | sed 's/^# *//' >&2
    exit 2
}

# glibc and the GL loaders: the target machine's own (a different glibc or GL dispatch would not match
# its driver).
is_system_lib() {
    case "$1" in
    ld-linux* | libc.so* | libm.so* | libdl.so* | libpthread.so* | librt.so* | libresolv.so* | libutil.so* | \
        libmvec.so* | libanl.so*) return 0 ;;
    libEGL.so* | libGL.so* | libGLX*.so* | libGLdispatch.so* | libOpenGL.so* | libGLESv*.so*) return 0 ;;
    esac
    return 1
}

copy_libs() { # EXE LIBDIR
    local name arrow path rest
    while read -r name arrow path rest; do
        [ "$arrow" = "=>" ] || continue # linux-vdso, the dynamic loader
        [ "$path" != "not" ] || die "$1 needs $name, which ldd does not find"
        is_system_lib "$name" || cp -L "$path" "$2/$name" || die "cannot copy $path"
    done < <(ldd "$1" || die "ldd $1 failed")
}

# The scene and every file it names (meshes, textures, environment maps), at the same relative paths.
copy_scene() { # ROOT REL BUNDLE
    local src="$1/$2" ref to inside
    [ -f "$src" ] || die "$src: no such scene"
    install -D -m 644 "$src" "$3/$2" || die "cannot copy $src"
    inside=$(realpath -m "$3")
    while read -r ref; do
        [ -n "$ref" ] || continue
        case "$ref" in /*) die "$src: $ref is an absolute path: the bundle needs paths relative to the scene" ;; esac
        to=$(realpath -m "$(dirname "$3/$2")/$ref")
        case "$to" in "$inside"/*) ;; *) die "$src: $ref lies outside the bundle" ;; esac
        [ -f "$(dirname "$src")/$ref" ] || die "$src: $ref: no such file"
        install -D -m 644 "$(dirname "$src")/$ref" "$to" || die "cannot copy $ref"
    done < <(grep -o '"[^"]*\.\(ply\|obj\|glb\|gltf\|bin\|hdr\|exr\|pfm\|png\|jpg\|jpeg\|sam\)"' "$src" | tr -d '"' | sort -u)
}

# Bytes of the checkout that travel with the bundle: tracked and untracked-not-ignored files, and .gl/.
checkout_bytes() { # ROOT
    local n=0
    if git -C "$1" rev-parse --is-inside-work-tree > /dev/null 2>&1; then
        n=$(cd "$1" && git ls-files -z --cached --others --exclude-standard | xargs -0 -r stat -L -c %s 2> /dev/null |
            awk '{s += $1} END {print s + 0}')
    fi
    [ -d "$1/.gl" ] && n=$((n + $(du -sb "$1/.gl" | cut -f1)))
    echo "$n"
}

bundle() { # BUILD_DIR BUNDLE_DIR
    local build=$1 out=$2 root exe bytes travel s
    root=$(cd "$(dirname "$SELF")/../.." && pwd)
    exe="$build/bench/bench_techniques"
    [ -x "$exe" ] || die "$exe: not built (cmake --build $build --target bench_techniques)"
    if [ -e "$out" ] && [ ! -f "$out/$MARKER" ] && [ -n "$(ls -A "$out" 2> /dev/null)" ]; then
        die "$out exists and is no bundle: not overwriting it"
    fi
    { rm -rf "$out" && mkdir -p "$out/bin" "$out/lib"; } || die "cannot create $out"
    touch "$out/$MARKER"
    { cp "$exe" "$out/bin/" && cp "$SELF" "$out/run.sh"; } || die "cannot copy into $out"
    copy_libs "$out/bin/bench_techniques" "$out/lib"
    for s in $SCENES; do copy_scene "$root" "$s" "$out"; done
    {
        echo "commit $(git -C "$root" rev-parse HEAD 2> /dev/null || echo unknown)$(git -C "$root" diff --quiet 2> /dev/null || echo ' (modified)')"
        echo "made $(date -u +%Y-%m-%dT%H:%M:%SZ) on $(uname -srm), glibc $(ldd --version | head -1 | awk '{print $NF}')"
        (cd "$out" && find . -type f ! -name MANIFEST -printf '%s\t%p\n' | sort -k2)
    } > "$out/MANIFEST"
    bytes=$(du -sb "$out" | cut -f1)
    travel=$((bytes + $(checkout_bytes "$root")))
    echo "bundle $out: $((bytes / 1024)) KiB; with the checkout that travels beside it $((travel / 1024)) KiB (limit $((LIMIT / 1024)))"
    [ "$bytes" -le "$LIMIT" ] || die "$out: $bytes bytes, over the 64 MiB a device call carries"
    [ "$travel" -le "$LIMIT" ] || die "$out with the checkout: $travel bytes, over the 64 MiB a device call carries"
}

env_info() { # BUNDLE
    echo "date $(date -u +%Y-%m-%dT%H:%M:%SZ)"
    echo "host $(uname -srm), $(nproc) CPUs, glibc $(ldd --version 2> /dev/null | head -1 | awk '{print $NF}')"
    if command -v nvidia-smi > /dev/null; then
        nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.max.sm,clocks.max.mem --format=csv 2>&1
    fi
    echo "__EGL_VENDOR_LIBRARY_FILENAMES=${__EGL_VENDOR_LIBRARY_FILENAMES:-}"
    command -v ldconfig > /dev/null && ldconfig -p | grep -E 'libEGL|libGLX|libOpenGL|libGLdispatch|nvidia' | head -20
    echo "--- bundle"
    cat "$1/MANIFEST"
    echo "--- ldd"
    ldd "$1/bin/bench_techniques" 2>&1
}

run() { # BUNDLE_DIR OUT_DIR [--small]
    local b out small=${3:-} scenes sizes args s rc
    [ -f "$1/$MARKER" ] || die "$1: not a bundle (bench/gpu/run.sh bundle BUILD_DIR BUNDLE_DIR makes one)"
    b=$(cd "$1" && pwd)
    { mkdir -p "$2" && out=$(cd "$2" && pwd); } || die "cannot create $2"
    export LD_LIBRARY_PATH="$b/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
    local missing vendor=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
    missing=$(ldd "$b/bin/bench_techniques" 2>&1 | grep "not found")
    [ -z "$missing" ] || die "libraries missing on this machine: $missing"
    # libepoxy opens the GL loaders at run time: the machine's, or .gl/'s unpacked into / (docs/performance.md)
    if command -v ldconfig > /dev/null && ! ldconfig -p | grep 'libEGL\.so\.1' > /dev/null; then
        die "no libEGL.so.1 on this machine: unpack the GL loaders first (docs/performance.md)"
    fi
    # the device tool's NVIDIA machines keep the driver's EGL vendor file outside glvnd's default folders
    if [ -z "${__EGL_VENDOR_LIBRARY_FILENAMES:-}" ] && [ -f "$vendor" ]; then
        export __EGL_VENDOR_LIBRARY_FILENAMES=$vendor
    fi
    if [ "$small" = --small ]; then
        scenes=$SMALL_SCENES sizes=$SMALL_SIZES args=(--warmup 1 --frames 2)
    else
        scenes=$SCENES sizes=$SIZES args=(--warmup 10 --frames 50 --budget 2)
    fi
    for s in $sizes; do args+=(--size "$s"); done
    env_info "$b" > "$out/env.txt" 2>&1
    rm -rf "$out/images" && mkdir -p "$out/images"
    # shellcheck disable=SC2086 # the scene list splits on spaces
    (cd "$b" && timeout "$BENCH_SECONDS" bin/bench_techniques $scenes "${args[@]}" --tsv "$out/bench.tsv" \
        --json "$out/bench.json" --images "$out/images") 2>&1 | tee "$out/bench.log"
    rc=$?
    [ "$rc" -ne 124 ] || echo "run.sh: the bench ran past ${BENCH_SECONDS} s and was stopped; the files hold the rows it finished" >&2
    tar -C "$out" -cf "$out/images.tar" images && rm -rf "$out/images"
    check "$out" "$small" || return 1
    return "$rc"
}

CHECK_TSV=$(
    cat << 'EOF'
function num(x) { return x ~ /^[0-9]+(\.[0-9]+)?([eE][-+]?[0-9]+)?$/ }
function bad(msg) { printf "bench.tsv line %d: %s\n", NR, msg; errors++ }
NR == 1 {
    if ($0 != "scene\ttechnique\twidth\theight\tzoom\tstatus\tframes\twarmup\ttiming_method\tframe_ms\twall_ms\ttechnique_bytes\tframe_bytes\trenderer_bytes\tnvx_bytes\tcreate_s\tpasses\terror")
        bad("unexpected header")
    next
}
{
    if (NF != 18) bad("expected 18 fields, found " NF)
    key = $1 SUBSEP $2 SUBSEP $3 "x" $4
    if (key in seen) bad("a second row for " $1 " " $2 " " $3 "x" $4)
    seen[key] = 1
    found[$2] = 1
    if ($6 != "ok") bad($2 " " $3 "x" $4 ": status " $6 " " $18)
    if (!num($7) || $7 < 1) bad("frames '" $7 "'")
    if (!num($10) || $10 <= 0 || !num($11) || $11 <= 0) bad("frame_ms '" $10 "', wall_ms '" $11 "'")
    if (!num($12) || $12 != int($12) || !num($13) || $13 <= 0 || !num($14) || $14 < $12 + $13) bad("bytes '" $12 "' '" $13 "' '" $14 "'")
    if ($15 != "n/a" && !num($15)) bad("nvx_bytes '" $15 "'")
    n = split($17, passes, ";")
    if (n < 1) bad("no passes")
    for (i = 1; i <= n; i++) {
        split(passes[i], kv, "=")
        if (kv[1] == "" || !num(kv[2])) bad("pass '" passes[i] "'")
    }
    rows++
}
END {
    nt = split(techs, t, " ")
    if (nt == 0) for (name in found) t[++nt] = name
    ns = split(scenes, s, " "); nz = split(sizes, z, " ")
    for (i = 1; i <= nt; i++) for (j = 1; j <= ns; j++) for (k = 1; k <= nz; k++)
        if (!((s[j] SUBSEP t[i] SUBSEP z[k]) in seen)) { printf "bench.tsv: no row for %s %s %s\n", s[j], t[i], z[k]; errors++ }
    if (rows != nt * ns * nz) { printf "bench.tsv: %d rows, expected %d\n", rows, nt * ns * nz; errors++ }
    exit (errors > 0)
}
EOF
)

# Every technique x size x scene has one row (status ok, a positive finite frame and wall time, finite
# non-negative per-pass times, byte counts, n/a or a count for the driver's view) and bench.json holds
# the same rows. The techniques: $SSS_EXPECT_TECHNIQUES (names separated by spaces), else those in the TSV.
check() { # OUT_DIR [--small]
    local out=$1 scenes=$SCENES sizes=$SIZES
    [ "${2:-}" = --small ] && scenes=$SMALL_SCENES sizes=$SMALL_SIZES
    { [ -f "$out/bench.tsv" ] && [ -f "$out/bench.json" ]; } || die "$out: bench.tsv or bench.json missing"
    awk -F'\t' -v scenes="$scenes" -v sizes="$sizes" -v techs="${SSS_EXPECT_TECHNIQUES:-}" "$CHECK_TSV" \
        "$out/bench.tsv" || return 1
    if command -v python3 > /dev/null; then
        python3 - "$out/bench.json" "$out/bench.tsv" << 'EOF' || return 1
import csv, json, math, sys
doc = json.load(open(sys.argv[1]))
tsv = list(csv.DictReader(open(sys.argv[2]), delimiter="\t"))
rows = doc["rows"]
assert doc["gl_renderer"] and doc["gl_version"], "GL strings missing"
assert len(rows) == len(tsv), f"{len(rows)} rows in bench.json, {len(tsv)} in bench.tsv"
for j, t in zip(rows, tsv):
    assert (j["scene"], j["technique"], str(j["width"]), str(j["height"])) == \
        (t["scene"], t["technique"], t["width"], t["height"]), f"rows differ: {j['technique']} / {t['technique']}"
    assert j["status"] == "ok" and math.isfinite(j["frame_ms"]) and j["frame_ms"] > 0, j
    assert abs(j["frame_ms"] - float(t["frame_ms"])) <= 1e-6 * j["frame_ms"], (j["frame_ms"], t["frame_ms"])
    assert all(math.isfinite(p["ms"]) and p["ms"] >= 0 for p in j["passes"]) and j["passes"], j["passes"]
    assert j["nvx_bytes"] == "n/a" or isinstance(j["nvx_bytes"], int), j["nvx_bytes"]
EOF
    fi
    echo "run.sh: $out: complete"
}

case "${1:-} $#" in
"bundle 3") bundle "$2" "$3" ;;
"run 3") run "$2" "$3" ;;
"run 4") [ "$4" = --small ] || usage; run "$2" "$3" --small ;;
"check 2") check "$2" ;;
"check 3") [ "$3" = --small ] || usage; check "$2" --small ;;
*) usage ;;
esac
