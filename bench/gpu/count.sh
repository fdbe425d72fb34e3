#!/bin/sh
# bench/gpu/count.sh - GPU instruction counts of the public evaluators, without a GPU.
#
# usage: sh bench/gpu/count.sh [-o CSV] [FUNCTION...]
#   FUNCTION: public function names (pf_shadow_vsm ...) and/or textbook baselines
#   (pf_textbook_vsm ..., bench/gpu/textbook.h). Default: every public function that compiles
#   as GLSL, then every textbook baseline. Prints one line per function:
#       function  spirv_ops  cond_branches  ptx  sass  regs
#   and with -o writes the same as CSV (header: kind,function,header,spirv_ops,cond_branches,
#   ptx,sass,regs; kind = library or textbook; header = the file that defines it). "n/a" where
#   a tool is missing (nvcc, cuobjdump) or a function does not exist in that language (C-only
#   functions have no GLSL count).
#
# How (issue 17): one shader per function, generated from the library source by
# tests/portability/gen.awk (the headers pasted after `#version 450` and `#define PF_GLSL 1`;
# the arguments are read from an SSBO so nothing folds; the result is written as one float),
# compiled with `glslangValidator -V`, optimized with `spirv-opt -O` (which inlines every call
# into main). spirv_ops = the instructions of main except loads, stores, access chains,
# variables, labels, branches, merges and returns, so the shader that copies one input to the
# output counts 0 (checked on every run). cond_branches = OpBranchConditional + OpSwitch.
# CUDA (when nvcc exists): one __global__ kernel per function around the gen.awk cuda wrapper,
# `nvcc -O3 --use_fast_math -ptx`; ptx = the kernel's instructions except ld/st/cvta/mov/
# ret/bra (the copy kernel counts 0 as well), regs = registers from ptxas for PF_NVCC_ARCH
# (default sm_75, else the oldest architecture nvcc lists); sass = SASS instructions from
# cuobjdump -sass except loads/stores/moves/EXIT/BRA/NOP (n/a without cuobjdump; that path was
# written without a cuobjdump to try it on: check its counts the first time it runs).
# The textbook baselines go through exactly the same wrapper generator and counting.
#
# Environment: PF_GPU_CACHE (below, at UNITS), NVCC (default: nvcc on PATH, else /usr/local/cuda/bin/nvcc; none: no CUDA),
# PF_NVCC_ARCH, PF_GPU_JOBS (shaders compiled at once; default PFB_THREADS, else every core;
# bench/pool.sh, with progress on stderr), PF_GPU_WORK (work
# directory, kept; default a fresh one under ${TMPDIR:-/tmp}, removed at the end).
# Needs glslangValidator (glslang-tools), spirv-opt and spirv-dis (spirv-tools); exits 2 when
# they are missing (make bench installs them through tests/deps.sh).
set -u
ROOT=$(cd "$(dirname "$0")/../.." && pwd) || exit 2
cd "$ROOT" || exit 2
INC=include
GEN=tests/portability/gen.awk
TB=bench/gpu/textbook.h
PX=bench/gpu/pixel.h   # one shaded pixel of the multi-lobe methods (m lobes, fetches excluded)

# spirv_count SPV: "ops branches" of main after spirv-opt -O (bench/gpu/spirv_ops.awk).
spirv_count() {
    spirv-opt -O "$1" -o "$1.opt" 2> "$1.log" || return 1
    spirv-dis "$1.opt" 2>> "$1.log" | awk -f bench/gpu/spirv_ops.awk
}

# cache_key FILE: the key of FILE's counts in PF_GPU_CACHE (its content with PF_GPU_TOOLS:
# the tools' versions and the counting rules)
cache_key() {
    { cat "$1"; echo "${PF_GPU_TOOLS:-}"; } | cksum | awk '{ print $1 "-" $2 }'
}

# spirv_file F.comp: compile, optimize, count; writes F.count ("ops branches", or "n/a n/a"
# with a message on stderr). Run in parallel through `count.sh --spirv F.comp`. With
# PF_GPU_CACHE, a shader counted before (same source, tools and rules) is not compiled again.
spirv_file() {
    b=${1%.comp}
    key=""
    if [ -n "${PF_GPU_CACHE:-}" ]; then
        key=$PF_GPU_CACHE/$(cache_key "$1").spirv
        [ -s "$key" ] && cp "$key" "$b.count" && return 0
    fi
    if glslangValidator -S comp -V --target-env vulkan1.0 -o "$b.spv" "$1" > "$b.glslang.log" 2>&1 &&
        r=$(spirv_count "$b.spv") && [ -n "$r" ]; then
        echo "$r" > "$b.count"
        [ -z "$key" ] || { cp "$b.count" "$key.$$" && mv "$key.$$" "$key"; }
    else
        echo "count.sh: $(basename "$b"): SPIR-V failed (log $b.glslang.log)" >&2
        echo "n/a n/a" > "$b.count"
    fi
}
if [ "${1:-}" = "--spirv" ]; then
    shift
    for c in "$@"; do spirv_file "$c"; done
    exit 0
