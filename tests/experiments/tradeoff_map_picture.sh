#!/usr/bin/env bash
# experiments/tradeoff-map.sh's table and picture from cells that are already decided, one grid per
# mix of kinds (resolved, at_least, none): gnuplot once failed, or crashed, on a plot clause for a
# kind that no cell of the table had. Then the runs a state point's two sets share, archived and
# unpacked again, and which cells are run again (a stand-in for terrace records the calls). The
# cells' tradeoff.json are written here, so no run is made.
#   tradeoff_map_picture.sh SOURCE_DIR
set -euo pipefail
src=$1
out=$(mktemp -d "${TMPDIR:-/tmp}/terrace-map-picture.XXXXXX")
trap 'rm -rf "$out"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

# cell FAMILY-SET RHO T KIND [RATIO]: a decided cell (KIND resolved or at_least) or one without a
# verdict (none).
cell() {
    local dir=$out/tradeoff-map/$1/rho$2-T$3
    mkdir -p "$dir"
    case $4 in
    none) echo '{"verdict": "no verdict: budget spent", "notes": ["a note"]}' ;;
    *) printf '{"verdict": "v", "notes": [], "cost": {"kind": "%s", "dmd": "dmd-uniform-dV0.5", "smd": "smd-verlet-dt3", "ratio_dmd_over_smd": %s, "ratio_lo": 1.2, "ratio_hi": 2.5, "ratio_level": 0.95}}\n' \
        "$([ "$4" = at_least ] && echo at_least || echo interval)" "$5" ;;
    esac >"$dir/tradeoff.json"
}
# map NAME "DENSITIES" "TEMPERATURES" EXPECTED_STATUSES
map() {
    local family=${1%-*} set=${1#*-}
    TERRACE=true TOOLS=true OUT=$out "$src/experiments/tradeoff-map.sh" "$family" "$set" "$2" "$3" 512 \
        >"$out/$1.log" 2>&1 || { cat "$out/$1.log" >&2; fail "$1: tradeoff-map.sh failed"; }
    local png=$out/tradeoff-map/$1.png
    [ -s "$png" ] && [ "$(head -c 4 "$png" | tail -c 3)" = PNG ] || fail "$1: no picture"
    local got
    got=$(awk -F, 'NR > 1 { printf "%s%s", sep, $3; sep = " " }' "$out/tradeoff-map/$1.csv")
    [ "$got" = "$4" ] || fail "$1: statuses '$got', expected '$4'"
}

cell rods-loose 0.5 1.4 at_least 1.6
map rods-loose "0.5" "1.4" "at_least"
cell rods-strict 0.5 1.4 at_least 1.6
cell rods-strict 0.03 1.4 none
map rods-strict "0.03 0.5" "1.4" "unresolved at_least"
# Two resolved cells on either side of break-even, one bound and one with no run at all.
cell lj-loose 0.03 1.4 resolved 0.5
cell lj-loose 0.1 1.4 resolved 2
cell lj-loose 0.5 1.4 at_least 3
map lj-loose "0.03 0.1 0.5 1" "1.4" "resolved resolved at_least failed"
[ -s "$out/tradeoff-map/lj-loose-breakeven.dat" ] || fail "lj-loose: no break-even between 0.03 and 0.1"
# The runs of a state point are shared by its two sets, in tradeoff-map/<family>-runs/rho-T:
# a cell's own runs (the layout before) move there, the archive keeps what tradeoff reads back
# from them (and no more: thermo.csv stays out), and runs/ comes back from it when gone.
run=$out/tradeoff-map/rods-strict/rho0.03-T1.4/runs/smd-verlet-dt3_r1
mkdir -p "$run"
echo '{"a": 1}' >"$run/summary.json"
echo 't,c' >"$run/thermo.csv"
map rods-strict "0.03" "1.4" "unresolved at_least"
pool=$out/tradeoff-map/rods-runs/rho0.03-T1.4
[ -L "${run%/*}" ] || fail "the cell's runs/ is not a link to the state point's"
[ "$(cat "$pool/runs/smd-verlet-dt3_r1/summary.json")" = '{"a": 1}' ] || fail "the run did not move"
archive=$pool/runs.tar.xz
[ -s "$archive" ] || fail "no runs.tar.xz for a state point without a verdict"
[ "$(tar -tJf "$archive" | sort | tr '\n' ' ')" = "runs/smd-verlet-dt3_r1/summary.json " ] ||
    fail "runs.tar.xz holds $(tar -tJf "$archive" | tr '\n' ' ')"
rm -rf "$pool/runs"
map rods-loose "0.03 0.5" "1.4" "failed at_least"
[ "$(cat "$out/tradeoff-map/rods-loose/rho0.03-T1.4/runs/smd-verlet-dt3_r1/summary.json")" = '{"a": 1}' ] ||
    fail "the loose set does not see the strict set's runs, unpacked from runs.tar.xz"
# A cell's own runs.tar.xz (the layout before) is merged into the state point's.
old=$out/tradeoff-map/rods-strict/rho0.1-T1.4
mkdir -p "$old/runs/smd-omelyan-dt3_r1"
echo '{"b": 2}' >"$old/runs/smd-omelyan-dt3_r1/summary.json"
(cd "$old" && tar -cJf runs.tar.xz runs && rm -rf runs)
map rods-strict "0.1" "1.4" "unresolved failed at_least"
[ ! -e "$old/runs.tar.xz" ] && [ "$(cat "$old/runs/smd-omelyan-dt3_r1/summary.json")" = '{"b": 2}' ] ||
    fail "a cell's own runs.tar.xz was not moved into the state point's runs"

# Which cells tradeoff is called for: a stand-in records its calls and, asked to, leaves a verdict.
fake=$out/fake-terrace
cat >"$fake" <<'SH'
#!/usr/bin/env bash
echo "$*" >>"$FAKE_CALLS"
while [ $# -gt 0 ]; do [ "$1" = --out ] && o=$2; shift; done
[ -z "${FAKE_DECIDE:-}" ] || printf '{"verdict": "v", "notes": [], "cost": {"kind": "interval", "dmd": "d", "smd": "s", "ratio_dmd_over_smd": 2, "ratio_lo": 1.5, "ratio_hi": 2.5, "ratio_level": 0.95}}\n' >"$o/tradeoff.json"
SH
chmod +x "$fake"
export FAKE_CALLS=$out/calls
calls() { # calls DESCRIPTION EXPECTED_COUNT FAMILY SET DENSITIES [ARGS...]
    local what=$1 expected=$2 family=$3 set=$4 densities=$5
    shift 5
    : >"$FAKE_CALLS"
    TERRACE=$fake TOOLS=true OUT=$out "$src/experiments/tradeoff-map.sh" "$family" "$set" \
        "$densities" "1.4" 512 "$@" >"$out/calls.log" 2>&1 || { cat "$out/calls.log" >&2; fail "$what: tradeoff-map.sh failed"; }
    [ "$(wc -l <"$FAKE_CALLS")" = "$expected" ] || fail "$what: $(wc -l <"$FAKE_CALLS") calls, expected $expected"
}
# Ended without a verdict under a budget and replica limit: finished for those, not for more.
mkdir -p "$out/tradeoff-map/lj-strict/rho0.2-T1.4"
echo '{"verdict": "no verdict: no DMD setting was resolved within", "notes": [], "budget_cpu_hours": 1, "max_replicas": 128}' \
    >"$out/tradeoff-map/lj-strict/rho0.2-T1.4/tradeoff.json"
calls "a finished cell" 0 lj strict 0.2 --budget-cpu-hours 1 --max-replicas 128
calls "a finished cell, a larger replica limit" 1 lj strict 0.2 --budget-cpu-hours 1 --max-replicas 256
calls "a finished cell, tradeoff's default budget" 1 lj strict 0.2 --max-replicas=128
echo '{"verdict": "not reached yet: round 3 done", "budget_cpu_hours": 1, "max_replicas": 128}' \
    >"$out/tradeoff-map/lj-strict/rho0.2-T1.4/tradeoff.json"
calls "a stopped cell" 1 lj strict 0.2 --budget-cpu-hours 1 --max-replicas 128
# The state point's runs are kept while one set lacks its verdict, and go when both have one.
mkdir -p "$out/tradeoff-map/lj-runs/rho0.2-T1.4/runs/x_r1"
echo '{}' >"$out/tradeoff-map/lj-runs/rho0.2-T1.4/runs/x_r1/summary.json"
FAKE_DECIDE=1 calls "the loose set" 1 lj loose 0.2
[ -s "$out/tradeoff-map/lj-runs/rho0.2-T1.4/runs.tar.xz" ] || fail "runs gone while strict has no verdict"
FAKE_DECIDE=1 calls "the strict set" 1 lj strict 0.2
[ ! -e "$out/tradeoff-map/lj-runs/rho0.2-T1.4" ] || fail "runs kept after both sets' verdicts"
calls "both decided" 0 lj strict 0.2
echo "tradeoff-map pictures: ok"
