#!/bin/sh
# tests/fuzz/run.sh - build and run the libFuzzer harnesses, one per module, float and double.
#
# usage: sh tests/fuzz/run.sh [BUILD_DIR]          (BUILD_DIR defaults to build)
# Environment:
#   FUZZ_SECONDS   seconds per harness and precision (default 5: 8 modules x 2 precisions
#                  ~ 1.5 min in CI; run longer by hand, e.g. FUZZ_SECONDS=600)
#   FUZZ_MODULES   modules to run (default: every tests/fuzz/fuzz_*.c)
#   FUZZ_JOBS      harnesses run at once (default 2)
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

sh tests/fuzz/coverage.sh || exit 1
command -v "$CLANG" >/dev/null 2>&1 || { echo "fuzz: $CLANG not found" >&2; exit 2; }

FLAGS="-std=c99 -pedantic -Wall -Wextra -Werror -Wdouble-promotion -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all -Iinclude -Itests/fuzz"
fail=0
for m in $MODULES; do
    for p in float double; do
        d=""; [ $p = double ] && d="-DPF_DOUBLE"
        if ! $CLANG $FLAGS $d "tests/fuzz/fuzz_$m.c" -lm -o "$OUT/bin/fuzz_$m-$p" 2> "$OUT/logs/build_$m-$p.log"; then
            echo "FAIL build fuzz_$m-$p (log: $OUT/logs/build_$m-$p.log)"; sed 's/^/  /' "$OUT/logs/build_$m-$p.log" | head -20
            fail=1
        fi
    done
done
[ $fail -eq 0 ] || exit 1

# run one harness: module precision
run_one() {
    m=$1; p=$2
    c="$OUT/corpus/$m-$p"
    mkdir -p "$c"
    if "$OUT/bin/fuzz_$m-$p" "$c" -max_total_time="$SECS" -timeout=20 -rss_limit_mb=2048 \
        -artifact_prefix="$OUT/artifacts/$m-$p-" -print_final_stats=1 > "$OUT/logs/run_$m-$p.log" 2>&1; then
        runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$OUT/logs/run_$m-$p.log" | tail -1)
        echo "ok   fuzz_$m-$p  ${runs:-?} runs in ${SECS}s"
    else
        echo "FAIL fuzz_$m-$p  (log: $OUT/logs/run_$m-$p.log; artifacts: $OUT/artifacts/$m-$p-*)"
        grep -E "pf_fuzz:|inputs:|outputs:|runtime error|ERROR: AddressSanitizer|SUMMARY" "$OUT/logs/run_$m-$p.log" | head -8 | sed 's/^/  /'
        return 1
    fi
}

# JOBS harnesses at a time; a status file per harness
rm -f "$OUT"/logs/*.status
set -- $(for m in $MODULES; do echo "$m:float $m:double"; done)
while [ $# -gt 0 ]; do
    pids=""
    k=0
    while [ $# -gt 0 ] && [ $k -lt "$JOBS" ]; do
        m=${1%%:*}; p=${1#*:}; shift
        ( run_one "$m" "$p"; echo $? > "$OUT/logs/$m-$p.status" ) &
        pids="$pids $!"
        k=$((k + 1))
    done
    for pid in $pids; do wait "$pid"; done
done
for f in "$OUT"/logs/*.status; do
    [ "$(cat "$f")" = 0 ] || fail=1
done
[ $fail -eq 0 ] && echo "fuzz: every harness clean (${SECS}s each)" || echo "fuzz: FINDINGS (see above)"
exit $fail