fi

csv=""
if [ "${1:-}" = "-o" ]; then csv=$2; shift 2; fi

for t in glslangValidator spirv-opt spirv-dis; do
    command -v "$t" >/dev/null 2>&1 ||
        { echo "count.sh: $t not found (Debian packages glslang-tools, spirv-tools; tests/deps.sh bench)" >&2; exit 2; }
done

if [ -n "${PF_GPU_WORK:-}" ]; then W=$PF_GPU_WORK; mkdir -p "$W" || exit 2; keep=1
else W=$(mktemp -d "${TMPDIR:-/tmp}/pf-gpu.XXXXXX") || exit 2; keep=0; fi
cleanup() { [ $keep = 1 ] || rm -rf "$W"; }
trap cleanup EXIT INT TERM

NVCC=${NVCC:-}
if [ "$NVCC" = none ]; then NVCC=""
elif [ -z "$NVCC" ]; then
    if command -v nvcc >/dev/null 2>&1; then NVCC=nvcc
    elif [ -x /usr/local/cuda/bin/nvcc ]; then NVCC=/usr/local/cuda/bin/nvcc; fi
fi
CUOBJDUMP=""
if [ -n "$NVCC" ]; then
    c=$(dirname "$(command -v "$NVCC")")/cuobjdump
    if [ -x "$c" ]; then CUOBJDUMP=$c; elif command -v cuobjdump >/dev/null 2>&1; then CUOBJDUMP=cuobjdump; fi
    ARCH=${PF_NVCC_ARCH:-}
    if [ -z "$ARCH" ]; then
        archs=$("$NVCC" --list-gpu-code 2>/dev/null | tr '\n' ' ')
        case " $archs " in
            *" sm_75 "*) ARCH=sm_75 ;;
            *) ARCH=$(echo "$archs" | tr ' ' '\n' | grep '^sm_' | sort -t_ -k2n | head -n 1) ;;
        esac
        [ -n "$ARCH" ] || ARCH=sm_75
    fi
fi

# A header's pf_ includes, recursively, deps first (a header may be listed twice: dedupe).
deps_rec() {
    for dep_ in $(sed -n 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*"\(pf_[A-Za-z0-9_]*\.h\)".*/\1/p' "$INC/$1"); do
        [ "$dep_" = "$1" ] || deps_rec "$dep_"
    done
    echo "$1"
}
HEADERS=$(cd "$INC" && ls pf_*.h | tr '\n' ' ')

# Units: each header (pasted after the headers it includes) with the wrappers of its public
# functions, and bench/gpu/textbook.h after pf_core.h. gen.awk's own main/kernel is cut off.
# bench/gpu/pixel.h after pf_vmf.h and its includes.
# gen_unit MODE UNIT > file; UNIT = a header basename, textbook.h or pixel.h.
gen_unit() {
    if [ "$1" = glsl ]; then printf '#version 450\n#define PF_GLSL 1\n'; fi
    case $2 in
        textbook.h) chain=pf_core.h ;;
        pixel.h) chain=$(deps_rec pf_vmf.h | awk '!seen[$0]++') ;;
        *) chain=$(deps_rec "$2" | awk '!seen[$0]++') ;;
    esac
    for h in $chain; do cat "$INC/$h"; echo; done
    [ "$2" = textbook.h ] && { cat "$TB"; echo; }
    [ "$2" = pixel.h ] && { cat "$PX"; echo; }
    awk -v mode="$1" -v targets="$2" -v includes="" -f "$GEN" "$INC"/pf_*.h "$TB" "$PX" > "$W/gen.$1.$2.out" || return 1
    # gen.awk reads inputs modulo 16 (in[k % 16]): m lobes of 4 texel values would repeat
    # after 4 lobes and a compiler could merge them (nvcc did). pixel.h's wrappers read
    # distinct inputs instead: the indices renumbered 0, 1, 2, ... per wrapper.
    if [ "$2" = pixel.h ]; then
        awk '/^(__device__ )?(pf_real|float) pfp_pf_/ { n = 0 }
             { out = ""; s = $0
               while (match(s, /(pfp_in\.v|in)\[[0-9]+\]/)) {
                   t = substr(s, RSTART, RLENGTH); sub(/\[[0-9]+\]/, "[" n++ "]", t)
                   out = out substr(s, 1, RSTART - 1) t; s = substr(s, RSTART + RLENGTH) }
               print out s }' "$W/gen.$1.$2.out" > "$W/gen.$1.$2.renum" && mv "$W/gen.$1.$2.renum" "$W/gen.$1.$2.out"
    fi
    awk '/^void main\(\)$/ || /^__global__ void pfp_kernel/ { exit } { print }' "$W/gen.$1.$2.out"
}

