#!/usr/bin/env bash
# Where DMD stops paying off (beyond the paper): the efficiency ratio DMD/SMD = (CPU s/ps of SMD)/
# (CPU s/ps of DMD) of the rods versus ρ* ∈ DENSITIES at T* = 1.4 and 10. The two settings
# compared are the paper's pair of equal accuracy, DMD at ΔV = kT/2 and SMD at dt = 1.8 fs (the
# paper finds their g(r), VACF and OACF in agreement); the table also gives the RMS distance of the
# two VACFs with its statistical floor, so that the equal-accuracy premise can be checked at every
# density rather than assumed.
#   density.sh "0.01 0.05 ..."
source "$(dirname "$0")/common.sh"
densities=$1
dir=$OUT/density
mkdir -p "$dir"
table=$dir/density.csv
echo "T,rho,cpu_dmd,cpu_dmd_err,cpu_smd,cpu_smd_err,ratio,ratio_err,collisions_per_ps,vacf_distance,vacf_floor,status" >"$table"
for T in 1.4 10; do
    for rho in $densities; do
        base=$RUNS/rho$rho-T$T
        dmd=$base/dmd-0.5-mayfail smd=$base/smd-1.8-mayfail
        if [ -f "$dmd/FAILED" ] || [ -f "$smd/FAILED" ]; then
            why=$(cat "$dmd/FAILED" "$smd/FAILED" 2>/dev/null | tr -d "," | cut -c1-160 || true)
            echo "$T,$rho,nan,nan,nan,nan,nan,nan,nan,nan,nan,failed: $why" >>"$table"
            continue
        fi
        # shellcheck disable=SC2046
        a=$("$TOOLS" summary dmd $(replica_dirs "$dmd"))
        # shellcheck disable=SC2046
        b=$("$TOOLS" summary smd $(replica_dirs "$smd"))
        read -r dist floor < <("$TOOLS" error "$smd/mean-vacf.csv" "$dmd/mean-vacf.csv" c 1)
        awk -F, -v T="$T" -v rho="$rho" -v a="$a" -v b="$b" -v d="$dist" -v f="$floor" 'BEGIN {
            split(a, x, ","); split(b, y, ",")
            r = y[5] / x[5]; e = r * sqrt((y[6] / y[5])^2 + (x[6] / x[5])^2)
            printf "%s,%s,%g,%g,%g,%g,%g,%g,%g,%s,%s,ok\n", T, rho, x[5], x[6], y[5], y[6], r, e, x[7], d, f
        }' >>"$table"
    done
done
gnuplot <<GP
set terminal $(png_terminal)
set output '$dir/density.png'
set datafile separator ','
set datafile missing 'nan'
set logscale xy
set grid
set xlabel '{/Symbol r}*'
set ylabel 'efficiency DMD / SMD (CPU s per ps of SMD / of DMD)'
set title 'rods: DMD ({/Symbol D}V = kT/2) vs SMD (dt = 1.8 fs), N = $DENSE_N'
set key top right
plot '$table' skip 1 using (\$1 == 1.4 ? \$2 : NaN):7:8 with yerrorlines pt 7 lw 2 lc rgb '#1f77b4' title 'T* = 1.4', \
     '' skip 1 using (\$1 == 10 ? \$2 : NaN):7:8 with yerrorlines pt 5 lw 2 lc rgb '#d62728' title 'T* = 10', \
     1 with lines dt 2 lc rgb 'black' title 'break-even'
GP
log "density done"
