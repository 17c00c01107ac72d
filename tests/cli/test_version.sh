#!/usr/bin/env bash
# `sss --version` and `sss version` print "sss MAJOR.MINOR.PATCH", the version CMakeLists.txt declares
# in project(sss VERSION ...); help lists the command.
# Usage: bash test_version.sh <sss-binary> <repo-root>
set -u
SSS=$1
ROOT=$2
fails=0
fail() {
    echo "FAIL: $*"
    fails=$((fails + 1))
}
version=$(sed -n 's/^project(sss VERSION \([0-9]*\.[0-9]*\.[0-9]*\).*/\1/p' "$ROOT/CMakeLists.txt")
[ -n "$version" ] || fail "no project(sss VERSION ...) in CMakeLists.txt"
for args in --version version; do
    out=$("$SSS" $args) || fail "sss $args exited $?"
    [ "$out" = "sss $version" ] || fail "sss $args printed '$out', expected 'sss $version'"
done
"$SSS" help | grep -Eq '^  version ' || fail "sss help does not list version"
"$SSS" help version | grep -q 'usage: sss version' || fail "sss help version"
"$SSS" version extra >/dev/null 2>&1
[ $? -eq 2 ] || fail "sss version extra: expected exit 2 (usage)"
[ $fails -eq 0 ] || { echo "$fails failure(s)"; exit 1; }
echo "version: OK"
