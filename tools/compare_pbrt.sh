#!/bin/sh
# tools/compare_pbrt.sh — compares `sss reference` with PBRT-v3's path tracer at matching depth
# (docs/reference.md, "Against PBRT-v3"). Contains no PBRT code: it needs a pbrt binary you built.
#
#   tools/compare_pbrt.sh PBRT [--sss SSS] [--out DIR] [--scale F] [--spp N] [--depths "1 2 3 16"]
#                         [--noise] [SCENE.json[@T] ...]
#
# For every scene (default: the eval scenes without an environment map) it writes a copy with the
# camera size times F (default 0.375: 512x288 -> 192x108, 384x384 -> 144x144), then for every depth D:
#   sss export pbrt --maxdepth D, PBRT renders it (nice -n 10) to a PFM;
#   sss reference --bounces D (D = 16: the default, bounces until converged) to a PFM, with --specular
#   from D = 2 on (PBRT's path tracer always follows the camera ray's mirror reflection off a
#   subsurface interface; the reflected ray sees a lit surface from depth 2 on);
# and prints one row: mean linear R/G/B of the reference as a fraction of PBRT's, and the DSSIM of
# `sss compare`. --noise adds PBRT's own noise floor at the largest depth: the DSSIM between its
# halton image and a second render with the independent "random" sampler at the same spp.
# Everything goes to DIR (default out/compare_pbrt); rerunning reuses the PBRT images already there.
set -eu

usage() { sed -n '4,6p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
[ $# -ge 1 ] || usage
PBRT=$1
shift
ROOT=$(cd "$(dirname "$0")/.." && pwd)
SSS=$ROOT/build/sss
OUT=out/compare_pbrt
SCALE=0.375
SPP=1024
DEPTHS="1 2 3 16"
NOISE=0
SCENES=""
while [ $# -gt 0 ]; do
    case $1 in
    --sss) SSS=$2; shift 2 ;;
    --out) OUT=$2; shift 2 ;;
    --scale) SCALE=$2; shift 2 ;;
    --spp) SPP=$2; shift 2 ;;
    --depths) DEPTHS=$2; shift 2 ;;
    --noise) NOISE=1; shift ;;
    -h | --help) usage ;;
    -*) echo "compare_pbrt.sh: unknown option $1" >&2; exit 2 ;;
    *) SCENES="$SCENES $1"; shift ;;
    esac
done
[ -x "$PBRT" ] || { echo "compare_pbrt.sh: $PBRT is not an executable" >&2; exit 2; }
[ -x "$SSS" ] || { echo "compare_pbrt.sh: $SSS is not an executable (build sss or pass --sss)" >&2; exit 2; }
if [ -z "$SCENES" ]; then
    for s in eval_backlit eval_front eval_dragon eval_trefoil_low eval_trefoil_high eval_twist.json@1; do
        case $s in *.json@*) SCENES="$SCENES $ROOT/scenes/$s" ;; *) SCENES="$SCENES $ROOT/scenes/$s.json" ;; esac
    done
fi
MAXDEPTH=$(echo "$DEPTHS" | tr ' ' '\n' | sort -n | tail -n 1)
mkdir -p "$OUT"

# The scene at F times its camera size, its paths made absolute (they are relative to its folder).
shrink() {
    python3 - "$1" "$2" "$SCALE" <<'EOF'
import json, os, sys
src, dst, f = sys.argv[1], sys.argv[2], float(sys.argv[3])
scene = json.load(open(src))
folder = os.path.dirname(os.path.abspath(src))
def absolute(node):
    if isinstance(node, dict):
        for k, v in node.items():
            if k in ("mesh", "splat_mesh", "texture", "file") and isinstance(v, str) and not os.path.isabs(v):
                node[k] = os.path.normpath(os.path.join(folder, v))
            else:
                absolute(v)
    elif isinstance(node, list):
        for v in node:
            absolute(v)
absolute(scene)
cam = scene["camera"]
cam["width"], cam["height"] = round(cam.get("width", 512) * f), round(cam.get("height", 512) * f)
json.dump(scene, open(dst, "w"), indent=1)
EOF
}

