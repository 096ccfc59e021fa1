#!/usr/bin/env bash
# What terrace sweep costs and how it scales (a benchmark, not part of `make all`):
#   sweep-bench.sh [SWEEP.json] [OUTDIR]       (default experiments/sweeps/bench.json, out/sweep-bench)
# Runs the sweep three times from scratch on this machine, best on an idle one:
#   serial   -j 1: the sweep's wall time against the sum of its runs' wall times (as the sweep
#            timed each from start to end): the overhead of planning, starting processes,
#            rewriting the table and noticing a run's end;
#   local    -j 2 on this machine's two cores: parallel efficiency T1 / (2 T2);
#   mpi      mpirun -np 2 (both ranks run): parallel efficiency the same way (if mpirun exists);
# then, from the serial runs' wall times, the throughput K ranks would reach, by replaying the
# sweep's dynamic hand-out (each run, in sweep order, to the first rank free) for K = 1 … 64.
# Writes OUTDIR/bench.txt.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
sweep=${1:-$here/sweeps/bench.json}
out=${2:-out/sweep-bench}
terrace=${TERRACE:-build/terrace}
mkdir -p "$out"

# timed NAME COMMAND...: wall seconds of COMMAND, the sweep output going to OUTDIR/NAME.
timed() {
    local name=$1 start end
    shift
    rm -rf "${out:?}/$name"
    start=$(date +%s.%N)
    "$@" --out "$out/$name" --quiet || [ $? -eq 1 ]
    end=$(date +%s.%N)
    awk -v a="$start" -v b="$end" 'BEGIN { printf "%.3f", b - a }'
}
# run_walls NAME: the runs' wall times from the sweep's table, in sweep order.
run_walls() {
    awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == "wall_seconds") c = i; next }
        { print $c }' "$out/$1/sweep.csv"
}

t1=$(timed serial "$terrace" sweep "$sweep" -j 1)
t2=$(timed local "$terrace" sweep "$sweep" -j 2)
tm=nan
if command -v mpirun >/dev/null; then
    export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
    tm=$(timed mpi mpirun --oversubscribe -np 2 "$terrace" sweep "$sweep" -j 1)
fi
sum=$(run_walls serial | awk '{ s += $1 } END { printf "%.3f", s }')
runs=$(run_walls serial | wc -l)
{
    echo "sweep: $sweep, $runs runs; $(nproc) cores, $(uname -n), $(date -u +%Y-%m-%dT%H:%MZ)"
    awk -v t1="$t1" -v s="$sum" -v n="$runs" 'BEGIN {
        printf "serial (-j 1): %.2f s wall, runs %.2f s in all: overhead %.2f s, %.2f %% (%.1f ms per run)\n",
               t1, s, t1 - s, 100 * (t1 - s) / t1, 1000 * (t1 - s) / n }'
    awk -v t1="$t1" -v t2="$t2" 'BEGIN {
        printf "local (-j 2): %.2f s wall, parallel efficiency %.3f\n", t2, t1 / (2 * t2) }'
    awk -v t1="$t1" -v t="$tm" 'BEGIN { if (t == "nan") print "mpi: no mpirun"
        else printf "mpi (mpirun -np 2): %.2f s wall, parallel efficiency %.3f\n", t, t1 / (2 * t) }'
    echo "throughput estimate, replaying the dynamic hand-out on the serial runs' wall times:"
    echo "ranks,makespan_s,efficiency,runs_per_hour"
    for k in 1 2 4 8 16 32 64; do
        run_walls serial | awk -v k="$k" '{ w[NR] = $1; s += $1 }
            END { for (r = 1; r <= k; ++r) free[r] = 0
                  for (i = 1; i <= NR; ++i) { b = 1
                      for (r = 2; r <= k; ++r) if (free[r] < free[b]) b = r
                      free[b] += w[i] }
                  m = 0; for (r = 1; r <= k; ++r) if (free[r] > m) m = free[r]
                  printf "%d,%.2f,%.3f,%.0f\n", k, m, s / (k * m), 3600 * NR / m }'
    done
} | tee "$out/bench.txt"
