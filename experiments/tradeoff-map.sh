#!/usr/bin/env bash
# Where DMD pays, resolved: `terrace tradeoff` at every state point of a density × temperature
# grid, for one model family and one set of tolerances.
#   tradeoff-map.sh FAMILY loose|strict "DENSITIES" "TEMPERATURES" [N] [extra tradeoff args...]
#   tradeoff-map.sh pack FAMILY [SET]      (archive every state point's runs now; see below)
# FAMILY: rods (dense-rods.json), lj (lj-liquid.json), gb (gay-berne-liquid.json) or dumbbell
# (dumbbell-liquid.json); the map's grid is the rods' and LJ's, the other two one cell each.
# Tolerance sets: strict = tradeoff's defaults (u 0.5 %, p 2 %, d 3 %, g 0.02, g_peak 1 %,
# tau 3 %); loose = u 2 %, p 5 %, d 10 %, g 0.05, g_peak 3 %, tau 10 %.
# Each cell's tradeoff lands in OUT/tradeoff-map/<family>-<set>/rho<ρ*>-T<T*>. A cell takes up to
# tens of CPU minutes and the map tens of hours, more than one sitting, so the runs must outlive
# the machine. The two sets of a state point share their runs: a setting's replica k is the same
# run (same scene, seed k) whatever the tolerances, and each set reads only the replicas it asks
# for, so the second set to run starts from the first's. They live in
# OUT/tradeoff-map/<family>-runs/rho<ρ*>-T<T*>/runs, each cell's runs/ a link there; after each
# cell (and on `pack`) the files tradeoff reads back from each run (scene.json, summary.json, the
# CSVs, FAILED.json) go into that directory's runs.tar.xz, a few MB, which is committed with the
# cells; a state point whose runs/ is missing is unpacked from it first, so tradeoff reuses every
# finished run (a cell's own runs or runs.tar.xz, as cells kept them before, is moved in). A cell
# that is finished is not run again: it has a verdict (a cost in its tradeoff.json, which keeps
# every estimate), or its search ended without one under a CPU budget and replica limit at least
# those asked for now (a larger --budget-cpu-hours or --max-replicas goes on from its runs). The
# runs and their archive are removed once both sets of the state point have their verdicts.
# SMD's step: the scene's smd.dt_fs, shortened by √(T_scene/T*) above the scene's temperature
# (the thermal speed sets the step a collision needs), to the next sample_fs/k below: tradeoff's
# SMD ladders run from it up to ten times it, and its reference from half of it.
# The map's bias runs take a g(r) frame every 10th sample, as tradeoff's did when the map began;
# tradeoff's own default is now every sample (docs/TRADEOFF.md, "Frames"). Kept, so that every
# cell is one protocol and a cell goes on from its runs (another spacing is another scene, and
# every run would be made again).
# Writes OUT/tradeoff-map/<family>-<set>.csv from every cell present, not only those named here:
#   rho,T,status,dmd,smd,ratio,lo,hi,level,why
# status resolved (a verdict: ratio = DMD's cost over SMD's, with its interval), at_least (the
# verdict of tradeoff's early stop, or of a cheaper setting left open: one engine is cheaper than
# any setting of the other could be, and the ratio, DMD's over SMD's, is a bound on the true one:
# from below when SMD is the cheaper, from above when DMD is) or the reason there is none; and <family>-<set>.png, log10 of the ratio at each
# cell with a verdict (triangles: bounds; crosses: no verdict), the break-even contour drawn only
# between resolved cells.
source "$(dirname "$0")/common.sh"
# The files of a run that tradeoff reads back (cli/tradeoff_measure.cpp, cli/sweep_table.cpp).
pack_runs() {
    local pool=$1
    [ -d "$pool/runs" ] || return 0
    (cd "$pool" && find runs -mindepth 2 -maxdepth 2 \( -name scene.json -o -name summary.json \
        -o -name rdf.csv -o -name vacf.csv -o -name oacf.csv -o -name FAILED.json \) -print0 |
        tar --null -T - --sort=name --mtime=@0 --owner=0 --group=0 --numeric-owner -cf - |
        xz -9 >runs.tar.xz.part && mv runs.tar.xz.part runs.tar.xz)
}
# The state point's shared runs for a cell: unpacked where only the archive is, the cell's own
# runs (the layout before sharing) moved in, and the cell's runs/ linked to them. A run already
# there is kept whole: never a file of another copy of it added (an old FAILED.json, say).
share_runs() {
    local cell=$1 pool=$2
    mkdir -p "$pool" "$cell"
    [ -d "$pool/runs" ] || [ ! -f "$pool/runs.tar.xz" ] || tar -xJf "$pool/runs.tar.xz" -C "$pool"
    mkdir -p "$pool/runs"
    if [ -d "$cell/runs" ] && [ ! -L "$cell/runs" ]; then
        move_runs "$cell/runs" "$pool/runs"
        rm -rf "$cell/runs"
    fi
    if [ -f "$cell/runs.tar.xz" ]; then
        local unpacked
        unpacked=$(mktemp -d "$pool/unpacked.XXXXXX")
        tar -xJf "$cell/runs.tar.xz" -C "$unpacked"
        move_runs "$unpacked/runs" "$pool/runs"
        rm -rf "$unpacked" "$cell/runs.tar.xz"
    fi
    ln -sfn "../../${pool#"${pool%/*/*}/"}/runs" "$cell/runs"
}
move_runs() { # FROM TO: each run directory of FROM that TO lacks
    local run
    for run in "$1"/*/; do
        [ -d "$run" ] || continue
        run=${run%/}
        [ -e "$2/${run##*/}" ] || mv "$run" "$2/"
    done
}
decided() { # the cell's tradeoff.json has a cost: a verdict, resolved or a bound
    python3 -c 'import json,sys; sys.exit(0 if json.load(open(sys.argv[1])).get("cost") else 1)' \
        "$1/tradeoff.json" 2>/dev/null
}
finished() { # decided, or its search ended without a verdict under limits at least these
    python3 - "$1/tradeoff.json" "$2" "$3" 2>/dev/null <<'PY'
import json, sys
t = json.load(open(sys.argv[1]))
verdict = t.get("verdict", "")
ended = verdict != "" and not verdict.startswith("not reached yet")
sys.exit(0 if t.get("cost") or (ended and t.get("budget_cpu_hours", 0) >= float(sys.argv[2])
                                and t.get("max_replicas", 0) >= int(sys.argv[3])) else 1)
PY
}

if [ "${1:-}" = pack ]; then
    for pool in "$OUT/tradeoff-map/$2-runs"/rho*-T*/; do
        [ -d "$pool" ] && pack_runs "${pool%/}"
    done
    exit 0
fi
family=$1 set=$2
read -r -a densities <<<"$3"
read -r -a temperatures <<<"$4"
n=${5:-512}
shift $(($# < 5 ? $# : 5))
case $family in
rods) scene=$SCENES/dense-rods.json ;;
lj) scene=$SCENES/lj-liquid.json ;;
gb) scene=$SCENES/gay-berne-liquid.json ;;
dumbbell) scene=$SCENES/dumbbell-liquid.json ;;
*) echo "usage: tradeoff-map.sh rods|lj|gb|dumbbell loose|strict DENSITIES TEMPERATURES [N]" >&2
   exit 2 ;;
