#!/usr/bin/env bash
# Convergence, measured: one model for both engines (g(r)·U, core/smoothed_potential.hpp), DMD
# terracing it (dmd.model = smoothed) at ΔV = 2, 1, ½, ¼, ⅛ kT against SMD at dt = REF_DT_FS
# (0.2 fs; 0.5 in the quick pipeline) as the reference, REF_PS_FACTOR times longer, seeds of its
# own. Two systems (runset.sh states): the paper's dense rods (conv-rods: dense-rods.json) and a
# dense Lennard-Jones liquid (conv-lj: lj-liquid.json, spheres in reduced units ε = 1 kJ/mol,
# σ = 1 Å, m = 1 g/mol, so τ = σ sqrt(m/ε) = 100 fs, at ρ* = 0.8 and T* = 0.9; at T* = 1 the
# level −kT of ΔV = 2 kT would fall on the minimum −ε, which the scene refuses).
# For each DMD setting and quantity q, an error e_q against the reference and its statistical
# uncertainty σ_q, all from independent replicas (runset.sh; paper_tools stats, summary, error):
#   U    ⟨U⟩/N as the engine reports it (summary.json potential_energy_mean): for DMD the
#        terraced energy V, for SMD the smoothed U
#   Uc   ⟨U⟩/N of the continuous model on the run's configurations (paper_tools configurational
#        on its trajectory): how far the terraced dynamics samples from the continuous one
#   P    the engine's own pressure P* = Pσ³/ε (summary.json pressure.mean_reduced: DMD's from its
#        impulses), nan until the runs report it
#   Pc   the continuous model's virial pressure on the run's configurations
#   g, vacf, oacf   RMS distance of the replica-mean curve from the reference's (paper_tools
#        error; g for r ≤ 12 Å ≈ 4σ (rods) or 3σ (LJ), VACF for t ≤ 1 ps (rods) or 3τ (LJ),
#        OACF for t ≤ 2 ps, rods only)
# Scalars: e = |x − x_ref| (the table keeps x, so the sign too), σ = sqrt(s.e.² + s.e._ref²). Curves: the RMS distance E contains the
# noise of both curves, E² ≈ D² + F² with F the statistical floor (paper_tools error), so
# e = sqrt(max(E² − F², 0)) estimates the true distance D, and σ = F bounds its uncertainty
# (the noise projected on the difference is at most F). Then the order of convergence per
# quantity: the slope of ln e against ln ΔV, weighted least squares with σ_ln e = σ/e, over the
# points resolved from zero (e ≥ 2σ; the others are marked fit_q = 0 and left out), with the
# Birge-ratio scaling of its error, and the local order from each ΔV to ΔV/2, log₂ of the
# factor by which the error shrinks (experiments/tools/convergence.hpp has the formulas and
# their sources).
#   convergence.sh rods | lj     $OUT/convergence/convergence-<system>.csv, one row per setting
#                                (dV_kT = 0: the reference) and orders-<system>.csv
#   convergence.sh figure        $OUT/convergence/orders.csv and convergence.png
source "$(dirname "$0")/common.sh"
dir=$OUT/convergence
mkdir -p "$dir"
DVS="2 1 0.5 0.25 0.125"
QUANTITIES="U Uc P Pc g vacf oacf"

# scalar_stats DIR FILE KEY : replica mean and standard error of KEY of DIR/seed-*/FILE, per body
# for energies ("nan nan" when a run lacks the key: pressure before the runs reported it).
scalar_stats() {
    local set=$1 file=$2 key=$3 d v values=() per=1
    for d in $(replica_dirs "$set"); do
        v=$("$TOOLS" get "$d/$file" "$key")
        [ "$file" = summary.json ] && [ "$key" = potential_energy_mean ] &&
            per=$("$TOOLS" get "$d/summary.json" n_bodies)
        v=$(awk -v v="$v" -v n="$per" 'BEGIN { print (v == "nan") ? "nan" : v / n }')
        values+=("$v")
    done
    case " ${values[*]} " in *" nan "*) echo "nan nan"; return ;; esac
    "$TOOLS" stats "${values[@]}"
}

# curve_error REF SET FILE COLUMN XMAX : the debiased distance and its floor ("nan nan" without
# the curve, e.g. the OACF of spheres).
curve_error() {
    if [ ! -s "$1/mean-$3.csv" ] || [ ! -s "$2/mean-$3.csv" ]; then echo "nan nan"; return; fi
    "$TOOLS" error "$1/mean-$3.csv" "$2/mean-$3.csv" "$4" "$5" |
        awk '{ d = $1 * $1 - $2 * $2; printf "%.6g %.6g\n", (d > 0 ? sqrt(d) : 0), $2 }'
}

