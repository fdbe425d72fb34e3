#!/bin/sh
# tests/fuzz/run.sh - build and run the libFuzzer harnesses, one per module, float and double.
#
# usage: sh tests/fuzz/run.sh [BUILD_DIR]          (BUILD_DIR defaults to build)
# Environment:
#   FUZZ_SECONDS   seconds per harness and precision (default 5: 24 harnesses x 2 precisions,
#                  2 at a time on 2 cores, is 2 min of fuzzing in CI; run longer by hand, e.g.
#                  FUZZ_SECONDS=600)
#   FUZZ_MODULES   harnesses to run (default: every tests/fuzz/fuzz_*.c)
#   FUZZ_JOBS      harnesses run at once (default: the online cores); the lines of every
#                  harness are printed together, in module order, at the end
#   CLANG          compiler (default clang; needs libclang_rt.fuzzer, e.g. libclang-rt-dev)
#   PF_FUZZ_KNOWN=1   also report the known findings (filtered by default, see pf_fuzz.h)
#   PF_FUZZ_STRICT=1  also fail on non-finite results from arbitrary finite inputs
# ONE BINARY PER PRECISION. Every harness includes pf_calls.h (every evaluator of every module),
# so building each harness on its own compiled the whole library 44 times under the sanitizers
# (about 10 s of CPU each, most of the fuzz job). Instead the harnesses are built into one
# binary per precision, BUILD_DIR/fuzz/bin/fuzz_all-<precision>: a generated file includes every
# tests/fuzz/fuzz_<name>.c with its LLVMFuzzerTestOneInput renamed, and the environment variable
# PF_FUZZ_HARNESS=<name> picks the harness at start (LLVMFuzzerInitialize). Each harness still
# runs alone, FUZZ_SECONDS, on its own corpus, exactly as its own binary did; each harness file
# is also compiled alone (-fsyntax-only), so each still builds by itself:
#   clang -fsanitize=fuzzer,address,undefined ... -Iinclude -Itests/fuzz tests/fuzz/fuzz_vmf.c
# Builds with -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all. Corpora are kept
# in BUILD_DIR/fuzz/corpus/<module>-<precision> (they grow across runs), crash artifacts and
# logs in BUILD_DIR/fuzz/artifacts and BUILD_DIR/fuzz/logs (a finding's reproducer:
# PF_FUZZ_HARNESS=<module> BUILD_DIR/fuzz/bin/fuzz_all-<precision> ARTIFACT). Checks coverage
# first (tests/fuzz/coverage.sh). Exits nonzero on any finding, build failure or coverage gap.
set -u
ROOT=$(cd "$(dirname "$0")/../.." && pwd) || exit 2
cd "$ROOT" || exit 2
BUILD=${1:-build}
OUT=$BUILD/fuzz
CLANG=${CLANG:-clang}
SECS=${FUZZ_SECONDS:-5}
JOBS=${FUZZ_JOBS:-$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo 2)}
MODULES=${FUZZ_MODULES:-$(cd tests/fuzz && ls fuzz_*.c | sed 's/^fuzz_//; s/\.c$//')}
mkdir -p "$OUT/bin" "$OUT/corpus" "$OUT/artifacts" "$OUT/logs" || exit 2

[ -n "${FUZZ_JOB:-}" ] || sh tests/fuzz/coverage.sh || exit 1
command -v "$CLANG" >/dev/null 2>&1 || { echo "fuzz: $CLANG not found" >&2; exit 2; }

FLAGS="-std=c99 -pedantic -Wall -Wextra -Werror -Wdouble-promotion -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all -Iinclude -Itests/fuzz"

