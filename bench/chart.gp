# bench/chart.gp - error versus cost for one family (called by bench/run.sh).
# Variables (gnuplot -e): fam (title), datf (tab-separated: ns, max rel error (mean abs error
# for methods entered with PFB_ENTRY_ABS: fractions), method,
# build 1 = float / 2 = double, label slot), outf (the .svg to write).
set terminal svg size 900,560 dynamic enhanced font 'Helvetica,12' background rgb 'white'
set output outf
set datafile separator "\t"
set title sprintf("%s: max error versus cost", fam) noenhanced
set xlabel "cost: median ns per evaluation (log)"
set ylabel "max relative error over the accuracy grid (mean absolute for fractions, log)"
set logscale xy
set format y "10^{%L}"
set grid xtics ytics mxtics mytics lc rgb '#dddddd'
set key top right box opaque
set offsets graph 0.05, graph 0.20, graph 0.10, graph 0.10

# labels: float above right, double below right; coincident points (column 5 = how many
# earlier points of the same build sit on this one) get their labels stacked further away
plot datf using 1:($4 == 1 ? $2 : NaN) with points pt 7 ps 1.3 lc rgb '#1f77b4' title 'float build', \
     datf using 1:($4 == 2 ? $2 : NaN) with points pt 5 ps 1.1 lc rgb '#d62728' title 'double build', \
     datf using 1:($4 == 1 ? $2 * 10**(0.45 * $5) : NaN):3 with labels left offset 0.9,0.5 font ',9' tc rgb '#1f77b4' noenhanced notitle, \
     datf using 1:($4 == 2 ? $2 / 10**(0.45 * $5) : NaN):3 with labels left offset 0.9,-0.5 font ',9' tc rgb '#d62728' noenhanced notitle
