#!/usr/bin/env bash
# CLI test of `sss kernel`: the taps of the pre-integrated and artist kernels (a header, N lines,
# offsets ascending and symmetric, each channel's weights summing to 1), the SVD's singular values
# (descending, non-negative), and exit codes (1: bad values, 2: usage).
# Usage: bash test_kernel.sh <sss-binary> <repo-root>
set -u
SSS=$1
fail=0
err() { echo "FAIL: $*" >&2; fail=1; }

# TSV after the '#' comments: header then taps; checks count, order, symmetry and sums.
check_taps() { # N OUTPUT
    printf '%s\n' "$2" | grep -v '^#' | awk -v n="$1" -F'\t' '
        NR == 1 { if ($0 != "offset\tR\tG\tB") { print "header: " $0 > "/dev/stderr"; bad = 1 }; next }
        { k++; off[k] = $1; for (c = 2; c <= 4; c++) { w[k, c] = $c; sum[c] += $c; if ($c < 0) bad = 1 } }
        END {
            if (k != n) { print "taps: " k > "/dev/stderr"; exit 1 }
            for (i = 1; i <= k; i++) {
                if (i > 1 && off[i] <= off[i - 1]) bad = 1
                d = off[i] + off[k + 1 - i]; if (d < 0) d = -d; if (d > 1e-6) bad = 1
                for (c = 2; c <= 4; c++) { d = w[i, c] - w[k + 1 - i, c]; if (d < 0) d = -d; if (d > 1e-7) bad = 1 }
            }
            for (c = 2; c <= 4; c++) { d = sum[c] - 1; if (d < 0) d = -d; if (d > 1e-5) { print "sum " sum[c] > "/dev/stderr"; bad = 1 } }
            exit bad
        }'
}

out=$("$SSS" kernel Skin1 --taps 7) || err "kernel Skin1 --taps 7: exit $?"
check_taps 7 "$out" || err "kernel Skin1 --taps 7: $out"
out=$("$SSS" kernel Marble --model dipole --taps 11 --scale 2) || err "kernel Marble dipole: exit $?"
check_taps 11 "$out" || err "kernel Marble --model dipole --taps 11: $out"
for p in single-layer multi-layer production; do
    out=$("$SSS" kernel --artist "$p" --taps 9) || err "kernel --artist $p: exit $?"
    check_taps 9 "$out" || err "kernel --artist $p: $out"
done
# The artist presets' s is in mm: at --scale 10 (10 mm per unit) the offsets are 10 times smaller.
a=$("$SSS" kernel --artist production | grep -v '^#' | awk -F'\t' 'NR == 2 {print $1}')
b=$("$SSS" kernel --artist production --scale 10 | grep -v '^#' | awk -F'\t' 'NR == 2 {print $1}')
awk -v a="$a" -v b="$b" 'BEGIN { d = a / b - 10; if (d < 0) d = -d; exit !(d < 1e-5) }' || err "artist scale: $a vs $b"

out=$("$SSS" kernel Skin1 --method svd --rank 2 --grid 16) || err "kernel svd: exit $?"
for ch in R G B; do
    printf '%s\n' "$out" | awk -v ch="$ch" '$1 == "#" && $2 == "singular" && $4 == ch ":" {
        found = 1
        for (i = 5; i <= NF; i++) { if ($i < 0 || (i > 5 && $i > $(i - 1))) exit 1 }
    } END { exit !found }' || err "svd singular values of $ch not descending: $out"
done
rows=$(printf '%s\n' "$out" | grep -v '^#' | tail -n +2 | wc -l)
[ "$rows" -eq 32 ] || err "svd: expected 2 x 16 vector rows, got $rows"

expect() { # CODE PATTERN ARGS...
    local code=$1 pat=$2
    shift 2
    local e
    e=$("$SSS" kernel "$@" 2>&1 >/dev/null)
    local rc=$?
    [ "$rc" -eq "$code" ] || err "kernel $*: exit $rc, expected $code"
    printf '%s\n' "$e" | grep -qi -- "$pat" || err "kernel $*: message '$e' lacks '$pat'"
}
expect 1 "taps" Skin1 --taps 6
expect 1 "unobtainium" Unobtainium
expect 1 "preset" --artist rubber
expect 1 "rank" Skin1 --method svd --rank 0
expect 2 "not both" Skin1 --artist production
expect 2 "method" Skin1 --method gaussian
expect 2 "needs --artist" Skin1 --method artist
expect 2 "missing MEDIUM" --taps 7
expect 2 "taps" Skin1 --taps seven
"$SSS" kernel --help | grep -q "usage: sss kernel" || err "--help"

[ "$fail" -eq 0 ] && echo "test_kernel: ok"
exit "$fail"
