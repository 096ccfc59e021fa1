#!/usr/bin/env bash
# Speed against accuracy on one model (DMD terraces the smoothed g(r)·U that SMD integrates), for
# each terrace design (dmd/terrace_design.hpp) and SMD, and the equal-accuracy efficiency:
#   fronts.sh front-dense | front-gas      every design, into OUT/fronts, with a figure
#   fronts.sh map[lj]-rho<ρ*>-T<T*>        uniform and virial levels over MAP_DVS, SMD over
#                                          MAP_DTS (Makefile.paper), into OUT/map/fronts
# Errors against the state's SMD reference set (smd-<dt>-ref: REF_DT_FS, or for the map a dt
# converged at the state's temperature; REF_PS_FACTOR times longer, seeds of its own): RMS of g(r)
# (r ≤ 12 Å), the VACF (t ≤ 1 ps) and the OACF (t ≤ 2 ps) with their statistical floors
# (paper_tools error), and |Δ⟨U⟩/N| (kJ/mol; DMD's own, terraced energy) and |ΔP*| with the
# replica errors of both combined. Cost: CPU s per simulated ps. Every design runs the ΔV ladder
# 2 … ⅛ kT; SMD runs dt = 0.5 … 4 fs (a setting whose runs fail is listed as failed); quick runs
# shorter ladders (Makefile.paper's FRONT_DVS, FRONT_DTS, FRONT_SCHEME_DTS).
# An SMD setting whose energy is not conserved (replicas' mean |drift| above
# MAX_DRIFT_NKT_PER_PS · N kT per ps) is marked unstable and takes no part in SMD's front: the
# equal-accuracy comparison is with SMD at a stable dt.
# paper_tools equal-accuracy then interpolates each engine's cost along its Pareto front at the
# error of SMD at 1.8 fs, or of the largest stable dt where 1.8 fs is not, and twice it: the
# equal-accuracy efficiency is SMD's cost over DMD's.
source "$(dirname "$0")/common.sh"
state=$1
case $state in
map-* | maplj-*)
    dir=$OUT/map/fronts figure=0
    designs=(uniform virial) schemes=() scheme_dts=()
    read -r -a dvs <<<"${MAP_DVS:?Makefile.paper sets MAP_DVS}"
    read -r -a dts <<<"${MAP_DTS:?Makefile.paper sets MAP_DTS}"
    ;;
*)
    dir=$OUT/fronts figure=1
    designs=(uniform optimal virial distance)
    read -r -a dvs <<<"${FRONT_DVS:-2 1 0.5 0.25 0.125}"
    read -r -a dts <<<"${FRONT_DTS:-0.5 1 1.8 3 4}"
    # SMD's other splittings (smd/splitting.hpp), each over the steps where it is competitive.
    schemes=(omelyan yoshida4)
    read -r -a scheme_dts <<<"${FRONT_SCHEME_DTS:-1 1.8 3 4.5}"
    ;;
