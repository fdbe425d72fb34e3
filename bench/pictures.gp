# bench/pictures.gp - one picture of bench/pictures.c: ncols x 2 panels (reference, LEADR, vMF
# m = 8, vMF m = 8 + horizon, naive; footprint side, the methods' errors: ncols = 5), each with its title and its numbered colour bar,
# every image panel drawn 1:1 (one data value per output pixel).
# Called by pictures.c as  gnuplot DIR/pic_NAME.gpv bench/pictures.gp ; the .gpv file sets:
#   datf        2 ncols float32 planes of w x h (bottom row first), NaN = no surface: radiance of
#               the reference and the ncols - 1 methods; footprint side (texels); the methods'
#               errors (%)
#   ncols       panels per row (default 3)
#   outf        the PNG to write;  w, h  panel size in pixels
#   expo, lmax  display curve (1 - exp(-expo L))^(1/2.2) of the shaded panels; their colour bar
#               runs from L = 0 to lmax
#   bg          background colour of the shaded panels ("#rrggbb")
#   errlo, errhi  error colour scale (%, log);  fplo, fphi  footprint colour scale (texels, log)
#   ttl, note   figure title and the line under the panels;  t0 .. t(2 ncols - 1)  panel titles
set encoding utf8
if (!exists("ncols")) ncols = 3

# layout in output pixels: a column is the image plus the colour bar, its numbers and label
pad = 12; gap = 20; cbgap = 8; cbw = 14; cbspace = cbgap + cbw + 62
figt = 48; tith = 42; noteh = 62
Wp = 2 * pad + ncols * (w + cbspace) + (ncols - 1) * gap    # the panels' width
W = Wp > 960 ? Wp : 960                        # at least the note's width
xo = (W - Wp) / 2                              # panels centred
H = figt + 2 * (tith + h) + gap + noteh
# pngcairo (in Debian's gnuplot-nox): the libgd "png" terminal draws no background under the
# images' NaN pixels and places the labels differently, so it is not a fallback
if (strstrt(GPVAL_TERMINALS, "pngcairo") == 0) {
    print "pictures.gp: this gnuplot has no pngcairo terminal (Debian: gnuplot-nox has it)"
    exit status 1
}
set terminal pngcairo size W, H noenhanced font "Sans,10" background rgb "white"
set output outf

sx(x) = x / (1.0 * W)         # pixels from the left edge  -> screen coordinate
sy(y) = 1.0 - y / (1.0 * H)   # pixels from the top edge   -> screen coordinate

set multiplot
set label 1 ttl at screen 0.5, sy(18) center font ",12"
set label 2 note at screen 0.5, sy(figt + 2 * (tith + h) + gap + 16) center font ",9"

unset border
unset xtics
unset ytics
unset key
set xrange [-0.5 : w - 0.5]
set yrange [-0.5 : h - 0.5]
set cbtics out nomirror scale 0.6
set mcbtics default

# The display curve of the shaded panels, v(g) = (1 - exp(-expo lmax g))^(1/2.2) on the
# palette's 0..1 (L from 0 to lmax), as a palette of 128 linear pieces evenly spaced in v (a
# "functions" palette draws the same, four times slower: it is evaluated per pixel).
ge(v) = -log(1.0 - v ** 2.2) / (expo * lmax)
vtop = (1.0 - exp(-expo * lmax)) ** (1.0 / 2.2)
greypal = "0 0 0 0"
do for [i = 1 : 127] {
    v = vtop * i / 128.0
    greypal = greypal . sprintf(", %.6g %.6g %.6g %.6g", ge(v), v, v, v)
}
greypal = greypal . sprintf(", 1 %.6g %.6g %.6g", vtop, vtop, vtop)

do for [k = 0 : 2 * ncols - 1] {
    c = k % ncols
    r = k / ncols
    x0 = xo + pad + c * (w + cbspace + gap)
    y0 = figt + tith + r * (h + tith + gap)
    set lmargin at screen sx(x0)
    set rmargin at screen sx(x0 + w)
    set tmargin at screen sy(y0)
    set bmargin at screen sy(y0 + h)
    set colorbox user origin screen sx(x0 + w + cbgap), sy(y0 + h) size screen sx(cbw), h / (1.0 * H) front
    set title value(sprintf("t%d", k)) offset 0, -0.4
    # what shows through where the data are NaN (no surface)
    set object 1 rectangle from graph 0, 0 to graph 1, 1 behind fillstyle solid noborder \
        fillcolor rgb (k < ncols ? bg : "#606060")
    if (k < ncols) {
        eval "set palette defined (" . greypal . ")"
        unset logscale cb
        set cbrange [0 : lmax]
        set cbtics auto
        set format cb "%g"
        set cblabel "radiance L" offset 1.2, 0
    } else {
        set logscale cb
        set format cb "%g"
        if (k == ncols) {
            # viridis
            set palette defined (0 "#440154", 1 "#3b528b", 2 "#21918c", 3 "#5ec962", 4 "#fde725")
            set cbrange [fplo : fphi]
            set cbtics ()
            do for [e = int(floor(log(fplo) / log(4) + 0.5)) : int(floor(log(fphi) / log(4) + 0.5))] {
                set cbtics add (sprintf("%g", 4.0 ** e) 4.0 ** e)
            }
            set cblabel "texels" offset 0.5, 0
        } else {
            # inferno
            set palette defined (0 "#000004", 1 "#420a68", 2 "#932667", 3 "#dd513a", \
                                 4 "#fca50a", 5 "#fcffa4")
            set cbrange [errlo : errhi]
            # tic labels are formats too: %% is a per cent sign
            set cbtics (sprintf("≤%.1f%%%%", errlo) errlo, "10%%" 10, "32%%" 31.6, \
                        "100%%" 100, sprintf("≥%.0f%%%%", errhi) errhi)
            set cblabel "relative error" offset 0.5, 0
        }
    }
    plot datf binary array = (w, h) skip = k * w * h * 4 format = "%float" with image
}
unset multiplot
