#!/bin/sh
# tests/portability/cell.sh - one cell of the compiler/flag matrix (and the ARM qemu run):
# compiles every tests/test_*.c with one compiler and one set of flags, then runs them.
#
# usage: sh tests/portability/cell.sh OUTDIR NAME MODE RUNNER KNOWN COMPILER [FLAGS...]
#   MODE     full     run every test case (the bounds of the module tests must hold)
#            edge     run only the edge_* cases (finite, in range, degenerate inputs): the
#                     -ffast-math cells and the cells kept short to fit the CI budget
#            compile  compile every test, run none
#            sizes    the whole suite of every test that can meet a size, a pointer or a buffer:
#                     the tests of a module with a pointer-taking CPU-only function (a
#                     PF_CPU_DEF in include/pf_<module>.h) and of the reference code (no
#                     include/pf_<module>.h); the tests of the pure-evaluator modules are
#                     compiled, not run (the x86-32 cells: with -mfpmath=sse their arithmetic is
#                     x86-64's, which the native cells and make test run; docs/porting.md)
#   RUNNER   -        run natively
#            CMD      run through CMD (qemu-arm for the ARM cross-build), with PF_TEST_REDUCED=1:
#                     the heaviest quadrature tests check fewer configurations under the
#                     emulator, with the same bounds (tests/pf_test.h, pf_test_reduced)
#   KNOWN    -        no failure tolerated
#            LIST     comma-separated failures this cell tolerates: "test_x:case_name" (that case
#                     may fail) or "test_x:*" (the binary is compiled, not run); every entry is
#                     explained in docs/porting.md (ARM: long double is double there)
# Writes OUTDIR/NAME/result: "ok <detail>" or "FAIL <detail>", logs OUTDIR/NAME/<test>.{log,out}.
# Run from the repository root (run.sh does).
set -u
out=$1/$2; name=$2; mode=$3; runner=$4; known=$(echo "$5" | tr ',' ' '); shift 5
[ "$known" = - ] && known=""
mkdir -p "$out" || exit 2

ncomp=0; nrun=0; nsk=0; passed=0; failed=0; ntol=0; bad=""; tol=""
for src in tests/test_*.c; do
    t=$(basename "$src" .c)
    if ! "$@" -DPF_TEST_CONFIG="\"$name\"" -Iinclude -Itests -Itests/reference "$src" -o "$out/$t" -lm > "$out/$t.log" 2>&1; then
        bad="$bad $t(compile)"; continue
    fi
    ncomp=$((ncomp + 1))
    [ "$mode" = compile ] && continue
    if [ "$mode" = sizes ]; then
        h=include/pf_${t#test_}.h
        if [ -f "$h" ] && ! grep -q '^PF_CPU_DEF' "$h"; then nsk=$((nsk + 1)); continue; fi
    fi
    case " $known " in *" $t:* "*) tol="$tol $t(not run)"; continue ;; esac
    arg=""; [ "$mode" = edge ] && arg=edge
    if [ "$runner" = - ]; then "$out/$t" $arg > "$out/$t.out" 2>&1; rc=$?
    else PF_TEST_REDUCED=1 $runner "$out/$t" $arg > "$out/$t.out" 2>&1; rc=$?
    fi
    nrun=$((nrun + 1))
    res=$(grep '^RESULT' "$out/$t.out" | tail -1)
    if [ -z "$res" ]; then bad="$bad $t(crashed, exit $rc)"; continue; fi
    np=$(echo "$res" | awk '{print $2}')
    passed=$((passed + np))
    # every failed case must be listed as known for this cell
    for c in $(awk '$1 == "FAIL" {print $2}' "$out/$t.out"); do
        case " $known " in
        *" $t:$c "*) ntol=$((ntol + 1)); tol="$tol $t:$c" ;;
        *) failed=$((failed + 1)); bad="$bad $t:$c" ;;
        esac
    done
    # and every known case of it that ran must still fail: a stale entry would hide a regression
    for k in $known; do
        case $k in "$t:"*) c=${k#"$t:"}
            if [ "$c" != "*" ] && awk -v c="$c" '$1 == "ok" && $2 == c { f = 1 } END { exit !f }' "$out/$t.out"; then
                bad="$bad $t:$c(listed as known but passes: remove it from the list)"
            fi ;;
        esac
    done
    nf=$(echo "$res" | awk '{print $3}')
    [ "$rc" -ne 0 ] && [ "$nf" -eq 0 ] && bad="$bad $t(exit $rc)"
done
case $mode in
compile) what="$ncomp tests compiled" ;;
sizes) what="$ncomp compiled, $nrun run (full; $nsk of pure-evaluator modules compiled only): $passed cases passed" ;;
*) what="$ncomp compiled, $nrun run ($mode): $passed cases passed" ;;
esac
[ -n "$tol" ] && what="$what; known, see docs/porting.md:$tol"
if [ -n "$bad" ]; then echo "FAIL $what; failed:$bad (logs in $out)" > "$out/result"
else echo "ok $what" > "$out/result"
fi
