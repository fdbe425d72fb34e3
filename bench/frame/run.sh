#!/bin/sh
# bench/frame/run.sh - the GPU-frame step of `make bench` (bench/frame/frame.c says what it
# measures): compiles bench/frame/frame.vert and frame.frag (one fragment shader per scene and
# method; PFB_THREADS compiles at once) to SPIR-V, counts each fragment shader's ops after spirv-opt -O (as bench/gpu/count.sh
# counts), runs the host and draws the GPU frame next to the reference (bench/frame/frame.gp).
#
# usage: sh bench/frame/run.sh BENCH_BIN_DIR OUT_DIR     (the binary is BENCH_BIN_DIR/frame)
# Device: lavapipe (Mesa's CPU Vulkan driver, through VK_ICD_FILENAMES) unless PF_VK_DEVICE is
# set (an index or a name substring, tests/gpu/vk_common.h), which leaves the loader alone so a
# real GPU can be picked. BENCH_QUICK=1: small frames. Writes OUT_DIR/frame.md, frame.csv,
# frame_plane.png, frame_sphere.png, frame_curved.csv, gpuspecaa.md. Needs glslang-tools, spirv-tools, libvulkan-dev,
# mesa-vulkan-drivers, gnuplot (tests/deps.sh bench); a missing one stops the step (exit 1).
set -u
bin=${1:-build/bench}/frame
out=${2:-bench/out}
spv=$(dirname "$bin")/frame_spv
mkdir -p "$spv" "$out" || exit 1
for t in glslangValidator spirv-opt spirv-dis gnuplot; do
    command -v $t >/dev/null 2>&1 || { echo "frame: $t not found (sh tests/deps.sh bench)" >&2; exit 1; }
done
[ -x "$bin" ] || { echo "frame: no $bin (make frame builds it)" >&2; exit 1; }
if [ -z "${PF_VK_DEVICE:-}" ]; then
    icd=""
    for f in /usr/share/vulkan/icd.d/lvp_icd.*.json /usr/share/vulkan/icd.d/lvp_icd.json; do
        [ -e "$f" ] && { icd=$f; break; }
    done
    [ -n "$icd" ] || { echo "frame: lavapipe's ICD not found (mesa-vulkan-drivers; or set PF_VK_DEVICE)" >&2; exit 1; }
    VK_ICD_FILENAMES=$icd VK_DRIVER_FILES=$icd
    export VK_ICD_FILENAMES VK_DRIVER_FILES
fi

glslangValidator -V --target-env vulkan1.0 -S vert -o "$spv/frame.vert.spv" bench/frame/frame.vert > "$spv/vert.log" 2>&1 ||
    { cat "$spv/vert.log"; exit 1; }
# The fragment shaders, PFB_THREADS at a time (default: the online cores; they are independent):
# frag KEY OUT SRC FLAGS... compiles SRC with FLAGS into OUT and writes "KEY ops branches" (ops of
# main after spirv-opt -O: the bench's one rule, bench/gpu/spirv_ops.awk) into OUT.ops; ops.txt
# is those lines in the order below, whatever order the compiles finish in.
jobs_max=${PFB_THREADS:-$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo 1)}
[ "$jobs_max" -ge 1 ] 2>/dev/null || jobs_max=1
running=0
outs=""
frag() {
    key=$1 f=$2 src=$3
    shift 3
    rm -f "$f.ops"
    { glslangValidator -V --target-env vulkan1.0 -S frag "$@" -o "$f" "$src" > "$f.log" 2>&1 &&
        spirv-opt -O "$f" -o "$f.opt" 2>> "$f.log" &&
        echo "$key $(spirv-dis "$f.opt" | awk -f bench/gpu/spirv_ops.awk)" > "$f.ops"; } || cat "$f.log"
}
queue() { # KEY OUT SRC FLAGS...: frag in the background, at most jobs_max at once
    outs="$outs $2"
    frag "$@" &
    running=$((running + 1))
    [ $running -lt "$jobs_max" ] || { wait; running=0; }
}
for s in 0 1; do
    sn=$(echo "plane sphere" | cut -d' ' -f$((s + 1)))
    for m in 0 1 2 3 4 5 6 7 8; do
        mn=$(echo "none leadr naive toksvig leadr_taps vmf4 vmf8 leadr_horizon vmf4_horizon" | cut -d' ' -f$((m + 1)))
        queue "$sn $mn" "$spv/frame_${sn}_$mn.spv" bench/frame/frame.frag -DPFF_SCENE=$s -DPFF_METHOD=$m -Iinclude
    done
    # LEADR from UNORM-encoded moments (pf_encode.h): the decode's ops are its count minus leadr's
    queue "$sn leadr_unorm" "$spv/frame_${sn}_leadr_unorm.spv" bench/frame/frame.frag -DPFF_SCENE=$s -DPFF_METHOD=1 -DPFF_ENCODED=1 -Iinclude
done
# the curved scenes of bench/specaa_scenes.h (bench/frame/curved.frag, one shader per form of
# bench/frame/curved_shade.h at the lod computed in the shader; quad and cross_taps: anisotropic
# reads in the shader by the EXT rule, PFC_TAPS; quad_drv16: quad's reads through the driver's 16x
# sampler, PFC_ANISO; box: the box kernel's form at the driver's lod, PFC_DRIVER_LOD, and box_lod
# the same at the shader's, the keys bench/report.sh reads)
for m in 0 1 2 3 4 5 6 7 8 9 10 11 12 13 14; do
    mn=$(echo "none box_lod box_iso tk filament hdrp godot vmf_box curved surf cross quad cross_taps quad_drv16 box" | cut -d' ' -f$((m + 1)))
    d="-DPFC_METHOD=$m"
    [ $m = 11 ] && d="-DPFC_METHOD=11 -DPFC_TAPS=1"
    [ $m = 12 ] && d="-DPFC_METHOD=10 -DPFC_TAPS=1"
    [ $m = 13 ] && d="-DPFC_METHOD=11 -DPFC_ANISO=1"
    [ $m = 14 ] && d="-DPFC_METHOD=1 -DPFC_DRIVER_LOD=1"
    # shellcheck disable=SC2086 # $d: several flags
    queue "curved $mn" "$spv/curved_$mn.spv" bench/frame/curved.frag $d -Iinclude -Ibench/frame
done
wait
: > "$spv/ops.txt"
for f in $outs; do
    [ -s "$f.ops" ] || { echo "frame: compiling $f failed" >&2; exit 1; }
    cat "$f.ops" >> "$spv/ops.txt"
done
LP_NUM_THREADS=${LP_NUM_THREADS:-2} "$bin" "$spv" "$out" "$spv/ops.txt" || { echo "frame: $bin failed" >&2; exit 1; }
for s in plane sphere; do
    gnuplot "$out/frame_$s.gpv" bench/frame/frame.gp || { echo "frame: gnuplot failed on $out/frame_$s.png" >&2; exit 1; }
    rm -f "$out/frame_$s.bin" "$out/frame_$s.gpv"
done
