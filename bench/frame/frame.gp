# bench/frame/frame.gp - the GPU frame next to the CPU brute-force reference (bench/frame/frame.c
# writes the data and the variables; bench/frame/run.sh calls  gnuplot frame_S.gpv frame.gp).
#   datf   2 float32 planes of w x h, bottom row first, NaN = no surface: reference, GPU LEADR
#   outf, w, h, expo (display curve 1 - exp(-expo L), gamma 2.2, as bench/pictures.gp), t0, t1
set encoding utf8
set terminal pngcairo size (2 * w + 120), (h + 70) noenhanced font "Sans,9" background rgb "white"
set output outf
set multiplot layout 1, 2 margins 0.02, 0.98, 0.04, 0.86 spacing 0.04, 0
unset border; unset xtics; unset ytics; unset key; unset colorbox
set xrange [-0.5 : w - 0.5]
set yrange [-0.5 : h - 0.5]
set size ratio -1
set cbrange [0 : 1]
set palette grey
disp(L) = (L != L) ? 0.25 : (1.0 - exp(-expo * L)) ** (1.0 / 2.2)
set title t0
plot datf binary array = (w, h) format = "%float" using (disp($1)) with image
set title t1
plot datf binary array = (w, h) skip = w * h * 4 format = "%float" using (disp($1)) with image
unset multiplot
