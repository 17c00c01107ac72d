#!/usr/bin/env bash
# bench/gpu/run.sh without a GPU: the bundle (a folder under the 64 MiB a device call carries, holding
# bench_techniques, the libraries ldd lists for it but neither glibc nor the GL loaders, which the
# target's driver provides, the two evaluation scenes and their meshes) run from a copy elsewhere in
# the --small mode on llvmpipe; bench.tsv and bench.json must hold one row per technique (the list
# `sss techniques` prints) x size x scene with positive finite times, and the checker must reject
# outputs with a row missing, a time that is not a number, or a cut-off JSON file.
# usage: test_gpu_bench.sh SSS_BINARY SOURCE_DIR
SSS=$1
SRC=$2
BUILD=$(dirname "$SSS")
RUN=$SRC/bench/gpu/run.sh
. "$SRC/tests/cli/harness.sh"

bash "$RUN" bundle "$BUILD" "$T/b" > "$T/bundle.log" 2>&1 || fail "bundle: $(cat "$T/bundle.log")"
[ -x "$T/b/bin/bench_techniques" ] || fail "no bench_techniques in the bundle"
for f in scenes/eval_front.json scenes/eval_backlit.json assets/head.ply assets/dragon.ply assets/dragon_low.ply; do
    [ -f "$T/b/$f" ] || fail "bundle lacks $f"
done
for lib in "$T"/b/lib/*; do
    case "$(basename "$lib")" in
    libc.so* | libm.so* | ld-linux* | libEGL* | libGL* | libOpenGL*) fail "bundle carries $(basename "$lib")" ;;
    esac
done
ls "$T"/b/lib/libepoxy.so* > /dev/null 2>&1 || fail "bundle lacks libepoxy (ldd lists it)"
[ "$(du -sb "$T/b" | cut -f1)" -le $((64 * 1024 * 1024)) ] || fail "bundle over 64 MiB"

# never overwrites a folder that is not a bundle
mkdir -p "$T/keep" && echo x > "$T/keep/file"
bash "$RUN" bundle "$BUILD" "$T/keep" > /dev/null 2>&1 && fail "bundle overwrote a folder that was no bundle"
[ -f "$T/keep/file" ] || fail "bundle removed a file of a folder that was no bundle"

# run from a copy elsewhere: the bundle must not depend on the build tree or the checkout
mv "$T/b" "$T/moved"
export SSS_EXPECT_TECHNIQUES
SSS_EXPECT_TECHNIQUES=$("$SSS" techniques | awk '{print $1}' | tr '\n' ' ')
(cd / && bash "$T/moved/run.sh" run "$T/moved" "$T/out" --small) > "$T/run.log" 2>&1 || fail "run --small: $(tail -20 "$T/run.log")"
for f in bench.tsv bench.json bench.log env.txt images.tar; do [ -s "$T/out/$f" ] || fail "no $f"; done
n=$(echo "$SSS_EXPECT_TECHNIQUES" | wc -w)
[ "$(tail -n +2 "$T/out/bench.tsv" | wc -l)" -eq "$n" ] || fail "bench.tsv: expected $n rows"
[ "$(tar -tf "$T/out/images.tar" | grep -c '\.png$')" -eq "$n" ] || fail "images.tar: expected $n images"
grep -q "llvmpipe" "$T/out/bench.json" || fail "bench.json does not name the GL renderer"

# the checker rejects incomplete or malformed outputs
bad() { # NAME: a copy of the outputs to spoil
    rm -rf "${T:?}/$1" && cp -r "$T/out" "$T/$1"
}
bad missing && sed -i '$d' "$T/missing/bench.tsv"
bash "$RUN" check "$T/missing" --small > /dev/null 2>&1 && fail "check accepted a missing row"
bad nan && awk -F'\t' -v OFS='\t' 'NR == 2 {$10 = "nan"} 1' "$T/out/bench.tsv" > "$T/nan/bench.tsv"
bash "$RUN" check "$T/nan" --small > /dev/null 2>&1 && fail "check accepted a NaN frame time"
bad cut && head -c 200 "$T/out/bench.json" > "$T/cut/bench.json"
bash "$RUN" check "$T/cut" --small > /dev/null 2>&1 && fail "check accepted a cut-off bench.json"
bash "$RUN" check "$T/out" --small > /dev/null 2>&1 || fail "check rejected the outputs it accepted in run"

[ "$fails" -eq 0 ]
