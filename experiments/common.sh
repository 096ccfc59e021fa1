# Shared by the figure and table scripts (sourced, not run). Environment, set by Makefile.paper:
#   TERRACE      the terrace executable            TOOLS  the paper_tools executable
#   OUT          where results go (results/)       SIZE   full | quick (tiny, short runs)
# Every run lands in its own directory, written under a temporary name and renamed when complete,
# so that parallel make jobs never share a file and an interrupted run is redone, not reused.
set -euo pipefail
: "${TERRACE:?TERRACE must name the terrace executable}"
: "${TOOLS:?TOOLS must name the paper_tools executable}"
: "${OUT:?OUT must name the output directory}"
SIZE=${SIZE:-full}
EXPERIMENTS=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
SCENES=$EXPERIMENTS/scenes
RUNS=$OUT/runs

# Run sizes. "full" is sized so that `make -f Makefile.paper all` stays within an hour on two
# cores (results/README.md lists the measured costs); "quick" only exercises the pipeline.
if [ "$SIZE" = quick ]; then
    REPLICAS=2          # the least that gives an error bar
    DENSE_N=216         # the smallest cube whose box holds two SMD cutoffs at rho* = 0.5
    GAS_N=64
    EQUIL_PS=0.1
    DENSE_PS=0.4
    GAS_PS=0.4
    REF_DT_FS=0.5       # converged reference of the trade-off (full: 0.2 fs)
    REF_PS_FACTOR=1
    SCAN_PS=0.3         # density scan
    SCAN_REPLICAS=2
else
    REPLICAS=4
    DENSE_N=512
    GAS_N=512
    EQUIL_PS=2
    DENSE_PS=10
    GAS_PS=20
    REF_DT_FS=0.2
    REF_PS_FACTOR=2
    SCAN_PS=4
    SCAN_REPLICAS=2     # the scan compares costs; two runs bound their spread
fi

log() { echo "[$(date +%H:%M:%S)] $*" >&2; }

# run_one DIR SCENE [--set key=value]... : one run, skipped when DIR already holds its summary.
run_one() {
    local dir=$1 scene=$2
    shift 2
    if [ -s "$dir/summary.json" ]; then return 0; fi
    local partial="$dir.partial"
    rm -rf "$partial"
    mkdir -p "$(dirname "$dir")"
    log "run $dir"
    if ! "$TERRACE" run "$scene" --quiet --out "$partial" "$@" >"$partial.log" 2>&1; then
        log "FAILED $dir (see $partial.log)"
        return 1
    fi
    rm -rf "$dir"
    mv "$partial" "$dir"
    mv "$partial.log" "$dir/run.log"
}

# run_replicas DIR SCENE [--set ...]... : REPLICAS independent runs DIR/seed-K (seeds 1..R).
run_replicas() {
    local dir=$1 scene=$2
    shift 2
    local k
    for k in $(seq 1 "$REPLICAS"); do
        run_one "$dir/seed-$k" "$scene" --set seed="$k" "$@"
    done
}

# replica_dirs DIR : the replica directories of DIR, one per line.
replica_dirs() { ls -d "$1"/seed-* ; }

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
