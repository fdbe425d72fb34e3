#!/bin/sh
# bench/report.sh OUT_DIR - assemble OUT_DIR/report.md, the bench report, from what the bench
# programs wrote into OUT_DIR during the same `make bench`:
#   summary.md, <module>.csv, <module>_<family>.svg   bench/run.sh (per-module families)
#   microsurface.md (+ csv, svg)                       bench/microsurface.c (ground truth)
#   storage.md (+ microsurface_storage.csv)            bench/microsurface.c's storage pass
#   pictures.md (+ png)                                bench/pictures.c
#   specaa.md (+ csv)                                  bench/specaa.c (roughness bakers, sphere)
#   frame.md (+ csv, png)                              bench/frame/ (the scenes on a Vulkan driver)
#   stability.md (+ csv)                               bench/stability.c
#   gpu_cost.md (+ csv, svg)                           bench/gpu/cost.sh (GPU instruction counts)
#   choosing.md                                        bench/choosing.sh (the method guide)
# A missing fragment is reported as missing in the report (never silently dropped).
# Images are referenced by bare file name: they sit beside report.md.
#
# bench/report.sh OUT_DIR --map "HOW": the report of `make bench MAP=...` (bench/map.sh) on the
# user's map: microsurface.md (ground truth on the map), choosing.md (--map guide), pictures.md,
# with a contents list; HOW is the command line it records.
set -e
out=${1:-bench/out}
rep="$out/report.md"
sum="$out/summary.md"

fragment() { # file title
    echo
    if [ -f "$out/$1" ]; then
        cat "$out/$1"
    else
        echo "## $2"
        echo
        echo "**Missing:** \`$1\` was not produced by this run (see the bench log)."
    fi
}

# contents: every second-level heading, linked by GitHub's anchor rule (lower case,
# punctuation dropped, spaces to hyphens), after the body's preamble and its summary section
# (a first section titled "Summary ..." stays on top, above the contents)
contents() { # body
    awk 'BEGIN { top = 1 }
         /^## / { if (seen++ || $0 !~ /^## Summary/) top = 0 }
         top' "$1"
    echo "## Contents"
    echo
    awk '/^## / { if (!seen++ && $0 ~ /^## Summary/) next
                  t = substr($0, 4); a = tolower(t); gsub(/[^a-z0-9 _-]/, "", a); gsub(/ /, "-", a)
                  printf "%d. [%s](#%s)\n", ++n, t, a }' "$1"
    echo
    awk 'BEGIN { top = 1 }
         /^## / { if (seen++ || $0 !~ /^## Summary/) top = 0 }
         !top' "$1"
}

