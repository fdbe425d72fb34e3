#!/bin/sh
# tests/fuzz/coverage.sh - every public evaluator has an entry in tests/fuzz/pf_calls.h.
#
# usage: sh tests/fuzz/coverage.sh        (from anywhere; exits 1 on a gap, 2 on a tool error)
#
# The public functions are what tests/portability/gen.awk calls (every `PF_DEF <type> pf_name(`
# of include/pf_*.h, the portability generator's own definition), plus the pointer-taking
# C-only ones it skips. Each must appear in pf_calls.h either as an entry
# `PFC_E(<module>, pf_name, ...)` under the module of the header that defines it (pf_<module>.h)
# or in pfc_skipped[]. Entries naming a function that no longer exists fail too. Used by
# tests/fuzz/run.sh and bench/stability.sh, so a new function cannot escape the stability
# table or the fuzzers silently.
set -u
ROOT=$(cd "$(dirname "$0")/../.." && pwd) || exit 2
cd "$ROOT" || exit 2
TMP=${TMPDIR:-/tmp}/pf_coverage.$$
mkdir -p "$TMP" || exit 2
trap 'rm -rf "$TMP"' EXIT INT TERM

: > "$TMP/public"
for h in include/pf_*.h; do
    b=$(basename "$h")
    m=${b#pf_}; m=${m%.h}
    awk -v mode=c -v targets="$b" -v includes="" -f tests/portability/gen.awk include/pf_*.h > "$TMP/gen" || {
        echo "coverage: gen.awk failed on $b" >&2; exit 2; }
    sed -n 's/.*PFP_FN(\(pf_[A-Za-z0-9_]*\)).*/\1/p' "$TMP/gen" | sed "s/^/$m /" >> "$TMP/public"
    sed -n 's/^\/\* [^ ]* \(pf_[A-Za-z0-9_]*\): C-only.*/\1/p' "$TMP/gen" | sed "s/^/$m /" >> "$TMP/skipped_public"
done
touch "$TMP/skipped_public"
sort -u "$TMP/public" > "$TMP/public.s"
cut -d' ' -f2 "$TMP/skipped_public" | sort -u > "$TMP/skipped_public.s"

F=tests/fuzz/pf_calls.h
sed -n 's/^ *PFC_E(\([a-z0-9_]*\), *\(pf_[A-Za-z0-9_]*\),.*/\1 \2/p' "$F" | sort -u > "$TMP/entries.s"
# pfc_skipped[]: the quoted names between its braces
awk '/pfc_skipped\[\] = \{/ {on = 1; next} on && /^\};/ {on = 0} on' "$F" |
    sed -n 's/^ *"\(pf_[A-Za-z0-9_]*\)".*/\1/p' | sort -u > "$TMP/skipped.s"

status=0
missing=$(comm -23 "$TMP/public.s" "$TMP/entries.s" | awk '{print $2}' | sort | comm -23 - "$TMP/skipped.s")
if [ -n "$missing" ]; then
    echo "coverage: public evaluators without an entry in $F (add PFC_E lines):" >&2
    echo "$missing" | sed 's/^/  /' >&2
    status=1
fi
stale=$(comm -13 "$TMP/public.s" "$TMP/entries.s")
if [ -n "$stale" ]; then
    echo "coverage: entries of $F with no such public function (or under the wrong module):" >&2
    echo "$stale" | sed 's/^/  /' >&2
    status=1
fi
unknown_skip=$(cut -d' ' -f2 "$TMP/public.s" | sort -u | cat - "$TMP/skipped_public.s" | sort -u | comm -13 - "$TMP/skipped.s")
if [ -n "$unknown_skip" ]; then
    echo "coverage: pfc_skipped names no public function:" >&2
    echo "$unknown_skip" | sed 's/^/  /' >&2
    status=1
fi
nskip_unlisted=$(comm -23 "$TMP/skipped_public.s" "$TMP/skipped.s")
if [ -n "$nskip_unlisted" ]; then
    echo "coverage: pointer-taking public functions neither in pfc_skipped nor with an entry:" >&2
    echo "$nskip_unlisted" | sed 's/^/  /' >&2
    status=1
fi
[ $status -eq 0 ] && echo "coverage: $(wc -l < "$TMP/entries.s" | tr -d ' ') entries, $(wc -l < "$TMP/skipped.s" | tr -d ' ') skipped, every public evaluator covered"
exit $status
