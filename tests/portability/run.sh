#!/bin/sh
# tests/portability/run.sh - `make portability`: every header compiles everywhere we promise.
#
# usage: sh tests/portability/run.sh [BUILD_DIR]      (BUILD_DIR defaults to build)
#
# Headers are discovered (include/pf_*.h); for each, gen.awk generates code that calls every
# public function, so a new module is gated without editing this script. Checks:
#   gen-selftest   the generator on tests/portability/selftest fixtures
#   tcc-float      tcc: each header alone (-c), then all headers + driver.c linked and run
#   tcc-double     same with -DPF_DOUBLE
#   nvcc-float     nvcc -c of a __global__ kernel calling every function (device code); ptxas
#                  must see no double-precision instruction. SKIP when nvcc is absent.
#   nvcc-double    same with -DPF_DOUBLE (no double check)
#   glsl-include   #version 450 + PF_GLSL + GL_GOOGLE_include_directive, per header: compute
#                  shader compiled to OpenGL SPIR-V (-G) and Vulkan SPIR-V (-V), both spirv-val
#   glsl-paste     the same shader with the header text pasted in (no include extension)
#   spirv-hlsl50   spirv-cross --hlsl --shader-model 50 on each SPIR-V module
#   spirv-hlsl60   spirv-cross --hlsl --shader-model 60
#   spirv-msl      spirv-cross --msl
#   m4f-float      arm-none-eabi-gcc Cortex-M4F -Os -Werror -Wdouble-promotion, one TU per
#                  header; nm: no soft-double helper (__aeabi_d*, __aeabi_*2d) or double libm call
#   m4f-double     same with -DPF_DOUBLE (compile and size only)
#   m4f-link       all float objects + a main linked against newlib (nano, nosys): the linked
#                  image must hold no soft-double helper either (libm's own float functions)
#   m4f-nolibm     -DPF_NO_MATH_H -ffreestanding -nostdinc, every PF_ math macro mapped to a
#                  user function: no header may include a system header or call libm directly
#   amalgam-*      prefilter.h (tests/portability/amalgamate.sh) is up to date, and smoke.c plus
#                  every public function build on it alone and run: C99/C11 (gcc, clang), C++11/
#                  17/20 (g++, clang++), tcc, nvcc host (+ device kernel); GLSL with the prelude
#   gpu-lavapipe   tests/gpu/run.sh: every GLSL-callable evaluator run on lavapipe (Mesa's CPU
#                  Vulkan driver) and compared with the C float and double builds (docs/gpu.md)
#   consumer-*     tests/consumer/run.sh: make install + plain -I, pkg-config, CMake
#                  find_package after cmake --install, CMake add_subdirectory; each built and run
#   arm-float      the float test suite cross-built with arm-linux-gnueabihf-gcc -static
#                  (hard-float) and run under qemu-arm, same bounds (cell.sh; long double
#                  cases listed in ARM_KNOWN below)
#   mx-*           the compiler/flag matrix: gcc, clang, g++, clang++ at -O0/-O2/-O3, with
#                  -ffp-contract=off, FMA contraction and -ffast-math, C99/C11/C++11/17/20,
#                  nvcc host, tcc; every cell compiles every test, runs the full suite or the
#                  edge_ cases (cell_list below; docs/porting.md has the table)
# PF_PORT_ONLY="name ..." runs only the checks whose names start with one of the words
# (`make matrix`, `make arm`, `make consumers`). Every cell and every group of checks is a job
# of one pool, PORT_JOBS at once (default nproc); each job's lines are kept in its own file and
# printed whole, in the order above, once all have ended (stderr says when each job ends).
# Prints one line per check (ok / FAIL / SKIP (reason)), the M4F code-size table (also written to
# BUILD_DIR/portability/sizes.md), and exits 1 on any FAIL. Logs: BUILD_DIR/portability/<check>/.
# Installs nothing. Environment: NVCC (nvcc path), PF_NVCC_ARCH (default sm_75, else the oldest
# architecture nvcc lists), PF_PORT_STRICT=0 (glslang warnings reported but not fatal; default 1: they fail the GLSL checks),
# PF_PORT_UPDATE_DOCS=1 (copy the size table into docs/porting.md between its markers).
set -u
ROOT=$(cd "$(dirname "$0")/../.." && pwd) || exit 2
cd "$ROOT" || exit 2
# Internal: sh run.sh --job BUILD_DIR group NAME | cell CELL-LINE... runs one job of the pool
# (below) and prints its lines; the parent prints every job's output, in order, at the end.
JOB=""
if [ "${1:-}" = --job ]; then BUILD=$2; JOB=$3; shift 3; else BUILD=${1:-build}; fi
OUT=$BUILD/portability
P=tests/portability
INC=include
[ -n "$JOB" ] || { rm -rf "$OUT" && mkdir -p "$OUT"; } || exit 2

HEADERS=$(cd "$INC" && ls pf_*.h 2>/dev/null)
NHEAD=$(echo $HEADERS | wc -w | tr -d ' ')
nok=0; nfail=0; nskip=0

report() { # status check detail
    case $1 in
    ok)   nok=$((nok + 1));   printf 'ok   %-13s %s\n' "$2" "$3" ;;
    FAIL) nfail=$((nfail + 1)); printf 'FAIL %-13s %s\n' "$2" "$3" ;;
    SKIP) nskip=$((nskip + 1)); printf 'SKIP %-13s (%s)\n' "$2" "$3" ;;
    esac
}

have() { command -v "$1" >/dev/null 2>&1; }

# missing TOOL PACKAGE: true (and reports FAIL for CHECK) when TOOL is not on PATH.
missing() { # check tool package
    have "$2" && return 1
    report FAIL "$1" "$2 not found (Debian package $3)"
    return 0
}

# gen MODE "TARGETS" "INCLUDES": generated code on stdout (gen.awk errors on stderr).
gen() { awk -v mode="$1" -v targets="$2" -v includes="$3" -f "$P/gen.awk" "$INC"/pf_*.h; }