esac
mkdir -p "$dir"
refs=("$RUNS/$state"/smd-*-ref)
[ ${#refs[@]} -eq 1 ] && [ -d "${refs[0]}" ] || { echo "fronts.sh: $state needs one reference set smd-<dt>-ref" >&2; exit 1; }
ref=${refs[0]}
ref_dt=${ref##*/smd-}
ref_dt=${ref_dt%-ref}
table=$dir/fronts-$state.csv

# replica_stats DIR KEY PER_BODY : mean and error over the replicas of a summary key (per body
# where PER_BODY is 1).
replica_stats() {
    local scale=total
    [ "$3" = 1 ] && scale=per-body
    # shellcheck disable=SC2046
    "$TOOLS" replica-stats "$2" "$scale" $(replica_dirs "$1")
}

# 0.1 % of the thermal energy per ps: 10 % over a 100 ps run.
MAX_DRIFT_NKT_PER_PS=1e-3

# drift_per_nkt DIR : the replicas' mean |energy drift| in units of N kT per ps.
drift_per_nkt() {
    # shellcheck disable=SC2046
    "$TOOLS" replica-stats energy.drift_per_ps abs-per-nkt $(replica_dirs "$1") | cut -d' ' -f1
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
    eo=nan fo=nan # spheres have no OACF
    if [ -s "$ref/mean-oacf.csv" ]; then
        read -r eo fo < <("$TOOLS" error "$ref/mean-oacf.csv" "$d/mean-oacf.csv" c1 2)
    fi
    read -r u ue < <(replica_stats "$d" potential_energy_mean 1)
    read -r p pe < <(replica_stats "$d" pressure.mean_reduced 0)
    local status=ok drift
    if [ "$2" = smd ]; then
        drift=$(drift_per_nkt "$d")
        if awk -v x="$drift" -v m="$MAX_DRIFT_NKT_PER_PS" 'BEGIN { exit !(x > m) }'; then
            status="unstable: energy drifts by $(printf '%.2g' "$drift") N kT per ps"
        fi
    fi
    awk -v row="$s,$2,$3,$4,$cost,$eg,$fg,$ev,$fv,$eo,$fo" -v u="$u" -v ue="$ue" -v ru="$refU" \
        -v rue="$refUErr" -v p="$p" -v pe="$pe" -v rp="$refP" -v rpe="$refPErr" -v status="$status" 'BEGIN {
        du = u - ru; dp = p - rp
        printf "%s,%.6g,%.6g,%.6g,%.6g,%s\n", row, du < 0 ? -du : du, sqrt(ue * ue + rue * rue),
               dp < 0 ? -dp : dp, sqrt(pe * pe + rpe * rpe), status }' >>"$table"
}
for design in "${designs[@]}"; do
    for dv in "${dvs[@]}"; do
        if [ "$design" = uniform ]; then row "dmd-$dv-mayfail" dmd uniform "$dv"
        else row "dmd-$dv-$design-mayfail" dmd "$design" "$dv"; fi
    done
done
for dt in "${dts[@]}"; do row "smd-$dt-mayfail" smd verlet "$dt"; done
for scheme in "${schemes[@]}"; do
    for dt in "${scheme_dts[@]}"; do row "smd-$dt-$scheme-mayfail" smd "$scheme" "$dt"; done
done

# What a DMD design's accuracy costs: collisions (terrace crossings and reflections) and all
# events (with virtual, cell and list events) per simulated ps, beside its g(r) error.
events=$dir/events-$state.csv
echo "set,design,param,collisions_per_ps,collisions_per_ps_err,events_per_ps,events_per_ps_err,err_g,cpu_s_per_ps" >"$events"
awk -F, 'NR > 1 && $2 == "dmd" && $NF == "ok" { print $1, $3, $4, $7, $5 }' "$table" |
    while read -r s design param eg cost; do
        read -r c ce < <(replica_stats "$RUNS/$state/$s" collisions_per_ps 0)
        read -r e ee < <(replica_stats "$RUNS/$state/$s" all_events_per_ps 0)
        echo "$s,$design,$param,$c,$ce,$e,$ee,$eg,$cost" >>"$events"
    done
# The target: the paper's SMD at 1.8 fs, or its largest stable dt below where 1.8 fs is not.
target=$(awk -F, '$2 == "smd" && $3 == "verlet" && $NF == "ok" && $4 <= 1.8 && $4 > best {
    best = $4; set = $1 } END { print set }' "$table")
if [ -z "$target" ]; then
    log "fronts $state: no stable SMD setting up to 1.8 fs: no equal-accuracy table"
    : >"$dir/equal-accuracy-$state.csv"
else
    "$TOOLS" equal-accuracy "$table" "$target" >"$dir/equal-accuracy-$state.csv"
    # Against the paper's splitting alone, to show what the other schemes change.
    if [ ${#schemes[@]} -gt 0 ]; then
        awk -F, '!($2 == "smd" && $3 != "verlet")' "$table" >"$dir/fronts-$state-verlet.csv"
        "$TOOLS" equal-accuracy "$dir/fronts-$state-verlet.csv" "$target" \
            >"$dir/equal-accuracy-$state-verlet.csv"
        rm -f "$dir/fronts-$state-verlet.csv"
    fi
fi

if [ "$figure" = 1 ]; then
gnuplot <<GP
set terminal $(png_terminal | sed 's/900,650/1500,900/')
set output '$dir/fronts-$state.png'
set datafile separator ','
set datafile missing 'nan'
set multiplot layout 2,3 title '${state#front-} rods, one model: error against SMD dt = $ref_dt fs vs cost'
set logscale xy
set grid
set xlabel 'CPU s per simulated ps'
set key bottom left font ',9'
names = "g(r) VACF OACF <U>/N P*"
do for [k = 1:5] {
    c = 5 + 2 * k
    set ylabel sprintf('error of %s', word(names, k))
    plot for [d in "${designs[*]}"] '$table' skip 1 \
            using (strcol(3) eq d ? \$5 : NaN):c with linespoints pt 7 lw 2 title 'DMD '.d, \
         for [sc in "verlet omelyan yoshida4"] '' skip 1 using (strcol(2) eq "smd" && strcol(3) eq sc && strcol(17) eq "ok" ? \$5 : NaN):c with linespoints pt (sc eq "verlet" ? 5 : sc eq "omelyan" ? 9 : 13) lw 2 lc rgb (sc eq "verlet" ? 'black' : sc eq "omelyan" ? '#555555' : '#999999') title 'SMD '.sc, \
         '' skip 1 using (strcol(2) eq "smd" && strcol(17) ne "ok" ? \$5 : NaN):c with points pt 4 ps 1.5 lc rgb 'black' title 'SMD, energy not conserved', \
         '' skip 1 using 5:(column(c + 1)) with points pt 1 lc rgb '#888888' title 'statistical floor'
}
unset multiplot
GP
fi
log "fronts $state done"
