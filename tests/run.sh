#!/bin/sh
# Runs every test binary of every build and sums the RESULT lines.
# usage: tests/run.sh BUILD_DIR "CONFIGS" "TESTS"
build=$1; configs=$2; tests=$3
passed=0; failed=0; crashed=0
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
        set -- $res
        passed=$((passed + $2)); failed=$((failed + $3))
        if [ "$rc" -ne 0 ] && [ "$3" -eq 0 ]; then
            echo "FAIL $t [$c] exit $rc with no failed case"; failed=$((failed + 1))
        fi
    done
done
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