# ---------------------------------------------------------------- CUDA: per unit, one kernel per function
# ptx = instructions of the kernel except ld/st/cvta/mov/ret/bra (parameter and buffer traffic;
# the copy kernel counts 0); regs from ptxas -v; sass from cuobjdump -sass when it exists.
ptx_count() {
    awk '/^\.visible \.entry / { k = $3; sub(/\(.*/, "", k); sub(/^pfk_/, "", k); n[k] = 0; next_k = k; next }
         next_k != "" && /^{/ { cur = next_k; next_k = ""; next }
         cur != "" && /^}/ { cur = ""; next }
         cur != "" {
             s = $0; sub(/^[ \t]+/, "", s)
             if (s == "" || s ~ /^[.{}]/ || s ~ /^\$[A-Za-z0-9_]*:/ || s ~ /^\/\//) next
             if (s ~ /^@/) { sub(/^@!?%[a-z0-9]+[ \t]+/, "", s) }
             op = s; sub(/[ \t;].*$/, "", op); sub(/\..*$/, "", op)
             if (op ~ /^(ld|st|cvta|mov|ret|bra)$/) next
             n[cur]++ }
         END { for (k in n) print k, n[k] }' "$1"
}
sass_count() {
    awk '/Function : / { k = $3; sub(/^pfk_/, "", k); cur = k; n[cur] = 0; next }
         cur != "" && /\/\*[0-9a-f]+\*\// {
             s = $0; sub(/^.*\*\/[ \t]*/, "", s); sub(/^@!?U?P[T0-9]+[ \t]+/, "", s)
             op = s; sub(/[ \t;].*$/, "", op)
             if (op ~ /^IMAD\.MOV/) next                 # the move idiom, not arithmetic
             sub(/\..*$/, "", op)
             if (op == "" || op ~ /^(LDG|STG|LDC|ULDC|LD|ST|MOV|EXIT|BRA|NOP|S2R|S2UR)$/) next
             n[cur]++ }
         END { for (k in n) print k, n[k] }'
}
PTXAS=""
[ -n "$NVCC" ] && { p=$(dirname "$(command -v "$NVCC")")/ptxas; [ -x "$p" ] && PTXAS=$p; }

