#!/usr/bin/env bash
# Numerical stability at the extremes (beyond the paper): DMD runs of the rods at every combination
# of ΔV ∈ {0.05, 8} kT, T* ∈ {0.5, 50} and ρ* ∈ {0.001, 0.8}: does the run finish, how well is the
# energy conserved (max |E(t) − E(0)| relative to |⟨U⟩|, and the paper's std(E)/|⟨U⟩|), how many
# events and collisions per ps. One run each (seed 1), N = EXTREME_N, short. Energy: the largest
# |E(t) − E(0)| relative to |⟨E⟩| (the terraced ⟨U⟩ can be exactly 0 when ΔV is large), and the
# paper's std(E)/|⟨U⟩| (infinite or undefined when ⟨U⟩ = 0).
#   extremes.sh run dV<ΔV>-T<T*>-rho<ρ*>     one run (a failure is recorded, not fatal)
#   extremes.sh table                        the table of all combinations
source "$(dirname "$0")/common.sh"
dir=$OUT/extremes
case $1 in
run)
    id=$2
    dV=${id#dV}; dV=${dV%%-*}
    T=${id#*-T}; T=${T%%-*}
    rho=${id##*-rho}
    run_dir=$RUNS/extremes/$id
    rm -f "$run_dir.failed"
    run_one "$run_dir" "$SCENES/dense-rods.json" --set engine=dmd --set dmd.dV="$dV" \
        --set state.temperature="$T" --set state.density="$rho" --set state.n="$EXTREME_N" \
        --set run.equilibrate_ps="$EXTREME_EQUIL_PS" --set run.time_ps="$EXTREME_PS" \
        --set run.sample_fs="$EXTREME_SAMPLE_FS" ||
        { tail -n 2 "$run_dir.partial.log" | tr -d ',' | tr '\n' ' ' >"$run_dir.failed"; }
    ;;
table)
    mkdir -p "$dir"
    table=$dir/extremes.csv
    echo "dV_kT,T,rho,finished,simulated_ps,cpu_s,events_per_ps,collisions_per_ps,energy_max_dev_rel_E,energy_rel_fluct,note" >"$table"
    for dV in 0.05 8; do for T in 0.5 50; do for rho in 0.001 0.8; do
        run_dir=$RUNS/extremes/dV$dV-T$T-rho$rho
        if [ -s "$run_dir/summary.json" ]; then
            "$TOOLS" get "$run_dir/summary.json" interrupted simulated_ps cpu_seconds events.total \
                collisions_per_ps energy.max_abs_dev energy.mean energy.rel_fluct |
                awk -F, -v OFS=, -v dV="$dV" -v T="$T" -v rho="$rho" '{
                    u = $7 < 0 ? -$7 : $7
                    print dV, T, rho, ($1 == 1 ? "interrupted" : "yes"), $2, $3, ($2 > 0 ? $4 / $2 : "nan"), $5,
                          (u > 0 ? $6 / u : "nan"), $8, ""
                }' >>"$table"
        else
            echo "$dV,$T,$rho,no,nan,nan,nan,nan,nan,nan,$(cat "$run_dir.failed" 2>/dev/null | cut -c1-200)" >>"$table"
        fi
    done; done; done
    awk -F, 'NR == 1 { print "| ΔV/kT | T* | ρ* | finished | events/ps | collisions/ps | max ΔE / ⟨E⟩ | std E / ⟨U⟩ | note |"; print "|---|---|---|---|---|---|---|---|---|"; next }
        { printf "| %s | %s | %s | %s | %.3g | %.3g | %.2g | %.2g | %s |\n", $1, $2, $3, $4, $7, $8, $9, $10, $11 }' "$table" >"$dir/extremes.md"
    log "extremes table done"
    ;;
*) echo "extremes.sh run ID | table" >&2; exit 2 ;;
esac
