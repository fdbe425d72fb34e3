#!/bin/sh
# bench/times.sh - measure the wall times the README states for the bench, on THIS machine.
# Run it on an idle machine (nothing else running: the numbers are the README's); it takes
# about the sum of the times it measures.
#
# usage: sh bench/times.sh [WHAT...]      WHAT: quick full map ci spread (default: quick full map)
# Each bench command runs with PFB_THREADS=1, 2 and every core (duplicates dropped: on a 2-core
# machine 1 and 2), after one
# untimed build (`make bench-build`), so the times are the runs' own; `ci` runs `bash .ci/run`
# once (it builds everything itself, on every core). Prints the README's table rows (markdown)
# on stdout and each run's log under bench/out/times/.
#   spread: how repeatable the per-module medians are at each time budget (pf_bench.h's
#        --budget-ms; make bench BENCH_BUDGET_MS=B): each of SPREAD_MODULES (default
#        "smith-float masks-double", binaries of build/bench) runs twice at each of
#        SPREAD_BUDGETS (default "250 125" ms), alone; prints per budget and module the median
#        and largest difference between the two runs over the methods, of ns/eval (relative)
#        and of x baseline (absolute), random and sorted inputs, and the timing phase's CPU
#        seconds (what the budget buys). Idle machine only: load moves medians more than budgets.
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
if [ "$what" != spread ]; then
    echo "| command | $(for t in $threads; do printf '%s thread%s | ' "$t" "$([ "$t" = 1 ] || echo s)"; done)"
    echo "|---|$(for t in $threads; do printf -- '--:|'; done)"
fi
# spread_rows MODULE BUDGET CSV1 CSV2 CPU1 CPU2: one markdown row (see the header)
spread_row() {
    awk -F, -v m="$1" -v b="$2" -v c1="$5" -v c2="$6" '
        function med(v, n,   i, j, t) { for (i = 1; i <= n; i++) for (j = i + 1; j <= n; j++) if (v[j] < v[i]) { t = v[i]; v[i] = v[j]; v[j] = t }
                                        return n % 2 ? v[(n + 1) / 2] : (v[n / 2] + v[n / 2 + 1]) / 2 }
        function mx(v, n,   i, x) { x = 0; for (i = 1; i <= n; i++) if (v[i] > x) x = v[i]; return x }
        FNR == 1 { f++; next }
        f == 1 { ns[$1 "/" $2] = $4; r[$1 "/" $2] = $5; nss[$1 "/" $2] = $15; rs[$1 "/" $2] = $16; next }
        f == 2 && ($1 "/" $2) in ns {
            k = $1 "/" $2; n++
            dn[n] = ($4 + ns[k] > 0) ? 200 * ($4 - ns[k]) / ($4 + ns[k]) : 0; if (dn[n] < 0) dn[n] = -dn[n]
            dr[n] = $5 - r[k]; if (dr[n] < 0) dr[n] = -dr[n]
            ds[n] = ($15 + nss[k] > 0) ? 200 * ($15 - nss[k]) / ($15 + nss[k]) : 0; if (ds[n] < 0) ds[n] = -ds[n]
            drs[n] = $16 - rs[k]; if (drs[n] < 0) drs[n] = -drs[n] }
        END { printf "| %s | %s ms | %d | %.1f%% / %.1f%% | %.3f / %.3f | %.1f%% / %.1f%% | %.3f / %.3f | %s s, %s s |\n",
                     m, b, n, med(dn, n), mx(dn, n), med(dr, n), mx(dr, n), med(ds, n), mx(ds, n), med(drs, n), mx(drs, n), c1, c2 }' "$3" "$4"
}
spread() {
    echo "| binary | budget | methods | ns/eval: median / largest difference | x baseline: median / largest | sorted ns/eval | sorted x baseline | timing CPU, run 1, run 2 |"
    echo "|---|--:|--:|--:|--:|--:|--:|--:|"
    for b in ${SPREAD_BUDGETS:-250 125}; do
        for m in ${SPREAD_MODULES:-smith-float masks-double}; do
            for r in 1 2; do
                rm -f "$logs/spread-$m-$b-$r.csv"
                "build/bench/bench_$m" --budget-ms "$b" --csv "$logs/spread-$m-$b-$r.csv" > "$logs/spread-$m-$b-$r.log" 2>&1 ||
                    { echo "times: build/bench/bench_$m failed ($logs/spread-$m-$b-$r.log)" >&2; return 1; }
            done
            cpu() { sed -n 's/.*timing \([0-9.]*\) s (one thread).*/\1/p' "$logs/spread-$m-$b-$1.log" | tail -n 1; }
            spread_row "$m" "$b" "$logs/spread-$m-$b-1.csv" "$logs/spread-$m-$b-2.csv" "$(cpu 1)" "$(cpu 2)"
        done
    done
}
for w in $what; do
    case $w in
        spread) spread; continue ;;
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