# cuda_unit UNIT: the unit's kernels (the requested functions it wraps, $W/fns.txt) compiled by
# nvcc, counted into $W/<unit>.ptx.txt, .regs.txt, .sass.txt (run in parallel: --cuda-unit)
cuda_unit() {
    u=$1
    m=${u%.h}
    fns_flat=" $(cat "$W/fns.txt") "
    gen_unit cuda "$u" > "$W/$m.cu" 2> /dev/null || return 0
    # kernels only for the requested functions this unit wraps (+ the copy kernel once)
    [ "$u" = textbook.h ] && echo 'extern "C" __global__ void pfk_pfp_copy(const pf_real *in, pf_real *out) { out[0] = in[0]; }' >> "$W/$m.cu"
    nk=0
    for f in $(sed -n 's/^__device__ pf_real pfp_\(pf_[A-Za-z0-9_]*\)(.*/\1/p' "$W/$m.cu"); do
        case "$fns_flat" in *" $f "*) ;; *) continue ;; esac
        printf 'extern "C" __global__ void pfk_%s(const pf_real *in, pf_real *out) { out[0] = pfp_%s(in); }\n' "$f" "$f" >> "$W/$m.cu"
        nk=$((nk + 1))
    done
    [ $nk -gt 0 ] || [ "$u" = textbook.h ] || return 0
    key=""
    if [ -n "${PF_GPU_CACHE:-}" ]; then
        key=$PF_GPU_CACHE/$(cache_key "$W/$m.cu").cuda
        if [ -f "$key.ptx" ]; then
            for k in ptx regs sass; do [ -f "$key.$k" ] && cp "$key.$k" "$W/$m.$k.txt"; done
            return 0
        fi
    fi
    if "$NVCC" -O3 --use_fast_math -arch="$ARCH" -ptx -I"$INC" -o "$W/$m.ptx" "$W/$m.cu" > "$W/$m.nvcc.log" 2>&1; then
        ptx_count "$W/$m.ptx" > "$W/$m.ptx.txt"
        if [ -n "$PTXAS" ] && "$PTXAS" -O3 -arch="$ARCH" -v -o "$W/$m.cubin" "$W/$m.ptx" > "$W/$m.ptxas.log" 2>&1; then
            awk '/Compiling entry function/ { k = $0; sub(/.*function .pfk_/, "", k); sub(/[^A-Za-z0-9_].*$/, "", k); cur = k }
                 /Used [0-9]+ registers/ && cur != "" { for (i = 1; i <= NF; i++) if ($(i + 1) ~ /^registers/) print cur, $i; cur = "" }' \
                "$W/$m.ptxas.log" > "$W/$m.regs.txt"
            [ -n "$CUOBJDUMP" ] && "$CUOBJDUMP" -sass "$W/$m.cubin" 2> /dev/null | sass_count > "$W/$m.sass.txt"
        fi
        if [ -n "$key" ]; then # the PTX file last: its presence marks a complete entry
            for k in regs sass ptx; do [ -f "$W/$m.$k.txt" ] && cp "$W/$m.$k.txt" "$key.$k.$$" && mv "$key.$k.$$" "$key.$k"; done
        fi
    else
        : > "$W/$m.nvcc.failed"
    fi
    return 0
}
if [ "${1:-}" = "--cuda-unit" ]; then
    cuda_unit "$2"
    exit 0
fi

# PF_GPU_CACHE (a directory; bench/run.sh: BUILD/gpu-cache): counts of shaders and CUDA units
# already counted, keyed by their source and PF_GPU_TOOLS (the tools' versions, nvcc's
# architecture and the counting rules: this script and spirv_ops.awk), so a run after a change
# compiles only the functions whose source changed.
if [ -n "${PF_GPU_CACHE:-}" ] && [ -z "${PF_GPU_TOOLS:-}" ]; then
    if mkdir -p "$PF_GPU_CACHE" 2> /dev/null; then
        PF_GPU_TOOLS=$( { glslangValidator --version; spirv-opt --version; cat "$ROOT/bench/gpu/spirv_ops.awk" "$ROOT/bench/gpu/count.sh"
                          [ -n "$NVCC" ] && { "$NVCC" --version; echo "$ARCH $PTXAS $CUOBJDUMP"; }; } 2>&1 | cksum)
        export PF_GPU_CACHE PF_GPU_TOOLS
    else
        PF_GPU_CACHE=""
    fi
fi

UNITS="$HEADERS textbook.h pixel.h"
jobs=${PF_GPU_JOBS:-${PFB_THREADS:-$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo 1)}}
# the units' shader sources, PF_GPU_JOBS at a time (each in its own scratch file)
if [ "${1:-}" = "--gen-unit" ]; then
    m=${3%.h}
    if gen_unit "$2" "$3" > "$W/$m.$2" 2> "$W/$m.gen.log"; then echo ok > "$W/$m.$2.status"
    else echo fail > "$W/$m.$2.status"; fi
    exit 0
fi
: > "$W/units.jobs"
for u in $UNITS; do
    echo "PF_GPU_WORK=$W sh $ROOT/bench/gpu/count.sh --gen-unit glsl $u" >> "$W/units.jobs"
done
PFB_THREADS=$jobs sh "$ROOT/bench/pool.sh" "count.sh: shader sources" "$W/units.jobs" || exit 2
: > "$W/glsl.map"
for u in $UNITS; do
    m=${u%.h}
    if [ "$(cat "$W/$m.glsl.status" 2>/dev/null)" = ok ]; then
        sed -n 's/^float pfp_\(pf_[A-Za-z0-9_]*\)()$/\1/p' "$W/$m.glsl" | sed "s/\$/ $m/" >> "$W/glsl.map"
    else
        echo "count.sh: gen.awk failed on $u ($(head -n 1 "$W/$m.gen.log")); its functions are not counted" >&2
    fi
done
glsl_fns=$(awk '{ print $1 }' "$W/glsl.map")