# deps HEADER: the pf_ headers it includes (transitively, deps first), then itself, one a line.
deps_rec() {
    for dep_ in $(sed -n 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*"\(pf_[A-Za-z0-9_]*\.h\)".*/\1/p' "$INC/$1"); do
        [ "$dep_" = "$1" ] || deps_rec "$dep_"
    done
    echo "$1"
}
deps() { deps_rec "$1" | awk '!seen[$0]++'; }

mod() { basename "$1" .h; }
# count of generated wrappers in a generated file
nwrap() { grep -c '^{   /\* ' "$1"; }
first_lines() { head -n "${2:-3}" "$1" | sed 's/^/       /'; }

if [ "$NHEAD" -eq 0 ]; then
    report FAIL discovery "no include/pf_*.h found"
    exit 1
fi

# ------------------------------------------------------------------ generator self-test
check_selftest() {
    d=$OUT/gen-selftest; mkdir -p "$d"; st=$P/selftest
    cc=""
    for c in cc gcc tcc; do have "$c" && { cc=$c; break; }; done
    awk -v mode=c -v targets=pf_fixture.h -v includes=pf_fixture.h -f "$P/gen.awk" \
        "$INC"/pf_*.h "$st/pf_fixture.h" > "$d/fixture.c" 2> "$d/gen.log" || {
        report FAIL gen-selftest "gen.awk failed on the fixture: $(head -1 "$d/gen.log")"; return; }
    awk -v mode=glsl -v targets=pf_fixture.h -v includes=pf_fixture.h -f "$P/gen.awk" \
        "$INC"/pf_*.h "$st/pf_fixture.h" > "$d/fixture.comp" 2>> "$d/gen.log" || {
        report FAIL gen-selftest "gen.awk (glsl) failed on the fixture"; return; }
    why=""
    grep -q 'pfp_pf_fx_multiline' "$d/fixture.c" || why="$why multi-line declaration missed;"
    grep -q 'pfp_a1.dir = pf_vec3_make(' "$d/fixture.c" || why="$why struct without maker not built;"
    grep -q 'pfp_r.n' "$d/fixture.c" || why="$why struct result leaves not summed;"
    grep -q 'pf_fx_in_comment\|pfp_pfi_' "$d/fixture.c" && why="$why comment or private function wrapped;"
    grep -q 'pf_fx_sum: C-only' "$d/fixture.c" || why="$why C-only pointer function not skipped;"
    grep -q 'pfp_pf_fx_glsl_only' "$d/fixture.c" && why="$why GLSL-only function called from C;"
    grep -q 'pfp_pf_fx_glsl_only' "$d/fixture.comp" || why="$why GLSL-only function not called from GLSL;"
    grep -q 'pfp_pf_fx_sum' "$d/fixture.comp" && why="$why C-only function called from GLSL;"
    if awk -v mode=c -v targets=pf_fixture_bad.h -f "$P/gen.awk" "$INC"/pf_*.h \
        "$st/pf_fixture_bad.h" > /dev/null 2> "$d/bad.log"; then
        why="$why pointer parameter accepted;"
    else
        grep -q 'pf_fx_bad' "$d/bad.log" || why="$why error does not name the function;"
    fi
    if [ -n "$cc" ]; then
        $cc -std=c99 -Wall -Werror -I"$INC" -I"$st" -c "$d/fixture.c" -o "$d/fixture.o" \
            > "$d/cc.log" 2>&1 || why="$why fixture TU does not compile with $cc (see $d/cc.log);"
    fi
    if [ -n "$why" ]; then report FAIL gen-selftest "$why"
    else report ok gen-selftest "fixture: $(nwrap "$d/fixture.c") wrappers; comments, private, C-only skipped; pointer rejected"
    fi
}

# ------------------------------------------------------------------ tcc
check_tcc() { # float|double
    name=tcc-$1; d=$OUT/$name; mkdir -p "$d"
    missing "$name" tcc tcc && return
    def=""; [ "$1" = double ] && def=-DPF_DOUBLE
    bad=""
    for h in $HEADERS; do
        m=$(mod "$h")
        gen c "$h" "$h" > "$d/$m.c" 2> "$d/$m.log" || { bad="$bad $h(gen: $(head -1 "$d/$m.log"))"; continue; }
        tcc -std=c99 -Wall -Werror $def -I"$INC" -c "$d/$m.c" -o "$d/$m.o" >> "$d/$m.log" 2>&1 ||
            { bad="$bad $h"; first_lines "$d/$m.log"; }
    done
    all=$(echo $HEADERS)
    if ! { gen c "$all" "$all" && cat "$P/driver.c"; } > "$d/all.c" 2> "$d/all.log"; then
        bad="$bad all-headers(gen)"
    elif ! tcc -std=c99 -Wall -Werror $def -I"$INC" "$d/all.c" -o "$d/all" -lm >> "$d/all.log" 2>&1; then
        bad="$bad all-headers-link"; first_lines "$d/all.log"
    elif ! "$d/all" > "$d/run.txt" 2>&1; then
        bad="$bad run(exit $?)"
    fi
    if [ -n "$bad" ]; then report FAIL "$name" "failed:$bad (logs in $d)"; return; fi
    set -- $(grep '^called' "$d/run.txt")
    note=""
    [ "${6:-0}" != 0 ] && note="; note: non-finite on inputs in (0,1): $(grep '^nonfinite' "$d/run.txt" | cut -d' ' -f2 | tr '\n' ' ')"
    report ok "$name" "$NHEAD headers alone; all together: ${2:-?} functions linked and ran, sum $4$note"
}

# ------------------------------------------------------------------ nvcc
NVCC_BIN=""
find_nvcc() {
    if [ -n "${NVCC:-}" ] && [ -x "$NVCC" ]; then NVCC_BIN=$NVCC
    elif have nvcc; then NVCC_BIN=$(command -v nvcc)
    elif [ -x /usr/local/cuda/bin/nvcc ]; then NVCC_BIN=/usr/local/cuda/bin/nvcc
    elif [ -n "${CUDA_HOME:-}" ] && [ -x "$CUDA_HOME/bin/nvcc" ]; then NVCC_BIN=$CUDA_HOME/bin/nvcc
    fi
}

check_nvcc() { # float|double
    name=nvcc-$1; d=$OUT/$name
    if [ -z "$NVCC_BIN" ]; then
        report SKIP "$name" "nvcc not found in \$NVCC, PATH, /usr/local/cuda/bin or \$CUDA_HOME/bin"; return
    fi
    mkdir -p "$d"
    arch=${PF_NVCC_ARCH:-}
    if [ -z "$arch" ]; then
        arch=sm_75
        list=$("$NVCC_BIN" --list-gpu-arch 2>/dev/null)
        if [ -n "$list" ] && ! echo "$list" | grep -qx compute_75; then
            arch=$(echo "$list" | head -1 | sed 's/compute_/sm_/')
        fi
    fi
    all=$(echo $HEADERS)
    gen cuda "$all" "$all" > "$d/all.cu" 2> "$d/all.log" || {
        report FAIL "$name" "$(head -1 "$d/all.log")"; return; }
    if [ "$1" = double ]; then extra=-DPF_DOUBLE; else extra="-Xptxas --warn-on-double-precision-use"; fi
    if "$NVCC_BIN" -c -arch="$arch" -Werror all-warnings $extra -I"$INC" "$d/all.cu" -o "$d/all.o" \
        >> "$d/all.log" 2>&1; then
        what="$(nwrap "$d/all.cu") functions in a __global__ kernel, -arch=$arch"
        [ "$1" = float ] && what="$what, no double-precision PTX"
        report ok "$name" "$what"
    else
        first_lines "$d/all.log" 5
        report FAIL "$name" "nvcc -arch=$arch failed (log: $d/all.log)"
    fi
}

# ------------------------------------------------------------------ GLSL and SPIR-V
glsl_warn=0
# shader_check FILE SPV LOG: OpenGL SPIR-V (-G, OpenGL 4.5 rules), Vulkan SPIR-V (-V), each
# through spirv-val. SPV is the Vulkan module (fed to spirv-cross). Returns 0 on success.
shader_check() {
    glslangValidator -S comp -G --target-env opengl -I"$ROOT/$INC" -o "$2.gl" "$1" > "$3" 2>&1 || return 1
    spirv-val --target-env opengl4.5 "$2.gl" >> "$3" 2>&1 || return 1
    glslangValidator -S comp -V --target-env vulkan1.0 -I"$ROOT/$INC" -o "$2" "$1" >> "$3" 2>&1 || return 1
    spirv-val --target-env vulkan1.0 "$2" >> "$3" 2>&1 || return 1
    return 0
}

check_glsl() { # include|paste
    name=glsl-$1; d=$OUT/$name; mkdir -p "$d"
    missing "$name" glslangValidator glslang-tools && return
    missing "$name" spirv-val spirv-tools && return
    bad=""; n=0; nw=0; wlog=""
    for h in $HEADERS; do
        m=$(mod "$h"); chain=$(deps "$h" | tr '\n' ' ')
        if [ "$1" = include ]; then
            gen glsl "$h" "$chain" > "$d/$m.comp" 2> "$d/$m.gen.log"
        else
            { printf '#version 450\n#define PF_GLSL 1\n'
              for c in $chain; do cat "$INC/$c"; echo; done
              gen glsl "$h" ""; } > "$d/$m.comp" 2> "$d/$m.gen.log"
        fi
        if [ $? -ne 0 ]; then bad="$bad $h(gen: $(head -1 "$d/$m.gen.log"))"; continue; fi
        n=$((n + $(nwrap "$d/$m.comp")))
        if ! shader_check "$d/$m.comp" "$d/$m.spv" "$d/$m.log"; then
            bad="$bad $h"; grep -i 'error' "$d/$m.log" | head -5 | sed 's/^/       /'
        fi
        w=$(grep -c '^WARNING' "$d/$m.log")
        [ "$w" -gt 0 ] && { nw=$((nw + w)); wlog="$wlog $d/$m.log"; }
    done
    if [ -n "$bad" ]; then report FAIL "$name" "failed:$bad (logs in $d)"; return; fi
    detail="$NHEAD shaders, $n calls; OpenGL and Vulkan SPIR-V, spirv-val clean"
    if [ "$nw" -eq 0 ]; then report ok "$name" "$detail"; return; fi
    # distinct warnings (GLSL reserves identifiers containing "__", ...), listed under the line
    grep -h '^WARNING' $wlog | sed 's/^WARNING: //; s/[[:space:]]*$//' |
        awk '{ k = $0; sub(/^[^ ]*: /, "", k); if (!(k in seen)) { seen[k] = 1; print } }' > "$d/warnings.txt"
    nw=$(wc -l < "$d/warnings.txt" | tr -d ' ')
    if [ "${PF_PORT_STRICT:-1}" = 1 ]; then
        report FAIL "$name" "$nw distinct glslang warnings, PF_PORT_STRICT=1:"
    else
        report ok "$name" "$detail; $nw distinct glslang warnings:"
    fi
    head -8 "$d/warnings.txt" | sed 's/^/       warning: /'
}

check_cross() { # check-name spirv-cross-args...
    name=$1; shift; d=$OUT/$name; mkdir -p "$d"
    missing "$name" spirv-cross spirv-cross && return
    bad=""; n=0
    for h in $HEADERS; do
        m=$(mod "$h"); spv=$OUT/glsl-include/$m.spv
        if [ ! -s "$spv" ]; then bad="$bad $h(no SPIR-V from glsl-include)"; continue; fi
        if spirv-cross "$@" --output "$d/$m.out" "$spv" > "$d/$m.log" 2>&1 && [ -s "$d/$m.out" ]; then
            n=$((n + 1))
        else
            bad="$bad $h"; first_lines "$d/$m.log"
        fi
    done
    if [ -n "$bad" ]; then report FAIL "$name" "failed:$bad (logs in $d)"
    else report ok "$name" "$n modules: spirv-cross $*"
    fi
}

# ------------------------------------------------------------------ Cortex-M4F
M4F="-mcpu=cortex-m4 -mthumb -mfpu=fpv4-sp-d16 -mfloat-abi=hard"
M4F_CFLAGS="$M4F -Os -std=c99 -Wdouble-promotion -Wall -Wextra -Werror"
# Undefined symbols that mean double precision in a float build: soft-double helpers
# (__aeabi_dadd, __aeabi_f2d, __aeabi_i2d, ...) and the double libm entry points.
DOUBLE_SYMS='^(__aeabi_d[a-z0-9]*|__aeabi_[a-z0-9]*2d|__(add|sub|mul|div|extendsf|truncdf)[a-z0-9]*df[0-9]*|sqrt|exp|exp2|expm1|log|log2|log10|log1p|fabs|floor|ceil|pow|sin|cos|tan|asin|acos|atan|atan2|sinh|cosh|tanh|erf|erfc|fmod|fmin|fmax|ldexp|frexp|cbrt|hypot|round|trunc)$'

undef_syms() { arm-none-eabi-nm -u "$1" | awk '{print $NF}'; }

check_m4f() { # float|double
    name=m4f-$1; d=$OUT/$name; mkdir -p "$d"
    missing "$name" arm-none-eabi-gcc gcc-arm-none-eabi && return
    def=""; [ "$1" = double ] && def=-DPF_DOUBLE
    bad=""
    for h in $HEADERS; do
        m=$(mod "$h")
        gen c "$h" "$h" > "$d/$m.c" 2> "$d/$m.log" || { bad="$bad $h(gen: $(head -1 "$d/$m.log"))"; continue; }
        if ! arm-none-eabi-gcc $M4F_CFLAGS $def -I"$INC" -c "$d/$m.c" -o "$d/$m.o" >> "$d/$m.log" 2>&1; then
            bad="$bad $h"; first_lines "$d/$m.log" 5; continue
        fi
        arm-none-eabi-size "$d/$m.o" | awk 'NR == 2 {print $1}' > "$d/$m.text"
        nwrap "$d/$m.c" > "$d/$m.count"
        undef_syms "$d/$m.o" | grep -v '^pfp_' | sort > "$d/$m.undef"
        if [ "$1" = float ]; then
            dbl=$(grep -E "$DOUBLE_SYMS" "$d/$m.undef" | tr '\n' ' ')
            [ -n "$dbl" ] && bad="$bad $h(double: $dbl)"
        fi
    done
    if [ -n "$bad" ]; then report FAIL "$name" "failed:$bad (logs in $d)"; return; fi
    if [ "$1" = float ]; then report ok "$name" "$NHEAD objects, no soft-double helper or double libm call"
    else report ok "$name" "$NHEAD objects compiled (size only)"
    fi
}

check_m4f_link() {
    name=m4f-link; d=$OUT/$name; mkdir -p "$d"; src=$OUT/m4f-float
    missing "$name" arm-none-eabi-gcc gcc-arm-none-eabi && return
    objs=""
    for h in $HEADERS; do
        m=$(mod "$h")
        [ -s "$src/$m.o" ] || { report FAIL "$name" "no object for $h from m4f-float"; return; }
        objs="$objs $src/$m.o"
    done
    # main calls every wrapper so --gc-sections keeps all of them and what they call.
    arm-none-eabi-nm -g --defined-only $objs | awk '$NF ~ /^pfp_/ {print $NF}' | sort -u > "$d/wrappers.txt"
    {
        echo "/* generated by run.sh: calls every wrapper of the m4f-float objects */"
        sed 's/.*/float &(const float *in);/' "$d/wrappers.txt"
        echo "volatile float pfp_in[16];"
        echo "volatile float pfp_out;"
        echo "int main(void)"
        echo "{"
        echo "    float in[16], acc = 0.0f;"
        echo "    int i;"
        echo "    for (i = 0; i < 16; i++) in[i] = pfp_in[i];"
        sed 's/.*/    acc += &(in);/' "$d/wrappers.txt"
        echo "    pfp_out = acc;"
        echo "    return 0;"
        echo "}"
    } > "$d/main.c"
    if ! arm-none-eabi-gcc $M4F_CFLAGS -c "$d/main.c" -o "$d/main.o" > "$d/link.log" 2>&1 ||
       ! arm-none-eabi-gcc $M4F -Os --specs=nano.specs --specs=nosys.specs -Wl,--gc-sections \
            "$d/main.o" $objs -lm -o "$d/all.elf" >> "$d/link.log" 2>&1; then
        first_lines "$d/link.log" 5
        report FAIL "$name" "link against newlib failed (is libnewlib-arm-none-eabi installed? log: $d/link.log)"
        return
    fi
    arm-none-eabi-nm "$d/all.elf" | awk '{print $NF}' | sort -u > "$d/syms.txt"
    dbl=$(grep -E '^(__aeabi_d[a-z0-9]*|__aeabi_[a-z0-9]*2d)$' "$d/syms.txt" | tr '\n' ' ')
    if [ -n "$dbl" ]; then
        report FAIL "$name" "newlib pulled soft-double helpers into the image: $dbl"
    else
        report ok "$name" "$(wc -l < "$d/wrappers.txt" | tr -d ' ') functions + newlib libm linked, no soft-double helper in the image"
    fi
}

check_m4f_nolibm() {
    name=m4f-nolibm; d=$OUT/$name; mkdir -p "$d"
    missing "$name" arm-none-eabi-gcc gcc-arm-none-eabi && return
    # Every math macro pf_core.h defaults (PF_SQRT(x) sqrtf(x), ...), with its arity.
    sed -n 's/^[[:space:]]*#[[:space:]]*define[[:space:]]*\(PF_[A-Z0-9_]*\)(\([^)]*\))[[:space:]]*[a-z][a-z0-9_]*(.*/\1 \2/p' \
        "$INC/pf_core.h" | grep -v '^PF_R ' | awk '!seen[$1]++' > "$d/macros.txt"
    if [ ! -s "$d/macros.txt" ]; then report FAIL "$name" "found no PF_ math macro in pf_core.h"; return; fi
    {
        echo "/* generated by run.sh: bare-metal prelude, every math macro user-provided */"
        echo "#define PF_NO_MATH_H 1"
        while read -r mac args; do
            fn=pfp_user_$(echo "$mac" | sed 's/^PF_//' | tr 'A-Z' 'a-z')
            n=$(echo "$args" | awk -F, '{print NF}')
            proto=float; i=1; while [ "$i" -lt "$n" ]; do proto="$proto, float"; i=$((i + 1)); done
            echo "float $fn($proto);"
            echo "#define $mac($args) $fn($args)"
        done < "$d/macros.txt"
    } > "$d/prelude.h"
    bad=""
    for h in $HEADERS; do
        m=$(mod "$h")
        { echo "#include \"prelude.h\""; gen c "$h" "$h"; } > "$d/$m.c" 2> "$d/$m.log" || { bad="$bad $h(gen)"; continue; }
        if ! arm-none-eabi-gcc $M4F_CFLAGS -ffreestanding -nostdinc -I"$d" -I"$INC" -c "$d/$m.c" -o "$d/$m.o" \
            >> "$d/$m.log" 2>&1; then
            bad="$bad $h"; first_lines "$d/$m.log" 5; continue
        fi
        other=$(undef_syms "$d/$m.o" | grep -v '^pfp_user_' | tr '\n' ' ')
        [ -n "$other" ] && bad="$bad $h(calls outside the PF_ macros: $other)"
    done
    if [ -n "$bad" ]; then report FAIL "$name" "failed:$bad (logs in $d)"
    else report ok "$name" "$(wc -l < "$d/macros.txt" | tr -d ' ') math macros user-provided, no system header, no other external call"
    fi
}

size_table() {
    f=$OUT/m4f-float; g=$OUT/m4f-double
    [ -d "$f" ] || return
    {
        echo "| module | functions | float .text (bytes) | double .text (bytes) | libm calls (float build) |"
        echo "|---|---:|---:|---:|---|"
        for h in $HEADERS; do
            m=$(mod "$h")
            [ -s "$f/$m.text" ] || continue
            dt=$(cat "$g/$m.text" 2>/dev/null || echo -)
            calls=$(tr '\n' ' ' < "$f/$m.undef" | sed 's/ $//')
            echo "| $h | $(cat "$f/$m.count") | $(cat "$f/$m.text") | $dt | ${calls:-none} |"
        done
        echo
        echo "Cortex-M4F, arm-none-eabi-gcc $(arm-none-eabi-gcc -dumpversion) -Os -mthumb -mfpu=fpv4-sp-d16" \
             "-mfloat-abi=hard; one object per header holding one extern wrapper per public function" \
             "(wrappers included, libm excluded). Generated by \`make portability\` on $(date -u +%Y-%m-%d)."
    } > "$OUT/sizes.md"
    echo
    cat "$OUT/sizes.md"
    # PF_PORT_UPDATE_DOCS=1: splice the table into docs/porting.md between its markers.
    if [ "${PF_PORT_UPDATE_DOCS:-0}" = 1 ] && grep -q '^<!-- sizes:begin' docs/porting.md 2>/dev/null; then
        awk -v table="$OUT/sizes.md" '
            /^<!-- sizes:begin/ { print; while ((getline l < table) > 0) print l; skip = 1; next }
            /^<!-- sizes:end/ { skip = 0 }
            !skip' docs/porting.md > "$OUT/porting.md.new" && cp "$OUT/porting.md.new" docs/porting.md &&
            echo "(docs/porting.md size table updated)"
    fi
}

# ------------------------------------------------------------------ amalgamation (prefilter.h)
# amalgam-fresh   tests/portability/amalgamate.sh regenerates prefilter.h into the build
#                 directory; it must equal the committed file (else: run `make amalgamate`)
# amalgam-c       smoke.c (known values vs the C library's double erfc, exp, sqrt) and every
#                 public function (gen.awk + driver.c) built on prefilter.h alone and run:
#                 gcc -std=c99 (float, double), gcc -std=c11, clang -std=c99/c11, -Werror
# amalgam-cxx     the same as C++: g++ and clang++ -std=c++11/c++17/c++20
# amalgam-tcc     the same with tcc (float, double)
# amalgam-nvcc    the same with nvcc (host code, run) and a __global__ kernel calling every
#                 function compiled for the device; SKIP without nvcc
# amalgam-glsl    #version 450 + #define PF_GLSL 1 + prefilter.h pasted + a compute shader calling
#                 every function: OpenGL and Vulkan SPIR-V, spirv-val
AM=$OUT/amalgam
# amalgam_build TAG COMPILER FLAGS...: smoke + every-function driver on prefilter.h; sets am_bad
amalgam_build() {
    tag=$1; shift
    if ! "$@" -I"$AM" -I"$P" "$P/smoke.c" -o "$AM/smoke-$tag" -lm > "$AM/$tag.log" 2>&1; then
        am_bad="$am_bad $tag(smoke compile)"; first_lines "$AM/$tag.log"; return
    fi
    "$AM/smoke-$tag" >> "$AM/$tag.log" 2>&1 || { am_bad="$am_bad $tag(smoke: $(grep '^smoke' "$AM/$tag.log" | tail -1))"; return; }
    if ! "$@" -I"$AM" "$AM/all.c" -o "$AM/all-$tag" -lm >> "$AM/$tag.log" 2>&1; then
        am_bad="$am_bad $tag(all compile)"; first_lines "$AM/$tag.log"; return
    fi
    "$AM/all-$tag" > "$AM/all-$tag.txt" 2>&1 || { am_bad="$am_bad $tag(all: exit $?)"; return; }
    n=$(awk '$1 == "called" {print $2}' "$AM/all-$tag.txt")
    [ "$n" = "$am_count" ] || am_bad="$am_bad $tag(called ${n:-0} of $am_count)"
    am_done="$am_done $tag"
}
check_amalgam() {
    mkdir -p "$AM"
    if ! sh "$P/amalgamate.sh" "$AM/prefilter.h" > "$AM/gen.log" 2>&1; then
        report FAIL amalgam-fresh "amalgamate.sh failed: $(head -1 "$AM/gen.log")"; return
    fi
    if [ ! -f prefilter.h ]; then report FAIL amalgam-fresh "prefilter.h missing: run make amalgamate"
    elif ! cmp -s prefilter.h "$AM/prefilter.h"; then
        report FAIL amalgam-fresh "prefilter.h is out of date with include/: run make amalgamate (diff: $AM/)"
    else report ok amalgam-fresh "prefilter.h = $NHEAD headers in dependency order: $(grep -c '^/\* =* include/' prefilter.h) sections, $(wc -l < prefilter.h | tr -d ' ') lines"
    fi
    all=$(echo $HEADERS)
    { gen c "$all" prefilter.h && cat "$P/driver.c"; } > "$AM/all.c" 2> "$AM/all.gen.log" ||
        { report FAIL amalgam-c "gen.awk: $(head -1 "$AM/all.gen.log")"; return; }
    am_count=$(nwrap "$AM/all.c")
    WC="-pedantic -Wall -Wextra -Werror -Wdouble-promotion"
    WX="-Wall -Wextra -Werror"
    am_bad=""; am_done=""
    amalgam_build gcc-c99 gcc -std=c99 $WC
    amalgam_build gcc-c99-double gcc -std=c99 $WC -DPF_DOUBLE
    amalgam_build gcc-c11 gcc -std=c11 $WC
    if have clang; then amalgam_build clang-c99 clang -std=c99 $WC; amalgam_build clang-c11 clang -std=c11 $WC; fi
    if [ -n "$am_bad" ]; then report FAIL amalgam-c "failed:$am_bad (logs in $AM)"
    else report ok amalgam-c "smoke + $am_count functions run:$am_done"
    fi
    am_bad=""; am_done=""
    for std in c++11 c++17 c++20; do
        amalgam_build "g++-$std" g++ -x c++ -std=$std $WX
        have clang++ && amalgam_build "clang++-$std" clang++ -x c++ -std=$std $WX
    done
    amalgam_build g++-c++17-double g++ -x c++ -std=c++17 $WX -DPF_DOUBLE
    if [ -n "$am_bad" ]; then report FAIL amalgam-cxx "failed:$am_bad (logs in $AM)"
    else report ok amalgam-cxx "smoke + $am_count functions run:$am_done"
    fi
    if ! missing amalgam-tcc tcc tcc; then
        am_bad=""; am_done=""
        amalgam_build tcc tcc -std=c99 -Wall -Werror
        amalgam_build tcc-double tcc -std=c99 -Wall -Werror -DPF_DOUBLE
        if [ -n "$am_bad" ]; then report FAIL amalgam-tcc "failed:$am_bad (logs in $AM)"
        else report ok amalgam-tcc "smoke + $am_count functions run:$am_done"
        fi
    fi
    if [ -z "$NVCC_BIN" ]; then report SKIP amalgam-nvcc "nvcc not found"
    else
        am_bad=""; am_done=""
        amalgam_build nvcc-host "$NVCC_BIN" -x cu -Werror all-warnings
        amalgam_build nvcc-host-double "$NVCC_BIN" -x cu -Werror all-warnings -DPF_DOUBLE
        gen cuda "$all" prefilter.h > "$AM/all.cu" 2>> "$AM/all.gen.log"
        if ! "$NVCC_BIN" -c -arch="${PF_NVCC_ARCH:-sm_75}" -Werror all-warnings -Xptxas --warn-on-double-precision-use \
            -I"$AM" "$AM/all.cu" -o "$AM/all-cu.o" > "$AM/nvcc-device.log" 2>&1; then
            am_bad="$am_bad device"; first_lines "$AM/nvcc-device.log"
        fi
        if [ -n "$am_bad" ]; then report FAIL amalgam-nvcc "failed:$am_bad (logs in $AM)"
        else report ok amalgam-nvcc "smoke + $am_count functions run:$am_done; device: $(nwrap "$AM/all.cu") functions in a kernel, no double-precision PTX"
        fi
    fi
    if missing amalgam-glsl glslangValidator glslang-tools || missing amalgam-glsl spirv-val spirv-tools; then return; fi
    { printf '#version 450\n#define PF_GLSL 1\n'; cat "$AM/prefilter.h"; gen glsl "$all" ""; } > "$AM/all.comp" 2>> "$AM/all.gen.log"
    if shader_check "$AM/all.comp" "$AM/all.spv" "$AM/glsl.log" && ! grep -q '^WARNING' "$AM/glsl.log"; then
        report ok amalgam-glsl "prefilter.h pasted after the prelude: $(nwrap "$AM/all.comp") calls; OpenGL and Vulkan SPIR-V, spirv-val clean"
    else
        grep -i 'error\|warning' "$AM/glsl.log" | head -5 | sed 's/^/       /'
        report FAIL amalgam-glsl "log: $AM/glsl.log"
    fi
}

# ------------------------------------------------------------------ test suite: matrix and ARM
# Every cell compiles every tests/test_*.c (cell.sh) and runs them: the whole suite ("full") in
# a few cells, the edge_ cases in the rest (the CI budget; docs/porting.md has the table).
# arm-float: arm-linux-gnueabihf-gcc -static (hard-float), run under qemu-arm: the float suite with
# the same bounds. Under the ARM EABI long double is double, so the cases below, which need the
# x87 80-bit long double (precision or exponent range) of their reference, are tolerated:
ARM_KNOWN="test_oracle:*"                                       # self-checks of the long double oracle at 1e-18
ARM_KNOWN="$ARM_KNOWN,test_gaussgrid:test_node_convergence"     # reference integrand exp(0.7 z) N(z) overflows double
ARM_KNOWN="$ARM_KNOWN,test_moments:test_esm_log_matches_direct" # reference expl(3000 z) overflows double
ARM_KNOWN="$ARM_KNOWN,test_height:test_visible_height_exact_tier" # oracle status: mass check at long double precision
ARM_KNOWN="$ARM_KNOWN,test_height:test_integer_lambda_expected_max" # checks a quadrature to 1e-17
# Matrix cells that show a known defect of a module or its test, reported to the module's
# owner; each entry names the case so nothing else in the cell may fail (docs/porting.md):
WC99="-pedantic -Wall -Wextra -Werror -Wdouble-promotion"
WCXX="-Wall -Wextra -Werror"
# gcc -O3 warns maybe-uninitialized in tests/test_moments.c (test code, reported): kept a warning
O3G="-O3 -Wno-error=maybe-uninitialized"
# name mode runner known compiler flags...   (one cell a line; mx- = matrix, arm- = ARM)
cell_list() {
    echo "arm-float full qemu-arm $ARM_KNOWN arm-linux-gnueabihf-gcc -std=c99 $WC99 -O2 -static"
    echo "mx-gcc-c11-O3 full - - gcc -std=c11 $WC99 $O3G"
    echo "mx-gcc-c99-O0 edge - - gcc -std=c99 $WC99 -O0"
    echo "mx-clang-c99-O2-nocontract-dbl full - - clang -std=c99 $WC99 -O2 -ffp-contract=off -DPF_DOUBLE"
    echo "mx-clang++-c++17-O3 edge - - clang++ -x c++ -std=c++17 $WCXX -O3"
    if [ "$PF_HAVE_FMA" = 1 ]; then
        echo "mx-gcc-c99-O2-fma full - - gcc -std=c99 $WC99 -O2 -mfma -ffp-contract=fast"
        echo "mx-gcc-c11-O2-fma-nocontract edge - - gcc -std=c11 $WC99 -O2 -mfma -ffp-contract=off"
        echo "mx-clang++-c++11-O2-fma edge - - clang++ -x c++ -std=c++11 $WCXX -O2 -mfma"
    fi
    echo "mx-nvcc-host full - - ${NVCC_BIN:-nvcc} -x cu -O2"     # SKIP without nvcc
    echo "mx-gcc-c99-O0-dbl edge - - gcc -std=c99 $WC99 -O0 -DPF_DOUBLE"
    echo "mx-gcc-c11-O3-fastmath-dbl edge - - gcc -std=c11 $WC99 $O3G -ffast-math -DPF_DOUBLE"
    echo "mx-g++-c++11-O0 edge - - g++ -x c++ -std=c++11 $WCXX -O0"
    echo "mx-g++-c++17-O2-fastmath edge - - g++ -x c++ -std=c++17 $WCXX -O2 -ffast-math"
    echo "mx-g++-c++20-O3 edge - - g++ -x c++ -std=c++20 $WCXX $O3G"
    echo "mx-clang-c11-O0-dbl edge - - clang -std=c11 $WC99 -O0 -DPF_DOUBLE"
    echo "mx-clang-c99-O3-fastmath edge - - clang -std=c99 $WC99 -O3 -ffast-math"
    echo "mx-clang-c11-O2-fastmath-dbl edge - - clang -std=c11 $WC99 -O2 -ffast-math -DPF_DOUBLE"
    echo "mx-clang++-c++20-O0 edge - - clang++ -x c++ -std=c++20 $WCXX -O0"
    echo "mx-tcc compile - - tcc -std=c99 -Wall -Werror"
    # 32-bit x86 (gcc/clang -m32, Debian gcc-multilib + libc6-dev-i386): 32-bit pointers,
    # long and size_t, PF_MAX_REALS = 2^28, so every size check of pf_core.h's policy and every
    # guarded-buffer test meets the narrow limits; the sanitizer cells run the whole suite under
    # ASan+UBSan there (a size accepted past PF_MAX_REALS writes out of bounds only on 32-bit
    # hosts). SSE arithmetic (-msse2 -mfpmath=sse), as x86-64 has: the cells test the sizes,
    # not the x87's excess precision. So they run in cell.sh's "sizes" mode: the whole suite of
    # every module with a pointer-taking CPU-only function and of the reference code; the tests
    # of the pure-evaluator modules (no size, pointer or buffer; their arithmetic is x86-64's)
    # are compiled, not run (they were two thirds of these cells' time).
    if [ "$PF_HAVE_M32" = 1 ]; then
        M32="-m32 -msse2 -mfpmath=sse"
        # clang's -Warray-bounds sees the constant indices of test_height's far-corner table
        # test exceed the 32-bit address space (the test skips itself at run time there): kept
        # a warning in the clang cells
        SAN32="-O1 -g -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer -Wno-error=array-bounds"
        echo "x86-32-gcc-float sizes - - gcc $M32 -std=c99 $WC99 -O2"
        echo "x86-32-gcc-double sizes - - gcc $M32 -std=c99 $WC99 -O2 -DPF_DOUBLE"
        echo "x86-32-clang-san-float sizes - - clang -m32 -msse2 -std=c99 $WC99 $SAN32"
        echo "x86-32-clang-san-double sizes - - clang -m32 -msse2 -std=c99 $WC99 $SAN32 -DPF_DOUBLE"
    fi
}
# plan_cells: the cells to run (cells/todo.txt, one cell.sh argument line each) and the plan
# (cells/plan.txt: "NAME run" or "NAME missing TOOL"); report_cells: their lines, in plan order.
plan_cells() {
    d=$OUT/cells; mkdir -p "$d"
    PF_HAVE_FMA=0
    grep -qw fma /proc/cpuinfo 2>/dev/null && PF_HAVE_FMA=1
    # the 32-bit x86 cells on x86-64 hosts (tests/deps.sh installs gcc-multilib there)
    PF_HAVE_M32=0
    case $(uname -m) in x86_64|amd64) PF_HAVE_M32=1 ;; esac
    cell_list | while read -r cname rest; do
        selected "$cname" || continue
        tool=$(echo "$rest" | awk '{print $4}')
        runner=$(echo "$rest" | awk '{print $2}')
        if ! have "$tool"; then echo "$cname missing $tool"
        elif [ "$runner" != - ] && ! have "$runner"; then echo "$cname missing $runner"
        else echo "$cname $rest" >> "$d/todo.txt"; echo "$cname run"
        fi
    done > "$d/plan.txt"
}
report_cells() {
    d=$OUT/cells
    while read -r cname what tool; do
        if [ "$what" = missing ]; then
            case $tool in
            qemu-arm) report FAIL "$cname" "qemu-arm not found (Debian package qemu-user)" ;;
            arm-linux-gnueabihf-gcc) report FAIL "$cname" "$tool not found (Debian package gcc-arm-linux-gnueabihf)" ;;
            *nvcc*) report SKIP "$cname" "nvcc not found" ;;
            *) report FAIL "$cname" "$tool not found" ;;
            esac
            continue
        fi
        r=$(cat "$d/$cname/result" 2>/dev/null || echo "FAIL no result")
        report "${r%% *}" "$cname" "${r#* }"
    done < "$d/plan.txt"
}

