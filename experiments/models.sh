#!/usr/bin/env bash
# The models beyond the paper's rods (experiments/scenes: gay-berne-liquid, dumbbell-liquid,
# triatomic-liquid), each in both engines on its one smoothed model: DMD at ΔV = kT/2 and kT/8,
# SMD at 1.8 fs, two seeds each, through `terrace sweep` (sweeps/models-*.json). Writes
# OUT/models/models.csv: per model and setting the mean over seeds of ⟨U⟩/N (kJ/mol), P*, T (K),
# collisions per ps, CPU seconds per simulated ps, and that cost over SMD's.
source "$(dirname "$0")/common.sh"
dir=$OUT/models
mkdir -p "$dir"
if [ "$SIZE" = quick ]; then
    sets=(--set run.equilibrate_ps=0.09 --set run.time_ps=0.18)
else
    sets=()
fi
out=$dir/models.csv
echo "model,engine,setting,runs,u_per_body_kJ_per_mol,pressure_reduced,temperature_K,collisions_per_ps,cpu_seconds_per_ps,cost_over_smd" >"$out"
for model in gay-berne dumbbell triatomic; do
    status=0
    "$TERRACE" sweep "$EXPERIMENTS/sweeps/models-$model.json" --out "$RUNS/models-$model" \
        --quiet "${sets[@]}" || status=$?
    [ "$status" -le 1 ] || { log "models: the $model sweep stopped (exit status $status)"; exit 1; }
    awk -F, -v model="$model" 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
        $c["status"] == "ok" {
            key = $c["engine"] "," ($c["engine"] == "dmd" ? "dV " $c["dmd.dV"] " kT" : "dt " $c["smd.dt_fs"] " fs")
            if (!(key in n)) order[++m] = key
            ++n[key]; u[key] += $c["potential_energy_kJ_per_mol"] / $c["n_bodies"]
            p[key] += $c["pressure_reduced"]; t[key] += $c["temperature_K"]
            coll[key] += $c["collisions_per_ps"]; cost[key] += $c["cpu_seconds_per_ps"]
            if ($c["engine"] == "smd") smd = key }
        END { for (k = 1; k <= m; ++k) { key = order[k]; x = n[key]
                  printf "%s,%s,%d,%.4f,%.4f,%.1f,%s,%.4g,%.3g\n", model, key, x, u[key] / x,
                      p[key] / x, t[key] / x, key ~ /^smd/ ? "" : sprintf("%.4g", coll[key] / x),
                      cost[key] / x, (cost[key] / x) / (cost[smd] / n[smd]) } }' \
        "$RUNS/models-$model/sweep.csv" >>"$out"
done
log "models done"
