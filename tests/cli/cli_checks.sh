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
determinism)
    # The same scene and seed give the same trajectory bit for bit (DESIGN.md "Interfaces").
    for engine in dmd smd; do
        for k in 1 2; do
            "$terrace" run "$src/experiments/scenes/dense-rods.json" --quiet --out "$work/$engine-$k" \
                --set engine="$engine" --set state.n=216 --set run.equilibrate_ps=0.1 \
                --set run.time_ps=0.3 --set output.trajectory_every_fs=9 >/dev/null ||
                fail "$engine run failed"
        done
        cmp -s "$work/$engine-1/trajectory.xyz" "$work/$engine-2/trajectory.xyz" ||
            fail "$engine: two runs of one scene and seed differ"
    done
    "$terrace" run "$src/experiments/scenes/dense-rods.json" --quiet --out "$work/dmd-3" \
        --set state.n=216 --set run.equilibrate_ps=0.1 --set run.time_ps=0.3 --set seed=2 \
        --set output.trajectory_every_fs=9 >/dev/null || fail "seed 2 run failed"
    cmp -s "$work/dmd-1/trajectory.xyz" "$work/dmd-3/trajectory.xyz" &&
        fail "a different seed gave the same trajectory"
    ;;
interrupt)
    # Ctrl-C ends a long run at the next sample with valid, flushed output and exit status 130.
    "$terrace" run "$src/experiments/scenes/dense-rods.json" --quiet --out "$work/int" \
        --set state.n=216 --set run.equilibrate_ps=0 --set run.time_ps=100000 \
        --set output.trajectory_every_fs=9 >/dev/null 2>&1 &
    pid=$!
    for _ in $(seq 1 100); do # wait until production has written a few frames
        written=$(grep -c '^216$' "$work/int/trajectory.xyz" 2>/dev/null || true)
        [ "${written:-0}" -ge 3 ] && break
        sleep 0.1
    done
    kill -INT $pid
    wait $pid
    status=$?
    [ $status -eq 130 ] || fail "exit status $status after SIGINT, expected 130"
    grep -q '"interrupted": true' "$work/int/summary.json" || fail "summary does not say interrupted"
    frames=$(grep -c '^216$' "$work/int/trajectory.xyz")
    lines=$(wc -l <"$work/int/trajectory.xyz")
    [ "$lines" -eq $((frames * 218)) ] || fail "trajectory not whole frames: $lines lines, $frames frames"
    "$terrace" analyse "$work/int" >/dev/null || fail "the interrupted run's trajectory does not analyse"
    ;;
*)
    fail "unknown check"
    ;;
esac
exit 0