# summary_page: the one-page summary on top of the report: per task, the most accurate shader
# method against the brute-force reference, what the exact-histogram oracle reaches, the
# cheapest method within 10%, at what cost; then per module family the most accurate and the
# cheapest method. Every number from this run's CSVs; links to the sections with the detail.
summary_page() {
    err="$out/microsurface_errors.csv"
    cost="$out/microsurface_cost.csv"
    echo "## Summary: the best method per task"
    echo
    echo "Every number below comes from this run's CSVs; the sections linked hold the detail. \`make bench\`"
    echo "measures each method against an independent reference: a brute force that shades every texel of"
    echo "a synthetic microsurface for the shading tasks, a long double evaluation of the same formula for"
    echo "the module families."
    echo
    if [ -f "$err" ] && [ -f "$cost" ]; then
        echo "**Shading tasks** ([ground truth](#ground-truth-on-synthetic-microsurfaces), [method guide](#choosing-a-method)):"
        echo "relative L2 error against the brute-force reference pooled over every surface kind, footprints of"
        echo "256-4096 texels and views up to 60 degrees, occluders inside the footprint (what a filtered"
        echo "model can represent). *Oracle*: the exact slope histogram of the footprint with Smith's"
        echo "visibility (\`oracle_histogram_smith\`, reads every texel): what the best filtered model of that"
        echo "kind could reach. Cost: ns per footprint on this CPU at the largest footprint (pyramid fetches"
        echo "included) and the ratio to LEADR specular; GPU: SPIR-V ops of the evaluators."
        echo
        echo "| task | most accurate shader method | error | oracle | its cost | cheapest within 10% | error | its cost |"
        echo "|---|---|--:|--:|--:|---|--:|--:|"
        awk -F, -v costf="$cost" -v gpuf="$out/gpu_methods.csv" '
            function fmt(e) { return (e >= 0.1) ? sprintf("%.2f", e) : (e >= 0.001 ? sprintf("%.3f", e) : sprintf("%.1e", e)) }
            function cst(m) {
                if (!(m in cns)) return "not timed"
                return sprintf("%.0f ns, %.2fx%s", cns[m], cx[m], (m in gops && gops[m] != "n/a") ? sprintf(", GPU %s ops", gops[m]) : "")
            }
            BEGIN {
                while ((getline line < gpuf) > 0) { split(line, c, ","); if (c[1] != "method") gops[c[1]] = c[2] }
                while ((getline line < costf) > 0) {
                    split(line, c, ",")
                    if (c[1] == "method") continue
                    if (!(c[1] in cfp) || c[2] + 0 >= cfp[c[1]]) { cfp[c[1]] = c[2] + 0; cns[c[1]] = c[3] + 0; cx[c[1]] = c[8] + 0 }
                }
            }
            NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i; next }
            $col["reference"] != "full" && $col["footprint_texels"] + 0 >= 256 && $col["view_deg"] + 0 <= 60 {
                t = $col["task"]; m = $col["method"]
                k = t SUBSEP m
                if (!(k in sr)) { ml[t] = ml[t] " " m; if (!(t in seen)) { seen[t] = 1; tl[++nt] = t } }
                se[k] += $col["sum_sq_err"]; sr[k] += $col["sum_sq_ref"]
            }
            END {
                for (i = 1; i <= nt; i++) {
                    t = tl[i]; n = split(ml[t], ms, " ")
                    best = ""; be = 1e30; orc = "-"; cheap = ""; cc = 1e30
                    for (j = 1; j <= n; j++) {
                        k = t SUBSEP ms[j]
                        if (sr[k] <= 0) continue
                        e = sqrt(se[k] / sr[k])
                        if (ms[j] == "oracle_histogram_smith") { orc = fmt(e); continue }
                        if (ms[j] ~ /^oracle/) continue
                        if (e < be) { be = e; best = ms[j] }
                    }
                    for (j = 1; j <= n; j++) {
                        k = t SUBSEP ms[j]
                        if (sr[k] <= 0 || ms[j] ~ /^oracle/ || !(ms[j] in cns)) continue
                        e = sqrt(se[k] / sr[k])
                        if (e <= 0.10 && cns[ms[j]] < cc) { cc = cns[ms[j]]; cheap = ms[j]; ce = e }
                    }
                    printf "| %s | `%s` | %s | %s | %s |", t, best, fmt(be), orc, cst(best)
                    if (cheap != "") printf " `%s` | %s | %s |\n", cheap, fmt(ce), cst(cheap)
                    else printf " none | - | - |\n"
                }
            }' "$err"
        echo
    else
        echo "**Missing:** \`microsurface_errors.csv\` or \`microsurface_cost.csv\` (bench/microsurface.c did not run): no task summary."
        echo
    fi
    echo "**Module families** ([speed against accuracy](#speed-against-accuracy-per-family)): float build; error ="
    echo "max relative error against a long double reference (mean absolute error of the lit fraction"
    echo "for the shadow tests), cost = ns per evaluation and the ratio to the family's baseline, timed"
    echo "side by side (the shadow lookups: to one PCF tap, not a candidate itself). *Cheapest*: the"
    echo "fastest method whose error is at most 10 times the best one's."
    echo
    echo "| family | most accurate method | error | cost | cheapest within 10x that error | error | cost |"
    echo "|---|---|--:|--:|---|--:|--:|"
    echo "$families" | while IFS='|' read -r label ids; do
        for id in $ids; do
            m=${id%%/*}; f=${id#*/}
            [ -f "$out/$m.csv" ] || { echo "| $m / $f | **missing** $m.csv | | | | | |"; continue; }
            # one PCF tap (the shadow lookups' baseline) is a cost anchor, not a filtered test
            skipbase=0
            [ "$id" = shadow/lookup ] && skipbase=1
            awk -F, -v f="$f" -v id="$id" -v skipbase=$skipbase '
                function fmt(e) { return (e >= 0.1) ? sprintf("%.2f", e) : (e >= 0.001 ? sprintf("%.3f", e) : sprintf("%.1e", e)) }
                NR > 1 && $1 == f && $3 == "float" && !(skipbase && $2 == $6) {
                    e = ($9 != "") ? $9 : $17
                    if (e == "") next
                    n++; nm[n] = $2; er[n] = e + 0; ns[n] = $4 + 0; rx[n] = $5 + 0; base = $6
                }
                END {
                    if (!n) { printf "| %s | no accuracy column | | | | | |\n", id; exit }
                    b = 1; for (i = 2; i <= n; i++) if (er[i] < er[b]) b = i
                    c = 0; for (i = 1; i <= n; i++) if (er[i] <= 10 * er[b] + 1e-300 && (!c || ns[i] < ns[c])) c = i
                    printf "| %s | `%s` | %s | %.2f ns, %.2fx | `%s` | %s | %.2f ns, %.2fx |\n", id, nm[b], fmt(er[b]), ns[b], rx[b],
                        nm[c], fmt(er[c]), ns[c], rx[c]
                }' "$out/$m.csv"
        done
    done
    echo
    stab="$out/stability.md"
    if [ -f "$stab" ]; then
        echo "**Stability** ([detail](#stability-non-finite-and-out-of-range-outputs)): $(sed -n 's/^Totals per build (non-finite in the domain \/ out of range \/ non-finite from an arbitrary finite input): //p' "$stab" | head -n 1)"
        echo
    fi
    if [ -f "$out/frame.csv" ]; then
        # frame.csv: scene, method, storage, max_anisotropy, lit, err_box ($6), ..., vs_cpu ($12), ..., nonfinite ($17), ...,
        # err_box_over_oracle ($21); frame_motion.csv: scene, method, max_anisotropy, frames, err, change, flicker ($7)
        echo "**GPU frame** ([detail](#the-frame-on-a-vulkan-driver)): the pictures' scenes through a Vulkan driver, LEADR from f32 textures, mean error per lit pixel against the brute force (box reference) at max anisotropy 1 / 16, in multiples of the per-pixel oracle's error (the exact histogram of the same texels with Smith's visibility), and the GPU against the library's CPU float path for the same pixels: $(awk -F, '
            NR > 1 && $2 == "leadr" && $3 == "f32" { e[$1, $4] = $6; o[$1, $4] = $21; if ($4 == 1) v[$1] = $12; if (!($1 in seen)) { seen[$1] = 1; sc[++n] = $1 } }
            NR > 1 { nf += $17 }
            END { for (i = 1; i <= n; i++) printf "%s%s %.1f%% / %.1f%% (%.1fx / %.1fx the oracle%ss; GPU vs CPU %.2f%%)", (i > 1 ? "; " : ""), sc[i], 100 * e[sc[i], 1], 100 * e[sc[i], 16], o[sc[i], 1], o[sc[i], 16], sprintf("%c", 39), 100 * v[sc[i]]
                  printf "; non-finite pixels over all still frames (every method, storage and sampler): %d.", nf }' "$out/frame.csv")$([ -f "$out/frame_motion.csv" ] && awk -F, '
            NR > 1 && $2 == "leadr" && $3 == 1 { f[++n] = $1 " " sprintf("%.2f", $7) }
            END { if (n) { printf " Flicker under motion (LEADR%ss change per frame over the box-filtered reference%ss own): ", sprintf("%c", 39), sprintf("%c", 39)
                  for (i = 1; i <= n; i++) printf "%s%s", (i > 1 ? ", " : ""), f[i]; printf "." } }' "$out/frame_motion.csv")$([ -f "$out/frame_curved.csv" ] && awk -F, '
            # frame_curved.csv: scene, diameter_px, alpha, form, err, err_over_oracle ($6), ..., flicker_over_ref ($8), vs_cpu ($9), ..., nonfinite ($11)
            NR > 1 && $4 == "box" { e += $6; f += $8; v += $9; nf += $11; n++ }
            NR > 1 && $4 == "box_lod" { vl += $9; nl++ }
            END { if (n) printf " Curved scenes of specular antialiasing (sphere, cylinder; LEADR + the box geometry kernel from hardware derivatives, mean over %d rows): %.2fx the oracle%ss error, flicker %.2fx the reference%ss, GPU vs CPU %.2f%% through the driver%ss lod (%.3f%% with the lod computed in the shader), non-finite pixels %d.", n, e / n, sprintf("%c", 39), f / n, sprintf("%c", 39), 100 * v / n, sprintf("%c", 39), nl ? 100 * vl / nl : 0, nf }' "$out/frame_curved.csv")"
        echo
    fi
    if [ -f "$out/gpu_cost.md" ]; then
        echo "**GPU cost** ([detail](#gpu-cost)): SPIR-V ops of every public evaluator and of the textbook formulas in \`gpu_cost.csv\`."
        echo
    fi
}

