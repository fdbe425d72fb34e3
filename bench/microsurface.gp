# bench/microsurface.gp - the charts of bench/microsurface.c (it calls gnuplot once per chart).
# Variables (gnuplot -e): datf (tab-separated wide table: a header row 'x<TAB>name...', then
# x and one value per column, '?' = missing), outf (.svg to write), ttl (title), xl, yl (axis
# labels), logx (1: log x axis), ncol (value columns), ymin (> 0: lower end of the y axis;
# lines below it are clipped at the frame, e.g. the ~0 errors where a method is exact).
# The y axis is always logarithmic.
set terminal svg size 900,560 dynamic enhanced font 'Helvetica,12' background rgb 'white'
set output outf
set datafile separator "\t"
set datafile missing "?"
set title ttl noenhanced
set xlabel xl noenhanced
set ylabel yl noenhanced
if (logx > 0) set logscale x
set logscale y
if (exists("ymin")) { if (ymin > 0) { set yrange [ymin:*] } }
set format y "10^{%L}"
set grid xtics ytics mxtics mytics lc rgb '#dddddd'
set key outside right top box noenhanced
plot for [c=2:ncol+1] datf using 1:c with linespoints lw 1.5 pt (c+4) ps 1.0 title columnheader(c)
