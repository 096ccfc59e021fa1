#!/usr/bin/env bash
# Where DMD pays at equal accuracy: the rods, or the LJ spheres, on one model (DMD terraces the
# smoothed g(r)·U that SMD integrates) over a grid of densities and temperatures.
#   map.sh map | maplj "DENSITIES" "TEMPERATURES"     (rods | LJ spheres)
# At each state point fronts.sh (state map[lj]-rho<ρ*>-T<T*>) has the errors and costs of SMD over its
# dt ladder and of DMD over the ΔV ladder with uniform levels (the paper's) and virial values,
# against SMD at a dt converged at that temperature, and paper_tools equal-accuracy's efficiency
# (SMD's cost over DMD's along their Pareto fronts) at the error of SMD at 1.8 fs (or its largest
# stable dt) and twice it. Writes OUT/map (NAME: map for the rods, map-lj for the spheres):
#   NAME.csv       every state, design, quantity and target: efficiency, costs, resolved, bound
#   NAME-best.csv  per state and quantity, at twice SMD's error (the stated target): the best
#                  design's efficiency (nan: no design reaches the target)
#   NAME-runs.csv  runs and CPU hours the map took (every run of its states, skin trials too)
#   NAME.png       the heat map of the best design's efficiency in g(r), the VACF and (rods) the
#                  OACF, with the break-even contour
source "$(dirname "$0")/common.sh"
prefix=$1
read -r -a densities <<<"$2"
read -r -a temperatures <<<"$3"
case $prefix in
map) name=map system=Rods quantities=(g vacf oacf) titles="g(r) VACF OACF" ;;
maplj) name=map-lj system="LJ spheres" quantities=(g vacf) titles="g(r) VACF" ;;
*) echo "usage: map.sh map | maplj DENSITIES TEMPERATURES" >&2; exit 2 ;;
esac
dir=$OUT/map
mkdir -p "$dir"

echo "rho,T,design,quantity,target,target_error,resolved,smd_cost,design_cost,efficiency,bound" >"$dir/$name.csv"
for T in "${temperatures[@]}"; do
    for rho in "${densities[@]}"; do
        f=$dir/fronts/equal-accuracy-$prefix-rho$rho-T$T.csv
        [ -s "$f" ] || { log "map: no equal-accuracy table for rho $rho, T $T"; continue; }
        # The first nine columns (design … bound): SMD runs one scheme here, smd_via says nothing.
        tail -n +2 "$f" | cut -d, -f1-9 | awk -v r="$rho" -v t="$T" '{ print r "," t "," $0 }' \
            >>"$dir/$name.csv"
    done
done

# The best design per state and quantity at twice SMD's error.
awk -F, 'NR > 1 && $5 ~ /^2x/ {
        key = $1 "," $2 "," $4
        if (!(key in best)) { best[key] = "nan"; design[key] = "none"; bound[key] = 0
                              resolved[key] = $7; order[++n] = key }
        if ($10 != "nan" && (best[key] == "nan" || $10 + 0 > best[key] + 0)) {
            best[key] = $10; design[key] = $3; bound[key] = $11 }
    }
    END { print "rho,T,quantity,best_design,efficiency,bound,resolved"
          for (k = 1; k <= n; ++k) { key = order[k]
              print key "," design[key] "," best[key] "," bound[key] "," resolved[key] } }' \
    "$dir/$name.csv" >"$dir/$name-best.csv"

# What the map cost: every run of its states (replicas, references, skin trials).
find "$RUNS" -path "$RUNS/$prefix-rho*" -name summary.json -print0 |
    xargs -0 -r cat | awk '/"cpu_seconds":/ { sub(/.*"cpu_seconds": */, ""); sub(/,.*/, ""); s += $0; ++n }
        END { printf "runs,cpu_seconds,cpu_hours\n%d,%.1f,%.3f\n", n, s, s / 3600 }' >"$dir/$name-runs.csv"

# The grid for gnuplot: one block per temperature, log10 of the efficiency; a target no design
# reaches counts as -2 (DMD 100 times dearer), so that the contour closes around it. The last
# column says what the cell holds: 0 a value, 1 a bound (a target within its statistical floor),
# 2 no value (no design reaches the target); the figure paints only values with the colour scale,
# hatches bounds over their colour and greys the cells without a value.
grid() { # QUANTITY
    local t r i j=0
    for t in "${temperatures[@]}"; do
        i=0
        for r in "${densities[@]}"; do
            awk -F, -v r="$r" -v t="$t" -v q="$1" -v i="$i" -v j="$j" \
                '$1 == r && $2 == t && $3 == q {
                    e = $5 == "nan" ? -2 : log($5) / log(10)
                    printf "%d %d %.6g %s %d\n", i, j, e, $5 == "nan" ? "-" : sprintf("%.2g%s", $5, $6 ? "*" : ""),
                        $5 == "nan" ? 2 : ($6 ? 1 : 0) }' \
                "$dir/$name-best.csv"
            i=$((i + 1))
        done
        echo
        j=$((j + 1))
    done
}
xtics=$(i=0; for r in "${densities[@]}"; do printf '"%s" %d,' "$r" $i; i=$((i + 1)); done)
ytics=$(j=0; for t in "${temperatures[@]}"; do printf '"%s" %d,' "$t" $j; j=$((j + 1)); done)
for q in "${quantities[@]}"; do
    grid "$q" >"$dir/$name-grid-$q.dat"
    # The break-even contour (efficiency 1) of the grid, as line segments.
    gnuplot <<GP 2>/dev/null || true
set table '$dir/$name-contour-$q.dat'
set contour base
set cntrparam levels discrete 0
set cntrparam linear
unset surface
splot '$dir/$name-grid-$q.dat' using 1:2:3 with lines
unset table
GP
done

gnuplot <<GP
set terminal $(png_terminal | sed "s/900,650/$((520 * ${#quantities[@]})),580/")
set output '$dir/$name.png'
set multiplot layout 1,${#quantities[@]} title "$system, one model: SMD cost / DMD cost at twice the error of SMD at 1.8 fs\\n(best of uniform and virial levels; hatched *: a bound, grey -: not reached; black line: break-even)"
set xtics (${xtics%,})
set ytics (${ytics%,})
set xlabel 'density {/Symbol r}*'
set ylabel 'temperature T*'
set xrange [-0.5:${#densities[@]} - 0.5]
set yrange [-0.5:${#temperatures[@]} - 0.5]
set cbrange [-1.5:1.5]
set cblabel 'log_{10} efficiency'
set palette defined (-1.5 '#b2182b', 0 '#f7f7f7', 1.5 '#2166ac')
unset key
names = "$titles"
files = "${quantities[*]}"
do for [k = 1:${#quantities[@]}] {
    set title word(names, k)
    plot '$dir/$name-grid-'.word(files, k).'.dat' \
             using (\$5 < 2 ? \$1 : NaN):2:(0.5):(0.5):3 with boxxyerror fs solid 1.0 lc palette, \
         '' using (\$5 == 1 ? \$1 : NaN):2:(0.5):(0.5) with boxxyerror fs transparent pattern 4 lc rgb 'black', \
         '' using (\$5 == 2 ? \$1 : NaN):2:(0.5):(0.5) with boxxyerror fs solid 1.0 lc rgb '#bdbdbd', \
         '' using 1:2:4 with labels font ',10', \
         '$dir/$name-contour-'.word(files, k).'.dat' using 1:2 with lines lw 3 lc rgb 'black'
}
unset multiplot
GP
log "map $name done"
