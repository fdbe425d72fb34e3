#!/bin/sh
# tests/deps.sh - the one dependency step of make test, make bench, make portability, make fuzz.
#
# usage: sh tests/deps.sh JOB...       JOB: test, bench, portability, fuzz
#
# Checks what the named jobs need (the table below: one line per Debian/Ubuntu package, with the
# check that says it is there and the reason it is needed) and, when something is missing:
#   - as root, or with sudo that needs no password: installs it with apt-get, then checks again;
#   - otherwise, or with PF_NO_INSTALL=1: stops at once (exit 1) with the one apt-get line to run.
# Nothing is skipped silently: a job runs only when everything it needs is here.
# Environment:
#   PF_NO_INSTALL=1   never install (machines where nothing may be installed): report and stop
#   CLANG             the clang the sanitizer and fuzz builds use (default clang)
# The headers need nothing of this: they are plain C99 (see README.md).
set -u
CLANG=${CLANG:-clang}

# package | jobs that need it | check: cmd NAME, file PATH or probe NAME | why
# (apt-get resolves each package's own dependencies; only direct needs are listed)
table() {
cat <<'EOF'
gcc|test bench portability|cmd gcc|C99 test and bench builds (float, double, -ffast-math)
g++|test portability|cmd g++|C++11 test build and the GLM cross-check
clang|test fuzz portability|cmd clang|ASan+UBSan test builds (float, double) and the libFuzzer harnesses
SANITIZER_RT|test fuzz|probe sanitizer|clang's ASan/UBSan/libFuzzer runtime (compiler-rt)
libglm-dev|test|file /usr/include/glm/glm.hpp|GLM: cross-checks the vector math from C++ (tests only)
gnuplot-nox|bench|cmd gnuplot|the bench's charts and the labelled pictures
libpng-dev|test bench|file /usr/include/png.h|libpng: reads the user's PNG height and normal maps (make bench MAP=..., tests/reference/pf_maps.h) and the map loader tests (tests/maps/)
valgrind|bench|cmd valgrind|instruction counts (callgrind) in the full bench run
tcc|portability|cmd tcc|a third C compiler (tcc) for the headers
glslang-tools|portability bench|cmd glslangValidator|GLSL 4.50 -> SPIR-V compile of every evaluator (portability; the bench's GPU cost)
spirv-tools|portability bench|cmd spirv-opt|SPIR-V validation, spirv-opt and spirv-dis (the bench's GPU cost counts optimized SPIR-V)
libvulkan-dev|portability bench|file /usr/include/vulkan/vulkan.h|the Vulkan hosts: the GLSL evaluators (tests/gpu/vk_run.c) and the bench's GPU frame (bench/frame/)
mesa-vulkan-drivers|portability bench|file /usr/share/vulkan/icd.d/lvp_icd.*.json|lavapipe, the CPU Vulkan driver the GLSL evaluators (gpu-lavapipe) and the bench's GPU frame run on
spirv-cross|portability|cmd spirv-cross|SPIR-V -> HLSL and MSL
gcc-arm-none-eabi|portability|cmd arm-none-eabi-gcc|Cortex-M4F (float-only FPU) build
libnewlib-arm-none-eabi|portability|file /usr/lib/arm-none-eabi/newlib/nano.specs|its C library (newlib, nano.specs: the link check)
gcc-arm-linux-gnueabihf|portability|cmd arm-linux-gnueabihf-gcc|ARM hard-float build of the float test suite
libc6-dev-armhf-cross|portability|file /usr/arm-linux-gnueabihf/lib/libc.a|its static C library
qemu-user|portability|cmd qemu-arm|runs the ARM test binaries
gcc-multilib|portability|probe m32|32-bit x86 build (gcc/clang -m32) of the test suite: sizes and guarded buffers against PF_MAX_REALS = 2^28, ASan+UBSan included (x86-64 hosts)
libc6-dev-i386|portability|probe m32|its 32-bit C library (both only on x86-64 hosts)
cmake|portability|cmd cmake|consumer projects: CMake find_package and add_subdirectory
pkgconf|portability|cmd pkg-config|consumer project through pkg-config
EOF
}

[ $# -gt 0 ] || { echo "usage: sh tests/deps.sh test|bench|portability|fuzz ..." >&2; exit 2; }
jobs=" $* "

# clang's sanitizer runtime: the package is libclang-rt-<major>-dev on Debian 12 and Ubuntu
# 23.04+ (older Ubuntu ships it inside clang's own dependencies, so the probe passes there).
sanitizer_ok() {
    command -v "$CLANG" >/dev/null 2>&1 || return 1
    d=$(mktemp -d 2>/dev/null || echo "/tmp/pf_deps.$$") && mkdir -p "$d" || return 1
    printf '%s\n' '#include <stddef.h>' '#include <stdint.h>' \
        'int LLVMFuzzerTestOneInput(const uint8_t *p, size_t n) { (void)p; (void)n; return 0; }' > "$d/f.c"
    echo 'int main(void) { return 0; }' > "$d/m.c"
    "$CLANG" -fsanitize=address,undefined "$d/m.c" -o "$d/m" >/dev/null 2>&1 &&
        "$CLANG" -fsanitize=fuzzer,address,undefined "$d/f.c" -o "$d/f" >/dev/null 2>&1
    r=$?
    rm -rf "$d"
    return $r
}
# gcc -m32 links a C program with libm (gcc-multilib and libc6-dev-i386 are there)
m32_ok() {
    command -v gcc >/dev/null 2>&1 || return 1
    d=$(mktemp -d 2>/dev/null || echo "/tmp/pf_deps_m32.$$") && mkdir -p "$d" || return 1
    printf '%s\n' '#include <math.h>' 'int main(int c, char **v) { (void)v; return (int)sqrt((double)c) - 1; }' > "$d/m.c"
    gcc -m32 "$d/m.c" -o "$d/m" -lm >/dev/null 2>&1
    r=$?
    rm -rf "$d"
    return $r
}
sanitizer_package() {
    major=$("$CLANG" --version 2>/dev/null | sed -n 's/.*clang version \([0-9][0-9]*\).*/\1/p' | head -n 1)
    if [ -n "$major" ]; then echo "libclang-rt-$major-dev"; else echo "libclang-rt-dev"; fi
}

# missing_packages: the packages the named jobs need that are not here, with their reasons
missing=""
reasons=""
scan() {
    missing=""
    reasons=""
    table > "${TMPDIR:-/tmp}/pf_deps_table.$$"
    while IFS='|' read -r pkg need check why; do
        use=0
        for j in $need; do case $jobs in *" $j "*) use=1 ;; esac; done
        [ $use -eq 1 ] || continue
        set -- $check
        case $1 in
        cmd) command -v "$2" >/dev/null 2>&1 && continue ;;
        file) [ -e "$2" ] && continue ;;
        probe)
            if [ "$2" = m32 ]; then
                # 32-bit x86 builds: only where the host is x86-64
                case $(uname -m) in x86_64|amd64) m32_ok && continue ;; *) continue ;; esac
            # without clang the runtime cannot be probed yet: clang's own line installs it;
            # the probe runs again after the install
            elif ! command -v "$CLANG" >/dev/null 2>&1; then pkg=libclang-rt-dev
            elif sanitizer_ok; then continue
            else pkg=$(sanitizer_package); fi ;;
        esac
        missing="$missing $pkg"
        reasons="$reasons
  $pkg: $why"
    done < "${TMPDIR:-/tmp}/pf_deps_table.$$"
    rm -f "${TMPDIR:-/tmp}/pf_deps_table.$$"
}

