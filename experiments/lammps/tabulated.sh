#!/usr/bin/env bash
# terrace SMD against LAMMPS on one model, the smoothed g(r)·U_LJ(r) that terrace integrates,
# given to LAMMPS as a table (pair_style table linear), at N = 512 and 32 000.
#
#   experiments/lammps/tabulated.sh [TERRACE] [ROUNDS] [OUT]
#     TERRACE  the terrace binary (default build/terrace), ROUNDS (default 3), OUT (default
#     out/lammps-tabulated); environment: SIZES (default "512 32000"), TABLEN (table points,
#     default 10000).
#
# The state: LJ spheres of experiments/scenes/lj-liquid.json, every parameter forced on the scene
# below: ε = 1 kJ/mol, σ = 1 Å, m = 1 g/mol (so τ = σ√(m/ε) = 100 fs), ρ* = 0.8, T* = 0.9, the
# cutoff smoothed between r_l = 2.5 σ and r_u = 3 σ (core/smoothed_cutoff.hpp), dt = 0.5 fs
# (0.005 τ), velocity Verlet (smd.scheme verlet), Verlet skin 0.3 σ, the lists rebuilt when some
# body has moved more than half the skin since the last build, checked every step (terrace's
# rule, smd/neighbour_list.hpp; LAMMPS: neigh_modify every 1 delay 0 check yes).
# terrace starts from its simple cubic lattice (⌈N^⅓⌉ sites per edge, the first N of them used:
# 32 000 of 32³ sites) with Maxwell-Boltzmann velocities and equilibrates for 0.9 ps, rescaling
# the velocities to T every 9 fs; both codes then run NVE production of the same length from the
# same state, terrace's at the start of its production (the first frame of its trajectory.xyz, to
# 17 digits), so that they run at the same total energy: 9 ps at N = 512, 0.9 ps at N = 32 000.
#
# Timing: each round runs terrace, then LAMMPS (serial lmp, one thread), ROUNDS rounds alternated
# so that a change in machine load hits both. Steps per CPU second of production: terrace
# steps / summary.json cpu_seconds (the engine's production calls only; sampling and analysis
# outside), LAMMPS steps / (Loop time × % CPU use) of a production run with no output or
# computes inside it (thermo only at its two ends). Reported: each round and the medians, the
# ratio terrace/LAMMPS per round.
#
# Agreement, from the first round: LAMMPS continues NVE for a second production of the same
# length, sampling U at terrace's sample interval and g(r) in 8 blocks (compute rdf, fix
# ave/time), with the cost of neither counted anywhere. ⟨U⟩ per body: both as the mean of the
# samples with the standard error of 8 contiguous blocks (terrace: potential_energy_mean and _err
# of summary.json); pass when |ΔU| < 3 combined standard errors. g(r): terrace's rdf.csv against
# LAMMPS's block mean, bins of 0.05 σ, over the first peak (bin centres 0.9 ≤ r/σ ≤ 1.5, 12 bins);
# pass when χ² = Σ (Δg/σ_Δ)² is below its 99.9 % point for 12 degrees of freedom (32.9).
#
# Units: terrace Å, g/mol, kJ/mol, K, fs/ps; LAMMPS real units (Å, g/mol, fs, kcal/mol, K):
# energies and forces divided by 4.184, velocities Å/ps → Å/fs; LAMMPS's temperatures use its
# k_B = 0.0019872067 kcal/mol/K, terrace's 0.0083144626 kJ/mol/K (the same to 2e-6).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
terrace=${1:-$root/build/terrace}
rounds=${2:-3}
out=${3:-$root/out/lammps-tabulated}
sizes=${SIZES:-"512 32000"}
tablen=${TABLEN:-10000}
command -v lmp >/dev/null || { echo "no lmp: apt-get install lammps" >&2; exit 1; }
[[ -x $terrace ]] || { echo "no terrace binary at $terrace" >&2; exit 1; }
export OMP_NUM_THREADS=1

# The model and state (terrace units), forced on the scene.
scene=$root/experiments/scenes/lj-liquid.json
eps=1.0 sigma=1.0 mass=1.0 rl=2.5 ru=3.0 rho=0.8 tstar=0.9
dt=0.5 skin=0.3 equil_ps=0.9 thermostat_fs=9
rlo=0.5 # σ: the table's inner end, far inside any distance the liquid reaches (U = 1.6×10⁴ ε)
key=GLJ