# ------------------------------------------------------------------ consumer projects
# consumer-make       make install PREFIX=<tmp>; a C program built with -I<prefix>/include
# consumer-pkgconfig  the same install; cflags from pkg-config --cflags prefilter
# consumer-cmake-find cmake --install of the repository to <tmp>; tests/consumer/find_package
#                     (C++) built with find_package(prefilter) against it
# consumer-cmake-subdir  tests/consumer/add_subdirectory (C) vendoring the source tree
# Each consumer builds tests/portability/smoke.c (or its own main) and runs it.
check_consumers() {
    d=$OUT/consumer; rm -rf "$d"; mkdir -p "$d"
    sh tests/consumer/run.sh "$d" "$ROOT" > "$d/run.log" 2>&1
    grep -E '^(ok|FAIL|SKIP) ' "$d/run.log" | while read -r st cname detail; do
        selected "$cname" || continue
        echo "$st|$cname|$detail"
    done > "$d/lines.txt"
    [ -s "$d/lines.txt" ] || { report FAIL consumer "tests/consumer/run.sh printed nothing (log: $d/run.log)"; return; }
    while IFS='|' read -r st cname detail; do
        case $st in SKIP) report SKIP "$cname" "$(echo "$detail" | sed 's/^(//; s/)$//')" ;; *) report "$st" "$cname" "$detail" ;; esac
    done < "$d/lines.txt"
}

