#!/usr/bin/env bash
# The documentation a user gets must not send them to files they do not have: the README, docs/,
# include/, src/ and the output of `sss help`, every `sss help COMMAND` and
# `sss techniques --params` must not cite the team's internal notes or paper files ("../shared",
# "shared/", "seeds/", "seed 000", "FACTS.md", "SCENE.md"). Papers are cited by name
# ("Maisch & Ropinski 2020, Eq. 5", docs/references.md), formulas by docs/physics.md, the scene
# format by docs/scene-format.md. Also: the documents that comments point to exist.
# Usage: bash test_doc_references.sh <sss-binary> <repo-root>
set -u
SSS=$1
ROOT=$2
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fail=0
err() { echo "FAIL: $*" >&2; fail=1; }

# Case-insensitive: "Seed 000" at a sentence start (the paper files' numbers; a random seed such as
# "seed 1" is fine); FACTS case-sensitive ("artifacts" is fine).
dangling_ci='\.\./shared|shared/|seeds/|seed 0[0-9]{2}|scene\.md'
dangling_cs='FACTS'

scan() { # scan NAME FILE...: reports every dangling reference in the given files
    local name=$1
    shift
    local hits
    hits=$(grep -I -n -i -E "$dangling_ci" "$@" 2>/dev/null; grep -I -n -E "$dangling_cs" "$@" 2>/dev/null)
    [ -z "$hits" ] || err "$name cites files a user does not have:"$'\n'"$hits"
}

cd "$ROOT" || { echo "FAIL: no repo root $ROOT" >&2; exit 1; }
for d in README.md docs include src; do
    [ -e "$d" ] || err "$d missing"
done
mapfile -t files < <(find README.md docs include src -type f | sort)
[ "${#files[@]}" -gt 100 ] || err "only ${#files[@]} files to scan under README.md docs include src"
scan "the sources and docs" "${files[@]}"

"$SSS" help > "$T/help.txt" 2>&1 || err "sss help: exit $?"
mapfile -t commands < <(awk '/^commands:/ {on = 1; next} on && NF == 0 {on = 0} on {print $1}' "$T/help.txt")
[ "${#commands[@]}" -ge 10 ] || err "sss help lists ${#commands[@]} commands: $(cat "$T/help.txt")"
for c in "${commands[@]}"; do
    [ "$c" = help ] && continue
    "$SSS" help "$c" > "$T/help_$c.txt" 2>&1
    grep -q . "$T/help_$c.txt" || err "sss help $c printed nothing"
done
"$SSS" techniques --params > "$T/techniques.txt" 2>&1 || err "sss techniques --params: exit $?"
grep -q maisch2020 "$T/techniques.txt" || err "sss techniques --params lacks maisch2020"
scan "the help texts" "$T"/*.txt

# What comments and docs point to must exist in the repository.
for f in docs/scene-format.md docs/physics.md docs/references.md LICENSE assets/README.md; do
    [ -s "$f" ] || err "$f missing"
done
# Every repository file the sources and docs cite by path (src/gl/techniques/ssss/tech_ssss.c, docs/dss.md) exists.
mapfile -t cited < <(grep -I -rhoE '(^|[^A-Za-z0-9_./-])(src|docs|include|tests|bench|tools|scenes|examples|python)/[A-Za-z0-9_./-]*[A-Za-z0-9_]\.(c|h|cpp|md|glsl|json|py|sh)\b' \
                         "${files[@]}" | sed -E 's/^[^A-Za-z]*//' | sort -u)
[ "${#cited[@]}" -ge 20 ] || err "only ${#cited[@]} cited paths found"
for f in "${cited[@]}"; do
    [ -e "$f" ] || err "a file or doc cites $f, which does not exist"
done
# Every "docs/physics.md §N" names a section heading "## N." / "### N" of docs/physics.md.
mapfile -t sections < <(grep -rhoE 'docs/physics\.md §[0-9]+(\.[0-9]+)?' "${files[@]}" | sed 's/.*§//' | sort -u)
[ "${#sections[@]}" -ge 5 ] || err "only ${#sections[@]} docs/physics.md sections cited"
for n in "${sections[@]}"; do
    grep -qE "^#+ ${n//./\\.}\.? " docs/physics.md || err "docs/physics.md has no section $n"
done

[ "$fail" = 0 ] && echo "ok: ${#files[@]} files, ${#commands[@]} commands, ${#sections[@]} physics sections"
exit "$fail"
