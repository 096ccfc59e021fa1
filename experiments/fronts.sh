#!/usr/bin/env bash
# Speed against accuracy on one model (DMD terraces the smoothed g(r)·U that SMD integrates), for
# each terrace design (dmd/terrace_design.hpp) and SMD, and the equal-accuracy efficiency:
#   fronts.sh front-dense | front-gas
# Errors against SMD at dt = REF_DT_FS (REF_PS_FACTOR times longer, seeds of its own): RMS of g(r)
# (r ≤ 12 Å), the VACF (t ≤ 1 ps) and the OACF (t ≤ 2 ps) with their statistical floors
# (paper_tools error), and |Δ⟨U⟩/N| (kJ/mol; DMD's own, terraced energy) and |ΔP*| with the
# replica errors of both combined. Cost: CPU s per simulated ps. Every design runs the ΔV ladder
# 2 … ⅛ kT; SMD runs dt = 0.5 … 4 fs (a setting whose runs fail is listed as failed).
# paper_tools equal-accuracy then interpolates each engine's cost along its Pareto front at the
# error of SMD at 1.8 fs, and twice it: the equal-accuracy efficiency is SMD's cost over DMD's.
source "$(dirname "$0")/common.sh"
state=$1
dir=$OUT/fronts
mkdir -p "$dir"
ref=$RUNS/$state/smd-$REF_DT_FS-ref
table=$dir/fronts-$state.csv
designs=(uniform optimal virial distance)
dvs=(2 1 0.5 0.25 0.125)

# replica_stats DIR KEY : mean and error over the replicas of a summary key (per body for U).
replica_stats() {
    local d values=()
    for d in $(replica_dirs "$1"); do
        values+=("$("$TOOLS" get "$d/summary.json" "$2" n_bodies |
            awk -F, -v perBody="$3" '{ printf "%.12g", perBody ? $1 / $2 : $1 }')")
    done
    "$TOOLS" stats "${values[@]}"
}
read -r refU refUErr < <(replica_stats "$ref" potential_energy_mean 1)
read -r refP refPErr < <(replica_stats "$ref" pressure.mean_reduced 0)

echo "set,engine,design,param,cpu_s_per_ps,cpu_s_per_ps_err,err_g,floor_g,err_vacf,floor_vacf,err_oacf,floor_oacf,err_u,floor_u,err_p,floor_p,status" >"$table"
row() { # SET ENGINE DESIGN PARAM
    local s=$1 d=$RUNS/$state/$1
    if [ -f "$d/FAILED" ] || [ ! -f "$d/mean-vacf.csv" ]; then
        echo "$s,$2,$3,$4,nan,nan,nan,nan,nan,nan,nan,nan,nan,nan,nan,nan,failed: $(tr -d ',' <"$d/FAILED" 2>/dev/null | cut -c1-160)" >>"$table"
        return
    fi
    local cost eg fg ev fv eo fo u ue p pe
    # shellcheck disable=SC2046
    cost=$("$TOOLS" summary "$s" $(replica_dirs "$d") | cut -d, -f5,6)
    read -r eg fg < <("$TOOLS" error "$ref/mean-rdf.csv" "$d/mean-rdf.csv" g 12)
    read -r ev fv < <("$TOOLS" error "$ref/mean-vacf.csv" "$d/mean-vacf.csv" c 1)
    read -r eo fo < <("$TOOLS" error "$ref/mean-oacf.csv" "$d/mean-oacf.csv" c1 2)
    read -r u ue < <(replica_stats "$d" potential_energy_mean 1)
    read -r p pe < <(replica_stats "$d" pressure.mean_reduced 0)
    awk -v row="$s,$2,$3,$4,$cost,$eg,$fg,$ev,$fv,$eo,$fo" -v u="$u" -v ue="$ue" -v ru="$refU" \
        -v rue="$refUErr" -v p="$p" -v pe="$pe" -v rp="$refP" -v rpe="$refPErr" 'BEGIN {
        du = u - ru; dp = p - rp
        printf "%s,%.6g,%.6g,%.6g,%.6g,ok\n", row, du < 0 ? -du : du, sqrt(ue * ue + rue * rue),
               dp < 0 ? -dp : dp, sqrt(pe * pe + rpe * rpe) }' >>"$table"
}
for design in "${designs[@]}"; do
    for dv in "${dvs[@]}"; do
        if [ "$design" = uniform ]; then row "dmd-$dv-mayfail" dmd uniform "$dv"
        else row "dmd-$dv-$design-mayfail" dmd "$design" "$dv"; fi
    done
done
for dt in 0.5 1 1.8 3 4; do row "smd-$dt-mayfail" smd - "$dt"; done
"$TOOLS" equal-accuracy "$table" smd-1.8-mayfail >"$dir/equal-accuracy-$state.csv"

gnuplot <<GP
set terminal $(png_terminal | sed 's/900,650/1500,900/')
set output '$dir/fronts-$state.png'
set datafile separator ','
set datafile missing 'nan'
set multiplot layout 2,3 title '${state#front-} rods, one model: error against SMD dt = $REF_DT_FS fs vs cost'
set logscale xy
set grid
set xlabel 'CPU s per simulated ps'
set key bottom left font ',9'
names = "g(r) VACF OACF <U>/N P*"
do for [k = 1:5] {
    c = 5 + 2 * k
    set ylabel sprintf('error of %s', word(names, k))
    plot for [d in "uniform optimal virial distance"] '$table' skip 1 \
            using (strcol(3) eq d ? \$5 : NaN):c with linespoints pt 7 lw 2 title 'DMD '.d, \
         '' skip 1 using (strcol(2) eq "smd" ? \$5 : NaN):c with linespoints pt 5 lw 2 lc rgb 'black' title 'SMD', \
         '' skip 1 using 5:(column(c + 1)) with points pt 1 lc rgb '#888888' title 'statistical floor'
}
unset multiplot
GP
log "fronts $state done"
