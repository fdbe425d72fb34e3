#!/bin/sh
# tests/fuzz/run.sh - build and run the libFuzzer harnesses, one per module, float and double.
#
# usage: sh tests/fuzz/run.sh [BUILD_DIR]          (BUILD_DIR defaults to build)
# Environment:
#   FUZZ_SECONDS   seconds per harness and precision (default 5: 8 modules x 2 precisions
#                  ~ 1.5 min in CI; run longer by hand, e.g. FUZZ_SECONDS=600)
#   FUZZ_MODULES   modules to run (default: every tests/fuzz/fuzz_*.c)
#   FUZZ_JOBS      harnesses built and run at once (default 2); each harness is one job (its
#                  build, then its run), so one harness builds while another runs; the lines
#                  of every harness are printed together, in module order, at the end
#   CLANG          compiler (default clang; needs libclang_rt.fuzzer, e.g. libclang-rt-dev)
#   PF_FUZZ_KNOWN=1   also report the known findings (filtered by default, see pf_fuzz.h)
#   PF_FUZZ_STRICT=1  also fail on non-finite results from arbitrary finite inputs
# Builds with -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all. Corpora are kept
# in BUILD_DIR/fuzz/corpus/<module>-<precision> (they grow across runs), crash artifacts and
# logs in BUILD_DIR/fuzz/artifacts and BUILD_DIR/fuzz/logs. Checks coverage first
# (tests/fuzz/coverage.sh). Exits nonzero on any finding, build failure or coverage gap.
set -u
ROOT=$(cd "$(dirname "$0")/../.." && pwd) || exit 2
cd "$ROOT" || exit 2
BUILD=${1:-build}
OUT=$BUILD/fuzz
CLANG=${CLANG:-clang}
SECS=${FUZZ_SECONDS:-5}
JOBS=${FUZZ_JOBS:-2}
MODULES=${FUZZ_MODULES:-$(cd tests/fuzz && ls fuzz_*.c | sed 's/^fuzz_//; s/\.c$//')}
mkdir -p "$OUT/bin" "$OUT/corpus" "$OUT/artifacts" "$OUT/logs" || exit 2

[ "${FUZZ_JOB:-}" = 1 ] || sh tests/fuzz/coverage.sh || exit 1
command -v "$CLANG" >/dev/null 2>&1 || { echo "fuzz: $CLANG not found" >&2; exit 2; }

FLAGS="-std=c99 -pedantic -Wall -Wextra -Werror -Wdouble-promotion -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all -Iinclude -Itests/fuzz"

# one harness, built then run: module precision; its lines go to logs/<module>-<precision>.line
# and its status (0 clean) to logs/<module>-<precision>.status
job() {
    m=$1; p=$2
    d=""; [ $p = double ] && d="-DPF_DOUBLE"
    line=$OUT/logs/$m-$p.line
    if ! $CLANG $FLAGS $d "tests/fuzz/fuzz_$m.c" -lm -o "$OUT/bin/fuzz_$m-$p" 2> "$OUT/logs/build_$m-$p.log"; then
        { echo "FAIL build fuzz_$m-$p (log: $OUT/logs/build_$m-$p.log)"; sed 's/^/  /' "$OUT/logs/build_$m-$p.log" | head -20; } > "$line"
        echo 1 > "$OUT/logs/$m-$p.status"
        return
    fi
    c="$OUT/corpus/$m-$p"
    mkdir -p "$c"
    if "$OUT/bin/fuzz_$m-$p" "$c" -max_total_time="$SECS" -timeout=20 -rss_limit_mb=2048 \
        -artifact_prefix="$OUT/artifacts/$m-$p-" -print_final_stats=1 > "$OUT/logs/run_$m-$p.log" 2>&1; then
        runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$OUT/logs/run_$m-$p.log" | tail -1)
        echo "ok   fuzz_$m-$p  ${runs:-?} runs in ${SECS}s" > "$line"
        echo 0 > "$OUT/logs/$m-$p.status"
    else
        { echo "FAIL fuzz_$m-$p  (log: $OUT/logs/run_$m-$p.log; artifacts: $OUT/artifacts/$m-$p-*)"
          grep -E "pf_fuzz:|inputs:|outputs:|runtime error|ERROR: AddressSanitizer|SUMMARY" "$OUT/logs/run_$m-$p.log" | head -8 | sed 's/^/  /'; } > "$line"
        echo 1 > "$OUT/logs/$m-$p.status"
    fi
}
if [ "${FUZZ_JOB:-}" = 1 ]; then
    job "$2" "$3"
    echo "$2-$3" >> "$OUT/logs/done.txt"
    echo "fuzz: fuzz_$2-$3 done ($(grep -c . "$OUT/logs/done.txt")/$(grep -c . "$OUT/logs/jobs.txt"))" >&2
    exit 0
fi

# JOBS harnesses at a time, each built and then run (so builds and runs overlap); every
# harness's lines printed whole, in module order, when all have ended
rm -f "$OUT"/logs/*.status "$OUT"/logs/*.line "$OUT/logs/done.txt"
for m in $MODULES; do echo "$m float"; echo "$m double"; done > "$OUT/logs/jobs.txt"
FUZZ_JOB=1 xargs -P "$JOBS" -L 1 sh tests/fuzz/run.sh "$BUILD" < "$OUT/logs/jobs.txt"
fail=0
while read -r m p; do
    if [ -f "$OUT/logs/$m-$p.line" ]; then cat "$OUT/logs/$m-$p.line"; else echo "FAIL fuzz_$m-$p  (the job wrote nothing)"; fi
    [ "$(cat "$OUT/logs/$m-$p.status" 2>/dev/null)" = 0 ] || fail=1
done < "$OUT/logs/jobs.txt"
[ $fail -eq 0 ] && echo "fuzz: every harness clean (${SECS}s each)" || echo "fuzz: FINDINGS (see above)"
exit $fail