# ------------------------------------------------------------------ GLSL executed on lavapipe
# gpu-lavapipe: tests/gpu/run.sh runs every GLSL-callable public evaluator on Mesa's CPU Vulkan
# driver and compares it with the C float and double builds (bounds from the GLSL / Vulkan
# precision rules, docs/gpu.md). FAILs (never SKIPs) when glslang-tools, libvulkan-dev or
# mesa-vulkan-drivers is missing.
check_gpu() {
    d=$OUT/gpu-lavapipe; mkdir -p "$d"
    sh tests/gpu/run.sh "$d" > "$d/run.log" 2>&1
    rc=$?
    set -- $(grep '^RESULT' "$d/run.log" | tail -1)
    t=$(sed -n 's/^[0-9]* functions on .*, \([0-9.]* s\)$/\1/p' "$d/run.log")
    if [ $rc -eq 0 ] && [ "${3:-1}" = 0 ]; then
        report ok gpu-lavapipe "${2:-?} functions on lavapipe within their GLSL precision bounds ($t; $d/gpu/results.md)"
    else
        grep -E '^FAIL|^gpu:' "$d/run.log" | head -8 | sed 's/^/       /'
        if grep -q '^gpu:' "$d/run.log"; then report FAIL gpu-lavapipe "tests/gpu/run.sh could not run (log: $d/run.log)"
        else report FAIL gpu-lavapipe "${3:-?} of $((${2:-0} + ${3:-0})) functions failed (log: $d/run.log)"; fi
    fi
}

