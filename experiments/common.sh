# Shared by the figure and table scripts (sourced, not run). Environment, set by Makefile.paper:
#   TERRACE      the terrace executable            TOOLS  the paper_tools executable
#   OUT          where results go (results/)       SIZE   full | quick (tiny, short runs)
# Every run lands in its own directory, so that parallel make jobs never share a file. Replica
# sets run as `terrace sweep`s (run_replicas): a run is reused only when its directory holds the
# complete result of the same scene, so an interrupted run is continued or redone, never reused;
# single runs (run_one) are written under a temporary name and renamed when complete.
set -euo pipefail
: "${TERRACE:?TERRACE must name the terrace executable}"
: "${TOOLS:?TOOLS must name the paper_tools executable}"
: "${OUT:?OUT must name the output directory}"
SIZE=${SIZE:-full}
EXPERIMENTS=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
SCENES=$EXPERIMENTS/scenes
RUNS=$OUT/runs

# Run sizes. "full" is sized so that `make -f Makefile.paper all` stays within an hour on two
# cores (results/runs.md lists the measured costs); "quick" only exercises the pipeline.
# Every length is a whole number of the intervals of its runs, as terrace requires: of SAMPLE_FS
# (9 fs: samples and thermostat) for the run sets and the skin trials (runset.sh moves them onto
# SMD's own grid where that is another, 8 fs at dt = 4 fs), of EXTREME_SAMPLE_FS for the
# extremes' production and of the scene's 9 fs thermostat for their equilibration. They are the
# lengths that the round numbers once asked for (1, 6, 20, 3 ps; quick 0.1, 0.4, 0.3 ps) were cut
# to, to the last whole interval, before lengths were checked: the runs results/ was made with.
if [ "$SIZE" = quick ]; then
    REPLICAS=2          # the least that gives an error bar
    DENSE_N=216         # the smallest cube whose box holds two SMD cutoffs at rho* = 0.5
    GAS_N=64
    EQUIL_PS=0.099      # 11 thermostat intervals of 9 fs
    DENSE_PS=0.396      # 44 samples
    GAS_PS=0.396
    TRADE_PS=0.396      # the trade-off's extra settings
    REF_DT_FS=${REF_DT_FS:-0.5} # converged reference of the trade-off (Makefile.paper sets it)
    REF_PS_FACTOR=1
    SCAN_PS=0.297       # density scan
    SCAN_REPLICAS=2
    EXTREME_N=216       # a box that holds two interaction ranges at ΔV = 0.05 kT, ρ* = 0.8
    EXTREME_EQUIL_PS=0.009 # one thermostat interval (the scene's 9 fs)
    EXTREME_PS=0.04
    EXTREME_SAMPLE_FS=2 # 21 samples: enough for the correlation files' 8 blocks
    SKIN_TRIAL_PS=0.099 # each trial run of smd-skin.sh
    CONV_REPLICAS=2     # convergence.sh (states conv-rods, conv-lj)
    CONV_RODS_N=216
    CONV_LJ_N=256       # the least whose box (ρ* = 0.8) holds two SMD cutoffs and a skin
    CONV_EQUIL_PS=0.099
    CONV_RODS_PS=0.198
    CONV_LJ_PS=0.198
    FRONT_REPLICAS=2    # fronts.sh (states front-dense, front-gas)
    FRONT_N=216
    FRONT_EQUIL_PS=0.099
    FRONT_PS=0.198
    MAP_REPLICAS=2      # map.sh (states map-rho<ρ*>-T<T*>)
    MAP_N=64
    MAP_EQUIL_PS=0.099
    MAP_PS=0.198
    MAP_LJ_PS=0.198
