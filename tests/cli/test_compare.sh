#!/usr/bin/env bash
# sss compare: output format, agreement with scikit-image's numbers (tests/data/images/
# ssim_reference.txt, from tools/ssim_reference.py) and NVIDIA's FLIP (tests/data/flip), exit codes and
# messages, the --map file.
# Usage: bash test_compare.sh <sss-binary> <repo-root>
set -u
SSS=$1
ROOT=$2
D=$ROOT/tests/data/images
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fails=0
fail() { echo "FAIL: $*" >&2; fails=$((fails + 1)); }

# run ARGS...: sets rc, out, err
run() {
    "$SSS" compare "$@" >"$T/out" 2>"$T/err"
    rc=$?
    out=$(cat "$T/out")
    err=$(cat "$T/err")
}

# Identical files: exactly one line, DSSIM 0, PSNR inf.
run "$D/base.png" "$D/base.png"
[ "$rc" -eq 0 ] || fail "identical: exit $rc ($err)"
[ "$(wc -l <"$T/out")" -eq 1 ] || fail "identical: expected one line, got: $out"
case "$out" in "dssim=0.000000 psnr=inf rmse=0.0000"*) ;; *) fail "identical: got '$out'" ;; esac
run "$D/base.png" "$D/base.png" --exposure 3
case "$out" in "dssim=0.000000 psnr=inf rmse=0.0000"*) ;; *) fail "identical at exposure 3: got '$out'" ;; esac

# Against scikit-image: the printed numbers equal the reference rounded to the printed digits.
while read -r tag a b ssim psnr rmse maxd; do
    [ "$tag" = pair ] || continue
    expect=$(awk -v s="$ssim" -v p="$psnr" -v r="$rmse" -v m="$maxd" \
        'BEGIN { printf "dssim=%.6f psnr=%.3f rmse=%.4f max=%d", (1 - s) / 2, p, r, m }')
    run "$D/$a" "$D/$b"
    [ "$rc" -eq 0 ] || fail "$a $b: exit $rc ($err)"
    case "$out" in "$expect flip="*) ;; *) fail "$a vs $b: got '$out', scikit-image gives '$expect'" ;; esac
    npairs=$((${npairs:-0} + 1))
done <"$D/ssim_reference.txt"
[ "${npairs:-0}" -ge 5 ] || fail "reference pairs not found"

# FLIP against NVIDIA's reference implementation (tests/data/flip/flip_reference.txt) at the default 67 ppd.
nflip=0
while read -r tag a b ppd mean; do
    [ "$tag" = flip ] && [ "$ppd" != 20 ] || continue
    run "$ROOT/tests/data/$a" "$ROOT/tests/data/$b"
    got=$(printf '%s\n' "$out" | sed -n 's/.* flip=\([0-9.]*\)$/\1/p')
    awk -v g="$got" -v m="$mean" 'BEGIN { exit !(g != "" && (g - m) ^ 2 < 2e-5 ^ 2) }' ||
        fail "$a vs $b: flip '$got', NVIDIA's FLIP gives $mean"
    nflip=$((nflip + 1))
done <"$ROOT/tests/data/flip/flip_reference.txt"
[ "$nflip" -eq 6 ] || fail "FLIP reference pairs not found ($nflip)"
case "$("$SSS" compare "$D/base.png" "$D/base.png")" in *" flip=0.000000") ;; *) fail "FLIP of identical images is not 0" ;; esac

# Different sizes: exit 1 naming both sizes.
run "$D/base.png" "$D/small_a.png"
[ "$rc" -eq 1 ] || fail "sizes: exit $rc"
case "$err" in *64x48*23x17*) ;; *) fail "sizes: message '$err'" ;; esac
[ -z "$out" ] || fail "sizes: stdout not empty: $out"

# Missing, malformed: exit 1 naming the file.
run "$D/base.png" "$T/missing.png"
[ "$rc" -eq 1 ] || fail "missing: exit $rc"
case "$err" in *"$T/missing.png"*) ;; *) fail "missing: message '$err'" ;; esac
echo "not an image" >"$T/text.png"
run "$T/text.png" "$D/base.png"
[ "$rc" -eq 1 ] || fail "malformed: exit $rc"
case "$err" in *"$T/text.png"*) ;; *) fail "malformed: message '$err'" ;; esac
head -c 1000 "$D/base.png" >"$T/cut.png"
run "$D/base.png" "$T/cut.png"
[ "$rc" -eq 1 ] || fail "truncated: exit $rc"
case "$err" in *"$T/cut.png"*) ;; *) fail "truncated: message '$err'" ;; esac

# Usage errors: exit 2.
for args in "" "$D/base.png" "$D/base.png $D/base.png $D/base.png" "--bogus $D/base.png $D/base.png" \
    "$D/base.png $D/base.png --exposure" "$D/base.png $D/base.png --exposure abc" \
    "$D/base.png $D/base.png --map $T/map.jpg" "$D/base.png $D/base.png --map-scale -1"; do
    # shellcheck disable=SC2086
    run $args
    [ "$rc" -eq 2 ] || fail "usage '$args': exit $rc"
done
run --help
[ "$rc" -eq 0 ] && [ -n "$out" ] || fail "--help: exit $rc"

# --map writes a 64x48 PNG (signature and IHDR size checked on the bytes); raw maps as EXR.
run "$D/base.png" "$D/noise.png" --map "$T/map.png"
[ "$rc" -eq 0 ] || fail "map: exit $rc ($err)"
[ "$(head -c 8 "$T/map.png" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] || fail "map: not a PNG"
[ "$(od -An -tu1 -j16 -N8 "$T/map.png" | tr -s ' ' | sed 's/^ //')" = "0 0 0 64 0 0 0 48" ] || fail "map: not 64x48"
run "$D/base.png" "$D/noise.png" --map "$T/map.exr"
[ "$rc" -eq 0 ] && [ -s "$T/map.exr" ] || fail "map exr: exit $rc ($err)"
# The raw DSSIM map of identical images is all zeros (PFM: 12-byte header, then 64 * 48 * 12 zero bytes).
run "$D/base.png" "$D/base.png" --map "$T/zero.pfm"
[ "$rc" -eq 0 ] || fail "zero map: exit $rc ($err)"
[ "$(head -c 12 "$T/zero.pfm" | tr '\n' ' ')" = "PF 64 48 -1 " ] || fail "zero map: header"
[ "$(tail -c +13 "$T/zero.pfm" | wc -c)" -eq 36864 ] || fail "zero map: size"
[ "$(tail -c +13 "$T/zero.pfm" | tr -d '\000' | wc -c)" -eq 0 ] || fail "zero map: not all zero"
# No map when the comparison fails.
run "$D/base.png" "$D/small_a.png" --map "$T/never.png"
[ "$rc" -eq 1 ] && [ ! -e "$T/never.png" ] || fail "map written although sizes differ"
# A map into a missing folder: exit 1, nothing written.
run "$D/base.png" "$D/noise.png" --map "$T/nofolder/map.png"
[ "$rc" -eq 1 ] || fail "map into missing folder: exit $rc"
[ ! -e "$T/nofolder" ] || fail "map into missing folder created something"
[ -z "$out" ] || fail "map failure still printed: $out"

if [ "$fails" -ne 0 ]; then
    echo "$fails failures" >&2
    exit 1
fi
echo "compare CLI: all checks passed"
