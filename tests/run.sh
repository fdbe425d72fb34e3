#!/bin/sh
# Runs every test binary of every build and sums the RESULT lines.
# usage: tests/run.sh BUILD_DIR "CONFIGS" "TESTS" ["CONFIGS2" "TESTS2" ...]
#   every test of a group runs in every config of that group (C tests in six builds, the
#   GLM C++ tests in two); one total at the end.
build=$1; shift
passed=0; failed=0; crashed=0
while [ $# -ge 2 ]; do
configs=$1; tests=$2; shift 2
for c in $configs; do
    mode=""
    case $c in fastmath-*) mode=edge ;; esac
    for t in $tests; do
        out=$("$build/$c/$t" $mode 2>&1); rc=$?
        printf '%s\n' "$out" | grep -v '^RESULT'
        res=$(printf '%s\n' "$out" | grep '^RESULT' | tail -1)
        if [ -z "$res" ]; then
            echo "FAIL $t [$c] crashed or exited early (exit $rc)"
            failed=$((failed + 1)); crashed=$((crashed + 1))
            continue
        fi
        # "RESULT passed failed" (not through set --: the positional parameters hold the groups)
        np=$(printf '%s\n' "$res" | awk '{ print $2 }'); nf=$(printf '%s\n' "$res" | awk '{ print $3 }')
        passed=$((passed + np)); failed=$((failed + nf))
        if [ "$rc" -ne 0 ] && [ "$nf" -eq 0 ]; then
            echo "FAIL $t [$c] exit $rc with no failed case"; failed=$((failed + 1))
        fi
    done
done
done
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
