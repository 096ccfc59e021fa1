#!/usr/bin/env bash
# One command-line check per call: cli_checks.sh CHECK TERRACE_BINARY SOURCE_DIR
set -u
check=$1 terrace=$2 src=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL ($check): $*" >&2; exit 1; }

# A run that must fail: non-zero status, a one-line message naming $2, no output directory.
expect_error() {
    local scene=$1 needle=$2
    shift 2
    local err
    err=$("$terrace" run "$scene" --out "$work/out" --quiet "$@" 2>&1 >/dev/null) &&
        fail "exit status 0 for a bad scene"
    [ "$(printf '%s\n' "$err" | wc -l)" -eq 1 ] || fail "error is not one line: $err"
    [[ $err == *"$needle"* ]] || fail "error does not name '$needle': $err"
    [ ! -e "$work/out" ] || fail "output written for a bad scene"
}

short_run() { # engine extra-args...
    local engine=$1
    shift
    "$terrace" run "$src/experiments/scenes/dense-rods.json" --quiet --out "$work/$engine" \
        --set engine="$engine" --set state.n=216 --set run.equilibrate_ps=0.1 \
        --set run.time_ps=0.5 --set output.trajectory_every_fs=20 "$@" >"$work/$engine.log" ||
        fail "run failed: $(cat "$work/$engine.log")"
    for f in summary.json scene.json initial.xyz trajectory.xyz rdf.csv vacf.csv oacf.csv msd.csv; do
        [ -s "$work/$engine/$f" ] || fail "$engine run did not write $f"
    done
    grep -q '"cpu_seconds_per_ps"' "$work/$engine/summary.json" || fail "summary lacks cpu_seconds_per_ps"
    grep -q '"rel_fluct"' "$work/$engine/summary.json" || fail "summary lacks energy.rel_fluct"
}

case $check in
help)
    "$terrace" --help | grep -q "terrace run" || fail "--help does not describe run"
    ;;
unknown_key)
    printf '{"name": "x", "dmd": {"dv": 1}}' >"$work/s.json"
    expect_error "$work/s.json" "dmd.dv: unknown key"
    expect_error "$src/experiments/scenes/dense-rods.json" "smd.bogus" --set smd.bogus=1
    ;;
not_json)
    printf '{ not json' >"$work/s.json"
    expect_error "$work/s.json" "not valid JSON"
    expect_error "$work/missing.json" "cannot open"
    ;;
bad_value)
    expect_error "$src/experiments/scenes/dense-rods.json" "dmd.dV" --set dmd.dV=-1
    expect_error "$src/experiments/scenes/dense-rods.json" "smd.dt_fs" --set smd.dt_fs=0
    expect_error "$src/experiments/scenes/dense-rods.json" "state.density" --set state.density=5
    ;;
end_to_end_dmd)
    short_run dmd
    grep -q '"collisions_per_ps"' "$work/dmd/summary.json" || fail "DMD summary lacks collisions_per_ps"
    ;;
end_to_end_smd)
    short_run smd --set smd.dt_fs=1.8
    grep -q '"neighbour_rebuilds"' "$work/smd/summary.json" || fail "SMD summary lacks neighbour_rebuilds"
    ;;
analyse_compare)
    short_run dmd --set output.trajectory_every_fs=10 # every sample: the same data both ways
    cp "$work/dmd/vacf.csv" "$work/vacf-run.csv"
    "$terrace" analyse "$work/dmd" >/dev/null || fail "analyse failed"
    "$terrace" compare "$work/vacf-run.csv" "$work/dmd/vacf.csv" >/dev/null ||
        fail "compare rejects a curve recomputed from the trajectory"
    awk -F, 'NR == 1 { print; next } { $2 = $2 + 0.5; print }' OFS=, "$work/dmd/vacf.csv" \
        >"$work/shifted.csv"
    "$terrace" compare "$work/vacf-run.csv" "$work/shifted.csv" >/dev/null &&
        fail "compare accepts a curve shifted by 0.5"
    ;;
*)
    fail "unknown check"
    ;;
esac
exit 0
