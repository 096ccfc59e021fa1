#!/usr/bin/env bash
# One set of replica runs, named by what it is (Makefile.paper has one target per set, so that
# `make -j` spreads the sets over the cores):
#   runset.sh STATE/ENGINE-PARAM[-OPTION...]    e.g. dense/dmd-0.5, dense/dmd-0.5-heap, rho0.1-T10/smd-1.8
#   STATE   dense | gas | rho<ρ*>-T<T*> (e.g. rho0.05-T1.4; rods as in dense-rods.json)
#           | conv-rods | conv-lj (convergence.sh: dense rods, LJ liquid; smoothed DMD model)
#           | front-dense | front-gas (fronts.sh: dense and gas rods; smoothed DMD model)
#           | map-rho<ρ*>-T<T*> | maplj-rho<ρ*>-T<T*> (map.sh: rods, LJ spheres at ρ*, T*;
#             smoothed DMD model)
#   ENGINE  dmd (PARAM = ΔV in kT) | smd (PARAM = dt in fs; Verlet skin tuned for the state by
#           smd-skin.sh)
#   OPTION  heap | bpq | tree | eager (DMD queue and invalidation, default tree + lazy)
#           optimal | virial | boltzmann | distance | volume (DMD terrace design, default the
#                    paper's uniform levels and midpoints; fronts.sh)
#           omelyan | yoshida4 (SMD splitting, default the paper's verlet; fronts.sh)
#           mayfail (a failed run marks the set FAILED instead of stopping make: unstable
#                    settings are a result of the trade-off, not an error of the pipeline;
#                    in the dense and gas states such sets run TRADE_PS)
#           ref (the trade-off's converged reference: REF_PS_FACTOR times longer, seeds 101…)
# Runs land in $RUNS/STATE/ENGINE-PARAM[-OPTION...]/seed-K; the set's replica means of rdf.csv,
# vacf.csv and oacf.csv go beside them (mean-rdf.csv, ...), and a run that wrote a trajectory gets
# its configurational.json (paper_tools configurational).
source "$(dirname "$0")/common.sh"
id=$1
state=${id%%/*}
IFS=- read -r engine param options_text <<<"${id#*/}"
read -r -a options <<<"${options_text//-/ }"

state_point "$state"
scene=$STATE_SCENE n=$STATE_N ps=$STATE_PS sets=("${STATE_SETS[@]}")
case $state in
rho*-T*) REPLICAS=$SCAN_REPLICAS ;;
conv-*) REPLICAS=$CONV_REPLICAS ;;
front-*) REPLICAS=$FRONT_REPLICAS ;;
map-* | maplj-*) REPLICAS=$MAP_REPLICAS ;;
esac
grid=$SAMPLE_FS # the run's sample and thermostat interval, fs
case $engine in
dmd) sets+=(--set engine=dmd --set dmd.dV="$param") ;;
smd)
    skin=$(smd_skin "$state")
    sets+=(--set engine=smd --set smd.dt_fs="$param" --set smd.skin="$skin")
    # Samples and thermostat on SMD's grid: the whole number of steps nearest SAMPLE_FS (9 fs at
    # dt = 0.2 ... 3 fs; 8 fs at 4 fs), as the run itself once rounded them and now refuses to.
    grid=$(awk -v s="$SAMPLE_FS" -v d="$param" \
        'BEGIN { k = int(s / d + 0.5); if (k < 1) k = 1; printf "%.10g", k * d }')
    sets+=(--set run.sample_fs="$grid" --set run.thermostat_fs="$grid")
    ;;
*) echo "runset.sh: unknown engine '$engine'" >&2; exit 2 ;;
esac
mayfail=0
for o in "${options[@]}"; do
    case $o in
    mayfail) mayfail=1 ;;
    heap | bpq | tree) sets+=(--set dmd.queue="$o") ;;
    # Terrace designs (dmd/terrace_design.hpp) over the same ΔV ladder: n levels in the well as
    # uniform levels of height ΔV put there (at least 2).
    optimal) sets+=(--set 'dmd.terraces={"levels":"optimal"}') ;;
    virial | boltzmann) sets+=(--set "dmd.terraces={\"levels\":\"energy\",\"values\":\"$o\"}") ;;
    distance | volume) sets+=(--set "dmd.terraces={\"levels\":\"$o\",\"values\":\"boltzmann\"}") ;;
    eager) sets+=(--set dmd.invalidation=eager) ;;
    omelyan | yoshida4) sets+=(--set smd.scheme="$o") ;; # SMD splitting (smd/splitting.hpp)
    ref)
        ps=$(awk -v p="$ps" -v f="$REF_PS_FACTOR" 'BEGIN{print p*f}')
        # Seeds of its own: a reference run from the same start as the run it judges would share
        # its noise and flatter it (most of all SMD at another dt, whose trajectory stays close).
        SEED_OFFSET=100
        ;;
    *) echo "runset.sh: unknown option '$o'" >&2; exit 2 ;;
    esac
done

# The trade-off's extra settings are shorter: their errors carry their own statistical floor.
if [ "$mayfail" = 1 ] && { [ "$state" = dense ] || [ "$state" = gas ]; }; then ps=$TRADE_PS; fi

# on_grid PS: the whole number of grid intervals nearest PS, in ps. terrace runs exactly the
# lengths asked for and refuses any that is not a whole number of samples (of thermostat
# intervals, for the equilibration). common.sh's lengths are whole numbers of SAMPLE_FS and so
# pass unchanged on that grid; SMD at dt = 4 fs samples every 8 fs, where they move by < 4 fs.
on_grid() {
    awk -v p="$1" -v g="$grid" 'BEGIN { k = int(p * 1000 / g + 0.5); if (k < 1) k = 1
        printf "%.10g", k * g / 1000 }'
}
ps=$(on_grid "$ps")
equilibrate=$(on_grid "$STATE_EQUIL_PS")

dir=$RUNS/$id
rc=0
run_replicas "$dir" "$scene" --set state.n="$n" --set run.equilibrate_ps="$equilibrate" \
    --set run.time_ps="$ps" "${sets[@]}" || rc=$?
if [ "$rc" -ne 0 ]; then
    [ "$rc" -eq 1 ] && [ "$mayfail" = 1 ] || exit 1
    # The reason is the failed run's own message, kept for the tables.
    cut -c1-300 "$dir/failures.txt" | tr "\n" " " >"$dir/FAILED"
    log "runset $id FAILED (recorded)"
    exit 0
fi
# Only now: a set that failed before and completes this time is no longer failed (removed after
# the sweep, which holds the set's lock, so that a second make on the same set cannot drop a
# failure it is recording).
rm -f "$dir/FAILED"
# Spheres have no OACF: a curve the runs did not write has no mean.
for f in rdf vacf oacf; do
    if [ -s "$(replica_dirs "$dir" | head -n 1)/$f.csv" ]; then
        mean_curve "$dir" $f.csv "$dir/mean-$f.csv"
    fi
done
# Sets that wrote a trajectory (convergence.sh's): the continuous model's U and P on each run's
# configurations.
for d in $(replica_dirs "$dir"); do
    if [ -s "$d/trajectory.xyz" ] && [ ! -s "$d/configurational.json" ]; then
        "$TOOLS" configurational "$d" >"$d/configurational.json.partial"
        mv "$d/configurational.json.partial" "$d/configurational.json"
    fi
done
log "runset $id done"
