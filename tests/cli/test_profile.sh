#!/usr/bin/env bash
# CLI test of `sss profile`: values against PBRT-v3's S_r (tests/data/pbrt_v3_sr.tsv) within 1%,
# the header line, --r spacing, and exit codes (1: unknown medium, 2: malformed option).
# Usage: bash test_profile.sh <sss-binary> <repo-root>
set -u
SSS=$1
ROOT=$2
REF=$ROOT/tests/data/pbrt_v3_sr.tsv
fail=0
err() { echo "FAIL: $*" >&2; fail=1; }

# Header line.
header=$("$SSS" profile Marble --r 0.01:0.01:1 | head -n 1)
[ "$header" = "$(printf 'r\tR\tG\tB')" ] || err "header is '$header'"

# Every PBRT row: run the CLI at that radius and compare the three channels within 1% (values below
# 1e-30, i.e. PBRT's exact zeros, compared absolutely).
rows=0
while IFS=$'\t' read -r medium eta scale r R G B; do
    [ "$medium" = "medium" ] && continue
    out=$("$SSS" profile "$medium" --eta "$eta" --scale "$scale" --r "$r:$r:1") || { err "$medium r=$r: exit $?"; continue; }
    line=$(printf '%s\n' "$out" | sed -n 2p)
    nlines=$(printf '%s\n' "$out" | wc -l)
    [ "$nlines" -eq 2 ] || err "$medium r=$r: expected 2 lines, got $nlines"
    echo "$line $R $G $B" | awk -v who="$medium r=$r" -v want_r="$r" '{
        bad = 0
        if ($1 + 0 != want_r + 0) { bad = 1; print who ": radius column " $1 > "/dev/stderr" }
        for (c = 0; c < 3; c++) {
            got = $(2 + c); ref = $(5 + c)
            if (ref < 1e-30) { if (got > 1e-30 || got < -1e-30) bad = 1 }
            else { d = (got - ref) / ref; if (d < 0) d = -d; if (d > 0.01) bad = 1 }
            if (bad) { print who ": got " $2 " " $3 " " $4 " want " $5 " " $6 " " $7 > "/dev/stderr"; exit 1 }
        }
    }' || err "$medium r=$r differs from PBRT"
    rows=$((rows + 1))
done < "$REF"
[ "$rows" -eq 40 ] || err "compared $rows rows, expected 40"

# Case-insensitive medium names.
a=$("$SSS" profile skin1 --r 0.1:0.1:1 | sed -n 2p)
b=$("$SSS" profile Skin1 --r 0.1:0.1:1 | sed -n 2p)
[ -n "$a" ] && [ "$a" = "$b" ] || err "case-insensitive lookup: '$a' vs '$b'"

# --r R0:R1:N gives N evenly spaced radii, both ends included.
radii=$("$SSS" profile Marble --r 0:2:5 | awk 'NR > 1 { printf "%s ", $1 }')
[ "$radii" = "0 0.5 1 1.5 2 " ] || err "--r 0:2:5 radii '$radii'"
# Default: a header and 64 rows, all finite and non-negative.
n=$("$SSS" profile Potato | awk 'NR > 1 && ($2 < 0 || $3 < 0 || $4 < 0 || $2 != $2 + 0) { bad = 1 } END { print (bad ? -1 : NR - 1) }')
[ "$n" = 64 ] || err "default output rows: $n"
# Dipole model runs and prints positive values.
"$SSS" profile Marble --model dipole --r 1:1:1 | awk 'NR == 2 && !($2 > 0 && $3 > 0 && $4 > 0) { exit 1 }' \
    || err "dipole model output"

# --help prints usage on stdout, exit 0.
"$SSS" profile --help | grep -q "usage: sss profile" || err "--help"

expect_exit() { # expected-code args...
    local want=$1; shift
    "$SSS" "$@" > /dev/null 2> /tmp/sss_profile_err.$$
    local got=$?
    [ "$got" -eq "$want" ] || err "sss $* exited $got, expected $want ($(cat /tmp/sss_profile_err.$$))"
}
expect_exit 1 profile Cheese
"$SSS" profile Cheese 2>&1 | grep -q "Marble" || err "unknown medium message does not list the media"
expect_exit 1 profile Marble --eta 5
expect_exit 1 profile Marble --scale 0
expect_exit 2 profile Marble --bogus
expect_exit 2 profile Marble --r 1:2
expect_exit 2 profile Marble --r 1:2:0
expect_exit 2 profile Marble --r a:2:3
expect_exit 2 profile Marble --r -1:2:3
expect_exit 2 profile Marble --eta
expect_exit 2 profile Marble --eta x
expect_exit 2 profile Marble --model bssrdf
expect_exit 2 profile
expect_exit 2 profile Marble Skin1
rm -f /tmp/sss_profile_err.$$

[ "$fail" -eq 0 ] && echo "test_profile.sh: all checks passed"
exit "$fail"
