#!/bin/sh
# tests/fuzz/coverage.sh - every public function has an entry in tests/fuzz/pf_calls.h (the
# evaluators) or tests/fuzz/pf_buffers.h (the pointer-taking CPU-only functions).
#
# usage: sh tests/fuzz/coverage.sh        (from anywhere; exits 1 on a gap, 2 on a tool error)
#
# The public evaluators are what tests/portability/gen.awk calls (every `PF_DEF <type> pf_name(`
# of include/pf_*.h, the portability generator's own definition); each must appear in
# pf_calls.h as an entry `PFC_E(<module>, pf_name, ...)` under the module of the header that
# defines it (pf_<module>.h). The public CPU-only functions are every `PF_CPU_DEF <type>
# pf_name(` of include/pf_*.h (and the typed samplers stamped by PFI_TYPED_SAMPLE); each must be
# named in a driver row `{ "pf_a pf_b ...", "<module>", ...` of pfb_table in pf_buffers.h.
# Entries naming a function that no longer exists (or under another module) fail too. Used by
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
done
sort -u "$TMP/public" > "$TMP/public.s"

F=tests/fuzz/pf_calls.h
sed -n 's/^ *PFC_E(\([a-z0-9_]*\), *\(pf_[A-Za-z0-9_]*\),.*/\1 \2/p' "$F" | sort -u > "$TMP/entries.s"

# CPU-only public functions, and the rows of pfb_table
: > "$TMP/cpu"
for h in include/pf_*.h; do
    m=$(basename "$h" .h); m=${m#pf_}
    { sed -n 's/^PF_CPU_DEF [^(]*[ *]\(pf_[A-Za-z0-9_]*\)(.*/\1/p' "$h"
      sed -n 's/^PFI_TYPED_SAMPLE([^,]*, *\(pf_[A-Za-z0-9_]*\),.*/\1/p' "$h"; } | sed "s/^/$m /" >> "$TMP/cpu"
done
sort -u "$TMP/cpu" > "$TMP/cpu.s"
B=tests/fuzz/pf_buffers.h
awk '/pfb_table\[\] = \{/ {on = 1; next} on && /^\};/ {on = 0}
     on && /^ *\{ "pf_/ { split($0, q, "\""); n = split(q[2], f, " "); for (i = 1; i <= n; i++) print q[4], f[i] }' "$B" |
    sort -u > "$TMP/bentries.s"

status=0
missing=$(comm -23 "$TMP/public.s" "$TMP/entries.s" | awk '{print $2}' | sort)
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
bmissing=$(comm -23 "$TMP/cpu.s" "$TMP/bentries.s")
if [ -n "$bmissing" ]; then
    echo "coverage: public CPU-only (PF_CPU_DEF) functions without a driver in $B's pfb_table:" >&2
    echo "$bmissing" | sed 's/^/  /' >&2
    status=1
fi
bstale=$(comm -13 "$TMP/cpu.s" "$TMP/bentries.s")
if [ -n "$bstale" ]; then
    echo "coverage: pfb_table names no such CPU-only function (or under the wrong module):" >&2
    echo "$bstale" | sed 's/^/  /' >&2
    status=1
fi
[ $status -eq 0 ] && echo "coverage: $(wc -l < "$TMP/entries.s" | tr -d ' ') evaluator entries, $(wc -l < "$TMP/bentries.s" | tr -d ' ') CPU-only functions in pf_buffers.h, every public function covered"
exit $status
