#!/bin/sh
# bench/gpu/cost.sh OUT_DIR - the GPU-cost step of `make bench` (called by bench/run.sh).
#
# Runs bench/gpu/count.sh on every public function and every textbook baseline, then writes
#   OUT_DIR/gpu_cost.csv           one row per function (columns: see count.sh)
#   OUT_DIR/gpu_cost.md            the report section: library evaluator against its textbook
#                                  formula (SPIR-V ops, conditional branches, PTX, SASS,
#                                  registers, ratios, issue 17's targets), then every function
#   OUT_DIR/gpu_cost.svg           the chart of the paired counts (bench/gpu/chart.gp)
#   OUT_DIR/gpu_methods.csv        GPU cost of the bench methods that bench/choosing.sh names
#                                  (bench/gpu/methods.txt maps a method to its evaluators)
#   OUT_DIR/gpu_agree.txt          bench/gpu/agree.c: each baseline against its library evaluator
# Environment: CC (for agree.c), BENCH_QUICK (only the compared functions), and count.sh's.
# nvcc missing is not an error: the CUDA columns say n/a. glslang and spirv-tools missing is
# (tests/deps.sh bench installs them).
set -e
out=${1:-bench/out}
dir=$(dirname "$0")
csv="$out/gpu_cost.csv"
md="$out/gpu_cost.md"
mkdir -p "$out"
# library evaluator | textbook baseline | what the baseline is | issue 17 target (max ratio of
# SPIR-V ops, empty: none). Rows of evaluators the library does not have are left out.
pairs='pf_shadow_vsm|pf_textbook_vsm|Chebyshev VSM|1.1
pf_shadow_evsm2|pf_textbook_evsm2|EVSM-2|1.1
pf_shadow_evsm4|pf_textbook_evsm4|EVSM-4|1.1
pf_shadow_msm|pf_textbook_msm|Hamburger 4MSM, Peters & Klein 2015 alg. 2|1.1
pf_leadr_specular|pf_textbook_lean_walter_specular|LEAN lobe x Walter G1(o) G1(i) x Schlick / (4 cos)|1.2
pf_beckmann_d|pf_textbook_lean_d|LEAN lobe|1.1
pf_g1_beckmann|pf_textbook_walter_g1|Walter G1 (from nu)|1.3
pf_g1_beckmann_fast|pf_textbook_walter_g1|Walter G1 (from nu)|
pf_g1_beckmann_walter|pf_textbook_walter_g1|Walter G1 (from nu)|
pf_lambda_beckmann|pf_textbook_walter_lambda|Walter Lambda|
pf_lambda_beckmann_walter|pf_textbook_walter_lambda|Walter Lambda|
pf_lambda_beckmann_fast|pf_textbook_walter_lambda|Walter Lambda|
pf_erfc|pf_textbook_erfc_as|A&S 7.1.26|
pf_erfc_fast|pf_textbook_erfc_as|A&S 7.1.26|'

# BENCH_QUICK (CI smoke run): only the evaluators of the comparison table and of
# bench/gpu/methods.txt, and their baselines.
only=""
case "${BENCH_QUICK:-0}" in
    ""|0|no|NO) ;;
    *) only="PAIRS" ;;
esac
t0=$(date +%s)
if [ -n "$only" ]; then
    only=$( { echo "$pairs" | awk -F'|' '{ print $1; print $2 }'
              grep -v '^#' "$dir/methods.txt" | awk '{ print $2 }' | tr '+' '\n'; } | awk 'NF && !seen[$0]++' | tr '\n' ' ')
fi
# count.sh's table to the log; its messages and progress to the log and, live, to stderr
# shellcheck disable=SC2086
{ sh "$dir/count.sh" -o "$csv" $only 2>&1 > "$out/gpu_cost.log"; echo $? > "$out/gpu_cost.status"; } |
    tee "$out/gpu_cost.err" >&2
[ "$(cat "$out/gpu_cost.status")" = 0 ] ||
    { echo "bench: bench/gpu/count.sh failed:" >&2; tail -n 5 "$out/gpu_cost.log" >&2; exit 1; }
cat "$out/gpu_cost.err" >> "$out/gpu_cost.log"
rm -f "$out/gpu_cost.err" "$out/gpu_cost.status"
secs=$(($(date +%s) - t0))

# The baselines compute what the library computes (bench/gpu/agree.c, double build, ordinary
# inputs): otherwise the ratios would compare different things. A disagreement is reported
# loudly in the log and the report, not fatal (the counts are still what they are).
agree_bin=$(mktemp "${TMPDIR:-/tmp}/pf-agree.XXXXXX")
if ${CC:-cc} -std=c99 -O2 -DPF_DOUBLE -Iinclude -I"$dir" "$dir/agree.c" -o "$agree_bin" -lm > "$out/gpu_agree.log" 2>&1; then
    if "$agree_bin" > "$out/gpu_agree.txt" 2>> "$out/gpu_agree.log"; then agree=ok; else agree=FAIL; fi
