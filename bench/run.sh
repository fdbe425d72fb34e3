#!/bin/sh
# bench/run.sh - the main job (make bench): every bench binary (float and double), the report
# programs, the stability sweep, the GPU counts, then bench/out/:
#   <module>.csv            one row per method and build (columns: see bench/pf_bench.h)
#   <module>.notes          inputs, grids, references, A/A checks (family<TAB>note)
#   <module>_<family>.svg   error versus cost, one chart per family (gnuplot; make bench installs
#                           it through tests/deps.sh: no chart is ever skipped)
#   summary.md              compiler, flags, CPU, date, then markdown tables per family
#   stages.txt              each stage: name<TAB>wall seconds<TAB>threads<TAB>CPU seconds
#   report.md               the report (bench/report.sh), choosing.md (bench/choosing.sh)
# Called by `make bench` from the repository root:  sh bench/run.sh BUILD_DIR
#
# EVERY CORE, AND TIMINGS ALONE. The stages run one after the other; within a stage the work is
# spread over PFB_THREADS threads or processes (default: every online core; PFB_THREADS=1 runs
# everything serially, the reference of the determinism check bench/determinism.sh):
#   1 callgrind    instruction counts, one valgrind per bench binary, all binaries at once
#   2 stability    the sweep's shards, at once (bench/stability.sh; its four builds are made by
#                  make bench-build beside the other builds, else here, at once)
#   3 gpu          the SPIR-V counts of every function, at once (bench/gpu/cost.sh)
#   4 vectorize    which timing loops the compiler vectorized (one compile per binary, at once)
#   5 microsurface, 6 pictures: their brute force on every core, their cost timings alone
#   7 modules      bench_<module>-float/-double one at a time: the accuracy grids on every core,
#                  then the timing loops on one thread while nothing else of the bench runs
#                  (BENCH_QUICK: PFB_THREADS modules at once, as nothing reads its timings)
#   8 charts, summary.md, choosing.md, report.md
# Nothing is timed while another process of the bench runs: every stage that times (5-7) runs
# alone, after the untimed parallel ones. Results do not depend on the thread count: the CSVs of
# PFB_THREADS=1 and of every core compare equal except their timing columns (bench/determinism.sh).
# Every stage prints its start and end with the time of day and its wall time; steps longer than
# a few seconds print progress with the time left on stderr (in place on a terminal).
#
# Environment: CC and BENCH_FLAGS (recorded in the summary), BENCH_QUICK=1 (CI smoke run: 3
# repetitions per timing and 1 ms of warm-up per method, smaller sweeps), CALLGRIND=0/1 (instruction counts; default: on in a full run when
# valgrind is installed, off under BENCH_QUICK), PROFILE=1 (opt-in profile mode, below),
# PFB_THREADS=N (threads and processes per stage), BENCH_OUT=dir (default bench/out),
# BENCH_BUDGET_MS=B (a full run's time budget per method and input order, --budget-ms; default
# pf_bench.h's PFB_BUDGET_MS; `sh bench/times.sh spread` measures the medians' repeatability).
#
# INSTRUCTION COUNTS. The instr/eval column of every method, float and double, is read: the
# report's family tables (float) and its appendix (both builds), and the generated tables of the
# module pages in docs/ (both builds). So a full run counts them all, in one callgrind run per
# binary: `--only all` runs every method's loop once and callgrind dumps after each
# (--dump-after=pfb_measured), with LD_BIND_NOW=1 so that no lazy symbol binding is counted.
# A binary that names PFB_SETUP_CACHE (bench_shadow.c) first runs one method natively to write
# its setup's tables to a file that the valgrind run reads: its setup (long double sums over the
# shadow scenes) took 15-30 s of CPU per build under valgrind, and valgrind evaluates long double
# at double precision, so the counted loops now read the same tables as the timed ones.
# Fewer evaluations per method would not give the same instr/eval: every costly method's count
# depends on its inputs (a prefix of 2048 or 8192 of the 65536 inputs moved the second decimal).
# PROFILE=1 (make bench PROFILE=1) adds what nothing in docs/ or the report reads: callgrind's
# branch simulation (conditional branches and mispredictions per evaluation, with the random
# inputs of the timing loops) and the per-method profiles kept for callgrind_annotate, in
# bench/out/profile/ (profile.md: one table per binary).
set -e