if [ "${2:-}" = --map ]; then
    cpu=$(awk -F': *' '/^model name/ { print $2; exit }' /proc/cpuinfo 2>/dev/null || true)
    [ -n "$cpu" ] || cpu=$(uname -m)
    {
        echo "# prefilter: which method for your map"
        echo
        echo "Generated by \`make bench MAP=...\` (bench/map.sh: bench/microsurface.c and bench/pictures.c"
        echo "with \`--map\`, then bench/choosing.sh and bench/report.sh with \`--map\`); do not edit by hand."
        echo "The brute-force ground truth of the main report, run on your own height or normal map: its"
        echo "slope statistics, the error of every filtered method against the brute force by footprint and"
        echo "view, the pictures, and the cheapest method for each error target on this surface. How maps are"
        echo "read (formats, borders, scale, normal-map integration): docs/maps.md."
        echo
        echo "- command: \`${3:-make bench MAP=...}\`"
        echo "- date: $(date -u '+%Y-%m-%d %H:%M:%S UTC')"
        echo "- compiler: \`${CC:-cc}\` = $(${CC:-cc} --version 2>/dev/null | head -n 1); flags \`${BENCH_FLAGS:-?}\`, float build"
        echo "- CPU: $cpu ($(getconf _NPROCESSORS_ONLN 2>/dev/null || echo "?") logical CPUs), $(uname -sr)"
        [ -n "${MAP_TIMES:-}" ] && echo "- run time: ${MAP_TIMES}"
        fragment microsurface.md "Ground truth on your map"
        fragment specaa.md "Specular antialiasing: roughness bakers on this map"
        fragment choosing.md "Choosing a method on this map"
        fragment pictures.md "Pictures"
    } > "$rep.body"
    contents "$rep.body" > "$rep"
    rm -f "$rep.body"
    echo "report: wrote $rep"
    exit 0
