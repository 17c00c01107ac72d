#!/usr/bin/env bash
# Runs every libFuzzer target of fuzz/ for a fixed time and prints one line per target.
#   fuzz/run_fuzz.sh [--ci] BUILD_DIR SECONDS [TARGET...]
# Seeds: fuzz/corpus/<t>/ and tests/data/fuzz-regressions/<t>/ (read only). Without --ci the working
# corpus grows in BUILD_DIR/fuzz-corpus/<t>/ from run to run; with --ci each run starts from the
# committed seeds alone (reproducible). Findings (crash, leak, timeout, out-of-memory, broken promise)
# are saved in BUILD_DIR/fuzz-artifacts/<t>/; turn each into a regression: copy it to
# tests/data/fuzz-regressions/<t>/ (tests/robustness/test_fuzz_regressions replays them).
# Targets run FUZZ_JOBS at a time (default: the processor count; each fuzzer is one process), each
# for SECONDS.
# Exit status: 0 no finding, 1 a finding, 2 usage or build problem.
set -u
ci=0
if [ "${1:-}" = --ci ]; then ci=1; shift; fi
if [ $# -lt 2 ]; then
    echo "usage: fuzz/run_fuzz.sh [--ci] BUILD_DIR SECONDS [TARGET...]" >&2
    exit 2
fi
build=$1
seconds=$2
shift 2
root=$(cd "$(dirname "$0")/.." && pwd)
targets=${*:-ply obj scene hdr pfm exr png sam env_cut gltf jpg}
case "$seconds" in '' | *[!0-9]*) echo "run_fuzz.sh: SECONDS must be a whole number" >&2; exit 2 ;; esac

for t in $targets; do
    if [ ! -x "$build/fuzz/fuzz_$t" ]; then
        echo "run_fuzz.sh: $build/fuzz/fuzz_$t not built (cmake -DSSS_FUZZ=ON, target fuzz_all)" >&2
        exit 2
    fi
done

# Fuzzes target $1 and writes its result line to BUILD_DIR/fuzz-artifacts/<t>.row.
fuzz_target() {
    local t=$1 bin=$build/fuzz/fuzz_$1 corpus
    if [ $ci -eq 1 ]; then
        corpus=$(mktemp -d)
    else
        corpus=$build/fuzz-corpus/$t
        mkdir -p "$corpus"
    fi
    local artifacts=$build/fuzz-artifacts/$t
    mkdir -p "$artifacts"
    local log=$build/fuzz-artifacts/$t.log
    local seeds=("$root/fuzz/corpus/$t")
    # Fixed regressions seed the run; open-* ones (bugs not fixed yet) would stop it at once.
    local regress=$build/fuzz-regressions/$t
    rm -rf "$regress"
    mkdir -p "$regress"
    if [ -d "$root/tests/data/fuzz-regressions/$t" ]; then
        find "$root/tests/data/fuzz-regressions/$t" -maxdepth 1 -type f ! -name 'open-*' -exec cp {} "$regress/" \;
    fi
    seeds+=("$regress")
    local dict=()
    [ -f "$root/fuzz/dict/$t.dict" ] && dict=(-dict="$root/fuzz/dict/$t.dict")
    # -timeout: an input taking 25 s is a finding (the readers are linear in their input);
    # -rss_limit_mb: the harness's inputs are small, so 2.5 GB means an allocation the header
    # should have refused. Leak detection is on (ASan + libFuzzer default).
    "$bin" -max_total_time="$seconds" -timeout=25 -rss_limit_mb=2560 -max_len=16384 -print_final_stats=1 \
        "${dict[@]}" -artifact_prefix="$artifacts/" "$corpus" "${seeds[@]}" >"$log" 2>&1
    local rc=$? result
    local execs rate units
    execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
    rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
    units=$(find "$corpus" -type f | wc -l)
    if [ $rc -eq 0 ]; then
        result=ok
    else
        local what
        what=$(grep -m1 -oE 'ERROR: [A-Za-z]+: [a-z-]+|ERROR: libFuzzer: [a-z-]+|broken promise: .*|runtime error: .*' "$log")
        result="FINDING (${what:-exit $rc}): see $log, input in $artifacts/"
    fi
    printf '%-6s %10s %9s %8s  %s\n' "$t" "${execs:-?}" "${rate:-?}" "$units" "$result" >"$build/fuzz-artifacts/$t.row"
    [ $ci -eq 1 ] && rm -rf "$corpus"
    return 0
}

mkdir -p "$build/fuzz-artifacts"
jobs_max=${FUZZ_JOBS:-$(nproc)}
running=0
for t in $targets; do
    rm -f "$build/fuzz-artifacts/$t.row"
    fuzz_target "$t" &
    running=$((running + 1))
    if [ "$running" -ge "$jobs_max" ]; then
        wait -n
        running=$((running - 1))
    fi
done
wait

findings=0
printf '%-6s %10s %9s %8s  %s\n' target execs "exec/s" corpus result
for t in $targets; do
    row=$build/fuzz-artifacts/$t.row
    if [ -s "$row" ]; then cat "$row"; else printf '%-6s  FINDING (no result line)\n' "$t"; fi
    grep -q ' ok$' "$row" 2>/dev/null || findings=$((findings + 1))
done
if [ $findings -gt 0 ]; then
    echo "run_fuzz.sh: $findings target(s) with findings" >&2
    exit 1
fi
exit 0
