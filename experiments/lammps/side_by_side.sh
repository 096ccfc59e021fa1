#!/usr/bin/env bash
# terrace SMD versus LAMMPS on the same input, timed in one run, alternating the two codes.
#
# Input (both codes): Lennard-Jones spheres, N = 512 from an 8^3 simple cubic lattice, ρ* = 0.5,
# T* = 1.4, smoothed between 2.5 and 3.0 σ, NVE, dt = 0.005 τ, Verlet skin 0.3 σ checked every
# step, 500 untimed steps to melt the lattice, then the timed production steps.
#   LAMMPS:  in.lj-smooth (pair_style lj/smooth 2.5 3.0, fix nve), serial `lmp` (Debian's lammps)
#   terrace: bench_smd's ljLammpsInput benchmark (the same state point and parameters)
# Each code runs ROUNDS times, alternately, so that a change in machine load hits both; the best
# round of each is compared. Reported: steps/s by CPU time (LAMMPS: loop time × its CPU use) and
# the ratio terrace/LAMMPS.
#   experiments/lammps/side_by_side.sh [BENCH_SMD] [ROUNDS] [STEPS]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
bench=${1:-$here/../../build/bench/bench_smd}
rounds=${2:-3}
steps=${3:-5000}
command -v lmp >/dev/null || { echo "no lmp: apt-get install lammps" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

lammps_rate() { # steps per CPU second of the production run
    (cd "$work" && lmp -in "$here/in.lj-smooth" -log none -var steps "$steps") |
        awk '/Loop time of/ { wall = $4; n = $9 } /% CPU use/ { cpu = $1 + 0 }
             END { printf "%.1f\n", n / (wall * cpu / 100) }'
}

terrace_rate() { # steps per CPU second; one benchmark iteration is one step
    "$bench" --benchmark_filter=ljLammpsInput --benchmark_format=csv 2>/dev/null |
        awk -F, '/ljLammpsInput/ { t = $4; u = $5; gsub(/"/, "", u)
                  s = (u == "ns") ? 1e-9 : (u == "us") ? 1e-6 : (u == "ms") ? 1e-3 : 1
                  printf "%.1f\n", 1 / (t * s) }'
}

best_l=0 best_t=0
for k in $(seq 1 "$rounds"); do
    l=$(lammps_rate) t=$(terrace_rate)
    echo "round $k: LAMMPS $l steps/s, terrace $t steps/s (CPU time)"
    best_l=$(awk -v a="$best_l" -v b="$l" 'BEGIN { print (b > a) ? b : a }')
    best_t=$(awk -v a="$best_t" -v b="$t" 'BEGIN { print (b > a) ? b : a }')
done
awk -v l="$best_l" -v t="$best_t" 'BEGIN {
    printf "best: LAMMPS %.0f steps/s (%.3g atom-steps/s), terrace %.0f steps/s (%.3g atom-steps/s)\n",
           l, l * 512, t, t * 512
    printf "ratio terrace/LAMMPS (CPU time): %.2f\n", t / l }'