table() {
    local system=$1 state=conv-$1 gmax vmax
    case $system in
    rods) gmax=12 vmax=1 ;;   # Å (≈ 4σ), ps
    lj) gmax=3 vmax=0.3 ;;    # 3σ, 3τ: the LJ VACF has decayed by then
    *) echo "convergence.sh: rods, lj or figure" >&2; exit 2 ;;
    esac
    local ref=$RUNS/$state/smd-$REF_DT_FS-ref raw=$dir/convergence-$system.raw.csv
    local header="dV_kT,cpu_s_per_ps,cpu_s_per_ps_err" q
    for q in U Uc P Pc; do header+=",$q,${q}_se"; done
    for q in $QUANTITIES; do header+=",err_$q,sigma_$q"; done
    echo "$header" >"$raw"
    declare -A refValue refError
    local set dV row cost value se e s key
    for dV in 0 $DVS; do
        if [ "$dV" = 0 ]; then set=$ref; else set=$RUNS/$state/dmd-$dV; fi
        # shellcheck disable=SC2046
        cost=$("$TOOLS" summary "$dV" $(replica_dirs "$set") | cut -d, -f5,6)
        row="$dV,$cost"
        local errors=""
        for q in U Uc P Pc; do
            case $q in
            U) key=(summary.json potential_energy_mean) ;;
            Uc) key=(configurational.json potential_energy_per_body) ;;
            P) key=(summary.json pressure.mean_reduced) ;;
            Pc) key=(configurational.json pressure_reduced) ;;
            esac
            read -r value se < <(scalar_stats "$set" "${key[@]}")
            row+=",$value,$se"
            if [ "$dV" = 0 ]; then
                refValue[$q]=$value refError[$q]=$se
                errors+=",nan,nan"
            else
                errors+=$(awk -v x="$value" -v s="$se" -v r="${refValue[$q]}" \
                    -v sr="${refError[$q]}" 'BEGIN {
                        if (x == "nan" || r == "nan") { print ",nan,nan"; exit }
                        d = x - r; printf ",%.6g,%.6g", (d < 0 ? -d : d), sqrt(s * s + sr * sr) }')
            fi
        done
        for q in g vacf oacf; do
            if [ "$dV" = 0 ]; then errors+=",nan,nan"; continue; fi
            case $q in
            g) read -r e s < <(curve_error "$ref" "$set" rdf g "$gmax") ;;
            vacf) read -r e s < <(curve_error "$ref" "$set" vacf c "$vmax") ;;
            oacf) read -r e s < <(curve_error "$ref" "$set" oacf c1 2) ;;
            esac
            errors+=",$e,$s"
        done
        echo "$row$errors" >>"$raw"
    done
    "$TOOLS" order "$raw" "$dir/convergence-$system.csv" >"$dir/orders-$system.csv"
    rm -f "$raw"
    log "convergence $system done"
}

figure() {
    local orders=$dir/orders.csv system
    echo "quantity,system,order,error,log_prefactor,chi2_per_dof,points" >"$orders"
    for system in rods lj; do
        tail -n +2 "$dir/orders-$system.csv" |
            awk -F, -v s="$system" 'BEGIN { OFS = "," } { $1 = $1 "," s; print }' >>"$orders"
    done
    # gnuplot variables of the fits: p_<q>_<system>, a_<q>_<system> (ln A), and the fitted ΔV
    # range (lo_, hi_: the resolved points'), NaN where there is no fit.
    local vars="" q p e a chi lo hi col fit
    for system in rods lj; do
        local csv=$dir/convergence-$system.csv
        for q in $QUANTITIES; do
            read -r p e a chi < <(awk -F, -v q="$q" -v s="$system" '$1 == q && $2 == s {
                for (k = 3; k <= 6; ++k) if ($k == "nan") $k = "NaN"
                print $3, $4, $5, $6 }' "$orders")
            col=$(head -1 "$csv" | tr ',' '\n' | grep -n -x "err_$q" | cut -d: -f1)
            fit=$(head -1 "$csv" | tr ',' '\n' | grep -n -x "fit_$q" | cut -d: -f1)
            read -r lo hi < <(awk -F, -v f="$fit" 'NR > 1 && $f == 1 {
                    if (lo == "" || $1 < lo) lo = $1; if (hi == "" || $1 > hi) hi = $1 }
                END { print (lo == "" ? "NaN" : lo), (hi == "" ? "NaN" : hi) }' "$csv")
            vars+="p_${q}_$system = ${p:-NaN}; e_${q}_$system = ${e:-NaN}; "
            vars+="a_${q}_$system = ${a:-NaN}; x_${q}_$system = ${chi:-NaN}; "
            vars+="lo_${q}_$system = $lo; hi_${q}_$system = $hi; c_${q}_$system = $col; "
        done
    done
    # Points per quantity: a panel without any (the engine's pressure before the runs reported
    # it; the OACF of spheres alone) says so instead of stopping gnuplot.
    for q in $QUANTITIES; do
        vars+="n_$q = $(for system in rods lj; do
            csv=$dir/convergence-$system.csv
            col=$(head -1 "$csv" | tr ',' '\n' | grep -n -x "err_$q" | cut -d: -f1)
            awk -F, -v c="$col" 'NR > 1 && $1 > 0 && $c != "nan" && $c > 0' "$csv"
        done | wc -l); "
    done
    gnuplot <<GP