esac
case $set in
strict) tolerances=() ;;
loose) tolerances=(--tolerance u=2% --tolerance p=5% --tolerance d=10% --tolerance g=0.05
                   --tolerance g_peak=3% --tolerance tau_v=10% --tolerance tau_o=10%) ;;
*) echo "tradeoff-map.sh: the tolerance set is loose or strict" >&2; exit 2 ;;
esac
dir=$OUT/tradeoff-map
name=$family-$set
mkdir -p "$dir/$name"
# tradeoff's limits (its defaults unless given): a cell finished under them is not run again.
budget=8 max_replicas=32
extra=("$@")
for ((i = 0; i < ${#extra[@]}; i++)); do
    case ${extra[i]} in
    --budget-cpu-hours) budget=${extra[i + 1]} ;;
    --budget-cpu-hours=*) budget=${extra[i]#*=} ;;
    --max-replicas) max_replicas=${extra[i + 1]} ;;
    --max-replicas=*) max_replicas=${extra[i]#*=} ;;
    esac
done
for T in "${temperatures[@]}"; do
    for rho in "${densities[@]}"; do
        cell=$dir/$name/rho$rho-T$T
        pool=$dir/$family-runs/rho$rho-T$T
        if finished "$cell" "$budget" "$max_replicas"; then
            log "tradeoff-map $name: rho $rho T $T is finished: $(head -c 200 "$cell.verdict")"
            continue
        fi
        share_runs "$cell" "$pool"
        dt=$(python3 - "$scene" "$T" <<'PY'
import json, math, sys
s = json.load(open(sys.argv[1]))
dt, sample = s["smd"]["dt_fs"], s["run"]["sample_fs"]
dt *= min(1.0, math.sqrt(s["state"]["temperature"] / float(sys.argv[2])))
print(f"{sample / math.ceil(sample / dt - 1e-9):.15g}")
PY
)
        status=0
        "$TERRACE" tradeoff "$scene" --set state.density="$rho" --set state.temperature="$T" \
            --set analysis.rdf_every=10 \
            --set state.n="$n" --set smd.dt_fs="$dt" "${tolerances[@]}" --out "$cell" --quiet \
            "$@" >"$cell.verdict" 2>"$cell.log" || status=$?
        both=true
        for s in loose strict; do decided "$dir/$family-$s/rho$rho-T$T" || both=false; done
        if [ $status = 0 ] && $both; then
            rm -rf "$pool" "$dir"/$family-*/rho$rho-T$T/runs
        else
            pack_runs "$pool"
        fi
        [ $status -lt 128 ] || exit $status # stopped by a signal: the same command goes on
        echo "$status" >"$cell.status"
        log "tradeoff-map $name: rho $rho T $T: $(head -c 200 "$cell.verdict")"
    done
done

# The table, from every cell of the family and set that has been run: a directory, or a verdict
# file where the tradeoff left no directory (it failed before making one).
table=$dir/$name.csv
echo "rho,T,status,dmd,smd,ratio,lo,hi,level,why" >"$table"
for cell in $(cd "$dir/$name" && ls -d rho*-T* 2>/dev/null | sed 's/\.[a-z]*$//' | sort -u); do
    cell=$dir/$name/$cell
    base=${cell##*/rho}
    status=$(cat "$cell.status" 2>/dev/null || echo 0)
    python3 - "$cell/tradeoff.json" "${base%-T*}" "${base#*-T}" "$status" <<'PY'
import json, sys
path, rho, T, status = sys.argv[1:]
try:
    t = json.load(open(path))
except OSError:
    print(f"{rho},{T},failed,,,nan,nan,nan,nan,no tradeoff.json")
    sys.exit(0)
c = t.get("cost")
why = "; ".join(t.get("notes", [])).replace(",", ";")
if status == "0" and c:
    kind = "at_least" if c.get("kind") == "at_least" else "resolved"
    print(f"{rho},{T},{kind},{c['dmd']},{c['smd']},{c['ratio_dmd_over_smd']},"
          f"{c['ratio_lo']},{c['ratio_hi']},{c['ratio_level']},{why}")
else:
    print(f"{rho},{T},unresolved,,,nan,nan,nan,nan,{t.get('verdict', '').replace(',', ';')} {why}")
PY
done | sort -t, -k2,2g -k1,1g >>"$table"

# Break-even between grid neighbours that both have a verdict and lie on either side of 1, placed
# by linear interpolation of log10(ratio) in log ρ* (or log T*): no line crosses a cell without one.
python3 - "$table" >"$dir/$name-breakeven.dat" <<'PY'
import csv, math, sys
cells = {}
for r in csv.DictReader(open(sys.argv[1])):
    if r["status"] == "resolved" and float(r["ratio"]) > 0:
        cells[(float(r["rho"]), float(r["T"]))] = math.log10(float(r["ratio"]))
rhos = sorted({k[0] for k in cells}); temps = sorted({k[1] for k in cells})
def cross(a, b, fa, fb):
    f = fa / (fa - fb)
    return 10 ** (math.log10(a) + f * (math.log10(b) - math.log10(a)))
for T in temps:
    for a, b in zip(rhos, rhos[1:]):
        if (a, T) in cells and (b, T) in cells and cells[(a, T)] * cells[(b, T)] < 0:
            print(f"{cross(a, b, cells[(a, T)], cells[(b, T)])},{T}")
for rho in rhos:
    for a, b in zip(temps, temps[1:]):
        if (rho, a) in cells and (rho, b) in cells and cells[(rho, a)] * cells[(rho, b)] < 0:
            print(f"{rho},{cross(a, b, cells[(rho, a)], cells[(rho, b)])}")
PY

title="$family, $set tolerances: DMD cost / SMD cost at equal accuracy (resolved cells)"
# One plot clause per kind of cell that the table holds: gnuplot fails on a clause whose every
# point is undefined, and a label clause of that sort beside another crashes it.
has() { awk -F, -v s="$1" 'NR > 1 && ($3 == s || (s == "none" && $3 != "resolved" && $3 != "at_least")) { n++ } END { exit !n }' "$table"; }
clauses=()
if has resolved; then
    clauses+=("'$table' skip 1 using 1:(strcol(3) eq \"resolved\" ? \$2 : NaN):(log10(\$6)) with points pt 7 ps 3 palette title 'resolved'"
              "'' skip 1 using 1:(strcol(3) eq \"resolved\" ? \$2 : NaN):(sprintf(\"%.2g\", \$6)) with labels offset 0,1.5 notitle")
fi
# A bound's label in one glyph where the terminal draws UTF-8 (cairo): ">=1.5" beside its
# neighbour's at the grid's densest spacing (ρ* 0.5 and 0.7) touched.
ge='>=' le='<='
case $(png_terminal) in pngcairo*) ge='≥' le='≤' ;; esac
if has at_least; then
    clauses+=("'$table' skip 1 using 1:(strcol(3) eq \"at_least\" ? \$2 : NaN):(log10(\$6)) with points pt 9 ps 3 palette title 'bound: the cheaper engine resolved, its advantage at least'"
              "'' skip 1 using 1:(strcol(3) eq \"at_least\" ? \$2 : NaN):(\$6 > 1 ? sprintf(\"$ge%.2g\", \$6) : sprintf(\"$le%.2g\", \$6)) with labels offset 0,1.5 notitle")
fi
if has none; then
    clauses+=("'$table' skip 1 using 1:(strcol(3) ne \"resolved\" && strcol(3) ne \"at_least\" ? \$2 : NaN) with points pt 2 ps 2 lc rgb '#888888' title 'no verdict'")
fi
if [ -s "$dir/$name-breakeven.dat" ]; then
    clauses+=("'$dir/$name-breakeven.dat' using 1:2 with points pt 6 ps 2 lw 2 lc rgb 'black' title 'break-even (between resolved cells)'")
fi
plot=""
for clause in "${clauses[@]}"; do plot="${plot:+$plot, }$clause"; done
if [ -z "$plot" ]; then
    log "tradeoff-map $name: no cell in $table, no picture"
    exit 0
fi
gnuplot <<GP
set terminal $(png_terminal)
set output '$dir/$name.png'
set datafile separator ','
set datafile missing 'nan'
set title '$title'
set logscale x
set xlabel '{/Symbol r}*'
set ylabel 'T*'
set logscale y
set offsets graph 0.08, graph 0.08, graph 0.08, graph 0.08
set cblabel 'log_{10}(DMD cost / SMD cost)'
set palette defined (-1 '#1f77b4', 0 '#ffffff', 1 '#d62728')
set cbrange [-1:1]
set grid
plot $plot
GP
log "tradeoff-map $name done"
