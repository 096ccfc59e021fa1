#!/usr/bin/env bash
# DMD against SMD on the default scene (the paper's dense rods, N = 512, ρ* = 0.5, T* = 1.4), the
# first thing `./quickstart.sh run` shows: one short run of each engine at the paper's fixed
# settings, with their thermo rows, and a reference run (SMD yoshida4 at half the step) that
# measures how far each engine's g(r) and VACF lie from the continuous model; then a side-by-side
# table (CPU s per simulated ps, collisions per ps, energy conservation, distances with their
# statistical floors) labelled as what it is, a comparison at unequal accuracy; and last the
# comparison the project exists for, at equal accuracy, as `terrace tradeoff` measured it on this
# scene (results/tradeoff-map). A figure of the three curves goes to OUTDIR/versus.png.
#   experiments/versus.sh [OUTDIR]          (default out/versus)
# Environment: TERRACE (default build/terrace), TOOLS (default build/paper_tools),
#   VERSUS_PS production ps per run (default 1.998: 222 samples of 9 fs), VERSUS_DV ΔV in kT
#   (default 0.5), VERSUS_DT_FS SMD time step (default 1.8). Equilibration: 0.495 ps.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
TERRACE=${TERRACE:-$root/build/terrace}
TOOLS=${TOOLS:-$root/build/paper_tools}
out=${1:-out/versus}
ps=${VERSUS_PS:-1.998} dV=${VERSUS_DV:-0.5} dt=${VERSUS_DT_FS:-1.8}
mkdir -p "$out"
common=(--quiet --set run.equilibrate_ps=0.495 --set run.time_ps="$ps" --set output.thermo_every_fs=198)
echo "DMD (ΔV = $dV kT), SMD (dt = $dt fs) and a reference (SMD yoshida4, dt = $(awk -v d="$dt" 'BEGIN{print d/2}') fs), default scene, $ps ps each ..." >&2
"$TERRACE" run "${common[@]}" --set engine=dmd --set dmd.dV="$dV" --out "$out/dmd" --overwrite >/dev/null
"$TERRACE" run "${common[@]}" --set engine=smd --set smd.dt_fs="$dt" --out "$out/smd" --overwrite >/dev/null
"$TERRACE" run "${common[@]}" --set engine=smd --set smd.scheme=yoshida4 \
    --set smd.dt_fs="$(awk -v d="$dt" 'BEGIN{print d/2}')" --out "$out/reference" --overwrite >/dev/null
# Each run's thermo rows every 0.198 ps: time, temperature, U and E per body (kJ/mol), P (bar).
for engine in dmd smd; do
    echo "thermo, $engine:"
    awk -F, 'NR == 1 { printf "  %8s %10s %12s %12s %10s\n", "t (ps)", "T (K)", "U/N", "E/N", "P (bar)"; next }
        /^#/ { if ($0 ~ /bodies/) { match($0, /of [0-9]+ bodies/); n = substr($0, RSTART + 3, RLENGTH - 10) } next }
        { printf "  %8.3f %10.1f %12.4f %12.4f %10.0f\n", $1, $7, $4 / n, $6 / n, $8 }' "$out/$engine/thermo.csv"
done

keys=(cpu_seconds_per_ps collisions_per_ps energy.rel_fluct energy.drift_per_ps temperature_K)
IFS=, read -r dcpu dcol dfl ddr dT < <("$TOOLS" get "$out/dmd/summary.json" "${keys[@]}")
IFS=, read -r scpu scol sfl sdr sT < <("$TOOLS" get "$out/smd/summary.json" "${keys[@]}")
read -r eg fg < <("$TOOLS" error "$out/smd/rdf.csv" "$out/dmd/rdf.csv" g 12)
read -r ev fv < <("$TOOLS" error "$out/smd/vacf.csv" "$out/dmd/vacf.csv" c 1)
read -r eo fo < <("$TOOLS" error "$out/smd/oacf.csv" "$out/dmd/oacf.csv" c1 2)
read -r gd gdf < <("$TOOLS" error "$out/reference/rdf.csv" "$out/dmd/rdf.csv" g 12)
read -r gs gsf < <("$TOOLS" error "$out/reference/rdf.csv" "$out/smd/rdf.csv" g 12)
read -r vd vdf < <("$TOOLS" error "$out/reference/vacf.csv" "$out/dmd/vacf.csv" c 1)
read -r vs vsf < <("$TOOLS" error "$out/reference/vacf.csv" "$out/smd/vacf.csv" c 1)
{
    printf '%-34s %16s %16s\n' "" "DMD dV=${dV}kT" "SMD dt=${dt}fs"
    printf '%-34s %16.3g %16.3g\n' "CPU s per simulated ps" "$dcpu" "$scpu"
    printf '%-34s %16.3g %16s\n' "collisions per ps" "$dcol" "-"
    printf '%-34s %16.2g %16.2g\n' "energy: std(E)/|<U>|" "$dfl" "$sfl"
    printf '%-34s %16.2g %16.2g\n' "energy drift (kJ/mol per ps)" "$ddr" "$sdr"
    printf '%-34s %16.1f %16.1f\n' "temperature (K)" "$dT" "$sT"
    echo
    printf '%-34s %16s %16s\n' "g(r) from the reference (floor)" "$(printf '%.3g (%.3g)' "$gd" "$gdf")" "$(printf '%.3g (%.3g)' "$gs" "$gsf")"
    printf '%-34s %16s %16s\n' "VACF from the reference (floor)" "$(printf '%.3g (%.3g)' "$vd" "$vdf")" "$(printf '%.3g (%.3g)' "$vs" "$vsf")"
    echo
    printf 'At these fixed settings, the paper'"'"'s comparison, DMD is %.2fx as fast per simulated ps as SMD:\n' \
        "$(awk -v a="$scpu" -v b="$dcpu" 'BEGIN{print a/b}')"
    echo 'at unequal accuracy (each engine'"'"'s distance from the reference above: a distance above its floor is'
    echo 'a bias, not noise).'
    printf 'RMS distance DMD - SMD (statistical floor):  g(r) %.3g (%.3g)   VACF %.3g (%.3g)   OACF %.3g (%.3g)\n' \
        "$eg" "$fg" "$ev" "$fv" "$eo" "$fo"
    verdict=$root/results/tradeoff-map/rods-loose/rho0.5-T1.4.verdict
    if [ -s "$verdict" ]; then
        echo
        echo 'At equal accuracy, what the project measures (terrace tradeoff on this scene, loose tolerances,'
        echo 'results/tradeoff-map; it takes CPU hours, so it is not rerun here):'
        head -1 "$verdict" | fold -s -w 96 | sed 's/^/  /'
    fi
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
