#!/bin/sh
# bench/update_docs.sh SUMMARY DOCS_DIR - copy each module's section of the bench summary into
# the docs page that asks for it. A page asks with the two marker lines
#     <!-- BEGIN GENERATED: smith -->
#     <!-- END GENERATED: smith -->
# and everything between them is replaced by the "## smith" section of SUMMARY (headings demoted
# one level), preceded by the summary's machine header. The charts the section links to are
# copied to DOCS_DIR/charts/ so the committed docs carry them.
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
# Test notes: a page asks with <!-- BEGIN GENERATED: tests smith --> ... <!-- END ... --> for
# the measured numbers each test of tests/test_smith.c records (pf_test_note), float and
# double side by side, from the test binaries in $BUILD (make docs builds them).
build=${BUILD:-build}
tests_table() { # module
    for cfg in c99-float c99-double; do
        bin="$build/$cfg/test_$1"
        [ -x "$bin" ] || { echo "update_docs: $bin missing (make docs builds it)" >&2; exit 1; }
        "$bin" | awk -v cfg="$cfg" '/^(ok|FAIL)/ { n = $2; sub(/^[^]]*\] ?/, ""); print cfg "\t" n "\t" $0 }'
    done | awk -F '\t' '
        { if (!($2 in seen)) { seen[$2] = 1; order[++k] = $2 } v = $3; gsub(/\|/, "\\|", v); note[$1, $2] = v }
        END {
            print "| test | float (c99-float) | double (c99-double) |"
            print "| --- | --- | --- |"
            for (i = 1; i <= k; i++) {
                t = order[i]
                if (note["c99-float", t] == "" && note["c99-double", t] == "") continue
                print "| `" t "` | " note["c99-float", t] " | " note["c99-double", t] " |"
            }
        }'
}

for page in "$docs"/*.md; do
    grep -q '<!-- BEGIN GENERATED: tests ' "$page" || continue
    awk '/<!-- BEGIN GENERATED: tests / { print; mod = $0; sub(/.*GENERATED: tests /, "", mod); sub(/ -->.*/, "", mod);
                                          print "@@TESTS " mod; skip = 1; next }
         /<!-- END GENERATED: tests / { skip = 0 }
         !skip { print }' "$page" > "$page.tmp"
    : > "$page.new"
    while IFS= read -r line; do
        case "$line" in
            "@@TESTS "*) tests_table "${line#@@TESTS }" >> "$page.new" ;;
            *) printf '%s\n' "$line" >> "$page.new" ;;
        esac
    done < "$page.tmp"
    mv "$page.new" "$page"
    rm -f "$page.tmp"
    echo "update_docs: test notes in $page"
done

for page in "$docs"/*.md; do
    grep -q '<!-- BEGIN GENERATED: [a-z]* -->' "$page" || continue
    awk -v summary="$summary" -v outdir="$(dirname "$summary")" '
        function section(mod,    line, on, hdr, out) {
            out = ""; on = 0; hdr = 1; found = 0
            while ((getline line < summary) > 0) {
                if (line ~ /^## /) { hdr = 0; on = (line == "## " mod); if (on) found = 1; continue }
                if (hdr && line ~ /^- (date|compiler|flags|CPU|timing|two input orders|instructions):/) {
                    out = out line "\n"; continue
                }
                if (on) {
                    if (line ~ /^###/) line = "#" line
                    gsub(/\]\(/, "](charts/", line)
                    out = out line "\n"
                }
            }
            close(summary)
            # not a module of the summary: a report fragment bench/out/<name>.md (stability)
            # is copied whole, its images pointed at charts/
            if (!found && (getline line < (outdir "/" mod ".md")) > 0) {
                out = ""
                do { gsub(/\]\(/, "](charts/", line); out = out line "\n" } while ((getline line < (outdir "/" mod ".md")) > 0)
                close(outdir "/" mod ".md")
            }
            return out
        }
        /<!-- BEGIN GENERATED: [a-z_]* -->/ {
            print
            mod = $0; sub(/.*GENERATED: /, "", mod); sub(/ -->.*/, "", mod)
            printf "%s", section(mod)
            skipping = 1
            next
        }
        /<!-- END GENERATED: [a-z_]* -->/ { skipping = 0 }
        !skipping { print }
    ' "$page" > "$page.tmp"
    mv "$page.tmp" "$page"
    mkdir -p "$docs/charts"
    for chart in $(grep -o '](charts/[^)]*)' "$page" | sed 's/](charts\///; s/)$//'); do
        cp "$(dirname "$summary")/$chart" "$docs/charts/$chart"
    done
    echo "update_docs: refreshed $page"
done

# The report and the pages generated whole from it: docs/report.md is bench/out/report.md and
# docs/choosing.md is bench/out/choosing.md, each with its images (SVG charts, PNG pictures)
# copied to docs/charts/ and the links rewritten to point there.
out_dir=$(dirname "$summary")
for page in report choosing; do
    src="$out_dir/$page.md"
    if [ ! -f "$src" ]; then
        echo "update_docs: $src missing; run a full 'make bench'" >&2
        exit 1
    fi
    mkdir -p "$docs/charts"
    for img in $(grep -o '](\([A-Za-z0-9_.-]*\)\.\(svg\|png\))' "$src" | sed 's/^](//; s/)$//' | sort -u); do
        cp "$out_dir/$img" "$docs/charts/$img"
    done
    # choosing.md stands alone in docs/: its headings move up a level and its links into the
    # report point at docs/report.md
    promote=""
    [ "$page" = choosing ] && promote='s/^##/#/; s/](#/](report.md#/g'
    sed 's/](\([A-Za-z0-9_.-]*\.\(svg\|png\)\))/](charts\/\1)/g; s/`make docs` copies it to docs\/report.md with its charts./This copy in docs\/ was refreshed by `make docs`./'"${promote:+; $promote}" "$src" > "$docs/$page.md"
    echo "update_docs: wrote $docs/$page.md"
done
