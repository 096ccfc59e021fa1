#!/usr/bin/env bash
# Terrace designs (dmd/terrace_design.hpp) on the paper's dense rods, smoothed model: U along the
# designs' reference alignment (s_i·s_j = 1/√2, where the rods' effective distance r_e = r) and
# its terraced value V, one panel a design, all with n = 4 levels in the well — the 1-D cut of
# the paper's Fig. 1 for each way of placing levels and valuing terraces. The level tables go
# beside the figure (designs/<design>.csv, from `terrace design`).
source "$(dirname "$0")/common.sh"
dir=$OUT/designs
mkdir -p "$dir"
designs=(energy-midpoint energy-virial distance-boltzmann volume-boltzmann distance-midpoint
         optimal-boltzmann)
for d in "${designs[@]}"; do
    spec="{\"levels\":\"${d%-*}\",\"values\":\"${d#*-}\",\"n\":4}"
    common=("$SCENES/dense-rods.json" --set dmd.model=smoothed --set "dmd.terraces=$spec")
    "$TERRACE" design "${common[@]}" >"$dir/$d.csv.tmp"
    "$TERRACE" design "${common[@]}" --profile >"$dir/$d-profile.csv.tmp"
    mv "$dir/$d.csv.tmp" "$dir/$d.csv"
    mv "$dir/$d-profile.csv.tmp" "$dir/$d-profile.csv"
done
plots=""
for d in "${designs[@]}"; do
    plots+="set title '${d/-/ levels, } values'
plot '$dir/$d-profile.csv' skip 1 using 1:2 with lines lw 2 lc rgb '#888888' title 'U', \
     '' skip 1 using 1:3 with steps lw 2 lc rgb '#c03020' title 'V'
"
done
gnuplot <<GP
set terminal $(png_terminal | sed 's/900,650/1200,800/')
set output '$dir/designs.png'
set datafile separator ','
set multiplot layout 2,3 title 'terrace designs, dense rods (smoothed, n = 4 levels in the well)'
set xlabel 'r_e (Å)'
set ylabel 'energy (kJ/mol)'
set xrange [3:9.5]
set yrange [-3.5:6]
set key bottom right
$plots
unset multiplot
GP
log "designs done"