fi
[ -f "$sum" ] || { echo "report: $sum missing (bench/run.sh writes it)" >&2; exit 1; }

# One row per family of the report: label, then module/family ids (charts and CSV rows).
families='erfc and erf|core/erfc core/erf
Smith Lambda and G1 (Beckmann, GGX)|smith/beckmann_lambda smith/beckmann_g1 smith/ggx
LEADR specular|beckmann/specular
LEADR diffuse (Gauss grid, SH irradiance)|gaussgrid/diffuse gaussgrid/diffuse_sh
Environment lighting: Gauss-grid node sets|gaussgrid/specular_env
Toksvig|toksvig/toksvig_lobe
Height fits: visible height, height visibility|height/visible_height_mean height/visible_height_dev height/height_visibility
Colour filtering|height/colormap
Shadow-map tests|shadow/lookup shadow/vs_textbook_vsm shadow/vs_textbook_vsm_bleed shadow/vs_textbook_evsm2 shadow/vs_textbook_evsm4 shadow/vs_textbook_msm
Moment reductions and pyramids|moments/esm_reduce2x2 moments/pyramid'

{
    echo "# prefilter bench report"
    echo
    echo "Generated by \`make bench\` (bench/run.sh, then bench/report.sh); do not edit by hand."
    echo "\`make docs\` copies it to docs/report.md with its charts. The same ground truth on your own"
    echo "height or normal map: \`make bench MAP=...\` (docs/maps.md)."
    echo
    summary_page
    echo "## This run"
    echo
    awk '/^## /{ exit } /^- /' "$sum"
    [ -f "$out/stages.txt" ] &&
        echo "- time per stage (bench/run.sh, $(awk -F'\t' 'NR == 1 { print $3 }' "$out/stages.txt") threads; wall, then CPU of its processes): $(awk -F'\t' '{ printf "%s%s %s s (CPU %s s)", (NR > 1 ? "; " : ""), $1, $2, $4 }' "$out/stages.txt")"
    echo
    echo "## Speed against accuracy, per family"
    echo
    echo "Each chart puts every method of a family at its cost (ns per evaluation, median, timed"
    echo "side by side with the family's baseline in one run) and its error against a long double"
    echo "reference (max relative error; mean absolute error for fraction-valued families, where"
    echo "the relative error of a value near 0 means nothing). Float build below; the appendix has"
    echo "the double build, the quartiles of the ratios and the sorted-input timings."
    echo "\`instr/eval\` (callgrind, deterministic) is the cost to trust when the ns column is noisy."
    echo "$families" | while IFS='|' read -r label ids; do
        echo
        echo "### $label"
        for id in $ids; do
            m=${id%%/*}; f=${id#*/}
            csv="$out/$m.csv"
            [ -f "$csv" ] || { echo; echo "**Missing:** $csv"; continue; }
            base=$(awk -F, -v f="$f" 'NR > 1 && $1 == f { print $6; exit }' "$csv")
            echo
            echo "**$m / $f** (baseline \`$base\`)"
            echo
            echo "| method (float) | ns/eval | x baseline | instr/eval | max rel err | mean abs err |"
            echo "|---|--:|--:|--:|--:|--:|"
            awk -F, -v f="$f" 'NR > 1 && $1 == f && $3 == "float" {
                printf "| `%s` | %.2f | %.3f | %s | %s | %s |\n", $2, $4, $5,
                    ($7 == "" ? "-" : $7), ($9 == "" ? "-" : $9), ($17 == "" ? "-" : $17) }' "$csv"
            if [ -f "$out/${m}_$f.svg" ]; then
                echo
                echo "![$m / $f: error against cost](${m}_$f.svg)"
            fi
        done
    done
    fragment microsurface.md "Ground truth on synthetic microsurfaces"
    # the storage pass of bench/microsurface.c (bench/storage.h): its fragment has no heading
    # (docs/encode.md shows it whole)
    echo
    echo "## Storage formats"
    echo
    if [ -f "$out/storage.md" ]; then cat "$out/storage.md"; else echo "**Missing:** \`storage.md\` was not produced by this run (see the bench log)."; fi
    fragment pictures.md "Pictures"
    fragment specaa.md "Specular antialiasing: roughness bakers and the sphere (pf_specaa.h)"
    fragment frame.md "The frame on a Vulkan driver"
    fragment stability.md "Stability"
    fragment gpu_cost.md "GPU cost"
    fragment choosing.md "Choosing a method"
    echo
    echo "## Appendix: every family, float and double"
    echo
    echo "The per-module tables of bench/out/summary.md (the same tables the module pages in docs/ carry)."
    awk '/^## / { on = 1 } on { if ($0 ~ /^#/) $0 = "#" $0; print }' "$sum"
} > "$rep.body"
# Contents: every second-level heading (contents above)
contents "$rep.body" > "$rep"
rm -f "$rep.body"
echo "report: wrote $rep"