# ---------------------------------------------------------------- callgrind job (one binary)
# sh bench/run.sh --count-instr BIN INSTR_FILE [PROFILE_DIR]: INSTR_FILE gets one line
# "family/method instructions evaluations" per method (what pf_bench.h's --instr reads).
if [ "${1:-}" = --count-instr ]; then
    bin=$2; instr=$3; pdir=${4:-}
    tmp=$(mktemp -d "${TMPDIR:-/tmp}/pf-cg.XXXXXX")
    set -- --tool=callgrind --callgrind-out-file="$tmp/cg" --collect-atstart=no \
        --toggle-collect=pfb_measured --dump-after=pfb_measured
    [ -n "$pdir" ] && set -- "$@" --branch-sim=yes --dump-instr=yes
    # A bench whose setup is slow under valgrind (bench_shadow.c: 15-30 s of long double scene
    # sums) reads its tables from PFB_SETUP_CACHE, filled here by a native run of one method;
    # the other benches do not name it.
    if grep -q PFB_SETUP_CACHE "$bin"; then
        PFB_SETUP_CACHE="$tmp/setup" "$bin" --only "$("$bin" --list | head -n 1)" > /dev/null 2>&1 || true
    fi
    if ! PFB_SETUP_CACHE="$tmp/setup" LD_BIND_NOW=1 valgrind "$@" "$bin" --only all > "$tmp/stdout" 2> "$tmp/log"; then
        echo "bench: callgrind failed on $bin:" >&2; tail -n 5 "$tmp/log" >&2; rm -rf "$tmp"; exit 1
    fi
    n=$(grep -c . "$tmp/stdout")
    k=0
    : > "$instr.tmp"
    while read -r id _ evals; do
        k=$((k + 1))
        [ -f "$tmp/cg.$k" ] || { echo "bench: callgrind: no dump $k for $id ($bin)" >&2; rm -rf "$tmp"; exit 1; }
        echo "$id $(awk '$1 == "summary:" { print $2; exit }' "$tmp/cg.$k") $evals" >> "$instr.tmp"
        if [ -n "$pdir" ]; then
            mkdir -p "$pdir"
            # Ir Bc Bcm Bi Bim of this method's loop
            echo "$id $evals $(awk '$1 == "summary:" { $1 = ""; print; exit }' "$tmp/cg.$k")" >> "$pdir/branches.txt"
            mv "$tmp/cg.$k" "$pdir/callgrind.$(echo "$id" | tr '/' '.')"
        fi
    done < "$tmp/stdout"
    [ "$k" -eq "$n" ] && [ ! -f "$tmp/cg.$((n + 1))" ] ||
        { echo "bench: callgrind: $n methods but other dumps ($bin)" >&2; rm -rf "$tmp"; exit 1; }
    mv "$instr.tmp" "$instr"
    rm -rf "$tmp"
    exit 0
fi

# The charts are the main job's point: without gnuplot, stop now rather than after minutes.
command -v gnuplot >/dev/null 2>&1 ||
    { echo "bench: gnuplot not found; run make bench (it installs it) or: sudo apt-get install -y gnuplot-nox" >&2; exit 1; }

