#!/bin/sh
# bench/run.sh - run every bench binary (float and double), then write bench/out/:
#   <module>.csv            one row per method and build (columns: see bench/pf_bench.h)
#   <module>.notes          inputs, grids, references, A/A checks (family<TAB>note)
#   <module>_<family>.svg   error versus cost, one chart per family (gnuplot; make bench installs
#                           it through tests/deps.sh: no chart is ever skipped)
#   summary.md              compiler, flags, CPU, date, then markdown tables per family
# Called by `make bench` from the repository root:  sh bench/run.sh BUILD_DIR
# Environment: CC and BENCH_FLAGS (recorded in the summary), CALLGRIND=0/1 (instruction counts;
# default: on in a full run when valgrind is installed), BENCH_QUICK=1 (CI smoke run).
set -e

# The charts are the main job's point: without gnuplot, stop now rather than after minutes.
command -v gnuplot >/dev/null 2>&1 ||
    { echo "bench: gnuplot not found; run make bench (it installs it) or: sudo apt-get install -y gnuplot-nox" >&2; exit 1; }

dir=${1:-build/bench}
out=bench/out
mkdir -p "$out"
rm -f "$out"/*.csv "$out"/*.notes "$out"/*.instr "$out"/*.svg "$out"/*.dat \
      "$out"/*.md "$out"/*.png "$out"/callgrind.*

t_start=$(date +%s)

# BENCH_QUICK=1 (CI smoke run): few repetitions; numbers are noisier, never copy them to docs.
quick=""
case "${BENCH_QUICK:-0}" in
    ""|0|no|NO) ;;
    *) quick="--reps 9"; echo "bench: BENCH_QUICK set, 9 repetitions (smoke run; do not publish these timings)" ;;
esac

# Instruction counts (callgrind) are deterministic where timings are noisy. Default: on in a
# full run when valgrind is installed (about 3 minutes more), off in a BENCH_QUICK run;
# CALLGRIND=0 or 1 forces it.
use_cg=0
cg=${CALLGRIND:-}
if [ -z "$cg" ]; then
    if [ -z "$quick" ] && command -v valgrind >/dev/null 2>&1; then cg=1; else cg=0; fi
fi
case "$cg" in
    0|no|NO) ;;
    *)
        if command -v valgrind >/dev/null 2>&1; then
            use_cg=1
        else
            echo "bench: CALLGRIND requested but valgrind is not installed; instr_per_eval left empty"
        fi ;;
esac

modules=""
for src in bench/bench_*.c; do
    m=${src#bench/bench_}
    modules="$modules ${m%.c}"
done

# ---------------------------------------------------------------- run
for m in $modules; do
    for b in float double; do
        bin="$dir/bench_$m-$b"
        if [ ! -x "$bin" ]; then
            echo "bench: missing $bin (run through make bench)" >&2
            exit 1
        fi
        instr=""
        if [ $use_cg = 1 ]; then
            instr="$out/$m-$b.instr"
            : > "$instr"
            echo "bench: callgrind, bench_$m ($b) ..."
            for id in $("$bin" --list); do
                valgrind --tool=callgrind --callgrind-out-file="$out/callgrind.out" \
                    --collect-atstart=no '--toggle-collect=pfb_measured*' \
                    "$bin" --only "$id" > "$out/callgrind.stdout" 2> "$out/callgrind.log"
                evals=$(awk '$1 == "evals" { print $2 }' "$out/callgrind.stdout")
                total=$(awk '$1 == "totals:" { print $2 }' "$out/callgrind.out")
                echo "$id ${total:-0} ${evals:-0}" >> "$instr"
            done
            rm -f "$out"/callgrind.*
        fi
        if [ -n "$instr" ]; then
            "$bin" $quick --csv "$out/$m.csv" --notes "$out/$m.notes" --instr "$instr"
        else
            "$bin" $quick --csv "$out/$m.csv" --notes "$out/$m.notes"
        fi
    done
done

# ---------------------------------------------------------------- report programs
# Each writes its own fragment <name>.md (and CSV, charts, images) into $out; BENCH_QUICK is
# inherited from the environment. Order: cheapest first.
for prog in microsurface pictures; do
    if [ ! -x "$dir/$prog" ]; then
        echo "bench: missing $dir/$prog (run through make bench)" >&2
        exit 1
    fi
    echo "bench: $prog ..."
    t0=$(date +%s)
    case $prog in
        microsurface) "$dir/$prog" --out "$out" --gp bench/microsurface.gp ;;
        *) "$dir/$prog" "$out" ;;
    esac
    echo "bench: $prog done ($(($(date +%s) - t0)) s)"
done
# The stability sweep (its own four builds; 10^6 inputs per evaluator and build in a full run,
# 10^5 under BENCH_QUICK; STABILITY_N overrides).
echo "bench: stability sweep ..."
t0=$(date +%s)
if [ -z "$quick" ]; then
    STABILITY_N=${STABILITY_N:-1000000} sh bench/stability.sh "$(dirname "$dir")"
else
    sh bench/stability.sh "$(dirname "$dir")"
fi
echo "bench: stability done ($(($(date +%s) - t0)) s)"
# GPU cost: SPIR-V (and PTX where nvcc exists) instruction counts of every public function and
# of the textbook formulas (bench/gpu/; gpu_cost.csv, gpu_cost.md, gpu_cost.svg, gpu_methods.csv).
echo "bench: GPU cost ..."
sh bench/gpu/cost.sh "$out"
# The frame on a Vulkan driver (bench/frame/run.sh: frame.md, frame.csv, frame_*.png).
echo "bench: GPU frame ..."
sh bench/frame/run.sh "$dir" "$out"

# ---------------------------------------------------------------- charts
charts=""
for m in $modules; do
    for fam in $(awk -F, 'NR > 1 && !seen[$1]++ { print $1 }' "$out/$m.csv"); do
        dat="$out/${m}_$fam.dat"
        # ns, error (floored at 1e-20 so an exact 0 stays on a log axis), label, build
        # (1 float, 2 double), label slot: how many earlier points of the same build sit
        # (nearly) on this one, so that the chart staggers their labels
        # max rel error, or mean abs error for fraction-valued families (max_rel_err empty)
        awk -F, -v f="$fam" 'NR > 1 && $1 == f && ($9 != "" || $17 != "") {
            e = ($9 != "" ? $9 : $17) + 0; if (e < 1e-20) e = 1e-20
            bd = ($3 == "float") ? 1 : 2
            lx = log($4 + 1e-9) / log(10); ly = log(e) / log(10); k = 0
            for (j = 0; j < n; ++j)
                if (pb[j] == bd && (px[j] - lx) ^ 2 < 0.01 && (py[j] - ly) ^ 2 < 0.09) ++k
            px[n] = lx; py[n] = ly; pb[n] = bd; ++n
            printf "%s\t%.6g\t%s\t%d\t%d\n", $4, e, $2, bd, k }' "$out/$m.csv" > "$dat"
        if [ -s "$dat" ]; then
            svg="$out/${m}_$fam.svg"
            gnuplot -e "fam='$m / $fam'; datf='$dat'; outf='$svg'" bench/chart.gp ||
                { echo "bench: gnuplot failed on $svg" >&2; exit 1; }
            charts="$charts ${m}_$fam.svg"
        fi
        rm -f "$dat"
    done
done

# ---------------------------------------------------------------- summary.md
sum="$out/summary.md"
cpu=$(awk -F': *' '/^model name/ { print $2; exit }' /proc/cpuinfo 2>/dev/null || true)
[ -n "$cpu" ] || cpu=$(uname -m)
ncpu=$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo "?")
ccver=$(${CC:-cc} --version 2>/dev/null | head -n 1)
# Which timing loops did the compiler vectorize? (gcc only: -fopt-info-vec-optimized names the
# source line of each vectorized loop; a timing loop sits on its PFB_METHOD line.)
vec="unknown (compiler without -fopt-info-vec-optimized)"
if ${CC:-cc} -fopt-info-vec-optimized -x c -c /dev/null -o /dev/null 2>/dev/null; then
    vec=""
    for src in bench/bench_*.c; do
        for d in "" -DPF_DOUBLE; do
            # shellcheck disable=SC2086
            ${CC:-cc} ${BENCH_FLAGS} $d -fopt-info-vec-optimized -c "$src" -o /dev/null 2>&1 |
                awk -F: -v s="$src" '$1 == s && /loop vectorized/ { print $2 }' | sort -u |
                while read -r line; do
                    sed -n "${line}p" "$src" | sed -n 's/^PFB_METHOD(\([a-z0-9_]*\),.*/\1/p'
                done
        done
    done > "$out/vec.tmp"
    vec=$(sort -u "$out/vec.tmp" | tr '\n' ' ')
    rm -f "$out/vec.tmp"
    [ -n "$vec" ] || vec="none"
