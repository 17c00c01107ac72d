#!/usr/bin/env bash
# make demo: evaluates the main technique (maisch2020, Maisch & Ropinski 2020) and its strongest competitors in
# Maisch & Ropinski 2020, section 8 (chen2012, dss), what engines ship (burley: Burley's normalized diffusion in screen
# space, Golubev 2018), the fast screen-space baseline (screen), and maisch2020 without the interreflection stage
# and as published, against the CPU ground
# truth on the default scene set: scenes/default.json (a Marble bunny lit from the side and behind)
# and scenes/eval_backlit.json (the dragon lit from behind, Maisch & Ropinski 2020, Fig. 6a). References are the
# committed ones in scenes/references/ (rendered only if missing or stale), with a second one at seed 1 that
# measures the scenes' noise (--reference-noise: the report marks a best technique only beyond it), and the
# single-event truth beside the full transport (--both-truths: light from the lights only; the difference of
# a technique's two scores is the light between surfaces, docs/eval.md "Two truths"). Writes out/demo/:
# report.html (self-contained: comparison sheets with DSSIM maps, plots, tables), results.json,
# results.csv, sheets and plots; prints a summary table.
# Usage: scripts/demo.sh [BUILD_DIR]   (DEMO_FRAMES=N timed frames per technique, DEMO_WARMUP=W untimed
# frames before them, DEMO_BUDGET=S seconds after which a technique's timed frames stop; timings are
# medians; default 3 after 1 within 3 s: on llvmpipe chen2012 and dss take 20-30 s a frame at 512x512,
# so they are timed on their first frame, and the report says so (docs/eval.md, "Timings"))
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:-build}
SSS="$BUILD/sss"
OUT=out/demo
FRAMES=${DEMO_FRAMES:-3}
WARMUP=${DEMO_WARMUP:-1}
BUDGET=${DEMO_BUDGET:-3}
SCENES=(scenes/default.json scenes/eval_backlit.json)

# the techniques of this build among the wanted ones (the list grows with the registry)
available=" $("$SSS" techniques | awk '{print $1}' | tr '\n' ' ') "
techs=""
for t in maisch2020 chen2012 dss burley screen; do
    case "$available" in *" $t "*) techs="${techs:+$techs,}$t" ;; esac
done
[ -n "$techs" ] || { echo "demo: none of maisch2020, chen2012, dss, burley, screen is built" >&2; exit 1; }
# maisch2020 also without the renderer's interreflection stage (the light between surfaces,
# docs/interreflection.md) and as published (preset=paper: no stage, the sqrt(i) brightening of section 6.1
# and the other departures of docs/maisch2020.md undone), next to the best-measured defaults
case "$techs" in *maisch2020*) techs="$techs,maisch2020:interreflection=0,maisch2020:preset=paper" ;; esac

echo "== sss demo: ${SCENES[*]}"
echo "   techniques: $techs (+ the CPU reference, cached in scenes/references/), median of up to $FRAMES frame(s) after $WARMUP warm-up, $BUDGET s of timed frames at most"
echo "   (software OpenGL renders in seconds per frame what a GPU does in milliseconds)"
echo
start=$(date +%s)
"$SSS" eval "${SCENES[@]}" --techniques "$techs" --frames "$FRAMES" --warmup "$WARMUP" --frame-budget "$BUDGET" --cached-reference --reference-noise --both-truths --out "$OUT"
echo
echo "demo: $(($(date +%s) - start)) s; open $(pwd)/$OUT/report.html"
