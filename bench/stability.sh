#!/bin/sh
# bench/stability.sh - the stability table (issue 9, item 4): builds bench/stability.c four
# ways (float, double, float -ffast-math, double -ffast-math), runs them two at a time, merges
# the counts into bench/out/stability.md (the report fragment) and bench/out/stability.csv,
# and copies the fragment into docs/stability.md between its GENERATED markers when
# STABILITY_UPDATE_DOCS=1 (make docs).
#
# usage: sh bench/stability.sh [BUILD_DIR]        (BUILD_DIR defaults to build)
# Environment:
#   BENCH_QUICK=1        10^5 inputs per evaluator and build instead of 10^8 (CI)
#   STABILITY_N=N        inputs per evaluator and build (overrides both)
#   STABILITY_SLOW_DIV=k entries flagged slow get N/k inputs (default 1)
#   STABILITY_BUFFERS_N=N calls per pointer-taking function and build (tests/fuzz/pf_buffers.h;
#                        default 1000, 500 with BENCH_QUICK=1: a few seconds per build)
#   STABILITY_JOBS=j     builds run at once (default 2)
#   CC                   compiler (default gcc, as the Makefile's fast-math test builds)
#   STABILITY_STRICT=1   exit 1 on any finding (default: findings are reported in the fragment
#                        and on stderr, exit 0, so `make bench` completes)
# Exits 1 on a coverage gap (a public evaluator without an entry in tests/fuzz/pf_calls.h), or
# on a finding under STABILITY_STRICT=1; 2 on a build or tool error. The fragment is always
# written.
set -u
ROOT=$(cd "$(dirname "$0")/.." && pwd) || exit 2
cd "$ROOT" || exit 2
BUILD=${1:-build}
DIR=$BUILD/stability
OUTDIR=bench/out
CC=${CC:-gcc}
JOBS=${STABILITY_JOBS:-2}
mkdir -p "$DIR" "$OUTDIR" || exit 2

sh tests/fuzz/coverage.sh || { echo "stability: coverage gap (see above)" >&2; cov=1; }
cov=${cov:-0}

WARN="-std=c99 -pedantic -Wall -Wextra -Werror -Wdouble-promotion"
build() { # name flags...
    n=$1; shift
    $CC $WARN -O2 "$@" -Iinclude bench/stability.c -lm -o "$DIR/stability-$n" || {
        echo "stability: build $n failed" >&2; exit 2; }
}
build float
build double -DPF_DOUBLE
build fastmath-float -ffast-math
build fastmath-double -ffast-math -DPF_DOUBLE

ARGS=""
[ -n "${STABILITY_N:-}" ] && ARGS="-n $STABILITY_N"
start=$(date +%s)
run() { # name label
    "$DIR/stability-$1" $ARGS --label "$2" --csv "$DIR/$1.csv" 2> "$DIR/$1.log"
    echo $? > "$DIR/$1.status"
}
set -- "float:float" "double:double" "fastmath-float:float -ffast-math" "fastmath-double:double -ffast-math"
while [ $# -gt 0 ]; do
    pids=""
    k=0
    while [ $# -gt 0 ] && [ $k -lt "$JOBS" ]; do
        n=${1%%:*}; l=${1#*:}; shift
        run "$n" "$l" &
        pids="$pids $!"
        k=$((k + 1))
    done
    for pid in $pids; do wait "$pid"; done
done
end=$(date +%s)
for n in float double fastmath-float fastmath-double; do
    s=$(cat "$DIR/$n.status")
    [ "$s" = 0 ] || [ "$s" = 1 ] || { echo "stability: run $n failed (status $s)" >&2; cat "$DIR/$n.log" >&2; exit 2; }
done
"$DIR/stability-double" --merge "$OUTDIR/stability.md" "$OUTDIR/stability.csv" \
    "$DIR/float.csv" "$DIR/double.csv" "$DIR/fastmath-float.csv" "$DIR/fastmath-double.csv"
merged=$?
[ $merged -le 1 ] || exit 2
printf '\nWall time of the sweep: %s s (%s builds at a time).\n' "$((end - start))" "$JOBS" >> "$OUTDIR/stability.md"
echo "stability: wrote $OUTDIR/stability.md and $OUTDIR/stability.csv ($((end - start)) s)"

if [ "${STABILITY_UPDATE_DOCS:-0}" = 1 ]; then
    DOC=docs/stability.md
    awk -v frag="$OUTDIR/stability.md" '
        /<!-- BEGIN GENERATED: stability -->/ { print; while ((getline l < frag) > 0) print l; skip = 1; next }
        /<!-- END GENERATED: stability -->/ { skip = 0 }
        !skip' "$DOC" > "$DOC.tmp" && mv "$DOC.tmp" "$DOC" && echo "stability: updated $DOC"
fi
[ $cov -eq 0 ] || exit 1
[ "${STABILITY_STRICT:-0}" = 1 ] && exit $merged
exit 0
