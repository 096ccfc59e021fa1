#!/usr/bin/env bash
# Figs. 3-5 of the paper (dense rods, N = 512, ρ* = 0.5, T* = 1.4): g(r) (fig3), the centre-of-mass
# VACF (fig4) and the long-axis OACF (fig5) of SMD at dt = 1.8 fs and of DMD at ΔV = 2, 1, ½, ¼ kT,
# each the mean of independent runs (runset.sh) with one-standard-error bars. Beside each figure:
# the curves as CSV and the RMS distance of each DMD curve from the SMD one (DMD → SMD as ΔV → 0).
#   correlation_figure.sh fig3|fig4|fig5
source "$(dirname "$0")/common.sh"
fig=$1
case $fig in
fig3) file=rdf column=g xlabel='r (Å)' ylabel='g(r)' xmax=12 range='[2:12]' ;;
fig4) file=vacf column=c xlabel='t (ps)' ylabel='VACF' xmax=1 range='[0:1]' ;;
fig5) file=oacf column=c1 xlabel='t (ps)' ylabel='OACF ⟨s(0)·s(t)⟩' xmax=2 range='[0:0.6]' ;;
*) echo "correlation_figure.sh: fig3, fig4 or fig5" >&2; exit 2 ;;
esac
dir=$OUT/$fig
mkdir -p "$dir"
sets=(smd-1.8 dmd-2 dmd-1 dmd-0.5 dmd-0.25)
labels=('SMD dt = 1.8 fs' 'DMD {/Symbol D}V = 2 kT' 'DMD {/Symbol D}V = kT' 'DMD {/Symbol D}V = kT/2'
    'DMD {/Symbol D}V = kT/4')
echo "set,rms_distance_from_smd,noise_floor" >"$dir/$fig-distance.csv"
for s in "${sets[@]}"; do
    cp "$RUNS/dense/$s/mean-$file.csv" "$dir/$fig-$s.csv"
    [ "$s" = smd-1.8 ] && continue
    read -r d noise < <("$TOOLS" error "$dir/$fig-smd-1.8.csv" "$dir/$fig-$s.csv" "$column" "$xmax")
    echo "$s,$d,$noise" >>"$dir/$fig-distance.csv"
done
colors=('#000000' '#d62728' '#ff7f0e' '#2ca02c' '#1f77b4')
plot=""
for k in "${!sets[@]}"; do
    f="$dir/$fig-${sets[$k]}.csv"
    err=$(head -1 "$f" | tr ',' '\n' | grep -n -x -e "${column}_err" -e err | head -1 | cut -d: -f1)
    col=$(head -1 "$f" | tr ',' '\n' | grep -n -x "$column" | cut -d: -f1)
    plot+="'$f' skip 1 using 1:$col:$err with yerrorlines pt 0 lw 2 lc rgb '${colors[$k]}' title '${labels[$k]}', "
done
gnuplot <<GP
set terminal $(png_terminal)
set output '$dir/$fig.png'
set datafile separator ','
set xlabel '$xlabel'
set ylabel '$ylabel'
set xrange $range
set grid
set key top right
set title 'dense rods, N = $DENSE_N, {/Symbol r}* = 0.5, T* = 1.4 ($REPLICAS runs each, ±1 s.e.)'
plot ${plot%, }
GP
log "$fig done"