dir=${1:-build/bench}
out=${BENCH_OUT:-bench/out}
mkdir -p "$out"
rm -rf "$out"/*.csv "$out"/*.notes "$out"/*.instr "$out"/*.svg "$out"/*.dat \
      "$out"/*.md "$out"/*.png "$out"/callgrind.* "$out"/stages.txt "$out"/profile
threads=${PFB_THREADS:-}
case $threads in ''|*[!0-9]*|0) threads=$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo 1) ;; esac

t_start=$(date +%s)
stage_t0=0
stage_cpu0=0
stage_name=""
# CPU seconds (user + system) of every finished child so far: the shell's `times`, run in
# this shell (not in a pipe or $(...), whose subshell has no children yet), then read back
cpu_now() {
    times > "$out/times.tmp"
    cpu_read=$(awk 'NR == 2 { split($1, u, /[ms]/); split($2, s, /[ms]/); printf "%.1f", u[1] * 60 + u[2] + s[1] * 60 + s[2] }' "$out/times.tmp")
    rm -f "$out/times.tmp"
}
# stage NAME: the start of a stage (ends the previous one); stage_end: the end of the last.
# stages.txt: name, wall seconds, threads, CPU seconds of the stage's processes (on a busy
# machine the CPU time, divided by the cores a stage keeps busy, estimates its idle wall time)
stage_end() {
    [ -n "$stage_name" ] || return 0
    el=$(($(date +%s) - stage_t0))
    cpu_now
    cpu=$(awk -v a="$cpu_read" -v b="$stage_cpu0" 'BEGIN { printf "%.1f", a - b }')
    echo "bench: [$(date +%H:%M:%S)] $stage_name done in $el s, $cpu s of CPU ($(($(date +%s) - t_start)) s since the start)" >&2
    printf '%s\t%s\t%s\t%s\n' "$stage_name" "$el" "$threads" "$cpu" >> "$out/stages.txt"
    stage_name=""
}
stage() {
    stage_end
    stage_name=$1
    stage_t0=$(date +%s)
    cpu_now
    stage_cpu0=$cpu_read
    echo "bench: [$(date +%H:%M:%S)] $1 ..." >&2
}

# BENCH_QUICK=1 (CI smoke run): few repetitions; numbers are noisier, never copy them to docs.
quick=""
case "${BENCH_QUICK:-0}" in
    ""|0|no|NO) ;;
    # 3 repetitions (the fewest with a median and quartiles) and 1 ms of warm-up: nothing reads
    # the quick run's timings (docs/ take them from a full run; bench/determinism.sh compares the
    # CSVs without their timing columns), so its timing loops only prove that they run
    *) quick="--reps 3 --budget-ms 5 --warmup-ms 1"; echo "bench: BENCH_QUICK set, 3 repetitions per timing, 1 ms of warm-up (smoke run; do not publish these timings)" ;;
esac
echo "bench: $threads threads per stage (PFB_THREADS to change), output in $out/"

# Instruction counts (callgrind) are deterministic where timings are noisy. Default: on in a
# full run when valgrind is installed, off in a BENCH_QUICK run; CALLGRIND=0 or 1 forces it.
use_cg=0
cg=${CALLGRIND:-}
profile=0
case "${PROFILE:-0}" in ""|0|no|NO) ;; *) profile=1; cg=1 ;; esac
if [ -z "$cg" ]; then
    if [ -z "$quick" ] && command -v valgrind >/dev/null 2>&1; then cg=1; else cg=0; fi
fi
case "$cg" in
    0|no|NO) ;;
    *)
        if command -v valgrind >/dev/null 2>&1; then
            use_cg=1
        else
            echo "bench: CALLGRIND or PROFILE requested but valgrind is not installed; instr_per_eval left empty"
            profile=0
        fi ;;
esac

modules=""
for src in bench/bench_*.c; do
    m=${src#bench/bench_}
    modules="$modules ${m%.c}"
done
for m in $modules; do
    for b in float double; do
        [ -x "$dir/bench_$m-$b" ] || { echo "bench: missing $dir/bench_$m-$b (run through make bench)" >&2; exit 1; }
    done
done
for prog in microsurface pictures specaa; do
    [ -x "$dir/$prog" ] || { echo "bench: missing $dir/$prog (run through make bench)" >&2; exit 1; }
done
jobs="$out/jobs.tmp"

# ---------------------------------------------------------------- 1. instruction counts
if [ $use_cg = 1 ]; then
    stage "callgrind (instruction counts of every method, float and double)"
    : > "$jobs"
    # the slowest binaries first (the most instructions counted: height's quadrature tiers,
    # vmf's lobe mixtures; bench_shadow's setup is read from a native run's cache)
    for m in height vmf shadow gaussgrid masks $modules; do
        for b in double float; do
            grep -q "bench_$m-$b " "$jobs" 2>/dev/null && continue
            p=""
            [ $profile = 1 ] && p=" $out/profile/bench_$m-$b"
            echo "sh bench/run.sh --count-instr $dir/bench_$m-$b $out/$m-$b.instr$p # bench_$m-$b " >> "$jobs"
        done
    done
    sh bench/pool.sh "bench: callgrind" "$jobs" || { echo "bench: callgrind failed" >&2; exit 1; }
fi

# ---------------------------------------------------------------- 2. stability sweep
# Its own four builds; 10^6 inputs per evaluator and build in a full run, 10^5 under
# BENCH_QUICK; STABILITY_N overrides.
stage "stability sweep"
if [ -z "$quick" ]; then
    BENCH_OUT=$out STABILITY_N=${STABILITY_N:-1000000} sh bench/stability.sh "$(dirname "$dir")"
else
    BENCH_OUT=$out sh bench/stability.sh "$(dirname "$dir")"
fi

# ---------------------------------------------------------------- 3. GPU cost
# SPIR-V (and PTX where nvcc exists) instruction counts of every public function and of the
# textbook formulas (bench/gpu/; gpu_cost.csv, gpu_cost.md, gpu_cost.svg, gpu_methods.csv).
# The counts of shaders whose source, tools and counting rules did not change since the last
# run are kept in BUILD/gpu-cache (PF_GPU_CACHE; empty: none), so a run after a change to one
# header compiles that header's shaders only.
stage "GPU cost (SPIR-V counts)"
PF_GPU_CACHE=${PF_GPU_CACHE-$(dirname "$dir")/gpu-cache} sh bench/gpu/cost.sh "$out"

# ---------------------------------------------------------------- 4. vectorized timing loops
# Which timing loops did the compiler vectorize? (gcc only: -fopt-info-vec-optimized names the
# source line of each vectorized loop; a timing loop sits on its PFB_METHOD line.)
# The Makefile's gcc builds write it beside each binary (BIN.vec); otherwise (older binaries,
# another build) each source is compiled again here with -fopt-info-vec-optimized.
stage "vectorization report"
rm -f "$out"/vec.*
if ${CC:-cc} -fopt-info-vec-optimized -x c -c /dev/null -o /dev/null 2>/dev/null; then
    : > "$jobs"
    for m in $modules; do
        for b in float double; do
            d=""
            [ $b = double ] && d=-DPF_DOUBLE
            if [ -f "$dir/bench_$m-$b.vec" ]; then
                cp "$dir/bench_$m-$b.vec" "$out/vec.bench_$m$d.log"
            else
                echo "${CC:-cc} ${BENCH_FLAGS} $d -fopt-info-vec-optimized -c bench/bench_$m.c -o /dev/null > $out/vec.bench_$m$d.log 2>&1" >> "$jobs"
            fi
        done
    done
    sh bench/pool.sh "bench: vectorization report" "$jobs" || { echo "bench: a vectorization compile failed" >&2; exit 1; }
    for src in bench/bench_*.c; do
        for d in "" -DPF_DOUBLE; do
            awk -F: -v s="$src" '$1 == s && /loop vectorized/ { print $2 }' "$out/vec.$(basename "$src" .c)$d.log" | sort -u |
                while read -r line; do
                    sed -n "${line}p" "$src" | sed -n 's/^PFB_METHOD(\([a-z0-9_]*\),.*/\1/p'
                done
        done
    done | sort -u > "$out/vec.txt"
    rm -f "$out"/vec.*.log