# Production length (ps) and sample interval (fs) by N: terrace's g(r) is an O(N²) pass per
# sample, so the large system samples less often.
plan() { if (($1 <= 4096)); then echo "9 9"; else echo "0.9 22.5"; fi; }

calc() { awk "BEGIN { printf \"%.17g\", $1 }"; }
eps_kcal=$(calc "$eps / 4.184")
rlo_a=$(calc "$rlo * $sigma") rl_a=$(calc "$rl * $sigma") ru_a=$(calc "$ru * $sigma")
skin_a=$(calc "$skin * $sigma")
mkdir -p "$out"

# The LAMMPS table of U_s = g(r)·U_LJ(r) and f = -dU_s/dr = -(g U' + g' U), with g and g' of
# core/smoothed_cutoff.hpp (paper eqs. 22-23), on LAMMPS's own grid uniform in r² (RSQ), in
# kcal/mol and kcal/mol/Å. With the internal table of as many points, LAMMPS's nodes are these
# values and it interpolates linearly in r² between them.
write_table() {
    awk -v n="$tablen" -v rlo="$rlo_a" -v rhi="$ru_a" -v rl="$rl_a" -v eps="$eps_kcal" \
        -v sig="$sigma" -v key="$key" 'BEGIN {
        printf "# g(r)*U_LJ(r), eps = %.10g kcal/mol, sigma = %g A, smoothed on [%g, %g] A\n",
               eps, sig, rl, rhi
        printf "# (terrace core/smoothed_cutoff.hpp); columns: index, r (A), U (kcal/mol), F = -dU/dr\n\n"
        printf "%s\nN %d RSQ %.17g %.17g\n\n", key, n, rlo, rhi
        w3 = (rhi - rl) ^ 3
        for (i = 0; i < n; i++) {
            r = (i == n - 1) ? rhi : sqrt(rlo * rlo + i * (rhi * rhi - rlo * rlo) / (n - 1))
            s6 = (sig / r) ^ 6
            u = 4 * eps * (s6 * s6 - s6); du = 4 * eps * (6 * s6 - 12 * s6 * s6) / r
            if (r <= rl) { g = 1; dg = 0 } else if (r >= rhi) { g = 0; dg = 0 }
            else { a = rhi - r; g = a * a * (rhi - 3 * rl + 2 * r) / w3; dg = -6 * (rhi - r) * (r - rl) / w3 }
            printf "%d %.17g %.17g %.17g\n", i + 1, r, g * u, -(g * du + dg * u)
        }
    }' >"$1"
}

# The table's own error: linear interpolation in r² between the nodes against the formula, the
# largest |δU| beyond 0.85 σ (the liquid's nearest approach is ~0.9 σ) and a bound on the bias of
# ⟨U⟩ per body, (ρ/2) ∫ 4πr² g_max |δU| dr with g_max = 3 (in ε).
table_error() {
    awk -v n="$tablen" -v rlo="$rlo_a" -v rhi="$ru_a" -v rl="$rl_a" -v sig="$sigma" \
        -v rho="$rho" 'function U(r,   s6, g, a) {
            s6 = (sig / r) ^ 6
            if (r <= rl) g = 1; else if (r >= rhi) g = 0
            else { a = rhi - r; g = a * a * (rhi - 3 * rl + 2 * r) / (rhi - rl) ^ 3 }
            return g * 4 * (s6 * s6 - s6) }
        BEGIN {
        h = (rhi * rhi - rlo * rlo) / (n - 1); pi = atan2(0, -1)
        for (i = 0; i < n - 1; i++) {
            s0 = rlo * rlo + i * h; r0 = sqrt(s0); r1 = sqrt(s0 + h)
            if (r1 < 0.85 * sig) continue
            e = 0.5 * (U(r0) + U(r1)) - U(sqrt(s0 + 0.5 * h)) # at the middle, in r²
            if (e < 0) e = -e
            if (e > m) m = e
            bias += 0.5 * rho / sig ^ 3 * 4 * pi * (r0 * r0) * 3 * e * (r1 - r0)
        }
        printf "%.2g %.2g\n", m, bias }'
}

