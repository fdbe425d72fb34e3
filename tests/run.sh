#!/bin/sh
# Runs every test binary of every build and sums the RESULT lines.
# usage: tests/run.sh BUILD_DIR "CONFIGS" "TESTS" ["CONFIGS2" "TESTS2" ...]
#   every test of a group runs in every config of that group (C tests in six builds, the
#   GLM C++ tests in two); one total at the end.
# The binaries run TEST_JOBS at once (default: the online cores); each one's output is kept in
# its own file and printed whole, in config and test order, once all have run, so the log reads
# as a serial run's.
build=$1; shift
jobs=${TEST_JOBS:-$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo 2)}
case $jobs in ''|*[!0-9]*|0) jobs=2 ;; esac
tmp=$(mktemp -d "${TMPDIR:-/tmp}/pf-tests.XXXXXX") || exit 2
trap 'rm -rf "$tmp"' EXIT

# the runs: one line "config test" each, in print order
k=0
while [ $# -ge 2 ]; do
    for c in $1; do
        for t in $2; do
            k=$((k + 1))
            echo "$k $c $t" >> "$tmp/list"
        done
    done
    shift 2
done
[ -f "$tmp/list" ] || { echo "0 passed, 0 failed"; exit 0; }
# each run: its output to K.out, its exit status to K.rc (the fastmath builds: the edge_ cases)
sed "s|\$| $tmp|" "$tmp/list" | xargs -P "$jobs" -L 1 sh -c '
    k=$1; c=$2; t=$3; mode=""
    case $c in fastmath-*) mode=edge ;; esac
    "$0/$c/$t" $mode > "$4/$k.out" 2>&1
    echo $? > "$4/$k.rc"' "$build"

passed=0; failed=0; crashed=0
while read -r k c t; do
    out=$(cat "$tmp/$k.out" 2>/dev/null); rc=$(cat "$tmp/$k.rc" 2>/dev/null || echo 127)
    printf '%s\n' "$out" | grep -v '^RESULT'
    res=$(printf '%s\n' "$out" | grep '^RESULT' | tail -1)
    if [ -z "$res" ]; then
        echo "FAIL $t [$c] crashed or exited early (exit $rc)"
        failed=$((failed + 1)); crashed=$((crashed + 1))
        continue
    fi
    # "RESULT passed failed"
    np=$(printf '%s\n' "$res" | awk '{ print $2 }'); nf=$(printf '%s\n' "$res" | awk '{ print $3 }')
    passed=$((passed + np)); failed=$((failed + nf))
    if [ "$rc" -ne 0 ] && [ "$nf" -eq 0 ]; then
        echo "FAIL $t [$c] exit $rc with no failed case"; failed=$((failed + 1))
    fi
done < "$tmp/list"
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
