#!/usr/bin/env bash
# Cost and memory from 512 to a million bodies, both engines, rods and LJ spheres (issue of
# scaling; results/scaling/README.md). One whole `terrace run` per row, started from the lattice,
# 0.09 ps of equilibration, then about 921.6 body-ps / N of production (1.8 ps at N 512, at
# least 5 sample intervals: 0.045 ps) at 9 fs samples, with the default analysis:
#   DMD    µs of engine CPU per event          (cpu_seconds / events.total)
#   SMD    µs of engine CPU per body-step      (cpu_seconds / (steps · N))
#   both   analysis CPU per sample (ms) and its share of engine + analysis CPU,
#          peak resident memory per body (GNU time's maximum RSS / N), whole-run wall seconds
# DMD runs once per queue of QUEUES (default: tree, the default dmd.queue; e.g.
# QUEUES="tree heap bpq" to compare them by N), for each model of MODELS (default: rods lj).
#   [QUEUES=…] [MODELS=…] experiments/scaling.sh [TERRACE] [OUT] [N ...]
# Writes OUT/scaling.csv (default results/scaling). Machine time: ~40 min on a quiet 2-core box.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
terrace=${1:-$here/../build/terrace}
out=${2:-$here/../results/scaling}
shift $(($# < 2 ? $# : 2))
sizes=${*:-512 4096 32768 262144 1000000}
# Production in ps for N bodies: whole 9 fs samples, about 921.6 body-ps, at least 5 intervals.
prod_ps() { awk -v n="$1" 'BEGIN { s = int(921.6 / n / 0.009); if (s < 5) s = 5; printf "%.3f", s * 0.009 }'; }
[ -x /usr/bin/time ] || { echo "scaling.sh needs GNU time (apt-get install time)" >&2; exit 1; }
mkdir -p "$out"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
csv=$out/scaling.csv
echo "model,engine,queue,n,cpu_s,events_or_steps,us_per_event_or_body_step,analysis_cpu_s,samples,analysis_ms_per_sample,analysis_share,peak_rss_kb,bytes_per_body,wall_s" >"$csv"

row() { # model scene engine queue n
    local model=$1 scene=$2 engine=$3 queue=$4 n=$5 dir=$work/run
    rm -rf "$dir"
    /usr/bin/time -f "%M %e" -o "$work/time" "$terrace" run "$here/scenes/$scene" --quiet \
        --set engine="$engine" --set dmd.queue="$queue" --set state.n="$n" \
        --set run.equilibrate_ps=0.09 --set run.time_ps="$(prod_ps "$n")" --set run.sample_fs=9 \
        --set run.thermostat_fs=9 --set output.thermo_every_fs=0 --out "$dir" >/dev/null
    read -r rss wall <"$work/time"
    python3 - "$dir/summary.json" "$model" "$engine" "$queue" "$n" "$rss" "$wall" >>"$csv" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
model, engine, queue, n, rss, wall = sys.argv[2], sys.argv[3], sys.argv[4], int(sys.argv[5]), float(sys.argv[6]), float(sys.argv[7])
cpu = s["cpu_seconds"]
if engine == "dmd":
    count = s["events"]["total"]
    per = 1e6 * cpu / count
else:
    count = s["steps"] * n
    per = 1e6 * cpu / count
a = s.get("analysis_cpu_seconds", 0.0)
samples = s["samples"]
print(f"{model},{engine},{queue if engine == 'dmd' else ''},{n},{cpu:.4g},{count},{per:.4g},"
      f"{a:.4g},{samples},{1e3 * a / samples:.4g},{a / (a + cpu):.3f},{rss:.0f},"
      f"{1024 * rss / n:.0f},{wall:.1f}")
PY
    tail -1 "$csv"
}

for n in $sizes; do
    for model in ${MODELS:-rods lj}; do
        case $model in
        rods) scene=dense-rods.json ;;
        lj) scene=lj-liquid.json ;;
        *) echo "scaling.sh: no model '$model' (rods, lj)" >&2; exit 1 ;;
        esac
        row $model $scene smd tree "$n"
        for queue in ${QUEUES:-tree}; do
            row $model $scene dmd "$queue" "$n"
        done
    done
done
echo "wrote $csv"
