#!/bin/sh
# bench/stability.sh - the stability table (issue 9, item 4): builds bench/stability.c four
# ways (float, double, float -ffast-math, double -ffast-math) at once, runs each in shards on
# every core (bench/pool.sh), merges the counts into bench/out/stability.md (the report
# fragment) and bench/out/stability.csv (the same tables for any PFB_THREADS),
# and copies the fragment into docs/stability.md between its GENERATED markers when
# STABILITY_UPDATE_DOCS=1 (make docs).
#
# usage: sh bench/stability.sh [--build-only] [BUILD_DIR]   (BUILD_DIR defaults to build)
#   --build-only: the four builds only (make bench-build runs it beside the bench's other
#   builds, so that the bench's stability stage finds them up to date and only runs the sweep)
# Environment:
#   BENCH_QUICK=1        10^5 inputs per evaluator and build instead of 10^8 (CI)
#   STABILITY_N=N        inputs per evaluator and build (overrides both)
#   STABILITY_SLOW_DIV=k entries flagged slow get N/k inputs (default 1)
#   STABILITY_BUFFERS_N=N calls per pointer-taking function and build (tests/fuzz/pf_buffers.h;
#                        default 1000, 500 with BENCH_QUICK=1: a few seconds per build)
#   PFB_THREADS=j        processes at once (default: every core)
#   STABILITY_SHARDS=k   shards per build (default 8)
#   BENCH_OUT=dir        where the fragment and CSV go (default bench/out)
#   CC                   compiler (default gcc, as the Makefile's fast-math test builds)
#   STABILITY_STRICT=1   exit 1 on any finding (default: findings are reported in the fragment
#                        and on stderr, exit 0, so `make bench` completes)
# Exits 1 on a coverage gap (a public evaluator without an entry in tests/fuzz/pf_calls.h), or
# on a finding under STABILITY_STRICT=1; 2 on a build or tool error. The fragment is always
# written.
set -u
ROOT=$(cd "$(dirname "$0")/.." && pwd) || exit 2
cd "$ROOT" || exit 2
build_only=0
[ "${1:-}" = --build-only ] && { build_only=1; shift; }
BUILD=${1:-build}
DIR=$BUILD/stability
OUTDIR=${BENCH_OUT:-bench/out}
CC=${CC:-gcc}
mkdir -p "$DIR" "$OUTDIR" || exit 2

cov=0
[ $build_only = 1 ] || sh tests/fuzz/coverage.sh || { echo "stability: coverage gap (see above)" >&2; cov=1; }

WARN="-std=c99 -pedantic -Wall -Wextra -Werror -Wdouble-promotion"
builds="float double fastmath-float fastmath-double"
flags() { # build -> its flags
    case $1 in
        float) echo "" ;;
        double) echo "-DPF_DOUBLE" ;;
        fastmath-float) echo "-ffast-math" ;;
        fastmath-double) echo "-ffast-math -DPF_DOUBLE" ;;
    esac
}
label() { # build -> the label in the table
    case $1 in
        float|double) echo "$1" ;;
        fastmath-*) echo "${1#fastmath-} -ffast-math" ;;
    esac
}

# The four builds at once (bench/pool.sh: PFB_THREADS processes, default every core), each only
# when its binary is missing, older than a source, or built with another command (BIN.cmd).
jobs="$DIR/jobs.txt"
: > "$jobs"
for n in $builds; do
    cmd="$CC $WARN -O2 $(flags "$n") -Iinclude -Itests/fuzz bench/stability.c -lm -o $DIR/stability-$n"
    bin=$DIR/stability-$n
    if [ -x "$bin" ] && [ "$(cat "$bin.cmd" 2>/dev/null)" = "$cmd" ] &&
        [ -z "$(find bench/stability.c include tests/fuzz -newer "$bin" -name '*.[ch]' 2>/dev/null | head -n 1)" ]; then
        continue
    fi
    rm -f "$bin.cmd"
    echo "$cmd > $DIR/build-$n.log 2>&1 && echo '$cmd' > $bin.cmd" >> "$jobs"
done
sh bench/pool.sh "stability: builds" "$jobs" || {
    for n in $builds; do [ -x "$DIR/stability-$n" ] || cat "$DIR/build-$n.log" >&2; done
    echo "stability: a build failed" >&2; exit 2; }
[ $build_only = 1 ] && exit 0

# The sweep: every build cut into SHARDS shards (entries K modulo SHARDS; each entry draws from
# its own seed, so the counts are those of one process), all run PFB_THREADS at a time, the
# slow double builds first. STABILITY_SHARDS overrides the count (default 8 per build).
SHARDS=${STABILITY_SHARDS:-8}
ARGS=""
[ -n "${STABILITY_N:-}" ] && ARGS="-n $STABILITY_N"
rm -f "$DIR"/*.csv "$DIR"/*.status "$DIR"/*.log.shard*
: > "$jobs"
for n in fastmath-double double fastmath-float float; do
    k=0
    while [ $k -lt "$SHARDS" ]; do
        echo "$DIR/stability-$n $ARGS --label '$(label "$n")' --shard $k/$SHARDS --csv $DIR/$n.$k.csv 2> $DIR/$n.log.shard$k; echo \$? > $DIR/$n.$k.status" >> "$jobs"
        k=$((k + 1))
    done
done
start=$(date +%s)
sh bench/pool.sh "stability: sweep" "$jobs"
end=$(date +%s)
csvs=""
for n in $builds; do
    k=0
    while [ $k -lt "$SHARDS" ]; do
        s=$(cat "$DIR/$n.$k.status" 2>/dev/null || echo missing)
        [ "$s" = 0 ] || [ "$s" = 1 ] || { echo "stability: run $n shard $k failed (status $s)" >&2; cat "$DIR/$n.log.shard$k" >&2; exit 2; }
        csvs="$csvs $DIR/$n.$k.csv"
        k=$((k + 1))
    done
done
# merged in build order (the table's columns: float, double, then -ffast-math)
# shellcheck disable=SC2086
"$DIR/stability-double" --merge "$OUTDIR/stability.md" "$OUTDIR/stability.csv" $csvs
merged=$?
[ $merged -le 1 ] || exit 2
nproc_=${PFB_THREADS:-$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo 1)}
printf '\nWall time of the sweep: %s s (%s shards per build, %s at a time).\n' "$((end - start))" "$SHARDS" "$nproc_" >> "$OUTDIR/stability.md"
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