else
    REPLICAS=4
    DENSE_N=512
    GAS_N=512
    EQUIL_PS=0.999      # 111 thermostat intervals of 9 fs
    DENSE_PS=5.994      # 666 samples
    GAS_PS=19.998       # 2222 samples
    TRADE_PS=2.997      # the trade-off's extra settings (ΔV = ⅛ kT alone costs ~14 CPU s/ps)
    REF_DT_FS=${REF_DT_FS:-0.2}
    REF_PS_FACTOR=2
    SCAN_PS=2.997
    SCAN_REPLICAS=2     # the scan compares costs; two runs bound their spread
    EXTREME_N=216
    EXTREME_EQUIL_PS=0.045 # 5 thermostat intervals; ΔV = 0.05 kT (dense) costs minutes per ps
    EXTREME_PS=0.2
    EXTREME_SAMPLE_FS=5
    SKIN_TRIAL_PS=0.999
    # convergence.sh: DMD at ΔV = ⅛ kT is the dearest set (~3 CPU s/ps for the rods, ~12 for
    # the LJ liquid), then the SMD reference at 0.2 fs (~2 and ~1 CPU s/ps), REF_PS_FACTOR longer.
    CONV_REPLICAS=4
    CONV_RODS_N=512     # the paper's dense state as the other figures run it
    CONV_LJ_N=256
    CONV_EQUIL_PS=0.9   # 100 thermostat intervals
    CONV_RODS_PS=5.4    # 600 samples
    CONV_LJ_PS=2.7      # 300 samples, 27 LJ time units (τ = σ sqrt(m/ε) = 100 fs there)
    # fronts.sh: every design over ΔV = 2 … ⅛ kT and SMD over its dt ladder, both states, at the
    # smallest N whose dense box holds two SMD cutoffs; the SMD reference REF_PS_FACTOR longer.
    FRONT_REPLICAS=4
    FRONT_N=216
    FRONT_EQUIL_PS=0.9  # 100 thermostat intervals
    FRONT_PS=3.6        # 400 samples
    # map.sh: the fronts of uniform and virial levels and SMD at every state point of the map,
    # as long as fronts.sh's (21 state points: ~0.3 CPU h in all).
    MAP_REPLICAS=4
    MAP_N=216
    MAP_EQUIL_PS=0.45   # 50 thermostat intervals
    MAP_PS=3.6          # 400 samples
    MAP_LJ_PS=1.8       # the LJ map: 18 LJ time units (τ = 100 fs), its DMD at ⅛ kT dearer
fi
# convergence.sh's sets write a trajectory frame this often (fs), for the continuous model's U
# and P on their configurations (paper_tools configurational).
CONV_TRAJECTORY_FS=45

# Sample interval of every run, fixed here rather than taken from the scenes: a whole number of
# SMD steps at dt = 0.2, 0.5, 1, 1.8 and 3 fs, so that all curves of one figure share one grid.
SAMPLE_FS=9

log() { echo "[$(date +%H:%M:%S)] $*" >&2; }

