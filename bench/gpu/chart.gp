# bench/gpu/chart.gp - GPU cost of the library evaluators against the textbook formulas
# (called by bench/gpu/cost.sh). Variables (gnuplot -e): datf (tab-separated: evaluator,
# library SPIR-V ops, textbook SPIR-V ops, library PTX, textbook PTX; "-" = not measured),
# outf (the .svg to write).
set terminal svg size 900,560 dynamic enhanced font 'Helvetica,12' background rgb 'white'
set output outf
set datafile separator "\t"
set datafile missing "-"
set title "GPU cost: library evaluator against its textbook formula (instructions, no GPU needed)" noenhanced
set ylabel "instructions per evaluation" noenhanced
set style data histograms
set style histogram clustered gap 1
set style fill solid 0.85 border -1
set boxwidth 0.9
set xtics rotate by -35 nomirror noenhanced font ',10'
set grid ytics lc rgb '#dddddd'
set key outside top center horizontal noenhanced
set yrange [0:*]
plot datf using 2:xtic(1) title 'library, SPIR-V ops (spirv-opt -O)' lc rgb '#1f77b4', \
     '' using 3 title 'textbook, SPIR-V ops' lc rgb '#ff7f0e', \
     '' using 4 title 'library, PTX (nvcc -O3 --use_fast_math)' lc rgb '#aec7e8', \
     '' using 5 title 'textbook, PTX' lc rgb '#ffbb78'
