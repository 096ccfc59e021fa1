#!/usr/bin/env bash
# DMD against SMD on the default scene (the paper's dense rods, N = 512, ρ* = 0.5, T* = 1.4): one
# short run of each, then a side-by-side table — CPU s per simulated ps, collisions per ps, energy
# conservation, and how far DMD's g(r), VACF and OACF are from SMD's (RMS distance, with the
# statistical floor from both runs' block error bars) — and a figure of the three curves.
#   experiments/versus.sh [OUTDIR]          (default out/versus)
# Environment: TERRACE (default build/terrace), TOOLS (default build/paper_tools),
#   VERSUS_PS production ps per run (default 1.998: 222 samples of 9 fs; terrace refuses a length
#   that is not a whole number of samples), VERSUS_DV ΔV in kT (default 0.5), VERSUS_DT_FS SMD
#   time step (default 1.8). Equilibration: 0.495 ps, 55 thermostat intervals of 9 fs.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
TERRACE=${TERRACE:-$root/build/terrace}
TOOLS=${TOOLS:-$root/build/paper_tools}
out=${1:-out/versus}
ps=${VERSUS_PS:-1.998} dV=${VERSUS_DV:-0.5} dt=${VERSUS_DT_FS:-1.8}
mkdir -p "$out"
common=(--quiet --set run.equilibrate_ps=0.495 --set run.time_ps="$ps")
echo "DMD (ΔV = $dV kT) and SMD (dt = $dt fs), default scene, $ps ps each ..." >&2
"$TERRACE" run "${common[@]}" --set engine=dmd --set dmd.dV="$dV" --out "$out/dmd" --overwrite >/dev/null
"$TERRACE" run "${common[@]}" --set engine=smd --set smd.dt_fs="$dt" --out "$out/smd" --overwrite >/dev/null

keys=(cpu_seconds_per_ps collisions_per_ps energy.rel_fluct energy.drift_per_ps temperature_K)
IFS=, read -r dcpu dcol dfl ddr dT < <("$TOOLS" get "$out/dmd/summary.json" "${keys[@]}")
IFS=, read -r scpu scol sfl sdr sT < <("$TOOLS" get "$out/smd/summary.json" "${keys[@]}")
read -r eg fg < <("$TOOLS" error "$out/smd/rdf.csv" "$out/dmd/rdf.csv" g 12)
read -r ev fv < <("$TOOLS" error "$out/smd/vacf.csv" "$out/dmd/vacf.csv" c 1)
read -r eo fo < <("$TOOLS" error "$out/smd/oacf.csv" "$out/dmd/oacf.csv" c1 2)
{
    printf '%-34s %16s %16s\n' "" "DMD dV=${dV}kT" "SMD dt=${dt}fs"
    printf '%-34s %16.3g %16.3g\n' "CPU s per simulated ps" "$dcpu" "$scpu"
    printf '%-34s %16.3g %16s\n' "collisions per ps" "$dcol" "-"
    printf '%-34s %16.2g %16.2g\n' "energy: std(E)/|<U>|" "$dfl" "$sfl"
    printf '%-34s %16.2g %16.2g\n' "energy drift (kJ/mol per ps)" "$ddr" "$sdr"
    printf '%-34s %16.1f %16.1f\n' "temperature (K)" "$dT" "$sT"
    echo
    printf 'DMD is %.2fx as efficient as SMD (CPU s per ps of SMD / of DMD).\n' \
        "$(awk -v a="$scpu" -v b="$dcpu" 'BEGIN{print a/b}')"
    printf 'RMS distance DMD - SMD (statistical floor):  g(r) %.3g (%.3g)   VACF %.3g (%.3g)   OACF %.3g (%.3g)\n' \
        "$eg" "$fg" "$ev" "$fv" "$eo" "$fo"
} | tee "$out/versus.txt"

if gnuplot -e 'set terminal pngcairo' >/dev/null 2>&1; then term="pngcairo size 1500,480 enhanced"; else term="png size 1500,480"; fi
gnuplot <<GP
set terminal $term
set output '$out/versus.png'
set datafile separator ','
set multiplot layout 1,3 title 'DMD ({/Symbol D}V = $dV kT) vs SMD (dt = $dt fs), dense rods, $ps ps each'
set grid
set key top right
set xlabel 'r (Å)'; set ylabel 'g(r)'; set xrange [2:12]
plot '$out/smd/rdf.csv' skip 1 using 1:2 with lines lw 2 lc rgb '#1f77b4' title 'SMD', \
     '$out/dmd/rdf.csv' skip 1 using 1:2 with lines lw 2 dt 2 lc rgb '#d62728' title 'DMD'
set xlabel 't (ps)'; set ylabel 'VACF'; set xrange [0:1]
plot '$out/smd/vacf.csv' skip 1 using 1:2 with lines lw 2 lc rgb '#1f77b4' title 'SMD', \
     '$out/dmd/vacf.csv' skip 1 using 1:2 with lines lw 2 dt 2 lc rgb '#d62728' title 'DMD'
set ylabel 'OACF'; set xrange [0:*]
plot '$out/smd/oacf.csv' skip 1 using 1:2 with lines lw 2 lc rgb '#1f77b4' title 'SMD', \
     '$out/dmd/oacf.csv' skip 1 using 1:2 with lines lw 2 dt 2 lc rgb '#d62728' title 'DMD'
unset multiplot
GP
echo "figure: $out/versus.png" >&2