# state_point STATE : the scene and settings of a state of runset.sh, in STATE_SCENE, STATE_N,
# STATE_PS (production ps), STATE_EQUIL_PS and the array STATE_SETS (--set options on top of the
# scene).
state_point() {
    STATE_EQUIL_PS=$EQUIL_PS
    case $1 in
    dense) STATE_SCENE=$SCENES/dense-rods.json STATE_N=$DENSE_N STATE_PS=$DENSE_PS STATE_SETS=() ;;
    gas) STATE_SCENE=$SCENES/gas-rods.json STATE_N=$GAS_N STATE_PS=$GAS_PS STATE_SETS=() ;;
    rho*-T*)
        local rho=${1#rho} temp=${1##*-T}
        rho=${rho%%-T*}
        STATE_SCENE=$SCENES/dense-rods.json STATE_N=$DENSE_N STATE_PS=$SCAN_PS
        STATE_SETS=(--set state.density="$rho" --set state.temperature="$temp")
        ;;
    # convergence.sh: one model for both engines (DMD terraces g(r)·U, dmd.model = smoothed);
    # a trajectory for the continuous model's U and P on the configurations.
    conv-rods | conv-lj)
        STATE_SETS=(--set dmd.model=smoothed
            --set output.trajectory_every_fs="$CONV_TRAJECTORY_FS")
        STATE_EQUIL_PS=$CONV_EQUIL_PS
        if [ "$1" = conv-rods ]; then
            STATE_SCENE=$SCENES/dense-rods.json STATE_N=$CONV_RODS_N STATE_PS=$CONV_RODS_PS
        else
            STATE_SCENE=$SCENES/lj-liquid.json STATE_N=$CONV_LJ_N STATE_PS=$CONV_LJ_PS
        fi
        ;;
    # fronts.sh: one model for both engines, the paper's two states.
    front-dense | front-gas)
        STATE_SETS=(--set dmd.model=smoothed)
        STATE_EQUIL_PS=$FRONT_EQUIL_PS STATE_N=$FRONT_N STATE_PS=$FRONT_PS
        if [ "$1" = front-dense ]; then
            STATE_SCENE=$SCENES/dense-rods.json
        else
            STATE_SCENE=$SCENES/gas-rods.json
        fi
        ;;
    # map.sh: one model, the dense rods' scene at another density and temperature.
    map-rho*-T*)
        local rho=${1#map-rho} temp=${1##*-T}
        rho=${rho%%-T*}
        STATE_SCENE=$SCENES/dense-rods.json STATE_N=$MAP_N STATE_PS=$MAP_PS
        STATE_EQUIL_PS=$MAP_EQUIL_PS
        STATE_SETS=(--set dmd.model=smoothed --set state.density="$rho"
            --set state.temperature="$temp")
        ;;
    # The same for the Lennard-Jones spheres of lj-liquid.json.
    maplj-rho*-T*)
        local rho=${1#maplj-rho} temp=${1##*-T}
        rho=${rho%%-T*}
        STATE_SCENE=$SCENES/lj-liquid.json STATE_N=$MAP_N STATE_PS=$MAP_LJ_PS
        STATE_EQUIL_PS=$MAP_EQUIL_PS
        STATE_SETS=(--set state.density="$rho" --set state.temperature="$temp")
        ;;
    *) echo "unknown state '$1'" >&2; return 2 ;;
    esac
}

# smd_skin STATE : SMD's Verlet skin for the state (σ), chosen once by smd-skin.sh; parallel run
# sets of one state wait for the first to choose it.
smd_skin() {
    mkdir -p "$RUNS/$1"
    flock "$RUNS/$1/smd-skin.lock" "$EXPERIMENTS/smd-skin.sh" "$1"
    cat "$RUNS/$1/smd-skin"
}

# The analysis settings of every run here: g(r) out to L/2 from every sample, and the first
# 128 lags (1.15 ps at 9 fs, past every curve distance measured here) on one uniform grid with
# every time origin, so that the curves and their distances are those of the all-origins
# analysis the committed results were made with (run_analysis.hpp: exact below p lags). No
# thermo.csv (written by default since): the committed runs wrote none, and their resolved scenes
# stay the same.
PAPER_ANALYSIS=(--set analysis.rdf_every=1 --set analysis.rdf_max=0 --set analysis.lags_per_level=128
    --set output.thermo_every_fs=0)

# run_one DIR SCENE [--set key=value]... : one run, skipped when DIR already holds its summary.
run_one() {
    local dir=$1 scene=$2
    shift 2
    if [ -s "$dir/summary.json" ]; then return 0; fi
    local partial="$dir.partial"
    rm -rf "$partial"
    mkdir -p "$(dirname "$dir")"
    log "run $dir"
    local rc=0
    "$TERRACE" run "$scene" --quiet --out "$partial" "${PAPER_ANALYSIS[@]}" "$@" >"$partial.log" 2>&1 || rc=$?
    if [ "$rc" -ne 0 ]; then
        # A crash leaves no message of its own; the exit status (128 + signal) is then the record.
        [ "$rc" -gt 128 ] && echo "terrace killed by signal $((rc - 128)) (exit status $rc)" >>"$partial.log"
        log "FAILED $dir (see $partial.log)"
        return 1
    fi
    rm -rf "$dir"
    mv "$partial" "$dir"
    mv "$partial.log" "$dir/run.log"
}

