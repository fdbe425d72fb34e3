#!/bin/sh
# bench/update_docs.sh SUMMARY DOCS_DIR - copy each module's section of the bench summary into
# the docs page that asks for it. A page asks with the two marker lines
#     <!-- BEGIN GENERATED: smith -->
#     <!-- END GENERATED: smith -->
# and everything between them is replaced by the "## smith" section of SUMMARY (headings demoted
# one level, chart links pointed at bench/out/), preceded by the summary's machine header.
set -e
summary=${1:-bench/out/summary.md}
docs=${2:-docs}
if [ ! -f "$summary" ]; then
    echo "update_docs: $summary not found; run 'make bench' first" >&2
    exit 1
fi
if grep -q 'BENCH_QUICK' "$summary" 2>/dev/null; then
    echo "update_docs: $summary comes from a BENCH_QUICK smoke run; run a full 'make bench'" >&2
    exit 1
fi
for page in "$docs"/*.md; do
    grep -q '<!-- BEGIN GENERATED: ' "$page" || continue
    awk -v summary="$summary" '
        function section(mod,    line, on, hdr, out) {
            out = ""; on = 0; hdr = 1
            while ((getline line < summary) > 0) {
                if (line ~ /^## /) { hdr = 0; on = (line == "## " mod); continue }
                if (hdr && line ~ /^- (date|compiler|flags|CPU|timing|two input orders|instructions):/) {
                    out = out line "\n"; continue
                }
                if (on) {
                    if (line ~ /^###/) line = "#" line
                    gsub(/\]\(/, "](../bench/out/", line)
                    out = out line "\n"
                }
            }
            close(summary)
            return out
        }
        /<!-- BEGIN GENERATED: / {
            print
            mod = $0; sub(/.*GENERATED: /, "", mod); sub(/ -->.*/, "", mod)
            printf "%s", section(mod)
            skipping = 1
            next
        }
        /<!-- END GENERATED: / { skipping = 0 }
        !skipping { print }
    ' "$page" > "$page.tmp"
    mv "$page.tmp" "$page"
    echo "update_docs: refreshed $page"
done
