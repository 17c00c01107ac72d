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
