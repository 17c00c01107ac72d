# tests/cli/harness.sh — sourced by the shell tests (tests/cli/test_*.sh, tests/install/): a temporary
# folder $T removed on exit, and fail MESSAGE, which prints "FAIL: MESSAGE" and counts it in $fails.
# The test ends with: [ "$fails" -eq 0 ] (or its own summary of $fails).
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fails=0
fail() {
    echo "FAIL: $*"
    fails=$((fails + 1))
}
