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
# Prints one line per check (ok / FAIL / SKIP (reason)), the M4F code-size table (also written to
# BUILD_DIR/portability/sizes.md), and exits 1 on any FAIL. Logs: BUILD_DIR/portability/<check>/.
# Installs nothing. Environment: NVCC (nvcc path), PF_NVCC_ARCH (default sm_75, else the oldest
# architecture nvcc lists), PF_PORT_STRICT=0 (glslang warnings reported but not fatal; default 1: they fail the GLSL checks),
# PF_PORT_UPDATE_DOCS=1 (copy the size table into docs/porting.md between its markers).
set -u
ROOT=$(cd "$(dirname "$0")/../.." && pwd) || exit 2
cd "$ROOT" || exit 2
BUILD=${1:-build}
OUT=$BUILD/portability
P=tests/portability
INC=include
rm -rf "$OUT" && mkdir -p "$OUT" || exit 2

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

# ------------------------------------------------------------------ run
echo "portability: $NHEAD headers: $(echo $HEADERS)"
find_nvcc
check_selftest
check_tcc float
check_tcc double
check_nvcc float
check_nvcc double
check_glsl include
check_glsl paste
check_cross spirv-hlsl50 --hlsl --shader-model 50
check_cross spirv-hlsl60 --hlsl --shader-model 60
check_cross spirv-msl --msl
check_m4f float
check_m4f double
check_m4f_link
check_m4f_nolibm
size_table
echo
echo "portability: $nok ok, $nfail FAIL, $nskip SKIP"
[ "$nfail" -eq 0 ]
