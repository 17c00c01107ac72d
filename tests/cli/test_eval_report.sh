#!/usr/bin/env bash
# report.html of sss eval opens in headless Chromium without errors and every image loads: a copy of
# the page with a small script appended marks the number of images and of broken ones (naturalWidth
# 0) on <body>, read back with --dump-dom; the same script finds, as laid out by the browser, the FLIP
# columns with numbers, no crops table (the crops are on the sheet: once), no best marked without a noise estimate, and
# the sheet (whose error maps carry the colour bars); a screenshot is taken and must not be blank. Skips (exit 0)
# when chromium is not installed (Debian package `chromium`: scripts/install-deps.sh --dev).
# Usage: bash test_eval_report.sh <sss-binary> <repo-root>
set -u
SSS=$1
ROOT=$2
CHROMIUM=""
for c in chromium chromium-browser google-chrome; do
    if command -v "$c" >/dev/null 2>&1; then CHROMIUM=$c; break; fi
done
if [ -z "$CHROMIUM" ]; then
    echo "skipped: chromium is not installed (scripts/install-deps.sh --dev installs it)"
    exit 0
fi
. "$(dirname "${BASH_SOURCE[0]}")/harness.sh"

cat >"$T/ball.json" <<'EOF'
{
  "camera": {"position": [0, 1.2, 4], "look_at": [0, 0.4, 0], "fov": 35, "width": 48, "height": 48},
  "objects": [
    {"procedural": {"shape": "sphere", "radius": 0.6, "subdivisions": 2},
     "transform": {"translate": [0, 0.6, 0]},
     "material": {"type": "subsurface", "medium": "Marble", "scale": 20.0}},
    {"procedural": {"shape": "plane", "size": 8}, "material": {"type": "diffuse", "reflectance": [0.5, 0.5, 0.5]}}
  ],
  "lights": [{"type": "point", "position": [1.5, 3, -1.5], "intensity": [6, 6, 6]}]
}
EOF
"$SSS" eval "$T/ball.json" --techniques local,ssss,nosuch --frames 1 --warmup 0 --reference-quality draft --out "$T/out" \
    >/dev/null 2>"$T/err" || { echo "FAIL: sss eval: $(head -c 400 "$T/err")"; exit 1; }
[ -s "$T/out/report.html" ] || { echo "FAIL: no report.html"; exit 1; }

chrome() {
    local profile
    profile=$(mktemp -d)
    timeout 120 "$CHROMIUM" --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
        --disable-background-networking --disable-component-update --disable-sync --disable-extensions \
        --user-data-dir="$profile" "$@"
    local rc=$?
    rm -rf "$profile"
    return $rc
}

# the page as written, plus a script that counts broken images once everything has loaded
probe='<script>window.addEventListener("load",function(){var im=document.images,b=0;for(var i=0;i<im.length;i++){if(!im[i].complete||im[i].naturalWidth===0)b++;}document.body.setAttribute("data-images",im.length);document.body.setAttribute("data-broken",b);'
# FLIP: header cells of the entry tables, numbers in [0, 1] in their cells, and the FLIP summary table
probe+='var fh=document.querySelectorAll("th.flip").length,fv=0;document.querySelectorAll("td.flip").forEach(function(c){var v=parseFloat(c.textContent);if(v>=0&&v<=1)fv++;});'
probe+='document.body.setAttribute("data-flip",fh+"/"+fv+"/"+document.querySelectorAll("table.summary-flip td.best").length);'
# crops: images in the crops table that loaded and are laid out at a visible size
probe+='var cr=0;document.querySelectorAll("table.crops img").forEach(function(c){if(c.complete&&c.naturalWidth>200&&c.getBoundingClientRect().width>100)cr++;});document.body.setAttribute("data-crops",cr);'
probe+='var sh=0;for(var i=0;i<im.length;i++){if(/^ball/.test(im[i].alt)&&im[i].naturalWidth>1000)sh++;}document.body.setAttribute("data-sheets",sh);});</script>'
sed "s#</body>#${probe//&/\\&}</body>#" "$T/out/report.html" >"$T/probe.html" # & is sed's match
chrome --virtual-time-budget=10000 --dump-dom "file://$T/probe.html" >"$T/dom.html" 2>"$T/chrome.err" ||
    fail "chromium --dump-dom failed: $(tail -3 "$T/chrome.err")"
body=$(grep -o '<body[^>]*>' "$T/dom.html" | head -1)
n_html=$(grep -o '<img ' "$T/out/report.html" | wc -l)
case "$body" in
*"data-images=\"$n_html\""*"data-broken=\"0\""*) ;;
*) fail "images not all loaded (page has $n_html): $body" ;;
esac
# three plots (DSSIM, FLIP, passes; one size: no resolution plot) and the sheet
[ "$n_html" -eq 4 ] || fail "report has $n_html images, not 4"
grep -q "nosuch" "$T/dom.html" || fail "the failed technique is not in the rendered page"
# one FLIP header per entry table (scene + SAM sweep not run: 1), two compared entries with a FLIP value
# (the quality size: local and ssss); no best marked (no noise estimate without --reference-noise, and
# the page says so); the zoomed crops only on the sheet, not a second time in a table
case "$body" in *'data-flip="1/2/0"'*) ;; *) fail "FLIP columns: $body" ;; esac
case "$body" in *'data-crops="0"'*) ;; *) fail "zoomed crops shown twice: $body" ;; esac
grep -q "No best technique is marked" "$T/dom.html" || fail "the page does not say why no best is marked"
case "$body" in *'data-sheets="1"'*) ;; *) fail "the sheet with the error maps and colour bars: $body" ;; esac
grep -q "colour bars" "$T/dom.html" || fail "the page does not explain the colour bars"
[ -e "$T/out/plot_sam_rmse.png" ] && fail "an empty SAM plot was written (no sweep ran)"
grep -q "No SAM plot" "$T/dom.html" || fail "the page does not say why there is no SAM plot"

# the probe must be able to fail: one corrupted image is counted as broken
sed "0,/base64,iVBOR/s//base64,XXXX/" "$T/probe.html" >"$T/broken.html"
chrome --virtual-time-budget=10000 --dump-dom "file://$T/broken.html" 2>/dev/null | grep -q 'data-broken="1"' ||
    fail "the probe does not notice a broken image"

# a screenshot of the report itself: written, and not blank (a blank page compresses to a few kB)
chrome --window-size=1280,2400 --hide-scrollbars --screenshot="$T/shot.png" "file://$T/out/report.html" \
    >/dev/null 2>"$T/chrome.err" || fail "chromium --screenshot failed: $(tail -3 "$T/chrome.err")"
[ -s "$T/shot.png" ] || fail "no screenshot"
size=$(wc -c <"$T/shot.png")
[ "$size" -gt 40000 ] || fail "screenshot looks blank ($size bytes)"
if [ "$fails" -ne 0 ]; then
    echo "$fails failure(s)"
    exit 1
fi
echo "ok"