fi

# ---------------------------------------------------------------- 5, 6. report programs
# Each writes its own fragment <name>.md (and CSV, charts, images) into $out; BENCH_QUICK is
# inherited from the environment. Each spreads its brute force over PFB_THREADS threads and
# times its cost section alone.
stage "microsurface (ground truth)"
"$dir/microsurface" --out "$out" --gp bench/microsurface.gp
stage "pictures"
"$dir/pictures" "$out"
stage "specaa (roughness bakers against the footprint NDF, the sphere reference)"
"$dir/specaa" --out "$out"
# The frame on a Vulkan driver (bench/frame/run.sh: lavapipe here; frame.md, frame.csv, frame_*.png)
stage "GPU frame (Vulkan)"
sh bench/frame/run.sh "$dir" "$out"

# ---------------------------------------------------------------- 7. per-module benches
# One binary at a time: its accuracy grids on every core, then its timing loops on one thread
# with nothing else of the bench running.
# BENCH_QUICK: nothing reads the quick run's timings (docs/ read a full run's), so there the
# modules run PFB_THREADS at a time (bench/pool.sh; each module's float then double binary in one
# job, as both append to <module>.csv and .notes in that order): same CSVs, less wall time.
if [ -z "$quick" ]; then
    stage "per-module benches (accuracy on every core, timings alone)"
else
    stage "per-module benches (quick: PFB_THREADS modules at once, timings not read)"
fi
: > "$jobs"
for m in $modules; do
    job=""
    for b in float double; do
        bin="$dir/bench_$m-$b"
        ins=""
        [ $use_cg = 1 ] && ins="--instr $out/$m-$b.instr"
        if [ -z "$quick" ]; then
            # shellcheck disable=SC2086
            "$bin" ${BENCH_BUDGET_MS:+--budget-ms "$BENCH_BUDGET_MS"} --csv "$out/$m.csv" --notes "$out/$m.notes" $ins
        else
            job="$job${job:+ && }$bin $quick --csv $out/$m.csv --notes $out/$m.notes $ins"
        fi
    done
    [ -z "$quick" ] || echo "{ $job; } > $out/$m.log 2>&1 || { cat $out/$m.log; exit 1; }" >> "$jobs"
