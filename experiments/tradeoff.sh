#!/usr/bin/env bash
# The speed–accuracy trade (beyond the paper): for each engine setting, the RMS error of g(r)
# (r ≤ 12 Å), the VACF (t ≤ 1 ps) and the OACF ⟨s(0)·s(t)⟩ (t ≤ 2 ps) against a converged
# reference (SMD at dt = REF_DT_FS, REF_PS_FACTOR times longer), versus CPU s per simulated ps.
# DMD over ΔV ∈ {4, 2, 1, ½, ¼, ⅛} kT, SMD over dt ∈ {0.5, 1, 1.8, 3, 4} fs. Each error comes with
# its statistical floor (replica standard errors of both curves, paper_tools error): below it the
# setting is as good as the reference can tell. A setting whose runs fail (e.g. SMD unstable at a
# large dt) is listed as failed.
#   tradeoff.sh dense | gas
source "$(dirname "$0")/common.sh"
state=$1
dir=$OUT/tradeoff
mkdir -p "$dir"
ref=$RUNS/$state/smd-$REF_DT_FS-ref
table=$dir/tradeoff-$state.csv
echo "set,engine,param,cpu_s_per_ps,cpu_s_per_ps_err,err_g,floor_g,err_vacf,floor_vacf,err_oacf,floor_oacf,status" >"$table"
for s in dmd-4 dmd-2 dmd-1 dmd-0.5 dmd-0.25 dmd-0.125 smd-0.5 smd-1 smd-1.8 smd-3 smd-4; do
    d=$RUNS/$state/$s
    [ -d "$d" ] || d=$RUNS/$state/$s-mayfail
    engine=${s%%-*} param=${s#*-}
    if [ -f "$d/FAILED" ] || [ ! -f "$d/mean-vacf.csv" ]; then
        echo "$s,$engine,$param,nan,nan,nan,nan,nan,nan,nan,nan,failed: $(tr -d ',' <"$d/FAILED" 2>/dev/null | cut -c1-160)" >>"$table"
        continue
    fi
    # shellcheck disable=SC2046
    cost=$("$TOOLS" summary "$s" $(replica_dirs "$d") | cut -d, -f5,6)
    read -r eg fg < <("$TOOLS" error "$ref/mean-rdf.csv" "$d/mean-rdf.csv" g 12)
    read -r ev fv < <("$TOOLS" error "$ref/mean-vacf.csv" "$d/mean-vacf.csv" c 1)
    read -r eo fo < <("$TOOLS" error "$ref/mean-oacf.csv" "$d/mean-oacf.csv" c1 2)
    echo "$s,$engine,$param,$cost,$eg,$fg,$ev,$fv,$eo,$fo,ok" >>"$table"
done

title="$state rods: error against SMD dt = $REF_DT_FS fs vs cost"
gnuplot <<GP
set terminal $(png_terminal | sed 's/900,650/1500,520/')
set output '$dir/tradeoff-$state.png'
set datafile separator ','
set datafile missing 'nan'
set multiplot layout 1,3 title '$title'
set logscale xy
set grid
set xlabel 'CPU s per simulated ps'
set key bottom left
do for [q in "g vacf oacf"] {
    c = q eq "g" ? 6 : (q eq "vacf" ? 8 : 10)
    set ylabel sprintf('RMS error of %s', q eq "g" ? "g(r)" : (q eq "vacf" ? "VACF" : "OACF"))
    plot '$table' skip 1 using (strcol(2) eq "dmd" ? \$4 : NaN):c with linespoints pt 7 lw 2 lc rgb '#d62728' title 'DMD ({/Symbol D}V/kT)', \
         '' skip 1 using (strcol(2) eq "dmd" ? \$4 : NaN):c:3 with labels offset 1.2,0.6 notitle, \
         '' skip 1 using (strcol(2) eq "smd" ? \$4 : NaN):c with linespoints pt 5 lw 2 lc rgb '#1f77b4' title 'SMD (dt/fs)', \
         '' skip 1 using (strcol(2) eq "smd" ? \$4 : NaN):c:3 with labels offset 1.2,-0.6 notitle, \
         '' skip 1 using 4:(column(c+1)) with points pt 1 lc rgb '#888888' title 'statistical floor'
}
unset multiplot
GP
log "tradeoff $state done"