# run_replicas DIR SCENE [--set ...]... : REPLICAS independent runs DIR/seed-K, seeds from
# SEED_OFFSET + 1 (offset 0 unless set), as one `terrace sweep` (DIR/sweep.json, its table
# DIR/sweep.csv; a run done before for the same scene is not run again). A failed run is a
# result, not a reason to stop: its seed and the engine's message go to DIR/failures.txt and the
# sweep is run again with one more seed per failure, up to 2 × REPLICAS seeds in all; the set
# fails (status 1) only when fewer than REPLICAS runs complete; a sweep that stops (a signal,
# another sweep holding DIR) returns 2.
#   SWEEP_LAUNCH  prefix of the sweep command, e.g. "mpirun -np 4" to spread a set's replicas
#                 over MPI ranks on a cluster (default: none)
#   SWEEP_JOBS    runs at once in the sweep's own process (default 1; 0 under mpirun: rank 0
#                 then only hands out)
run_replicas() {
    local dir=$1 scene=$2
    shift 2
    local seeds=$REPLICAS done status first=$((${SEED_OFFSET:-0} + 1))
    mkdir -p "$dir"
    while true; do
        printf '{"scene": "%s", "seeds": [%s]}\n' "$(realpath "$scene")" \
            "$(seq -s, "$first" $((first + seeds - 1)))" >"$dir/sweep.json"
        log "sweep $dir ($seeds seeds)"
        status=0
        # shellcheck disable=SC2086
        ${SWEEP_LAUNCH:-} "$TERRACE" sweep "$dir/sweep.json" --out "$dir" --quiet \
            -j "${SWEEP_JOBS:-1}" --set run.sample_fs="$SAMPLE_FS" "${PAPER_ANALYSIS[@]}" "$@" || status=$?
        # 0: every run done; 1: some failed (recorded); anything else (a signal, another sweep
        # holding the set) stops the set with status 2: not a result, whatever mayfail says.
        [ "$status" -le 1 ] || { log "sweep $dir stopped (exit status $status)"; return 2; }
        done=$(awk -F, 'NR > 1 && $3 == "ok"' "$dir/sweep.csv" | wc -l)
        sweep_failures "$dir" >"$dir/failures.txt"
        [ "$done" -lt "$REPLICAS" ] && [ "$seeds" -lt $((2 * REPLICAS)) ] || break
        seeds=$((seeds + REPLICAS - done))
        [ "$seeds" -le $((2 * REPLICAS)) ] || seeds=$((2 * REPLICAS))
    done
    [ -s "$dir/failures.txt" ] || rm -f "$dir/failures.txt"
    [ "$done" -ge "$REPLICAS" ]
}

# sweep_failures DIR : "seed-K: message" for each failed run of DIR (its FAILED.json).
sweep_failures() {
    local d
    for d in "$1"/seed-*; do
        [ -s "$d/FAILED.json" ] || continue
        echo "$(basename "$d"): $(sed -n 's/^  "error": "\(.*\)",\{0,1\}$/\1/p' "$d/FAILED.json")"
    done
}

# replica_dirs DIR : the completed replica directories of DIR, one per line: those with a
# summary and no recorded failure (a run that failed keeps its directory, with FAILED.json).
replica_dirs() {
    local d
    for d in "$1"/seed-*; do
        case $d in *.partial | *.log) continue ;; esac
        [ -e "$d/FAILED.json" ] && continue
        if [ -s "$d/summary.json" ]; then echo "$d"; fi
    done
}

# mean_curve DIR FILE OUTCSV : replica mean and standard error of DIR/seed-*/FILE.
mean_curve() {
    local dir=$1 file=$2 out=$3
    # shellcheck disable=SC2046
    "$TOOLS" mean "$out" $(for d in $(replica_dirs "$dir"); do echo "$d/$file"; done)
}

# gnuplot terminal: pngcairo when this gnuplot has it, else the libgd png terminal.
png_terminal() {
    if gnuplot -e 'set terminal pngcairo' >/dev/null 2>&1; then
        echo "pngcairo size 900,650 enhanced font 'sans,11'"
    else
        echo "png size 900,650 enhanced"
    fi
}