set terminal $(png_terminal | sed 's/900,650/1600,800/')
set output '$dir/convergence.png'
set datafile separator ','
set datafile missing 'nan'
$vars
set multiplot layout 2,4 title 'DMD (smoothed model) against SMD at dt = $REF_DT_FS fs: error vs {/Symbol D}V (filled: fitted; open: within the statistical floor)'
set logscale xy
set format y '%g'
set grid
set xrange [0.09:2.8]
set xlabel '{/Symbol D}V / kT'
set key bottom right font ',9' samplen 1
line(x, a, p, lo, hi) = (x >= lo * 0.999 && x <= hi * 1.001) ? exp(a) * x**p : NaN
array T[7] = ["⟨U⟩/N (kJ/mol), the engine's (DMD: terraced)", \
              "⟨U⟩/N (kJ/mol), continuous, on the configurations", \
              "P*, the engine's (DMD: impulses)", "P*, continuous, on the configurations", \
              "g(r), RMS", "VACF, RMS", "OACF, RMS"]
do for [k = 1:7] {
    q = word("$QUANTITIES", k)
    set title T[k]
    set ylabel 'error'
    cr = value(sprintf("c_%s_rods", q)); cl = value(sprintf("c_%s_lj", q))
    pr = value(sprintf("p_%s_rods", q)); pl = value(sprintf("p_%s_lj", q))
    er = value(sprintf("e_%s_rods", q)); el = value(sprintf("e_%s_lj", q))
    xr = value(sprintf("x_%s_rods", q)); xl = value(sprintf("x_%s_lj", q))
    ar = value(sprintf("a_%s_rods", q)); al = value(sprintf("a_%s_lj", q))
    lr = value(sprintf("lo_%s_rods", q)); hr = value(sprintf("hi_%s_rods", q))
    ll = value(sprintf("lo_%s_lj", q)); hl = value(sprintf("hi_%s_lj", q))
    set samples 200
    if (value(sprintf("n_%s", q)) == 0) {
        set label 1 'no data' at graph 0.5, 0.5 center
        set yrange [0.1:1]
        plot 0.5 lc rgb 'white' notitle
        unset label 1
        set autoscale y
        continue
    }
    plot '$dir/convergence-rods.csv' skip 1 using (\$1 > 0 && column(cr + 2) == 1 ? \$1 : NaN):cr:(column(cr + 1)) with yerrorbars pt 7 ps 1.2 lc rgb '#d62728' title (pr == pr ? sprintf('rods, p = %.2f ± %.2f, {/Symbol c}^2/{/Symbol n} %.3g', pr, er, xr) : 'rods, no fit'), \
         '' skip 1 using (\$1 > 0 && column(cr + 2) == 0 ? \$1 : NaN):cr:(column(cr + 1)) with yerrorbars pt 6 ps 1.2 lc rgb '#d62728' notitle, \
         line(x, ar, pr, lr, hr) with lines lw 2 lc rgb '#d62728' notitle, \
         '$dir/convergence-lj.csv' skip 1 using (\$1 > 0 && column(cl + 2) == 1 ? \$1 : NaN):cl:(column(cl + 1)) with yerrorbars pt 5 ps 1.2 lc rgb '#1f77b4' title (pl == pl ? sprintf('LJ, p = %.2f ± %.2f, {/Symbol c}^2/{/Symbol n} %.3g', pl, el, xl) : 'LJ, no fit'), \
         '' skip 1 using (\$1 > 0 && column(cl + 2) == 0 ? \$1 : NaN):cl:(column(cl + 1)) with yerrorbars pt 4 ps 1.2 lc rgb '#1f77b4' notitle, \
         line(x, al, pl, ll, hl) with lines lw 2 lc rgb '#1f77b4' notitle
}
unset multiplot
GP
    log "convergence figure done"
}

case ${1:-} in
rods | lj) table "$1" ;;
figure) figure ;;
*) echo "usage: convergence.sh rods | lj | figure" >&2; exit 2 ;;
esac
