#!/bin/sh
# bench/map.sh BENCH_BUILD_DIR - the ground truth on the user's own map: what
# `make bench MAP=path [MAP_KIND=...] [MAP_SCALE=... | MAP_RMS_SLOPE=...] [MAP_BORDER=...]
# [MAP_RAW_SIZE=WxH]` runs (docs/maps.md). Writes MAP_OUT (default bench/out/map):
#   report.md                  the map's report: slope statistics, errors by footprint and view,
#                              the pictures, the method guide for that map (bench/report.sh --map)
#   microsurface.md, *.csv, *.svg   bench/microsurface.c --map (ground truth, cost, charts)
#   pictures.md, pic_*.png     bench/pictures.c --map (the plane and the sphere tiled with the map)
#   specaa.md, specaa_bakers.csv   bench/specaa.c --map (every roughness baker on the map's mips)
#   choosing.md                bench/choosing.sh --map (cheapest method per error target)
# The map is read and checked first (microsurface --check): a missing, corrupt, flat or
# mis-sized map stops here with one message and exit status 1, and nothing is written or removed.
# Environment: MAP, MAP_KIND (height | normal-gl | normal-dx), MAP_SCALE, MAP_RMS_SLOPE,
# MAP_BORDER (periodic | clamped), MAP_RAW_SIZE (raw float32: WxH), MAP_OUT, CC and BENCH_FLAGS
# (recorded), BENCH_QUICK=1 (smaller pictures and fewer samples: a smoke run).
set -e
dir=${1:-build/bench}
out=${MAP_OUT:-bench/out/map}
[ -n "${MAP:-}" ] || { echo "map: no map given (make bench MAP=path/to/map.png)" >&2; exit 2; }
command -v gnuplot >/dev/null 2>&1 ||
    { echo "map: gnuplot not found; run make bench (it installs it) or: sudo apt-get install -y gnuplot-nox" >&2; exit 1; }
for prog in microsurface pictures specaa; do
    [ -x "$dir/$prog" ] || { echo "map: missing $dir/$prog (run through make bench MAP=...)" >&2; exit 1; }
done
set -- --map "$MAP" --map-kind "${MAP_KIND:-height}" --map-scale "${MAP_SCALE:-}" \
       --map-rms-slope "${MAP_RMS_SLOPE:-}" --map-border "${MAP_BORDER:-periodic}" --map-raw-size "${MAP_RAW_SIZE:-}"
how="make bench MAP=$MAP"
for v in MAP_KIND MAP_SCALE MAP_RMS_SLOPE MAP_BORDER MAP_RAW_SIZE; do
    eval "val=\${$v:-}"
    [ -n "$val" ] && how="$how $v=$val"
done
[ -n "${BENCH_QUICK:-}" ] && [ "${BENCH_QUICK:-}" != 0 ] && how="$how BENCH_QUICK=$BENCH_QUICK"

t_start=$(date +%s)
# read and check the map before touching the output directory
"$dir/microsurface" --check "$@"
mkdir -p "$out"
rm -f "$out"/*.md "$out"/*.csv "$out"/*.svg "$out"/*.png "$out"/*.dat "$out"/*.bin "$out"/*.gpv

# Each program spreads its brute force over PFB_THREADS threads (default every core) and
# prints its progress with the time left on stderr; its cost timings run alone.
echo "map: [$(date +%H:%M:%S)] ground truth (bench/microsurface.c --map) ..." >&2
t0=$(date +%s)
"$dir/microsurface" --out "$out" --gp bench/microsurface.gp "$@"
t_ms=$(($(date +%s) - t0))
echo "map: [$(date +%H:%M:%S)] ground truth done in $t_ms s" >&2
echo "map: [$(date +%H:%M:%S)] pictures (bench/pictures.c --map) ..." >&2
t0=$(date +%s)
"$dir/pictures" "$out" --gp bench/pictures.gp "$@"
t_pic=$(($(date +%s) - t0))
echo "map: [$(date +%H:%M:%S)] pictures done in $t_pic s" >&2
echo "map: [$(date +%H:%M:%S)] roughness bakers (bench/specaa.c --map) ..." >&2
"$dir/specaa" --out "$out" "$@"
sh bench/choosing.sh "$out" --map
MAP_TIMES="ground truth ${t_ms} s, pictures ${t_pic} s, $(($(date +%s) - t_start)) s in all, ${PFB_THREADS:-$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo 1)} threads" \
    sh bench/report.sh "$out" --map "$how"
echo "map: the report is $out/report.md ($(($(date +%s) - t_start)) s in all)"
