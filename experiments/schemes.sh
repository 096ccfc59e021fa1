#!/usr/bin/env bash
# The stability limit of each SMD splitting (smd/splitting.hpp) in the dense rod liquid (N = 216,
# ρ* = 0.5, T* = 1.4, one model): sweeps/schemes-stability.json runs every scheme over dt = 2 … 9
# fs, two seeds each, through `terrace sweep`; a setting is stable when both runs finish and their
# mean |energy drift| stays below 10⁻³ N kT per ps (fronts.sh's criterion). Writes OUT/schemes:
#   stability.csv   scheme, dt, runs finished, mean |drift| in N kT per ps, std(E)/|⟨U⟩|, stable
#   limits.csv      per scheme the largest stable dt, its force evaluations per ps
source "$(dirname "$0")/common.sh"
dir=$OUT/schemes
mkdir -p "$dir"
sweep=$EXPERIMENTS/sweeps/schemes-stability.json
if [ "$SIZE" = quick ]; then
    sets=(--set run.equilibrate_ps=0.036 --set run.time_ps=0.36)
else
    sets=()
fi
status=0
"$TERRACE" sweep "$sweep" --out "$RUNS/schemes" --quiet "${sets[@]}" || status=$?
[ "$status" -le 1 ] || { log "schemes: the sweep stopped (exit status $status)"; exit 1; }

# Columns of sweep.csv by name.
table=$RUNS/schemes/sweep.csv
awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
    { key = $c["smd.scheme"] "," $c["smd.dt_fs"]
      if (!(key in n)) { order[++m] = key; n[key] = 0; ok[key] = 0 }
      ++n[key]
      if ($c["status"] == "ok") {
          ++ok[key]
          kT = 8.314462618e-3 * $c["temperature_K"]
          d = $c["energy_drift_per_ps"]; if (d < 0) d = -d
          drift[key] += d / ($c["n_bodies"] * kT)
          fluct[key] += $c["energy_rel_fluct"]
      } }
    END { print "scheme,dt_fs,runs,finished,drift_nkt_per_ps,rel_fluct,stable"
          for (k = 1; k <= m; ++k) { key = order[k]
              f = ok[key] ? drift[key] / ok[key] : "nan"; r = ok[key] ? fluct[key] / ok[key] : "nan"
              stable = ok[key] == n[key] && f < 1e-3
              printf "%s,%d,%d,%.3g,%.3g,%d\n", key, n[key], ok[key], f, r, stable } }' \
    "$table" >"$dir/stability.csv"
# The largest dt below which every dt is stable, and what it costs in force evaluations.
awk -F, 'NR == 1 { next }
    { if (!($1 in seen)) { seen[$1] = 1; order[++m] = $1; broken[$1] = 0; limit[$1] = "nan" }
      if ($7 == 1 && !broken[$1]) limit[$1] = $2; else broken[$1] = 1 }
    END { print "scheme,largest_stable_dt_fs,force_evaluations_per_ps"
          for (k = 1; k <= m; ++k) { s = order[k]
              f = s == "verlet" ? 1 : s == "omelyan" ? 2 : 3
              printf "%s,%s,%.0f\n", s, limit[s], limit[s] == "nan" ? 0 : 1000 * f / limit[s] } }' \
    "$dir/stability.csv" >"$dir/limits.csv"
log "schemes done"
