#!/usr/bin/env bash
# CLI test of `sss lut`: writes the image (EXR and PFM), prints r_max = max over channels of
# ln(sigma_s' / 1e-7) / sigma_t' (Maisch & Ropinski 2020, section 7.1, computed here from the docs/physics.md §2.3 Marble
# coefficients) and A_max = pi r_max^2; the image's layout (x = r, row 0 = A = 0 holds R_d itself,
# compared with `sss profile` at the texel radii); errors exit 1 (bad medium, size, file type) or 2
# (usage) and leave no file.
# Usage: bash test_lut.sh <sss-binary> <repo-root>
set -u
SSS=$1
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fail=0
err() { echo "FAIL: $*" >&2; fail=1; }

out=$("$SSS" lut Marble --size 64 -o "$T/x.exr") || err "lut Marble --size 64: exit $?"
[ -s "$T/x.exr" ] || err "no EXR written"
head -c 4 "$T/x.exr" | od -An -tx1 | grep -q "76 2f 31 01" || err "x.exr lacks the OpenEXR magic number"
rmax=$(printf '%s\n' "$out" | awk '$1 == "r_max" {print $2}')
amax=$(printf '%s\n' "$out" | awk '$1 == "A_max" {print $2}')
ms=$(printf '%s\n' "$out" | awk '$1 == "build_ms" {print $2}')
[ -n "$rmax" ] && [ -n "$amax" ] && [ -n "$ms" ] || err "missing r_max / A_max / build_ms in: $out"
awk -v r="$rmax" -v a="$amax" 'BEGIN {
    split("2.19 2.62 3.00", s); split("0.0021 0.0041 0.0071", k)
    want = 0
    for (c = 1; c <= 3; c++) { v = log(s[c] / 1e-7) / (s[c] + k[c]); if (v > want) want = v }
    d = (r - want) / want; if (d < 0) d = -d
    e = (a - 3.14159265358979 * r * r) / a; if (e < 0) e = -e
    exit !(d < 1e-6 && e < 1e-6)
}' || err "r_max $rmax / A_max $amax do not follow Q(r_max) = 1e-7"

# PFM (bottom row first on disk): the top image row is A = 0, i.e. R_d at r_i = r_max i / 63.
"$SSS" lut Marble --size 64 --model dipole -o "$T/x.pfm" > /dev/null || err "lut to .pfm: exit $?"
"$SSS" profile Marble --model dipole --r "0:$rmax:64" > "$T/profile.tsv" || err "sss profile failed"
python3 - "$T/x.pfm" "$T/profile.tsv" <<'PY' || err "row A = 0 of the LUT differs from sss profile"
import math, struct, sys
data = open(sys.argv[1], 'rb').read()
parts = data.split(b'\n', 3)
assert parts[0] == b'PF', parts[0]
w, h = map(int, parts[1].split()); scale = float(parts[2])
vals = struct.unpack(('<' if scale < 0 else '>') + 'f' * (w * h * 3), parts[3][:w * h * 12])
rows = [vals[(h - 1 - y) * w * 3:(h - y) * w * 3] for y in range(h)]  # top row first
prof = [list(map(float, l.split('\t'))) for l in open(sys.argv[2]).read().split('\n')[1:] if l]
assert w == h == 64 and len(prof) == 64
ok = all(abs(rows[0][3 * i + c] - prof[i][1 + c]) <= 1e-5 * abs(prof[i][1 + c]) + 1e-30
         for i in range(64) for c in range(3))
# Every other row is an average over a disc: finite, positive, at most the peak of R_d.
ok = ok and all(math.isfinite(v) and 0 < v <= rows[0][c % 3] * (1 + 1e-6)
                for r in rows[1:] for c, v in enumerate(r))
sys.exit(0 if ok else 1)
PY

"$SSS" lut Marble --size 32 --axes sqrt --model dipole --scale 10 --eta 1.5 -o "$T/s.exr" > /dev/null ||
    err "sqrt axes / dipole / scale / eta: exit $?"

# Errors: exit code, message naming the problem, no file left behind.
expect() { # CODE PATTERN ARGS...
    local code=$1 pat=$2
    shift 2
    local e
    e=$("$SSS" lut "$@" 2>&1 >/dev/null)
    local rc=$?
    [ "$rc" -eq "$code" ] || err "lut $*: exit $rc, expected $code"
    printf '%s\n' "$e" | grep -qi -- "$pat" || err "lut $*: message '$e' lacks '$pat'"
}
expect 1 "unobtainium" Unobtainium --size 16 -o "$T/bad1.exr"
expect 1 "size" Marble --size 1 -o "$T/bad2.exr"
expect 1 "bad3.png" Marble --size 16 -o "$T/bad3.png"
expect 1 "eta" Marble --size 16 --eta 0.5 -o "$T/bad4.exr"
expect 1 "no_dir" Marble --size 16 -o "$T/no_dir/bad5.exr"
expect 2 "missing -o" Marble --size 16
expect 2 "axes" Marble --axes log -o "$T/bad6.exr"
expect 2 "size" Marble --size 12x -o "$T/bad7.exr"
expect 2 "missing MEDIUM" -o "$T/bad8.exr"
left=$(ls "$T" | grep -c bad)
[ "$left" -eq 0 ] || err "files left behind after errors: $(ls "$T")"
"$SSS" lut --help | grep -q "usage: sss lut" || err "--help"

[ "$fail" -eq 0 ] && echo "test_lut: ok"
exit "$fail"