else
    agree=build; : > "$out/gpu_agree.txt"
fi
rm -f "$agree_bin"
case $agree in
    FAIL) echo "bench: gpu: WARNING: a textbook baseline disagrees with the library (bench/gpu/agree.c):" >&2
          grep 'FAIL$' "$out/gpu_agree.txt" | sed 's/^/bench: gpu:   /' >&2 ;;
    build) echo "bench: gpu: WARNING: bench/gpu/agree.c did not build (log $out/gpu_agree.log)" >&2 ;;
esac

field() { # function column -> value (n/a when absent)
    awk -F, -v f="$1" -v c="$2" 'NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i; next }
        $2 == f { print $col[c]; found = 1; exit } END { if (!found) print "n/a" }' "$csv"
}
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { if (a ~ /^[0-9]+$/ && b ~ /^[0-9]+$/ && b > 0) printf "%.2f", a / b; else printf "n/a" }'; }

have_ptx=$(awk -F, 'NR > 1 && $6 != "n/a" { print "yes"; exit }' "$csv")
have_sass=$(awk -F, 'NR > 1 && $7 != "n/a" { print "yes"; exit }' "$csv")
nvcc=${NVCC:-$(command -v nvcc || echo /usr/local/cuda/bin/nvcc)}
[ "$nvcc" != none ] || nvcc=nvcc
if [ "$have_ptx" = yes ]; then
    cuda="$($nvcc --version 2>/dev/null | grep -i release | sed 's/.*release/release/')"
    cuda_note="\`nvcc -O3 --use_fast_math\` (CUDA $cuda), PTX of one kernel per function; registers from ptxas for ${PF_NVCC_ARCH:-sm_75}"
    [ "$have_sass" = yes ] || cuda_note="$cuda_note; SASS n/a (no cuobjdump beside nvcc)"
else
    cuda_note="n/a: nvcc not found (the CUDA toolkit is not a Debian package; set NVCC=... to count PTX)"
fi