# ------------------------------------------------------------------ run
# PF_PORT_ONLY="a b": only the checks whose name starts with a or b (make matrix, arm, consumers).
selected() {
    [ -z "${PF_PORT_ONLY:-}" ] && return 0
    for p_ in $PF_PORT_ONLY; do
        case $1 in "$p_"*) return 0 ;; esac
        case $p_ in "$1"*) return 0 ;; esac     # a group (amalgam, mx-) when one of its checks is named
    done
    return 1
}
# The checks run as jobs of one pool, PORT_JOBS at once (default: the online cores): each
# matrix cell, and each group below (checks that read another's files share a group). A job's
# lines go to its own file, printed whole, in this order, when every job has ended; a line on
# stderr says when each job ends.
run_group() {
    case $1 in
    selftest) selected gen-selftest && check_selftest ;;
    tcc) selected tcc-float && check_tcc float
         selected tcc-double && check_tcc double ;;
    nvcc) selected nvcc-float && check_nvcc float
          selected nvcc-double && check_nvcc double ;;
    glsl-include) # the spirv-* checks read glsl-include's SPIR-V
        { selected glsl-include || selected spirv-; } && check_glsl include
        selected spirv-hlsl50 && check_cross spirv-hlsl50 --hlsl --shader-model 50
        selected spirv-hlsl60 && check_cross spirv-hlsl60 --hlsl --shader-model 60
        selected spirv-msl && check_cross spirv-msl --msl ;;
    glsl-paste) selected glsl-paste && check_glsl paste ;;
    m4f-float) # m4f-link links m4f-float's objects
        { selected m4f-float || selected m4f-link; } && check_m4f float
        selected m4f-link && check_m4f_link ;;
    m4f-double) selected m4f-double && check_m4f double ;;
    m4f-nolibm) selected m4f-nolibm && check_m4f_nolibm ;;
    amalgam) selected amalgam && check_amalgam ;;
    consumer) selected consumer- && check_consumers ;;
    gpu) selected gpu-lavapipe && check_gpu ;;
    esac
    return 0
}
GROUPS="selftest tcc nvcc glsl-include glsl-paste m4f-float m4f-double m4f-nolibm amalgam consumer gpu"

