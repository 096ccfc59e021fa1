#!/usr/bin/env bash
# Fig. 2 of the paper: the adaptive root search with cubic interpolation (sec. 3) on a real pair
# of the dense-rod start at ΔV = kT/2: U along free motion, the grid points, the cubic Hermite
# interpolants between them, their extrema (where grazing is checked), the samples inside
# bracketed intervals (extremum checks and root refinement) and the root found.
source "$(dirname "$0")/common.sh"
dir=$OUT/fig2
mkdir -p "$dir"
"$TOOLS" search-trace "$dir" 0.5
read -r lower upper < <(awk -F'[:,]' '/lower_level/{l=$2} /upper_level/{u=$2} END{print l, u}' "$dir/fig2_info.json")
gnuplot <<GP
set terminal $(png_terminal)
set output '$dir/fig2.png'
set datafile separator ','
set xlabel 't (fs)'
set ylabel 'U (kJ/mol)'
set key outside bottom center horizontal
set title 'adaptive root search on a real pair (dense rods, {/Symbol D}V = kT/2)'
plot '$dir/fig2_exact.csv' skip 1 using 1:2 with lines lw 2 lc rgb '#555555' title 'U(t)', \
     '$dir/fig2_cubic.csv' skip 1 using 1:2 with lines dt 2 lw 2 lc rgb '#1f77b4' title 'cubic interpolants', \
     '$dir/fig2_grid.csv' skip 1 using 1:2 with points pt 7 ps 1.6 lc rgb '#1f77b4' title 'grid points', \
     '$dir/fig2_extrema.csv' skip 1 using 1:2 with points pt 6 ps 2 lc rgb '#2ca02c' title 'interpolant extrema', \
     '$dir/fig2_inner.csv' skip 1 using 1:2 with points pt 1 ps 1.2 lc rgb '#ff7f0e' title 'extremum check / refinement', \
     '$dir/fig2_root.csv' skip 1 using 1:2 with points pt 5 ps 2 lc rgb '#d62728' title 'root', \
     $lower with lines lt 0 lc rgb 'black' title 'levels', $upper with lines lt 0 lc rgb 'black' notitle
GP
log "fig2 done"
