#!/usr/bin/env bash
# experiments/tradeoff-map.sh's table and picture from cells that are already decided, one grid per
# mix of kinds (resolved, at_least, none): gnuplot once failed, or crashed, on a plot clause for a
# kind that no cell of the table had. Then a cell's runs archived and unpacked again. The cells'
# tradeoff.json are written here and `true` stands for terrace, so no run is made.
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
# A cell without a verdict keeps what tradeoff reads back from its runs in runs.tar.xz (and no
# more: thermo.csv stays out), and a cell whose runs/ is gone gets them back from it.
run=$out/tradeoff-map/rods-strict/rho0.03-T1.4/runs/smd-verlet-dt3_r1
mkdir -p "$run"
echo '{"a": 1}' >"$run/summary.json"
echo 't,c' >"$run/thermo.csv"
map rods-strict "0.03" "1.4" "unresolved at_least"
archive=$out/tradeoff-map/rods-strict/rho0.03-T1.4/runs.tar.xz
[ -s "$archive" ] || fail "no runs.tar.xz for a cell without a verdict"
[ "$(tar -tJf "$archive" | sort | tr '\n' ' ')" = "runs/smd-verlet-dt3_r1/summary.json " ] ||
    fail "runs.tar.xz holds $(tar -tJf "$archive" | tr '\n' ' ')"
rm -rf "${run%/*}"
map rods-strict "0.03" "1.4" "unresolved at_least"
[ "$(cat "$run/summary.json")" = '{"a": 1}' ] || fail "the runs were not unpacked from runs.tar.xz"
echo "tradeoff-map pictures: ok"