if [ -n "$JOB" ]; then
    t0_=$(date +%s)
    case $JOB in
    group) find_nvcc; run_group "$1" > "$OUT/jobs/group-$1.out" 2>&1 ;;
    cell) sh "$P/cell.sh" "$OUT/cells" "$@" ;;
    esac
    echo "$1" >> "$OUT/jobs/done.txt"
    echo "portability: $1 done in $(($(date +%s) - t0_)) s ($(grep -c . "$OUT/jobs/done.txt")/$(grep -c . "$OUT/jobs/list.txt") jobs)" >&2
    exit 0
fi

echo "portability: $NHEAD headers: $(echo $HEADERS)"
find_nvcc
mkdir -p "$OUT/jobs"
plan_cells
# longest first, so that no long job starts last: the cells that run the whole suite (under
# the sanitizers first, then qemu-arm), then the groups, then the edge_ and compile-only cells
touch "$OUT/cells/todo.txt"
{
    awk '($2 == "full" || $2 == "sizes") && / -fsanitize=/' "$OUT/cells/todo.txt"
    awk '($2 == "full" || $2 == "sizes") && !/ -fsanitize=/' "$OUT/cells/todo.txt"
} | sed 's/^/cell /' > "$OUT/jobs/list.txt"
for g in $GROUPS; do echo "group $g"; done >> "$OUT/jobs/list.txt"
awk '$2 != "full" && $2 != "sizes"' "$OUT/cells/todo.txt" | sed 's/^/cell /' >> "$OUT/jobs/list.txt"
njobs=${PORT_JOBS:-$(nproc 2>/dev/null || echo 2)}
echo "portability: $(grep -c . "$OUT/jobs/list.txt") jobs, $njobs at once" >&2
xargs -P "$njobs" -L 1 sh "$P/run.sh" --job "$BUILD" < "$OUT/jobs/list.txt"
# every group's lines, in order; its ok/FAIL/SKIP lines counted as report() counts them
for g in $GROUPS; do
    f=$OUT/jobs/group-$g.out
    [ -f "$f" ] || { report FAIL "$g" "the job wrote nothing"; continue; }
    cat "$f"
    nok=$((nok + $(grep -c '^ok   ' "$f")))
    nfail=$((nfail + $(grep -c '^FAIL ' "$f")))
    nskip=$((nskip + $(grep -c '^SKIP ' "$f")))
done
report_cells
size_table
echo
echo "portability: $nok ok, $nfail FAIL, $nskip SKIP"
[ "$nfail" -eq 0 ]