if [ $# -gt 0 ]; then fns=$*
else fns=$(echo "$glsl_fns" | grep -v '^pf_textbook_'; echo "$glsl_fns" | grep '^pf_textbook_'); fi

# One shader per function: UNIT's source with a main that writes pfp_<f>() (and the copy
# shader, main = out[0] = in[0]), compiled PF_GPU_JOBS at a time (default: nproc).
write_comp() { # name unit body
    { cat "$W/$2.glsl"; printf 'void main()\n{\n%s\n}\n' "$3"; } > "$W/$1.comp"
}
write_comp pfp_copy textbook '    pfp_out.v[0] = pfp_in.v[0];'
comps="$W/pfp_copy.comp"
for f in $fns; do
    u=$(awk -v f="$f" '$1 == f { print $2; exit }' "$W/glsl.map")
    [ -n "$u" ] || continue
    write_comp "$f" "$u" "    pfp_out.v[0] = pfp_$f();"
    comps="$comps $W/$f.comp"
done
for c in $comps; do echo "sh $ROOT/bench/gpu/count.sh --spirv $c"; done > "$W/spirv.jobs"
PFB_THREADS=$jobs sh "$ROOT/bench/pool.sh" "count.sh: SPIR-V counts" "$W/spirv.jobs" || exit 2

# The copy shader must count 0: otherwise the counting is wrong, and every number with it.
copy=$(cat "$W/pfp_copy.count")
if [ "$copy" != "0 0" ]; then
    echo "count.sh: the copy shader counts '$copy', not '0 0': fix the counting" >&2
    exit 1
fi

: > "$W/ptx.txt"; : > "$W/regs.txt"; : > "$W/sass.txt"
ptx_ok=0
if [ -n "$NVCC" ]; then
    ptx_ok=1
    # one nvcc (+ ptxas, cuobjdump) per unit, PF_GPU_JOBS at a time; merged in unit order
    echo $fns > "$W/fns.txt"
    for u in $UNITS; do
        echo "PF_GPU_WORK=$W PF_NVCC_ARCH=$ARCH NVCC=$NVCC sh $ROOT/bench/gpu/count.sh --cuda-unit $u"
    done > "$W/cuda.jobs"
    PFB_THREADS=$jobs sh "$ROOT/bench/pool.sh" "count.sh: CUDA (PTX) counts" "$W/cuda.jobs" || exit 2
    for u in $UNITS; do
        m=${u%.h}
        for k in ptx regs sass; do [ -f "$W/$m.$k.txt" ] && cat "$W/$m.$k.txt" >> "$W/$k.txt"; done
        [ -f "$W/$m.nvcc.failed" ] && echo "count.sh: nvcc failed on $u (log $W/$m.nvcc.log); its PTX counts are n/a" >&2
    done
    c=$(awk '$1 == "pfp_copy" { print $2 }' "$W/ptx.txt")
    [ "$c" = 0 ] || echo "count.sh: warning: the PTX copy kernel counts '${c:-nothing}', not 0" >&2
fi

lookup() { # file key -> value or n/a
    v=""
    [ -s "$1" ] && v=$(awk -v k="$2" '$1 == k { print $2; exit }' "$1")
    echo "${v:-n/a}"
}

[ -n "$csv" ] && echo "kind,function,header,spirv_ops,cond_branches,ptx,sass,regs" > "$csv"
printf '%-36s %9s %8s %6s %6s %5s\n' function spirv_ops branches ptx sass regs
for f in $fns; do
    u=$(awk -v f="$f" '$1 == f { print $2; exit }' "$W/glsl.map")
    if [ -n "$u" ] && [ -s "$W/$f.count" ]; then
        set -- $(cat "$W/$f.count")
    else
        set -- n/a n/a
    fi
    ops=$1; br=$2
    ptx=n/a; sass=n/a; regs=n/a
    if [ $ptx_ok = 1 ]; then
        ptx=$(lookup "$W/ptx.txt" "$f"); sass=$(lookup "$W/sass.txt" "$f"); regs=$(lookup "$W/regs.txt" "$f")
    fi
    case $f in pf_textbook_*) kind=textbook ;; pf_pixel_*) kind=pixel ;; *) kind=library ;; esac
    printf '%-36s %9s %8s %6s %6s %5s\n' "$f" "$ops" "$br" "$ptx" "$sass" "$regs"
    [ -n "$csv" ] && echo "$kind,$f,${u:-n/a}${u:+.h},$ops,$br,$ptx,$sass,$regs" >> "$csv"
done
exit 0
