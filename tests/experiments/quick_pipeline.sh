#!/usr/bin/env bash
# `make -f Makefile.paper quick` into a temporary directory, then checks that every figure and
# table was produced and that the numbers in them are sane (not their statistical values: the
# quick runs are far too short for those).
#   quick_pipeline.sh TERRACE PAPER_TOOLS SOURCE_DIR
set -euo pipefail
terrace=$1 tools=$2 src=$3
out=$(mktemp -d "${TMPDIR:-/tmp}/terrace-quick.XXXXXX")
trap 'rm -rf "$out"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

start=$(date +%s)
make -C "$src" -f Makefile.paper quick -j2 TERRACE="$terrace" TOOLS="$tools" QUICK_OUT="$out" \
    >"$out.log" 2>&1 || { tail -n 30 "$out.log" >&2; rm -f "$out.log"; fail "make quick failed"; }
rm -f "$out.log"
echo "make quick: $(($(date +%s) - start)) s"

for f in fig1/fig1.png fig2/fig2.png fig3/fig3.png fig4/fig4.png fig5/fig5.png \
    table/efficiency.csv table/queues.csv tradeoff/tradeoff-dense.png tradeoff/tradeoff-gas.png \
    density/density.png extremes/extremes.csv versus/versus.png versus/versus.txt machine.txt \
    runs.csv convergence/convergence.png convergence/convergence-rods.csv \
    convergence/convergence-lj.csv convergence/orders.csv designs/designs.png \
    designs/optimal-boltzmann.csv fronts/fronts-front-dense.png fronts/fronts-front-gas.png \
    fronts/equal-accuracy-front-dense.csv fronts/equal-accuracy-front-gas.csv \
    fronts/events-front-dense.csv map/map.png map/map.csv map/map-best.csv map/map-runs.csv \
    map/map-lj.png map/map-lj.csv map/map-lj-best.csv map/map-lj-runs.csv; do
    [ -s "$out/$f" ] || fail "missing or empty $f"
done
# PNG files start with the PNG signature.
for f in "$out"/*/*.png; do
    [ "$(head -c 4 "$f" | tail -c 3)" = PNG ] || fail "$f is not a PNG"
done

# Efficiency table: five settings for each state, positive costs, DMD energy conserved to
# round-off (the collision rule conserves it exactly; 1e-8 leaves room for summation error).
dmd_energy_limit=1e-8
awk -F, -v lim=$dmd_energy_limit 'NR > 1 {
        ++n; if (!($5 > 0)) { print "non-positive cost: " $1; bad = 1 }
        if ($2 == "dmd" && !($11 < lim)) { print "DMD energy not conserved: " $1 " " $11; bad = 1 }
        if ($2 == "dmd" && !($7 > 0) && $1 ~ /^dense/) { print "no collisions: " $1; bad = 1 }
    } END { if (n != 10) { print "expected 10 rows, got " n; bad = 1 } exit bad }' \
    "$out/table/efficiency.csv" || fail "efficiency table"

# Trade-off: eleven settings per state, the reference's own step among them with a finite error.
for s in dense gas; do
    [ "$(tail -n +2 "$out/tradeoff/tradeoff-$s.csv" | wc -l)" -eq 11 ] || fail "tradeoff-$s rows"
done
# Convergence: the reference and five ΔV per system, one order per quantity and system.
for s in rods lj; do
    [ "$(tail -n +2 "$out/convergence/convergence-$s.csv" | wc -l)" -eq 6 ] ||
        fail "convergence-$s rows"
done
[ "$(tail -n +2 "$out/convergence/orders.csv" | wc -l)" -eq 14 ] || fail "orders rows"
# Fronts (quick's ladders): 4 designs × 3 ΔV, 3 SMD steps and 2 other SMD schemes × 2 steps per
# state; equal accuracy for 4 designs × 5 quantities × 2 targets, against all SMD and the paper's
# alone.
for s in dense gas; do
    [ "$(tail -n +2 "$out/fronts/fronts-front-$s.csv" | wc -l)" -eq 19 ] || fail "fronts-$s rows"
    [ "$(tail -n +2 "$out/fronts/equal-accuracy-front-$s-verlet.csv" | wc -l)" -eq 40 ] ||
        fail "equal-accuracy-$s-verlet rows"
    [ "$(tail -n +2 "$out/fronts/equal-accuracy-front-$s.csv" | wc -l)" -eq 40 ] ||
        fail "equal-accuracy-$s rows"
done
# Map: 2 densities × 2 temperatures; per state 2 designs × 5 quantities × 2 targets, and the
# best design per state and quantity; the replica sets ran as sweeps.
for m in map map-lj; do
    [ "$(tail -n +2 "$out/map/$m.csv" | wc -l)" -eq 80 ] || fail "$m rows"
    [ "$(tail -n +2 "$out/map/$m-best.csv" | wc -l)" -eq 20 ] || fail "$m-best rows"
    awk -F, 'NR == 2 { exit !($1 > 0) }' "$out/map/$m-runs.csv" || fail "$m runs not counted"
done
[ -s "$out/runs/map-rho0.1-T10/dmd-1-mayfail/sweep.csv" ] || fail "no sweep.csv in a replica set"
# SMD schemes: 3 schemes × 8 steps, a limit per scheme.
[ "$(tail -n +2 "$out/schemes/stability.csv" | wc -l)" -eq 24 ] || fail "schemes stability rows"
[ "$(tail -n +2 "$out/schemes/limits.csv" | wc -l)" -eq 3 ] || fail "schemes limits rows"
# Every extreme combination is listed (finished or with its reason).
[ "$(tail -n +2 "$out/extremes/extremes.csv" | wc -l)" -eq 8 ] || fail "extremes rows"

# Fig. 1: V is an integer ≥ V_min = −2 within ½ of U wherever U ≥ −3/2 (the terraced surface).
awk -F, 'NF == 4 && NR > 1 {
        if ($4 < -2 || $4 != int($4)) bad = 1
        if ($3 >= -1.5 && ($4 - $3 > 0.5 + 1e-9 || $3 - $4 > 0.5 + 1e-9)) bad = 1
    } END { exit bad }' "$out/fig1/fig1.csv" || fail "fig1 terraces"
echo "quick pipeline OK"
