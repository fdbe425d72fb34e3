#!/bin/sh
# bench/determinism.sh - the bench's results do not depend on the thread count.
#
# usage: sh bench/determinism.sh            (make bench-determinism)
#        sh bench/determinism.sh --compare DIR_A DIR_B     only compare two output directories
#
# Runs the quick bench (make bench BENCH_QUICK=1, callgrind counts included when valgrind is
# installed) twice, with PFB_THREADS=1 (every stage serial: the reference) and with every core
# (PFB_THREADS=DET_THREADS, default the online cores), into DET_DIR/threads-1 and
# DET_DIR/threads-N (default DET_DIR=bench/out/determinism), then compares every CSV the two
# runs wrote, column by column, except the columns that hold timings:
#   <module>.csv             ns_per_eval, ratio_to_baseline, ratio_q1, ratio_q3,
#                            ns_per_eval_sorted, ratio_to_baseline_sorted
#   microsurface_cost.csv    ns_per_footprint, ns_q1, ns_q3, batch (sized from a timing),
#                            x_leadr_specular (a ratio of two timings)
#   stability.csv            seconds (both of its tables)
#   any CSV                  a column named ns*, *_ns, *_ms, seconds, secs, time*, wall*, ratio*
#                            or x_* (the convention for timing columns; say so when adding one)
# Every other column must be identical, byte for byte (instr_per_eval, the accuracy columns,
# the ground-truth errors, the stability counts, the GPU counts). A CSV written by only one of
# the two runs is a failure too. Prints one line per CSV and exits 1 on any difference.
# Environment: DET_THREADS, DET_DIR, DET_CALLGRIND=0 (skip the instruction counts), BUILD.
set -u
ROOT=$(cd "$(dirname "$0")/.." && pwd) || exit 2
cd "$ROOT" || exit 2

# keep SPEC: the columns of a CSV header line that are compared (1) or skipped (0), by name
norm() { # file -> the file without its timing columns (each table's header line decides)
    awk -F, -v base="$(basename "$1")" '
        function timing(name, b) {
            if (name ~ /^(ns|ns_.*|.*_ns|.*_ms|seconds|secs|time.*|wall.*|ratio.*|x_.*)$/) return 1
            if (b == "microsurface_cost.csv" && name == "batch") return 1
            return 0
        }
        NR == 1 || prev == "" {
            # a header line: the first line, or the first after a blank line (stability.csv
            # holds two tables)
            if ($0 != "") { for (i = 1; i <= NF; i++) skip[i] = timing($i, base); nf = NF }
        }
        {
            prev = $0
            out = ""
            for (i = 1; i <= NF; i++) out = out (i > 1 ? "," : "") (skip[i] ? "~" : $i)
            print out
        }' "$1"
}

compare() { # dirA dirB -> 0 when every CSV matches
    a=$1; b=$2; bad=0; n=0
    for f in $( { (cd "$a" && ls *.csv 2>/dev/null); (cd "$b" && ls *.csv 2>/dev/null); } | sort -u); do
        n=$((n + 1))
        if [ ! -f "$a/$f" ] || [ ! -f "$b/$f" ]; then
            echo "determinism: $f: written by one run only" >&2; bad=1; continue
        fi
        norm "$a/$f" > "$a/$f.norm"
        norm "$b/$f" > "$b/$f.norm"
        if cmp -s "$a/$f.norm" "$b/$f.norm"; then
            echo "determinism: $f: identical ($(wc -l < "$a/$f" | tr -d ' ') lines, timing columns excluded)"
        else
            echo "determinism: $f: DIFFERS (first differences, '~' = a timing column):" >&2
            diff "$a/$f.norm" "$b/$f.norm" | head -n 10 >&2
            bad=1
        fi
        rm -f "$a/$f.norm" "$b/$f.norm"
    done
    [ $n -gt 0 ] || { echo "determinism: no CSV in $a or $b" >&2; return 1; }
    [ $bad = 0 ] && echo "determinism: every CSV identical ($n files) between $a and $b"
    return $bad
}

if [ "${1:-}" = --compare ]; then
    compare "$2" "$3"
    exit $?
fi

nt=${DET_THREADS:-$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo 1)}
dd=${DET_DIR:-bench/out/determinism}
cg=${DET_CALLGRIND:-1}
command -v valgrind >/dev/null 2>&1 || cg=0
[ "$nt" -gt 1 ] || echo "determinism: only one core here: set DET_THREADS=4 (or more) to check the parallel paths" >&2
mkdir -p "$dd"
for t in 1 "$nt"; do
    echo "determinism: quick bench with PFB_THREADS=$t (callgrind: $cg) into $dd/threads-$t ..."
    t0=$(date +%s)
    if ! PFB_THREADS=$t BENCH_OUT="$dd/threads-$t" make --no-print-directory bench BENCH_QUICK=1 CALLGRIND="$cg" \
        ${BUILD:+BUILD="$BUILD"} > "$dd/threads-$t.log" 2>&1; then
        echo "determinism: the run with PFB_THREADS=$t failed (log $dd/threads-$t.log):" >&2
        tail -n 20 "$dd/threads-$t.log" >&2
        exit 1
    fi
    echo "determinism: PFB_THREADS=$t took $(($(date +%s) - t0)) s (log $dd/threads-$t.log)"
done
compare "$dd/threads-1" "$dd/threads-$nt"