dat="$out/gpu_cost.dat"
: > "$dat"
{
    echo "## GPU cost"
    echo
    echo "Generated by \`make bench\` (bench/gpu/cost.sh, bench/gpu/count.sh); do not edit by hand."
    echo "What each evaluator costs in a shader, counted without a GPU from the same source the"
    echo "library ships: one compute shader per function (\`#version 450\`, \`#define PF_GLSL 1\`,"
    echo "the headers pasted; the arguments read from a buffer, so nothing folds; one float written),"
    echo "\`glslangValidator -V\`, then \`spirv-opt -O\` (which inlines everything into main)."
    echo "**SPIR-V ops** = the instructions of main except loads, stores, access chains, labels,"
    echo "branches, merges and returns (the shader that copies its input counts 0; checked every run);"
    echo "**branches** = conditional branches left after optimization. CUDA: $cuda_note;"
    echo "**PTX** = the kernel's instructions except ld/st/cvta/mov/ret/bra (the copy kernel counts 0)."
    echo "The textbook formulas are our own plain code of the published formulas as engines ship them"
    echo "(bench/gpu/textbook.h: native min/max, no guards), given the same inputs and counted the same"
    echo "way. Instruction counts are not timings: a transcendental (exp, sqrt, division) costs several"
    echo "simple ops, and branches cost more when they diverge, but the ratios track what a shader pays."
    echo "Tools: $(glslangValidator --version 2>/dev/null | head -n 1 | sed 's/^Glslang Version: *//;s/^/glslang /'); $(spirv-opt --version 2>&1 | grep -m 1 . | sed 's/ unknown hash//'). Step time: ${secs} s."
    echo
    echo "| library evaluator | SPIR-V ops | branches | PTX / SASS | regs | textbook formula | SPIR-V ops | branches | PTX / SASS | regs | ratio (SPIR-V) | ratio (PTX) | issue 17 target (SPIR-V) |"
    echo "|---|--:|--:|--:|--:|---|--:|--:|--:|--:|--:|--:|---|"
    echo "$pairs" | while IFS='|' read -r lib tb label target; do
        # a row only for the evaluators this version of the library has
        awk -F, -v f="$lib" '$2 == f { found = 1 } END { exit !found }' "$csv" || continue
        lo=$(field "$lib" spirv_ops); lb=$(field "$lib" cond_branches); lp=$(field "$lib" ptx); lr=$(field "$lib" regs)
        to=$(field "$tb" spirv_ops); tbr=$(field "$tb" cond_branches); tp=$(field "$tb" ptx); tr=$(field "$tb" regs)
        ls=$(field "$lib" sass); ts=$(field "$tb" sass)
        rs=$(ratio "$lo" "$to"); rp=$(ratio "$lp" "$tp")
        tg="-"
        if [ -n "$target" ]; then
            if [ "$rs" = n/a ]; then tg="<= $target: n/a"
            elif awk -v r="$rs" -v t="$target" 'BEGIN { exit !(r + 0 <= t + 0) }'; then tg="<= $target: met"
            else tg="<= $target: **not met**"; fi
        fi
        echo "| \`$lib\` | $lo | $lb | $lp / $ls | $lr | $label (\`$tb\`) | $to | $tbr | $tp / $ts | $tr | $rs | $rp | $tg |"
        # chart data: label, library ops, textbook ops, library PTX, textbook PTX (- when n/a)
        printf '%s\t%s\t%s\t%s\t%s\n' "${lib#pf_}" "$lo" "$to" "$(echo "$lp" | sed 's,n/a,-,')" "$(echo "$tp" | sed 's,n/a,-,')" >> "$dat"
    done
    echo
    echo "Issue 17's shadow target also asks for no conditional branch left in the four shadow tests."
    echo
    echo "The baselines compute what the library computes: bench/gpu/agree.c compares each with its"
    echo "library evaluator on ordinary inputs (random footprints of 2-6 depths, directions within 70"
    echo "degrees of the normal, double build; details in its header comment):"
    echo
    if [ $agree = build ]; then
        echo "**FAIL:** bench/gpu/agree.c did not build (bench/out/gpu_agree.log)."
    else
        echo "| textbook | library | inputs | largest difference | bound | |"
        echo "|---|---|--:|--:|--:|---|"
        awk -F'\t' '{ printf "| `%s` | %s | %s | %s | %s | %s |\n", $1, ($2 ~ / / ? $2 : "`" $2 "`"), $3, $4, $5, ($6 == "ok" ? "ok" : "**FAIL**") }' "$out/gpu_agree.txt"
    fi
    if gnuplot -e "datf='$dat'; outf='$out/gpu_cost.svg'" "$dir/chart.gp" 2> "$out/gpu_chart.log"; then
        echo
        echo "![GPU cost: library evaluators against the textbook formulas](gpu_cost.svg)"
    else
        echo
        echo "**Missing:** the chart (gnuplot failed: $(head -n 1 "$out/gpu_chart.log"))."
    fi
    echo
    echo "### Every public function"
    echo
    [ -z "$only" ] || echo "**BENCH_QUICK run:** only the functions above and those of bench/gpu/methods.txt were counted."
    [ -z "$only" ] || echo
    echo "One row per public function that compiles as GLSL (C-only buffer walkers have no shader"
    echo "count), by header; n/a where the shader or kernel did not build (see bench/out/gpu_cost.log)."
    skipped=$(sed -n 's/^count.sh: gen.awk failed on \([^ ]*\) .*/\1/p' "$out/gpu_cost.log" | tr '\n' ' ')
    [ -z "$skipped" ] || printf '\n%s\n' "**Not counted:** the shader generator (tests/portability/gen.awk) cannot wrap the functions of: $skipped(bench/out/gpu_cost.log says why)."
    echo
    echo "| header | function | SPIR-V ops | branches | PTX | regs |"
    echo "|---|---|--:|--:|--:|--:|"
    awk -F, 'NR > 1 && $1 == "library" { printf "| %s | `%s` | %s | %s | %s | %s |\n", $3, $2, $4, $5, $6, $8 }' "$csv"
} > "$md"
rm -f "$dat" "$out/gpu_chart.log"

# Methods of bench/choosing.sh: the sum of their evaluators' counts.
{
    echo "method,spirv_ops,ptx,fetches"
    grep -v '^#' "$dir/methods.txt" | while read -r meth fns fetches; do
        [ -n "$meth" ] || continue
        so=0; sp=0
        for f in $(echo "$fns" | tr '+' ' '); do
            o=$(field "$f" spirv_ops); p=$(field "$f" ptx)
            case $o in n/a|"") so=n/a ;; *) [ "$so" = n/a ] || so=$((so + o)) ;; esac
            case $p in n/a|"") sp=n/a ;; *) [ "$sp" = n/a ] || sp=$((sp + p)) ;; esac
        done
        echo "$meth,$so,$sp,${fetches:-n/a}"
    done
} > "$out/gpu_methods.csv"
echo "bench: gpu cost: $(awk -F, 'NR > 1' "$csv" | wc -l | tr -d ' ') functions counted ($secs s); wrote gpu_cost.csv, gpu_cost.md, gpu_cost.svg, gpu_methods.csv"
