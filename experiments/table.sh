#!/usr/bin/env bash
# The paper's efficiency comparison ("Comparison between standard molecular dynamics and
# event-driven simulations"): collisions per ps and CPU s per simulated ps of DMD at each ΔV and of
# SMD (dt = 1.8 fs), and the efficiency ratio DMD/SMD = (CPU s/ps of SMD)/(CPU s/ps of DMD), for
# the dense rods and the gas (T* = 10, ρ* = 0.01). Means ± standard errors over the replica runs;
# the ratio's error adds the relative errors in quadrature.
#   table.sh efficiency | queues
# queues: DMD at ΔV = kT/2, dense: bounded priority queue vs binary heap vs tournament tree, lazy
# vs eager invalidation (paper: the bounded queue ≈ 15 % faster than a binary tree, not deleting
# stale events ≈ 15 % more).
source "$(dirname "$0")/common.sh"
what=$1
dir=$OUT/table
mkdir -p "$dir"

rows() { # rows STATE SET... : summary rows of the sets
    local state=$1
    shift
    "$TOOLS" summary-header
    for s in "$@"; do
        # shellcheck disable=SC2046
        "$TOOLS" summary "$state/$s" $(replica_dirs "$RUNS/$state/$s")
    done
}

case $what in
efficiency)
    for state in dense gas; do
        rows "$state" smd-1.8 dmd-2 dmd-1 dmd-0.5 dmd-0.25
    done | awk -F, -v OFS=, '
        NR == 1 { print $0, "efficiency_vs_smd", "efficiency_vs_smd_err"; next }
        $1 == "label" { next }
        { split($1, p, "/"); if (p[2] == "smd-1.8") { smd[p[1]] = $5; smdErr[p[1]] = $6 } row[++n] = $0 }
        END {
            for (k = 1; k <= n; ++k) {
                split(row[k], f, ","); split(f[1], p, "/")
                r = smd[p[1]] / f[5]
                e = r * sqrt((smdErr[p[1]] / smd[p[1]])^2 + (f[6] / f[5])^2)
                print row[k], r, e
            }
        }' >"$dir/efficiency.csv"
    awk -F, 'NR == 1 { print "| run | CPU s / ps | collisions / ps | events / ps | energy rel. fluct. | DMD/SMD efficiency |"; print "|---|---|---|---|---|---|"; next }
        { printf "| %s | %.3g ± %.2g | %.3g ± %.2g | %.3g | %.2g | %.3g ± %.2g |\n", $1, $5, $6, $7, $8, $9, $11, $17, $18 }' \
        "$dir/efficiency.csv" >"$dir/efficiency.md"
    ;;
queues)
    rows dense dmd-0.5-bpq dmd-0.5-heap dmd-0.5-tree dmd-0.5-bpq-eager dmd-0.5-heap-eager \
        dmd-0.5-tree-eager |
        awk -F, -v OFS=, 'NR == 1 { print $0, "cpu_relative_to_bpq_lazy"; next }
            NR == 2 { base = $5 } { print $0, $5 / base }' >"$dir/queues.csv"
    awk -F, 'NR == 1 { print "| queue, invalidation | CPU s / ps | relative to bpq + lazy |"; print "|---|---|---|"; next }
        { q = ($1 ~ /heap/) ? "binary heap" : ($1 ~ /tree/) ? "tournament tree" : "bounded priority queue"
          i = ($1 ~ /eager/) ? "eager" : "lazy"
          printf "| %s, %s | %.3g ± %.2g | %.3f |\n", q, i, $5, $6, $NF }' "$dir/queues.csv" >"$dir/queues.md"
    ;;
*) echo "table.sh: efficiency or queues" >&2; exit 2 ;;
esac
log "table $what done"