# build PRECISION: the generated all-harness source and its binary; status in logs/build-<p>.status
build() {
    p=$1
    d=""; [ $p = double ] && d="-DPF_DOUBLE"
    src=$OUT/src/fuzz_all.c
    log=$OUT/logs/build_all-$p.log
    if $CLANG $FLAGS $d "$src" -lm -o "$OUT/bin/fuzz_all-$p" > "$log" 2>&1; then
        echo 0 > "$OUT/logs/build-$p.status"
    else
        echo 1 > "$OUT/logs/build-$p.status"
    fi
}
# run MODULE PRECISION: one harness on its corpus; its lines go to logs/<module>-<precision>.line
# and its status (0 clean) to logs/<module>-<precision>.status
run() {
    m=$1; p=$2
    line=$OUT/logs/$m-$p.line
    if [ "$(cat "$OUT/logs/build-$p.status" 2>/dev/null)" != 0 ]; then
        { echo "FAIL build fuzz_all-$p (log: $OUT/logs/build_all-$p.log)"; sed 's/^/  /' "$OUT/logs/build_all-$p.log" | head -20; } > "$line"
        echo 1 > "$OUT/logs/$m-$p.status"
        return
    fi
    c="$OUT/corpus/$m-$p"
    mkdir -p "$c"
    if PF_FUZZ_HARNESS=$m "$OUT/bin/fuzz_all-$p" "$c" -max_total_time="$SECS" -timeout=20 -rss_limit_mb=2048 \
        -artifact_prefix="$OUT/artifacts/$m-$p-" -print_final_stats=1 > "$OUT/logs/run_$m-$p.log" 2>&1; then
        runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$OUT/logs/run_$m-$p.log" | tail -1)
        echo "ok   fuzz_$m-$p  ${runs:-?} runs in ${SECS}s" > "$line"
        echo 0 > "$OUT/logs/$m-$p.status"
    else
        { echo "FAIL fuzz_$m-$p  (log: $OUT/logs/run_$m-$p.log; artifacts: $OUT/artifacts/$m-$p-*)"
          grep -E "pf_fuzz:|inputs:|outputs:|runtime error|ERROR: AddressSanitizer|SUMMARY|PF_FUZZ_HARNESS" "$OUT/logs/run_$m-$p.log" | head -8 | sed 's/^/  /'; } > "$line"
        echo 1 > "$OUT/logs/$m-$p.status"
    fi
}
case "${FUZZ_JOB:-}" in
build) build "$2"; echo "fuzz: fuzz_all-$2 built" >&2; exit 0 ;;
syntax) # every harness file compiles alone (float; the build above compiles both precisions)
    bad=""
    for m in $(cat "$OUT/logs/modules.txt"); do
        $CLANG $FLAGS -fsyntax-only "tests/fuzz/fuzz_$m.c" > "$OUT/logs/syntax_$m.log" 2>&1 || bad="$bad $m"
    done
    echo "$bad" > "$OUT/logs/syntax.bad"
    exit 0 ;;
run)
    run "$2" "$3"
    echo "$2-$3" >> "$OUT/logs/done.txt"
    echo "fuzz: fuzz_$2-$3 done ($(grep -c . "$OUT/logs/done.txt")/$(grep -c . "$OUT/logs/jobs.txt"))" >&2
    exit 0 ;;
esac