fi
timing=$(cat "$out"/*.notes | awk -F'\t' '$1 == "*" { print $2; exit }')
{
    echo "# prefilter bench summary"
    echo
    echo "Generated by \`make bench\` (bench/run.sh); do not edit by hand, re-run it."
    echo
    echo "- date: $(date -u '+%Y-%m-%d %H:%M:%S UTC')"
    [ -n "$quick" ] && echo "- BENCH_QUICK smoke run ($quick): timings are rough; not for docs"
    echo "- compiler: \`${CC:-cc}\` = $ccver"
    echo "- flags: \`${BENCH_FLAGS:-?}\` (double build adds \`-DPF_DOUBLE\`); -std=c99 implies -ffp-contract=off, so no FMA contraction; no -ffast-math"
    echo "- CPU: $cpu ($ncpu logical CPUs), $(uname -sr)"
    if [ $use_cg = 1 ]; then
        echo "- instructions: $(valgrind --version) callgrind, collection on in pfb_measured only; instr/eval includes the loop (load, store, index, branch: ~4-5 instructions)"
    else
        echo "- instructions: not measured (BENCH_QUICK run or valgrind missing; \`make bench CALLGRIND=1\` forces it)"
    fi
    echo "- timing: each method in its own loop with the method inlined, over $timing; ns/eval = median; in each repetition every method is timed back to back with the baseline (alternating which goes first, methods in rotating order); x baseline = median over repetitions of method/baseline of the pair (quartiles in the CSV)"
    echo "- two input orders: the headline columns use the random inputs as generated (branches on the input unpredictable, like incoherent rays; the buffer is large so the branch predictor cannot learn it); the sorted columns use the same inputs sorted ascending (branches predictable, like neighbouring pixels). Branchy methods (Walter: nu >= 1.6 test) differ a lot between the two"
    echo "- timing loops vectorized by the compiler at these flags: $vec"
    echo "- accuracy: dense deterministic grid per family (below) against a long double reference; max rel only where the reference is a normal number of the build's type; worst input = where the max ulp (erfc/erf) or max rel error (others) occurs"
    echo "- the machine may be shared: absolute ns move between runs, ratios much less (see the A/A check per family)"
    for m in $modules; do
        echo
        echo "## $m"
        for fam in $(awk -F, 'NR > 1 && !seen[$1]++ { print $1 }' "$out/$m.csv"); do
            echo
            echo "### $fam"
            echo
            # notes first, then the A/A checks
            awk -F'\t' -v f="$fam" '$1 == f && $2 !~ /^A\/A/ && !seen[$2]++ { print "- " $2 }' "$out/$m.notes"
            awk -F'\t' -v f="$fam" '$1 == f && $2 ~ /^A\/A/ && !seen[$2]++ { print "- " $2 }' "$out/$m.notes"
            echo
            echo "| method | build | ns/eval | x baseline | sorted: ns/eval | sorted: x baseline | instr/eval | max abs err | max rel err | max ulp | mean abs err | worst input |"
            echo "|---|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|---|"
            awk -F, -v f="$fam" 'NR > 1 && $1 == f {
                base = ($2 == $6) ? " (baseline)" : ""
                printf "| `%s`%s | %s | %.2f | %.3f | %.2f | %.3f | %s | %s | %s | %s | %s | %s |\n",
                    $2, base, $3, $4, $5, $15, $16, ($7 == "" ? "-" : $7), ($8 == "" ? "-" : $8),
                    ($9 == "" ? "-" : $9), ($10 == "" ? "-" : $10), ($17 == "" ? "-" : $17),
                    ($11 == "" ? "-" : $11) }' "$out/$m.csv"
            if [ -f "$out/${m}_$fam.svg" ]; then
                echo
                echo "![$m / $fam: max error versus cost](${m}_$fam.svg)"
            fi
        done
    done
} > "$sum"

echo
files="summary.md"
for m in $modules; do files="$files, $m.csv"; done
for c in $charts; do files="$files, $c"; done
echo "bench: wrote $files in $out/ ($(($(date +%s) - t_start)) s)"

# ---------------------------------------------------------------- method guide and report
sh bench/choosing.sh "$out"
sh bench/report.sh "$out"
echo "bench: the report is $out/report.md ($(($(date +%s) - t_start)) s in all)"
