#!/bin/sh
# tests/gpu/run.sh - the GLSL path executed: every GLSL-callable public evaluator of every header
# run on a Vulkan driver and compared with the C float and double builds (docs/gpu.md).
#
# usage: sh tests/gpu/run.sh [BUILD_DIR]        (BUILD_DIR defaults to build; output in BUILD_DIR/gpu)
#
# Steps: tests/gpu/gen.awk (on tests/portability/gen.awk's parser) writes one compute shader
# per header and the C wrappers of the same functions; glslangValidator compiles the shaders to
# Vulkan SPIR-V; the C wrappers are built three times (float, double, emulated driver) into
# vk_run, which runs on lavapipe (Mesa's CPU Vulkan driver, forced through VK_ICD_FILENAMES /
# VK_DRIVER_FILES) and prints one line per function (tests/gpu/vk_run.c says what is compared
# and how the bounds come from the GLSL / Vulkan precision rules).
# Needs (Debian): glslang-tools, libvulkan-dev, mesa-vulkan-drivers, a C compiler (tests/deps.sh
# portability installs them). Missing ones are reported and the run fails (exit 1); it never
# skips. Environment: CC (default cc), PFG_ICD (the ICD json; default: lavapipe's, found under
# /usr/share/vulkan/icd.d), PFG_HEADERS (only these headers, e.g. "pf_height.h"), PFG_UPDATE_DOCS=1
# (copy the per-header tables into docs/gpu.md between its GENERATED markers), PFG_N, PFG_EDGE, PFG_SEED, PFG_ONLY (vk_run.c).
# Last line: "RESULT <passed> <failed>"; exit 0 when nothing failed.
set -u
ROOT=$(cd "$(dirname "$0")/../.." && pwd) || exit 2
cd "$ROOT" || exit 2
BUILD=${1:-build}
OUT=$BUILD/gpu
CC=${CC:-cc}
mkdir -p "$OUT/spv" || exit 2

why=""
command -v glslangValidator >/dev/null 2>&1 || why="$why glslangValidator (Debian package glslang-tools);"
command -v "$CC" >/dev/null 2>&1 || why="$why $CC (a C compiler);"
[ -e /usr/include/vulkan/vulkan.h ] || why="$why vulkan/vulkan.h (libvulkan-dev);"
icd=${PFG_ICD:-}
if [ -z "$icd" ]; then
    for f in /usr/share/vulkan/icd.d/lvp_icd.*.json /usr/share/vulkan/icd.d/lvp_icd.json; do
        [ -e "$f" ] && { icd=$f; break; }
    done
fi
[ -n "$icd" ] && [ -e "$icd" ] || why="$why lavapipe's ICD lvp_icd*.json (mesa-vulkan-drivers);"
if [ -n "$why" ]; then
    echo "gpu: missing:$why run: sh tests/deps.sh portability"
    echo "RESULT 0 1"
    exit 1
fi

GEN="awk -f tests/gpu/gen.awk -f tests/portability/gen.awk"
HEADERS=${PFG_HEADERS:-$(cd include && ls pf_*.h)}