rm -f "$OUT"/logs/*.status "$OUT"/logs/*.line "$OUT/logs/done.txt" "$OUT/logs/syntax.bad"
echo "$MODULES" | tr ' ' '\n' | grep . > "$OUT/logs/modules.txt"
# the all-harness source: every harness file (all of them, whatever FUZZ_MODULES says, so that
# the binary is the same), its LLVMFuzzerTestOneInput renamed pffa_<name>, and a table by name
mkdir -p "$OUT/src"
all=$(cd tests/fuzz && ls fuzz_*.c | sed 's/^fuzz_//; s/\.c$//')
{
    echo "/* generated by tests/fuzz/run.sh: every tests/fuzz/fuzz_*.c harness in one binary;"
    echo "   PF_FUZZ_HARNESS=<name> in the environment picks the harness. Do not edit. */"
    echo "#define _DEFAULT_SOURCE 1"
    for m in $all; do
        echo "#define LLVMFuzzerTestOneInput pffa_$m"
        echo "#include \"fuzz_$m.c\""
        echo "#undef LLVMFuzzerTestOneInput"
    done
    echo "#include <stdio.h>"
    echo "#include <stdlib.h>"
    echo "#include <string.h>"
    echo "typedef int (*pffa_fn)(const unsigned char *, size_t);"
    echo "static const struct { const char *name; pffa_fn fn; } pffa_table[] = {"
    for m in $all; do echo "    { \"$m\", pffa_$m },"; done
    echo "};"
    echo "static pffa_fn pffa_run;"
    echo "int LLVMFuzzerInitialize(int *argc, char ***argv);"
    echo "int LLVMFuzzerInitialize(int *argc, char ***argv)"
    echo "{"
    echo "    const char *h = getenv(\"PF_FUZZ_HARNESS\");"
    echo "    size_t i;"
    echo "    (void)argc; (void)argv;"
    echo "    for (i = 0; h && i < sizeof pffa_table / sizeof pffa_table[0]; ++i)"
    echo "        if (!strcmp(h, pffa_table[i].name)) pffa_run = pffa_table[i].fn;"
    echo "    if (!pffa_run) {"
    printf '%s\n' '        fprintf(stderr, "PF_FUZZ_HARNESS=%s: no such harness (tests/fuzz/fuzz_<name>.c)\n", h ? h : "(unset)");'
    echo "        exit(2);"
    echo "    }"
    echo "    return 0;"
    echo "}"
    echo "int LLVMFuzzerTestOneInput(const unsigned char *data, size_t size);"
    echo "int LLVMFuzzerTestOneInput(const unsigned char *data, size_t size) { return pffa_run(data, size); }"
} > "$OUT/src/fuzz_all.c.tmp"
# rebuilt only when the source, a harness or a header changed (a re-run fuzzes at once)
rebuild=1
if cmp -s "$OUT/src/fuzz_all.c.tmp" "$OUT/src/fuzz_all.c" && [ -f "$OUT/bin/fuzz_all-float" ] && [ -f "$OUT/bin/fuzz_all-double" ] &&
   [ -z "$(find include tests/fuzz -newer "$OUT/bin/fuzz_all-float" -type f 2>/dev/null | head -1)" ] &&
   [ -z "$(find include tests/fuzz -newer "$OUT/bin/fuzz_all-double" -type f 2>/dev/null | head -1)" ] &&
   [ "$(cat "$OUT/bin/flags.txt" 2>/dev/null)" = "$CLANG $FLAGS" ]; then
    rebuild=0
fi
mv "$OUT/src/fuzz_all.c.tmp" "$OUT/src/fuzz_all.c"
if [ $rebuild = 1 ]; then
    rm -f "$OUT/bin/fuzz_all-float" "$OUT/bin/fuzz_all-double"
    # both precisions at once, and the per-file syntax check beside them
    t0=$(date +%s)
    printf 'build float\nbuild double\nsyntax -\n' |
        xargs -P "$JOBS" -L 1 sh -c 'FUZZ_JOB=$1 sh tests/fuzz/run.sh "$0" "$2"' "$BUILD"
    echo "$CLANG $FLAGS" > "$OUT/bin/flags.txt"
    echo "fuzz: built in $(($(date +%s) - t0)) s" >&2
else
    echo 0 > "$OUT/logs/build-float.status"; echo 0 > "$OUT/logs/build-double.status"; echo "" > "$OUT/logs/syntax.bad"
    echo "fuzz: fuzz_all-float and fuzz_all-double up to date" >&2
fi
fail=0
sbad=$(cat "$OUT/logs/syntax.bad" 2>/dev/null)
if [ -n "$sbad" ]; then
    for m in $sbad; do echo "FAIL fuzz_$m.c does not compile alone (log: $OUT/logs/syntax_$m.log)"; sed 's/^/  /' "$OUT/logs/syntax_$m.log" | head -10; done
    fail=1
fi
# JOBS harnesses at a time; every harness's lines printed whole, in module order, at the end
for m in $MODULES; do echo "$m float"; echo "$m double"; done > "$OUT/logs/jobs.txt"
FUZZ_JOB=run xargs -P "$JOBS" -L 1 sh tests/fuzz/run.sh "$BUILD" < "$OUT/logs/jobs.txt"
while read -r m p; do
    if [ -f "$OUT/logs/$m-$p.line" ]; then cat "$OUT/logs/$m-$p.line"; else echo "FAIL fuzz_$m-$p  (the job wrote nothing)"; fi
    [ "$(cat "$OUT/logs/$m-$p.status" 2>/dev/null)" = 0 ] || fail=1
done < "$OUT/logs/jobs.txt"
[ $fail -eq 0 ] && echo "fuzz: every harness clean (${SECS}s each)" || echo "fuzz: FINDINGS (see above)"
exit $fail