# A LAMMPS data file of the first frame of a terrace trajectory.xyz (extended XYZ: X x y z vx vy
# vz body; unwrapped Å, Å/ps), positions wrapped into the box [0, L)³.
write_data() {
    awk -v mass="$mass" 'NR == 1 { n = $1 }
        NR == 2 { match($0, /Lattice="[^ ]+/); L = substr($0, RSTART + 9, RLENGTH - 9) + 0
                  print "terrace trajectory.xyz, first frame, real units\n"; print n " atoms\n1 atom types\n"
                  printf "0 %.17g xlo xhi\n0 %.17g ylo yhi\n0 %.17g zlo zhi\n\nMasses\n\n1 %s\n\nAtoms # atomic\n\n", L, L, L, mass }
        NR > 2 && NR <= n + 2 { k++
            for (c = 2; c <= 4; c++) { p[c] = $c - L * int($c / L); if (p[c] < 0) p[c] += L; if (p[c] >= L) p[c] -= L }
            x[k] = sprintf("%.17g %.17g %.17g", p[2], p[3], p[4])
            v[k] = sprintf("%.17g %.17g %.17g", $5 / 1000, $6 / 1000, $7 / 1000) }
        NR > n + 2 { exit }
        END { for (i = 1; i <= k; i++) print i, 1, x[i]
              print "\nVelocities\n"
              for (i = 1; i <= k; i++) print i, v[i] }' "$1" >"$2"
}

# The first value of "key": in a summary.json.
json() { awk -v k="\"$1\":" '$1 == k { v = $2; sub(/,$/, "", v); print v; exit }' "$2"; }

# Block mean and standard error (8 contiguous blocks) of numbers on stdin, one per line.
block_stats() {
    awk '{ x[n++] = $1 } END {
        for (b = 0; b < 8; b++) {
            lo = int(b * n / 8); hi = int((b + 1) * n / 8); s = 0
            for (i = lo; i < hi; i++) s += x[i]
            m[b] = s / (hi - lo)
        }
        t = 0; for (i = 0; i < n; i++) t += x[i]; mean = t / n
        bm = 0; for (b = 0; b < 8; b++) bm += m[b]; bm /= 8
        v = 0; for (b = 0; b < 8; b++) v += (m[b] - bm) ^ 2
        printf "%.10g %.3g\n", mean, sqrt(v / 7 / 8) }'
}

rounds_csv=$out/rounds.csv
table_csv=$out/tabulated.csv
echo "n,round,terrace_steps_per_cpu_s,lammps_steps_per_cpu_s,ratio,terrace_cpu_s,lammps_cpu_s,steps,terrace_rebuilds,lammps_rebuilds" >"$rounds_csv"
echo "n,time_ps,steps,rounds,terrace_steps_per_cpu_s,lammps_steps_per_cpu_s,ratio_median,ratio_min,ratio_max,terrace_atom_steps_per_cpu_s,lammps_atom_steps_per_cpu_s,u_terrace,u_terrace_err,u_lammps,u_lammps_err,u_z,u_pass,t_terrace_k,t_lammps_k,gr_chi2,gr_bins,gr_max_z,gr_pass,table_points,table_max_du,table_u_bias,e0_lammps_minus_terrace,goal_1p5" >"$table_csv"

table=$out/table-$tablen.txt
write_table "$table"
read -r tab_max tab_bias <<<"$(table_error)"
echo "table: $tablen points in r² on [$rlo_a, $ru_a] Å; interpolation |δU| ≤ $tab_max ε beyond 0.85 σ, ⟨U⟩/N bias ≤ $tab_bias ε"