# Mean linear R/G/B of a PFM (finite values only), three numbers.
pfm_mean() {
    python3 - "$1" <<'EOF'
import struct, sys, math
data = open(sys.argv[1], "rb").read()
parts, pos = [], 0
while len(parts) < 4:  # "PF", width, height, scale (whitespace separated)
    while data[pos:pos + 1].isspace(): pos += 1
    end = pos
    while not data[end:end + 1].isspace(): end += 1
    parts.append(data[pos:end].decode()); pos = end
pos += 1
w, h, scale = int(parts[1]), int(parts[2]), float(parts[3])
n = w * h * 3
vals = struct.unpack(("<" if scale < 0 else ">") + "%df" % n, data[pos:pos + 4 * n])
s = [0.0, 0.0, 0.0]
for i, v in enumerate(vals):
    if math.isfinite(v): s[i % 3] += v
print(" ".join("%.6g" % (x / (w * h)) for x in s))
EOF
}

ratio() { # "a b c" "x y z" -> "a/x/b/y/c/z" as 0.00/0.00/0.00
    echo "$1 $2" | awk '{ printf "%.2f/%.2f/%.2f", ($4 > 0 ? $1 / $4 : 0), ($5 > 0 ? $2 / $5 : 0), ($6 > 0 ? $3 / $6 : 0) }'
}

ROW="%-22s %5s %12s %-16s %8s\n" # scene, depth, bounces, mean R/G/B ratio, DSSIM
# shellcheck disable=SC2059
printf "$ROW" scene depth bounces "mean R/G/B" dssim
for spec in $SCENES; do
    scene=${spec%@*}
    time_opt=""
    tag=$(basename "$scene" .json)
    if [ "$spec" != "$scene" ]; then time_opt="--time ${spec##*@}"; tag="${tag}_t${spec##*@}"; fi
    small=$OUT/$tag.json
    shrink "$scene" "$small"
    for d in $DEPTHS; do
        base=$OUT/${tag}_d$d
        if [ ! -s "$base.pbrt.pfm" ]; then
            # shellcheck disable=SC2086
            "$SSS" export pbrt "$small" -o "$base.pbrt" --maxdepth "$d" --spp "$SPP" $time_opt
            nice -n 10 "$PBRT" --quiet --outfile "$base.pbrt.pfm" "$base.pbrt"
        fi
        bounces_opt="--bounces $d" bounces=$d mine=$base.sss
        if [ "$d" = "$MAXDEPTH" ] && [ "$d" -ge 16 ]; then bounces_opt="" bounces=default; fi
        if [ "$d" -ge 2 ]; then bounces_opt="$bounces_opt --specular" bounces="$bounces+spec" mine=$base.sss_spec; fi
        if [ ! -s "$mine.pfm" ]; then
            # shellcheck disable=SC2086
            "$SSS" reference "$small" -o "$mine.png" --pfm "$mine.pfm" --quiet $bounces_opt $time_opt
        fi
        dssim=$("$SSS" compare "$mine.pfm" "$base.pbrt.pfm" | sed 's/.*dssim=\([^ ]*\).*/\1/')
        # shellcheck disable=SC2059
        printf "$ROW" "$tag" "$d" "$bounces" \
            "$(ratio "$(pfm_mean "$mine.pfm")" "$(pfm_mean "$base.pbrt.pfm")")" "$dssim"
    done
    if [ "$NOISE" = 1 ]; then
        base=$OUT/${tag}_d$MAXDEPTH
        if [ ! -s "$base.random.pfm" ]; then
            sed 's/^Sampler "halton"/Sampler "random"/' "$base.pbrt" >"$base.random.pbrt"
            nice -n 10 "$PBRT" --quiet --outfile "$base.random.pfm" "$base.random.pbrt"
        fi
        dssim=$("$SSS" compare "$base.random.pfm" "$base.pbrt.pfm" | sed 's/.*dssim=\([^ ]*\).*/\1/')
        # shellcheck disable=SC2059
        printf "$ROW" "$tag" "$MAXDEPTH" "noise" \
            "$(ratio "$(pfm_mean "$base.random.pfm")" "$(pfm_mean "$base.pbrt.pfm")")" "$dssim"
    fi
done