scan
[ -z "$missing" ] && exit 0

line="apt-get install -y$missing"
echo "deps: make $(echo $jobs) needs packages that are not installed:$reasons"

how=""
if [ "${PF_NO_INSTALL:-0}" = 1 ]; then how=""
elif ! command -v apt-get >/dev/null 2>&1; then how=""
elif [ "$(id -u)" = 0 ]; then how="root"
elif command -v sudo >/dev/null 2>&1 && sudo -n true >/dev/null 2>&1; then how="sudo"
fi

if [ -z "$how" ]; then
    if [ "${PF_NO_INSTALL:-0}" = 1 ]; then why="PF_NO_INSTALL=1"
    elif ! command -v apt-get >/dev/null 2>&1; then why="no apt-get here: install the equivalents of these Debian packages"
    else why="not root and no password-less sudo"; fi
    echo "deps: not installing ($why). Run:"
    echo "  sudo apt-get update && sudo $line"
    exit 1
fi

sudo=""
[ "$how" = sudo ] && sudo="sudo -n"
echo "deps: installing as $how: $line"
export DEBIAN_FRONTEND=noninteractive
# the package lists of a fresh machine may be empty or stale: update once, then install
$sudo apt-get update -qq >/dev/null 2>&1 || $sudo apt-get update -qq
$sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends $missing >/dev/null ||
    { echo "deps: apt-get install failed; run: sudo $line" >&2; exit 1; }

# the sanitizer runtime can only be probed once clang is here
scan
if [ -n "$missing" ]; then
    $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends $missing >/dev/null 2>&1
    scan
fi
if [ -n "$missing" ]; then
    echo "deps: still missing after the install:$reasons" >&2
    exit 1
fi
echo "deps: installed:$(echo "$line" | sed 's/^apt-get install -y//')"
exit 0