for n in $sizes; do
    read -r time_ps sample_fs <<<"$(plan "$n")"
    steps=$(calc "$time_ps * 1000 / $dt")
    usample=$(calc "$sample_fs / $dt")
    block=$(calc "$steps / 8")
    awk -v s="$steps" -v u="$usample" -v b="$block" 'BEGIN { exit !(s == int(s) && u == int(u) && b == int(b) && b % u == 0) }' ||
        { echo "N = $n: $steps steps must split into 8 blocks of whole samples of $usample steps" >&2; exit 1; }
    echo "N = $n: terrace equilibration $equil_ps ps, production $time_ps ps ($steps steps), dt $dt fs, sample $sample_fs fs"
    for k in $(seq 1 "$rounds"); do
        td=$out/n$n/round$k/terrace ld=$out/n$n/round$k/lammps
        rm -rf "$td" "$ld"; mkdir -p "$(dirname "$td")" "$ld"
        "$terrace" run "$scene" --set engine=smd --set seed=1 --set state.n="$n" \
            --set state.density="$rho" --set state.temperature="$tstar" --set body.mass="$mass" \
            --set potential.epsilon="$eps" --set potential.sigma="$sigma" \
            --set "potential.cutoff=[$rl,$ru]" --set smd.dt_fs="$dt" --set smd.skin="$skin" \
            --set smd.scheme=verlet --set run.equilibrate_ps="$equil_ps" \
            --set run.thermostat_fs="$thermostat_fs" --set run.time_ps="$time_ps" \
            --set run.sample_fs="$sample_fs" \
            --set output.trajectory_every_fs="$(calc "$time_ps * 1000")" --out "$td" >"$td.log" 2>&1 ||
            { echo "terrace failed, see $td.log" >&2; exit 1; }
        write_data "$td/trajectory.xyz" "$ld/data.lmp"
        (cd "$ld" && lmp -in "$here/in.lj-table" -log log.lammps -screen none \
            -var data data.lmp -var table "$table" -var key "$key" -var tablen "$tablen" \
            -var cutoff "$ru_a" -var skin "$skin_a" -var dt "$dt" -var prod "$steps" \
            -var sample $((k == 1)) -var blockevery "$usample" -var blocksteps "$block" \
            -var blockrepeat "$(calc "$block / $usample")" \
            -var rdfbins "$(calc "$ru / 0.05")") ||
            { echo "LAMMPS failed, see $ld/log.lammps" >&2; exit 1; }
        ts=$td/summary.json
        tcpu=$(json cpu_seconds "$ts") tsteps=$(json steps "$ts") trebuild=$(json neighbour_rebuilds "$ts")
        # LAMMPS: the first run is the timed production.
        read -r lcpu lsteps lrebuild <<<"$(awk '/^Loop time of/ { if (++r == 1) { w = $4; s = $9 } }
            /% CPU use/ { if (++c == 1) u = $1 + 0 }
            /^Neighbor list builds/ { if (++b == 1) nb = $5 }
            END { printf "%.6g %d %d\n", w * u / 100, s, nb }' "$ld/log.lammps")"
        [[ $tsteps == "$steps" && $lsteps == "$steps" ]] ||
            { echo "steps differ: terrace $tsteps, LAMMPS $lsteps, planned $steps" >&2; exit 1; }
        awk -v n="$n" -v k="$k" -v tc="$tcpu" -v lc="$lcpu" -v s="$steps" -v tb="$trebuild" -v lb="$lrebuild" 'BEGIN {
            t = s / tc; l = s / lc
            printf "%d,%d,%.1f,%.1f,%.3f,%.3f,%.3f,%d,%d,%d\n", n, k, t, l, t / l, tc, lc, s, tb, lb }' >>"$rounds_csv"
        tail -1 "$rounds_csv" | awk -F, '{ printf "  round %d: terrace %s steps/CPU s, LAMMPS %s, ratio %s (list builds %s and %s)\n", $2, $3, $4, $5, $9, $10 }'
    done

    # Agreement, round 1.
    td=$out/n$n/round1/terrace ld=$out/n$n/round1/lammps
    ut=$(json potential_energy_mean "$td/summary.json") ute=$(json potential_energy_err "$td/summary.json")
    tt=$(json temperature_K "$td/summary.json")
    # The total energy of the one state both start from, by each code's own model (terrace's
    # "energy": {"initial": ...} comes first in its summary.json): the table and units checked.
    e0t=$(json initial "$td/summary.json")
    e0l=$(awk '/^ *Step / { getline; print $5; exit }' "$ld/log.lammps")
    de0=$(awk -v a="$e0t" -v b="$e0l" -v n="$n" 'BEGIN { printf "%.2g", (b * 4.184 - a) / n }')
    # The sampled continuation is the second run: its thermo rows (step temp pe ke etotal).
    awk '/^ *Step / { blockno++; on = (blockno == 2); next } /^Loop time/ { on = 0 }
         on && NF == 5 && $1 ~ /^[0-9]+$/ { print $2, $3 }' "$ld/log.lammps" >"$ld/thermo.txt"
    read -r ul ule <<<"$(awk -v n="$n" '{ print $2 * 4.184 / n }' "$ld/thermo.txt" | block_stats)"
    tl=$(awk '{ s += $1 } END { printf "%.6g", s / NR }' "$ld/thermo.txt")
    read -r upb upt utm utme <<<"$(awk -v n="$n" -v a="$ut" -v ae="$ute" -v b="$ul" -v be="$ule" 'BEGIN {
        a /= n; ae /= n; z = (a - b) / sqrt(ae * ae + be * be)
        printf "%s %.3f %.8g %.3g\n", (z < 3 && z > -3) ? "pass" : "fail", z, a, ae }')"
    # g(r): LAMMPS's 8 blocks (rows: bin r g coord) against terrace's rdf.csv.
    read -r gchi gbins gmax gpass <<<"$(awk -F'[ ,]+' -v w=0.05 '
        FNR == 1 { file++ }
        file == 1 && FNR > 1 { k = int($1 / w); gt[k] = $2; et[k] = $3; next }
        file == 2 && /^#/ { next }
        file == 2 && NF == 2 { blk++; next }
        file == 2 { sub(/^ +/, ""); k = int($2 / w); s[k] += $3; s2[k] += $3 * $3; cnt[k]++ }
        END {
            for (k in cnt) {
                r = (k + 0.5) * w
                if (r < 0.9 - 1e-9 || r > 1.5 + 1e-9) continue
                m = s[k] / cnt[k]; v = (s2[k] / cnt[k] - m * m) * cnt[k] / (cnt[k] - 1)
                el = sqrt(v / cnt[k]); z = (gt[k] - m) / sqrt(et[k] ^ 2 + el ^ 2)
                chi += z * z; bins++; if (z * z > zmax * zmax) zmax = (z < 0 ? -z : z)
            }
            # 99.9 % point of chi-squared (Wilson-Hilferty), z = 3.090
            q = bins * (1 - 2 / (9 * bins) + 3.090 * sqrt(2 / (9 * bins))) ^ 3
            printf "%.2f %d %.2f %s\n", chi, bins, zmax, chi < q ? "pass" : "fail" }' \
        "$td/rdf.csv" "$ld/rdf.blocks")"
    awk -F, -v n="$n" -v tp="$time_ps" -v s="$steps" -v r="$rounds" \
        -v ut="$utm" -v ute="$utme" -v ul="$ul" -v ule="$ule" -v uz="$upt" -v up="$upb" \
        -v tt="$tt" -v tl="$tl" -v gc="$gchi" -v gb="$gbins" -v gm="$gmax" -v gp="$gpass" \
        -v tn="$tablen" -v tm="$tab_max" -v tbias="$tab_bias" -v de0="$de0" '
        function median(a, m,   i, j, x) { for (i = 1; i <= m; i++) for (j = i + 1; j <= m; j++)
            if (a[j] < a[i]) { x = a[i]; a[i] = a[j]; a[j] = x }
            return (m % 2) ? a[(m + 1) / 2] : 0.5 * (a[m / 2] + a[m / 2 + 1]) }
        $1 == n { m++; t[m] = $3; l[m] = $4; q[m] = $5 }
        END {
            mt = median(t, m); ml = median(l, m); mq = median(q, m); lo = q[1]; hi = q[m]
            printf "%d,%s,%d,%d,%.1f,%.1f,%.3f,%.3f,%.3f,%.4g,%.4g,%.6f,%.6f,%.6f,%.6f,%s,%s,%.2f,%.2f,%s,%s,%s,%s,%d,%s,%s,%s,%s\n",
                n, tp, s, r, mt, ml, mq, lo, hi, mt * n, ml * n, ut, ute, ul, ule, uz, up, tt, tl, gc, gb, gm, gp, tn, tm, tbias, de0,
                (mq >= 1.5 ? "met" : "not met") }' "$rounds_csv" >>"$table_csv"
    tail -1 "$table_csv" | awk -F, '{
        printf "N = %d: median steps/CPU s terrace %s, LAMMPS %s; ratio terrace/LAMMPS %s (rounds %s to %s); 1.5x goal %s\n", $1, $5, $6, $7, $8, $9, $28
        printf "  <U>/N (kJ/mol): terrace %s +- %s, LAMMPS %s +- %s, z = %s: %s; T: %s K and %s K\n", $12, $13, $14, $15, $16, $17, $18, $19
        printf "  g(r), first peak (%s bins, 0.9-1.5 sigma): chi2 = %s, max |z| = %s: %s\n", $21, $20, $22, $23
        printf "  E of the common start, LAMMPS - terrace: %s kJ/mol per body\n", $27 }'
done
echo "rounds: $rounds_csv; table: $table_csv"
