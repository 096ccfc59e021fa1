#!/usr/bin/env bash
# Fig. 1 of the paper: the continuous rod potential U(r, c) and its terraced form V(r, c) with
# ε = 5/2, σ = 1, ζ = 1, ΔV = 1, V_min = −2, U_k = V_min + (k − ½)ΔV (paper eq. 7). The data come
# from the project's own potential and levels (paper_tools potential-map).
source "$(dirname "$0")/common.sh"
dir=$OUT/fig1
mkdir -p "$dir"
"$TOOLS" potential-map "$dir/fig1.csv"
gnuplot <<GP
set terminal $(png_terminal | sed 's/900,650/900,1100/')
set output '$dir/fig1.png'
set datafile separator ','
set multiplot layout 2,1
set xlabel 'r'
set ylabel 'c'
set zrange [-3:2]
set cbrange [-3:2]
set view 60, 35
set pm3d
set palette rgbformulae 33,13,10
unset colorbox
set key off
set ztics 1
clip(x) = x > 2 ? 2 : x
set title 'continuous U(r, c)'
splot '$dir/fig1.csv' skip 1 using 1:2:(clip(\$3)) with pm3d
set title 'terraced V(r, c), {/Symbol D}V = 1, V_{min} = -2'
splot '$dir/fig1.csv' skip 1 using 1:2:(clip(\$4)) with pm3d
unset multiplot
GP
log "fig1 done"