# deps HEADER: the pf_ headers it includes (transitively, deps first), then itself
deps_rec() {
    for d_ in $(sed -n 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*"\(pf_[A-Za-z0-9_]*\.h\)".*/\1/p' "include/$1"); do
        [ "$d_" = "$1" ] || deps_rec "$d_"
    done
    echo "$1"
}

# the three C builds of the wrappers compile in the background while glslang works
$GEN -v out=c -v targets="$(echo $HEADERS)" include/pf_*.h > "$OUT/fns.c" 2> "$OUT/gen.log" || { echo "gpu: gen.awk (c) failed: $(head -1 "$OUT/gen.log")"; echo "RESULT 0 1"; exit 1; }
CFL="-std=c99 -O2 -Wall -Wextra -Werror -Iinclude -Itests/gpu"
# the emulated driver divides through reciprocals (x / y as x * (1 / y), within the 2.5 ULP
# GLSL allows division; lavapipe does it) and contracts a*b+c into FMAs where the CPU has them
EMU_FMA=""
EMU_FMA="-freciprocal-math"
grep -qw fma /proc/cpuinfo 2>/dev/null && EMU_FMA="$EMU_FMA -mfma -ffp-contract=fast"
( $CC $CFL -Wno-unused-function -DPFG_VARIANT=0 -c "$OUT/fns.c" -o "$OUT/fns_f.o" > "$OUT/build_f.log" 2>&1 &&
  $CC $CFL $EMU_FMA -Wno-unused-function -DPFG_VARIANT=2 -c "$OUT/fns.c" -o "$OUT/fns_e.o" > "$OUT/build_e.log" 2>&1 ) &
cpid=$!

bad=""
for h in $HEADERS; do
    m=$(basename "$h" .h)
    chain=$(deps_rec "$h" | awk '!seen[$0]++' | tr '\n' ' ')
    $GEN -v out=glsl -v targets="$h" -v includes="$chain" include/pf_*.h > "$OUT/spv/$m.comp" 2> "$OUT/spv/$m.log" ||
        { bad="$bad $h(gen)"; continue; }
    glslangValidator -S comp -V --target-env vulkan1.0 -Iinclude -o "$OUT/spv/$m.spv" "$OUT/spv/$m.comp" \
        >> "$OUT/spv/$m.log" 2>&1 || { bad="$bad $h"; sed -n '1,5p' "$OUT/spv/$m.log"; }
done
$CC $CFL -Wno-unused-function -DPFG_VARIANT=1 -DPF_DOUBLE -c "$OUT/fns.c" -o "$OUT/fns_d.o" > "$OUT/build.log" 2>&1 &&
$CC $CFL -c tests/gpu/vk_run.c -o "$OUT/vk_run.o" >> "$OUT/build.log" 2>&1
brc=$?
wait $cpid || brc=1
cat "$OUT/build_f.log" "$OUT/build_e.log" >> "$OUT/build.log" 2>/dev/null
if [ -n "$bad" ]; then echo "gpu: shaders failed:$bad (logs in $OUT/spv)"; echo "RESULT 0 1"; exit 1; fi
[ $brc -eq 0 ] &&
$CC "$OUT/vk_run.o" "$OUT/fns_f.o" "$OUT/fns_d.o" "$OUT/fns_e.o" -o "$OUT/vk_run" -lvulkan -lm >> "$OUT/build.log" 2>&1 ||
    { sed -n '1,8p' "$OUT/build.log"; echo "gpu: build failed (log: $OUT/build.log; libvulkan-dev?)"; echo "RESULT 0 1"; exit 1; }

VK_ICD_FILENAMES=$icd VK_DRIVER_FILES=$icd LP_NUM_THREADS=${LP_NUM_THREADS:-2} \
    "$OUT/vk_run" tests/gpu/domains.txt "$OUT/spv" "$OUT/results.md" > "$OUT/run.txt" 2>&1
rc=$?
cat "$OUT/run.txt"
# the per-header tables of docs/gpu.md, from results.md; PFG_UPDATE_DOCS=1 splices them into
# docs/gpu.md between its GENERATED markers (only after a run where everything passed)
if [ -s "$OUT/results.md" ]; then
    { awk -F'|' '
        /^\| `/ {
            for (i = 2; i <= 10; i++) { f[i] = $i; gsub(/^ +| +$/, "", f[i]) }
            if (f[3] != h) {
                if (h != "") print ""
                h = f[3]
                print "#### `" h "`\n"
                print "| function | GPU | C float | driver allowance | GPU / bound | edge (finite / NaN-inf) |"
                print "| --- | --- | --- | --- | --- | --- |"
            }
            printf "| %s | %s%s | %s | %s | %s | %s |\n", f[2], f[4], (f[8] != "" ? " (target " f[8] ")" : ""), f[5], f[6], f[7], f[9]
        }' "$OUT/results.md"
      echo
      echo "Generated by \`tests/gpu/run.sh\` on $(date -u +%Y-%m-%d): $(sed -n 's/^device: //p' "$OUT/run.txt"), $(sed -n 's/^samples: //p' "$OUT/run.txt")."
    } > "$OUT/tables.md"
    if [ "${PFG_UPDATE_DOCS:-0}" = 1 ] && [ $rc -eq 0 ] && grep -q '^<!-- BEGIN GENERATED: gpu' docs/gpu.md 2>/dev/null; then
        awk -v table="$OUT/tables.md" '
            /^<!-- BEGIN GENERATED: gpu/ { print; while ((getline l < table) > 0) print l; skip = 1; next }
            /^<!-- END GENERATED: gpu/ { skip = 0 }
            !skip' docs/gpu.md > "$OUT/gpu.md.new" && cp "$OUT/gpu.md.new" docs/gpu.md &&
            echo "(docs/gpu.md tables updated)"
    fi
fi
[ $rc -eq 0 ] || [ $rc -eq 1 ] || { echo "gpu: vk_run stopped (exit $rc)"; echo "RESULT 0 1"; exit 1; }
exit $rc
