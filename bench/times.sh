#!/bin/sh
# bench/times.sh - measure the wall times the README states for the bench, on THIS machine.
# Run it on an idle machine (nothing else running: the numbers are the README's); it takes
# about the sum of the times it measures.
#
# usage: sh bench/times.sh [WHAT...]      WHAT: quick full map ci (default: quick full map)
# Each bench command runs with PFB_THREADS=1, 2 and every core (duplicates dropped: on a 2-core
# machine 1 and 2), after one
# untimed build (`make bench-build`), so the times are the runs' own; `ci` runs `bash .ci/run`
# once (it builds everything itself, on every core). Prints the README's table rows (markdown)
# on stdout and each run's log under bench/out/times/.
#   map: TIMES_MAP=path (with TIMES_MAP_ARGS="MAP_KIND=... MAP_SCALE=..."), default a 512 x 512
#        Gaussian height field (tests/reference/pf_microsurface.h) written as raw float32.
set -u
ROOT=$(cd "$(dirname "$0")/.." && pwd) || exit 2
cd "$ROOT" || exit 2
what=${*:-quick full map}
nc=$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo 1)
threads=$(printf '%s\n' 1 2 "$nc" | awk '$1 <= '"$nc"' && !seen[$1]++' | tr '\n' ' ')
logs=bench/out/times
mkdir -p "$logs"
load=$(cut -d' ' -f1 /proc/loadavg 2>/dev/null || echo "?")
echo "times: $nc cores, load average $load before the runs (should be ~0)" >&2
make --no-print-directory bench-build > "$logs/build.log" 2>&1 || { echo "times: build failed ($logs/build.log)" >&2; exit 1; }

map=${TIMES_MAP:-}
map_args=${TIMES_MAP_ARGS:-}
if [ -z "$map" ]; then
    map=$logs/gaussian512.raw
    map_args="MAP_RAW_SIZE=512x512"
    cat > "$logs/mkmap.c" <<'EOF'
#include "pf_maps.h"
int main(int argc, char **argv)
{
    pfm_surface s;
    static float h[512 * 512];
    int i;
    if (argc < 2 || pfm_surface_make(&s, 512, 512, 1.0, pfm_params_default(PFM_GAUSSIAN)) != 0) return 1;
    for (i = 0; i < 512 * 512; ++i) h[i] = (float)s.height[i];
    return pfmap_write_raw(argv[1], h, (size_t)512 * 512) != 0;
}
EOF
    ${CC:-cc} -std=c99 -O2 -Iinclude -Itests/reference "$logs/mkmap.c" -o "$logs/mkmap" -lpng -lm &&
        "$logs/mkmap" "$map" || { echo "times: could not write the test map" >&2; exit 1; }
fi

# run LABEL THREADS COMMAND...: prints the wall seconds (the table's cell); on stderr also the
# CPU seconds (user + system of the command and its children, the shell's `times` in the
# $(...) subshell that runs it), which a busy machine inflates far less than the wall time
run() { # label threads command...
    l=$1; t=$2; shift 2
    t0=$(date +%s)
    if PFB_THREADS=$t "$@" > "$logs/$l-$t.log" 2>&1; then
        el=$(($(date +%s) - t0))
        times > "$logs/times.tmp" # not in a pipe: a pipe's subshell has no children
        cpu=$(awk 'NR == 2 { split($1, u, /[ms]/); split($2, s, /[ms]/); printf "%.0f", u[1] * 60 + u[2] + s[1] * 60 + s[2] }' "$logs/times.tmp")
        echo "times: $l, PFB_THREADS=$t: $el s wall, $cpu s CPU (user + system)" >&2
        echo "$el"
    else
        echo "failed ($logs/$l-$t.log)"
    fi
}
echo "| command | $(for t in $threads; do printf '%s thread%s | ' "$t" "$([ "$t" = 1 ] || echo s)"; done)"
echo "|---|$(for t in $threads; do printf -- '--:|'; done)"
for w in $what; do
    case $w in
        quick) row="| \`make bench BENCH_QUICK=1\` |"
               for t in $threads; do row="$row $(run quick "$t" make --no-print-directory bench BENCH_QUICK=1) s |"; done ;;
        full)  row="| \`make bench\` |"
               for t in $threads; do row="$row $(run full "$t" make --no-print-directory bench) s |"; done ;;
        map)   row="| \`make bench MAP=\` (512 x 512) |"
               # shellcheck disable=SC2086
               for t in $threads; do row="$row $(run map "$t" make --no-print-directory bench MAP="$map" $map_args) s |"; done ;;
        ci)    row="| \`bash .ci/run\` (all of CI, builds included, every core) | $(run ci "$nc" bash .ci/run) s |" ;;
        *) echo "times: unknown WHAT $w (quick full map ci)" >&2; exit 2 ;;
    esac
    echo "$row"
done
echo "times: measured $(date -u '+%Y-%m-%d %H:%M UTC'), $nc cores, $(awk -F': *' '/^model name/ { print $2; exit }' /proc/cpuinfo 2>/dev/null)" >&2