done
if [ -n "$quick" ]; then
    sh bench/pool.sh "bench: per-module benches" "$jobs" || { echo "bench: a per-module bench failed" >&2; exit 1; }
    # their tables on stdout, in module order, as a serial run prints them
    for m in $modules; do cat "$out/$m.log"; rm -f "$out/$m.log"; done
fi

# ---------------------------------------------------------------- 8. charts
stage "charts, summary, method guide, report"
: > "$jobs"
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
            echo "gnuplot -e \"fam='$m / $fam'; datf='$dat'; outf='$svg'\" bench/chart.gp > $dat.log 2>&1 && rm -f $dat $dat.log" >> "$jobs"
            charts="$charts ${m}_$fam.svg"
        else
            rm -f "$dat"
        fi
    done
done
sh bench/pool.sh "bench: charts" "$jobs" || { cat "$out"/*.dat.log >&2; echo "bench: gnuplot failed" >&2; exit 1; }
rm -f "$jobs"

# ---------------------------------------------------------------- summary.md
sum="$out/summary.md"
cpu=$(awk -F': *' '/^model name/ { print $2; exit }' /proc/cpuinfo 2>/dev/null || true)
[ -n "$cpu" ] || cpu=$(uname -m)
ncpu=$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo "?")
ccver=$(${CC:-cc} --version 2>/dev/null | head -n 1)
vec="unknown (compiler without -fopt-info-vec-optimized)"
[ -f "$out/vec.txt" ] && { vec=$(tr '\n' ' ' < "$out/vec.txt"); [ -n "$vec" ] || vec="none"; }
rm -f "$out/vec.txt"
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
        echo "- instructions: $(valgrind --version) callgrind, collection on in pfb_measured only, one run per binary (a dump after each method's loop), symbols bound at start (LD_BIND_NOW=1: no lazy binding counted); instr/eval includes the loop (load, store, index, branch: ~4-5 instructions)"
    else
        echo "- instructions: not measured (BENCH_QUICK run or valgrind missing; \`make bench CALLGRIND=1\` forces it)"
    fi
    echo "- timing: each method in its own loop with the method inlined, over $timing; ns/eval = median; in each repetition every method is timed back to back with the baseline (alternating which goes first, methods in rotating order); x baseline = median over repetitions of method/baseline of the pair (quartiles in the CSV); slow methods get fewer repetitions (the time budget; each family's counts are in its A/A line)"
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

# ---------------------------------------------------------------- profile mode
if [ $profile = 1 ]; then
    {
        echo "# prefilter bench profile (make bench PROFILE=1)"
        echo
        echo "Per method and build: callgrind's counts of the timing loop over the same random inputs as the"
        echo "ns columns (per evaluation; the loop's own load, store, index and branch included):"
        echo "instructions, conditional branches executed and mispredicted, indirect branches and their"
        echo "mispredictions (callgrind --branch-sim=yes: a simple predictor, not this CPU's). The"
        echo "annotated profile of each method's loop: \`callgrind_annotate --auto=yes profile/bench_<module>-<build>/callgrind.<family>.<method>\`."
        for p in "$out"/profile/bench_*; do
            [ -f "$p/branches.txt" ] || continue
            echo
            echo "## $(basename "$p")"
            echo
            echo "| method | instr/eval | cond. branches/eval | mispredicted/eval | indirect/eval | mispredicted/eval |"
            echo "|---|--:|--:|--:|--:|--:|"
            awk '{ n = $2; printf "| `%s` | %.2f | %.3f | %.3f | %.3f | %.3f |\n", $1, $3 / n, $4 / n, $5 / n, $6 / n, $7 / n }' "$p/branches.txt"
        done
    } > "$out/profile/profile.md"
    echo "bench: profile mode: $out/profile/profile.md and the per-method callgrind profiles in $out/profile/"
fi

echo
files="summary.md"
for m in $modules; do files="$files, $m.csv"; done
for c in $charts; do files="$files, $c"; done
echo "bench: wrote $files in $out/ ($(($(date +%s) - t_start)) s)"

# ---------------------------------------------------------------- method guide and report
sh bench/choosing.sh "$out"
sh bench/report.sh "$out"
stage_end
echo "bench: the report is $out/report.md ($(($(date +%s) - t_start)) s in all, $threads threads per stage; stage times in $out/stages.txt)"
