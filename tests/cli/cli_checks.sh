#!/usr/bin/env bash
# One command-line check per call: cli_checks.sh CHECK TERRACE_BINARY SOURCE_DIR
set -u
check=$1 terrace=$(realpath "$2") src=$3
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

# wait_frames FILE BODIES COUNT [TRIES]: until FILE holds COUNT frames of BODIES (0.01 s a try).
wait_frames() {
    local written
    for _ in $(seq 1 "${4:-1000}"); do
        written=$(grep -c "^$2\$" "$1" 2>/dev/null || true)
        [ "${written:-0}" -ge "$3" ] && return 0
        sleep 0.01
    done
}

# sweep_file FILE: six short runs of 64 rods, DMD and SMD, and two that the run refuses (a
# trajectory of 10^11 frames, some hundred PiB, for any disk).
sweep_file() {
    cat >"$1" <<END
{"scene": "$src/experiments/scenes/dense-rods.json",
 "set": {"state.n": 64, "state.density": 0.1, "run.equilibrate_ps": 0.018, "run.time_ps": 0.09},
 "axes": [{"cases": [{"engine": "dmd"}, {"engine": "smd"},
                     {"engine": "smd", "run.time_ps": 1e9, "output.trajectory_every_fs": 9}],
           "labels": ["dmd", "smd", "too-long"]}],
 "seeds": [1, 2]}
END
}

# hold_lock DIR LOG: holds DIR's run lock, in the background, until LOG says a sweep is waiting
# for it, at most 60 s (then the check that looks for those words fails); returns once the lock is
# held. Held for a fixed time instead, the lock could be free again before a slow start (mpirun's,
# on a cold machine) reached the run.
hold_lock() {
    mkdir -p "$1"
    rm -f "$work/holding"
    flock "$1/.terrace.lock" bash -c 'touch "$1"; for _ in $(seq 1 600); do
        grep -q "holds its directory.s lock; waiting" "$0" 2>/dev/null && exit 0; sleep 0.1
    done' "$2" "$work/holding" &
    holder=$!
    for _ in $(seq 1 3000); do [ -e "$work/holding" ] && break; sleep 0.01; done
}

short_run() { # engine extra-args...
    local engine=$1
    shift
    "$terrace" run "$src/experiments/scenes/dense-rods.json" --quiet --out "$work/$engine" \
        --set engine="$engine" --set state.n=216 --set run.equilibrate_ps=0.099 \
        --set run.time_ps=0.495 --set output.trajectory_every_fs=18 "$@" >"$work/$engine.log" ||
        fail "run failed: $(cat "$work/$engine.log")"
    for f in summary.json scene.json initial.xyz trajectory.xyz rdf.csv vacf.csv oacf.csv msd.csv; do
        [ -s "$work/$engine/$f" ] || fail "$engine run did not write $f"
    done
    grep -q '"cpu_seconds_per_ps"' "$work/$engine/summary.json" || fail "summary lacks cpu_seconds_per_ps"
    grep -q '"rel_fluct"' "$work/$engine/summary.json" || fail "summary lacks energy.rel_fluct"
    # block errors of the means, numbers (55 samples in 8 blocks), for regression checks
    grep -Eq '"potential_energy_err": [0-9]' "$work/$engine/summary.json" ||
        fail "summary lacks a number for potential_energy_err"
    grep -Eq '"temperature_err_K": [0-9]' "$work/$engine/summary.json" ||
        fail "summary lacks a number for temperature_err_K"
    grep -Eq '"green_kubo_err": [0-9]' "$work/$engine/summary.json" ||
        fail "summary lacks a number for the Green-Kubo D's error"
    if [ "$engine" = dmd ]; then
        grep -Eq '"collisions_per_ps_err": [0-9]' "$work/$engine/summary.json" ||
            fail "summary lacks a number for collisions_per_ps_err"
    fi
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
    # What is asked for is what is run: a run length off its interval's grid is run as typed
    # under DMD; under SMD, a length between two steps is refused with the nearest valid ones.
    expect_error "$src/experiments/scenes/dense-rods.json" \
        "run.time_ps: must be a whole multiple of smd.dt_fs = 1.8 fs, got 2 ps; nearest valid: 1.9998 or 2.0016 ps" \
        --set engine=smd --set run.time_ps=2
    # No level in the well and none a thermal pair meets: U = 0 throughout, refused.
    expect_error "$src/experiments/scenes/dense-rods.json" \
        "dmd.dV: 1e+06 kT puts the first level at -2.1e+06 kJ/mol" --set dmd.dV=1e6
    expect_error "$src/experiments/scenes/dumbbell-liquid.json" \
        "body.sites: span 100 Å, more than half the box edge 24.5167 Å" \
        --set 'body.sites=[{"r":[0,0,50],"mass":14,"epsilon":0.31,"sigma":3.31},{"r":[0,0,-50],"mass":14,"epsilon":0.31,"sigma":3.31}]'
    # A --set without its value: said so, in terrace's words (was boost's "too many positional
    # options"), exit 2, nothing written.
    err=$("$terrace" run "$src/experiments/scenes/dense-rods.json" --set --out "$work/out" 2>&1 >/dev/null)
    [ $? -eq 2 ] || fail "a --set without a value: exit status not 2"
    [[ $err == "terrace run: --set needs a key.path=value after it, got the option '--out'"* ]] ||
        fail "a --set without a value: $err"
    [ ! -e "$work/out" ] || fail "output written for a bad command line"
    err=$("$terrace" run "$src/experiments/scenes/dense-rods.json" extra.json 2>&1 >/dev/null)
    [[ $err == "terrace run: takes one scene file;"* ]] || fail "two scene files: $err"
    ;;
command_help)
    # Every command has its own help, on standard output with status 0, by --help, -h and
    # terrace help COMMAND; each lists that command's options.
    for c in run analyse compare design sweep tradeoff; do
        for flag in --help -h; do
            out=$("$terrace" $c $flag 2>"$work/err") || fail "terrace $c $flag: exit status $?"
            [[ $out == "Usage:"*"terrace $c"*"Options:"*"--help"* ]] ||
                fail "terrace $c $flag is not its usage: $out $(cat "$work/err")"
            [ ! -s "$work/err" ] || fail "terrace $c $flag wrote to standard error"
        done
        [ "$("$terrace" help $c)" = "$out" ] || fail "terrace help $c differs from terrace $c -h"
    done
    "$terrace" compare --help | grep -q -- "--tol-sigma X" || fail "compare --help lacks --tol-sigma"
    "$terrace" run --help | grep -q -- "--strict" || fail "run --help lacks --strict"
    "$terrace" tradeoff --help | grep -q -- "--budget-cpu-hours" || fail "tradeoff --help lacks its options"
    # A misspelt option or command: the nearest known one, status 2, nothing run.
    err=$("$terrace" compare a.csv b.csv --tol-sigam 2 2>&1 >/dev/null)
    [ $? -eq 2 ] || fail "a misspelt option: exit status not 2"
    [[ $err == "terrace compare: unrecognised option '--tol-sigam'; did you mean --tol-sigma? (try terrace compare --help)" ]] ||
        fail "a misspelt option: $err"
    err=$("$terrace" run --out "$work/out" --strcit 2>&1 >/dev/null)
    [[ $err == *"did you mean --strict?"* ]] || fail "a misspelt --strict: $err"
    [ ! -e "$work/out" ] || fail "output written for a bad command line"
    err=$("$terrace" tradof 2>&1 >/dev/null)
    [ $? -eq 2 ] || fail "an unknown command: exit status not 2"
    [[ $err == *"unknown command 'tradof'; did you mean tradeoff?"* ]] || fail "an unknown command: $err"
    err=$("$terrace" help lammps 2>&1 >/dev/null)
    [ $? -eq 2 ] || fail "help for no command: exit status not 2"
    ;;
did_you_mean)
    # An unknown key names the known key nearest it, whether from --set or from the file.
    expect_error "$src/experiments/scenes/lj-liquid.json" \
        "smd.dt: unknown key; did you mean smd.dt_fs?" --set smd.dt=0.5
    expect_error "$src/experiments/scenes/lj-liquid.json" \
        "state.temp: unknown key; did you mean state.temperature?" --set state.temp=2
    printf '{"name": "x", "state": {"desnity": 0.3}}' >"$work/s.json"
    expect_error "$work/s.json" "state.desnity: unknown key; did you mean state.density?"
    expect_error "$src/experiments/scenes/lj-liquid.json" \
        'smd.scheme: must be one of omelyan | verlet | yoshida4, got "verlett"; did you mean verlet?' \
        --set smd.scheme=verlett
    ;;
engine_keys)
    # A --set key of the engine not running: a warning naming the engine, in summary.json too;
    # under --strict a refusal before anything is written.
    lj=("$src/experiments/scenes/lj-liquid.json" --set state.n=108 --set state.density=0.3
        --set run.equilibrate_ps=0 --set run.time_ps=0.09)
    "$terrace" run "${lj[@]}" --set smd.dt_fs=0.7 --out "$work/dmd" --quiet >/dev/null 2>"$work/err" ||
        fail "a DMD run with an SMD key failed: $(cat "$work/err")"
    grep -q "warning: --set smd.dt_fs=0.7: the run's engine, dmd, does not read the smd section, so the setting has no effect" "$work/err" ||
        fail "no warning for an SMD key on a DMD run: $(cat "$work/err")"
    grep -q 'does not read the smd section' "$work/dmd/summary.json" || fail "the warning is not in summary.json"
    "$terrace" run "${lj[@]}" --set engine=smd --set dmd.dV=0.25 --out "$work/smd" --quiet >/dev/null 2>"$work/err" ||
        fail "an SMD run with a DMD key failed: $(cat "$work/err")"
    grep -q "warning: --set dmd.dV=0.25: the run's engine, smd, does not read the dmd section" "$work/err" ||
        fail "no warning for a DMD key on an SMD run: $(cat "$work/err")"
    "$terrace" run "${lj[@]}" --set engine=smd --set smd.dt_fs=0.45 --out "$work/plain" --quiet >/dev/null 2>"$work/err" ||
        fail "an SMD run with its own key failed"
    ! grep -q "does not read" "$work/err" || fail "a warning for the engine's own key: $(cat "$work/err")"
    expect_error "$src/experiments/scenes/lj-liquid.json" \
        "--set smd.dt_fs=0.7: the run's engine, dmd, does not read the smd section, so the setting has no effect (refused under --strict)" \
        --set smd.dt_fs=0.7 --strict
    # terrace design reads the dmd section only.
    "$terrace" design "$src/experiments/scenes/lj-liquid.json" --set smd.dt_fs=0.7 >/dev/null 2>"$work/err" ||
        fail "design with an SMD key failed"
    grep -q "warning: --set smd.dt_fs=0.7: terrace design, which shows DMD's terraces, does not read the smd section" "$work/err" ||
        fail "design: no warning: $(cat "$work/err")"
    "$terrace" design "$src/experiments/scenes/lj-liquid.json" --set smd.dt_fs=0.7 --strict >/dev/null 2>&1 &&
        fail "design --strict accepted an SMD key"
    # A sweep: the ladders of two engines and common keys of both are meant, and said nothing
    # of, by the sweep or its runs; a common key of an engine no run has is a warning, and under
    # --strict a bad sweep (status 2, nothing run).
    common='"state.n": 108, "state.density": 0.3, "run.equilibrate_ps": 0, "run.time_ps": 0.09, "smd.skin": 0.4'
    cat >"$work/ladders.json" <<END
{"scene": "$src/experiments/scenes/lj-liquid.json", "set": {$common},
 "axes": [{"cases": [{"engine": "dmd", "dmd.dV": 0.25}, {"engine": "smd", "smd.dt_fs": 0.45}],
           "labels": ["dmd", "smd"]}]}
END
    cat >"$work/dmd-only.json" <<END
{"scene": "$src/experiments/scenes/lj-liquid.json", "set": {$common},
 "axes": [{"cases": [{"engine": "dmd", "dmd.dV": 0.25}, {"engine": "dmd", "smd.dt_fs": 0.45}],
           "labels": ["a", "b"]}]}
END
    "$terrace" sweep "$work/ladders.json" --set dmd.horizon_fs=2 --out "$work/sw" --quiet 2>"$work/err" ||
        fail "the ladders' sweep failed: $(cat "$work/err")"
    ! grep -q "does not read" "$work/err" "$work/sw/dmd/run.log" "$work/sw/smd/run.log" ||
        fail "a warning for keys a sweep of both engines sets: $(cat "$work/err" "$work/sw"/*/run.log)"
    "$terrace" sweep "$work/dmd-only.json" --out "$work/sw1" --quiet 2>"$work/err" ||
        fail "a one-engine sweep failed: $(cat "$work/err")"
    grep -q "warning: .*axes set smd.dt_fs for 1 run of engine dmd (first: b): their engine, dmd, does not read the smd section" "$work/err" ||
        fail "no warning for an axis's SMD key on a DMD run: $(cat "$work/err")"
    grep -q "warning: .*smd.skin=0.4 (for every run): every run's engine, dmd, does not read the smd section" "$work/err" ||
        fail "no warning for a common SMD key of a DMD sweep: $(cat "$work/err")"
    err=$("$terrace" sweep "$work/dmd-only.json" --strict --out "$work/sw2" 2>&1)
    [ $? -eq 2 ] || fail "sweep --strict: exit status not 2: $err"
    [[ $err == *"(refused under --strict)" ]] || fail "sweep --strict: $err"
    [ ! -e "$work/sw2" ] || fail "sweep --strict wrote its directory"
    ;;
nearest_value)
    # A refused value names the valid values nearest it: LJ at T* 2 with dV = 1 puts a level on
    # the minimum; dV = 0.5 puts it midway between two, and runs.
    expect_error "$src/experiments/scenes/lj-liquid.json" \
        "dmd.dV: a level falls on the potential minimum U = -1.000000 kJ/mol (a terrace of zero width); dmd.dV = 0.5 puts it midway between two levels" \
        --set state.temperature=2 --set dmd.dV=1
    "$terrace" run "$src/experiments/scenes/lj-liquid.json" --set state.temperature=2 --set dmd.dV=0.5 \
        --set state.n=108 --set run.equilibrate_ps=0 --set run.time_ps=0.09 --out "$work/ok" --quiet >/dev/null ||
        fail "the dV named is refused"
    # A box narrower than twice DMD's interaction range names how many more bodies it takes.
    expect_error "$src/experiments/scenes/lj-liquid.json" \
        "dmd.dV: the box edge 5.42884 Å is shorter than twice the interaction range r_m = 2.75303 Å; use at least 1.04328 times as many bodies at this density (state.n), or a larger dV" \
        --set state.n=8 --set state.density=0.05 --set dmd.dV=0.01
    # A box too small for SMD's cutoff names the bodies or density that fit.
    expect_error "$src/experiments/scenes/lj-liquid.json" \
        "potential.cutoff: the box edge 4.7622 Å is shorter than 2·(r_u + skin) = 6.6 Å; use state.n >= 288, state.density <= 0.3756" \
        --set engine=smd --set state.n=108 --set state.density=1
    ;;
output_names)
    # Runs of one scene with different --set land apart by default, under out/ in a name that
    # says the overrides; a collision says --overwrite or a new --out, and --continue only where
    # a restart file is.
    lj=("$src/experiments/scenes/lj-liquid.json" --set state.n=108 --set state.density=0.3
        --set run.equilibrate_ps=0 --set run.time_ps=0.09 --quiet)
    (cd "$work" && "$terrace" run "${lj[@]}" --set engine=smd --set smd.dt_fs=0.45 >/dev/null &&
        "$terrace" run "${lj[@]}" --set engine=smd --set smd.dt_fs=0.9 >/dev/null) || fail "a run failed"
    # Sorted by the whole key: run.*, smd.*, state.*.
    for d in "lj-liquid-smd-equilibrate_ps=0,time_ps=0.09,dt_fs=0.45,density=0.3,n=108" \
             "lj-liquid-smd-equilibrate_ps=0,time_ps=0.09,dt_fs=0.9,density=0.3,n=108"; do
        [ -s "$work/out/$d/summary.json" ] || fail "no out/$d: $(ls "$work/out")"
    done
    err=$(cd "$work" && "$terrace" run "${lj[@]}" --set smd.dt_fs=0.9 --set engine=smd 2>&1 >/dev/null) &&
        fail "a second run into the same default directory was not refused"
    [[ $err == *"holds an earlier run's results"*"add --overwrite to replace them or give another --out" ]] ||
        fail "collision: $err"
    [[ $err != *"--continue"* ]] || fail "--continue offered without a restart file: $err"
    : >"$work/out/lj-liquid-smd-equilibrate_ps=0,time_ps=0.09,dt_fs=0.9,density=0.3,n=108/restart.bin"
    err=$(cd "$work" && "$terrace" run "${lj[@]}" --set smd.dt_fs=0.9 --set engine=smd 2>&1 >/dev/null)
    [[ $err == *", or resume that run with --continue out/lj-liquid-smd-equilibrate_ps=0,"* ]] ||
        fail "--continue not offered beside a restart file: $err"
    ;;
design)
    # The table of a design: a header, then one row a terrace, terrace 0 carrying exactly 0.
    "$terrace" design "$src/experiments/scenes/dense-rods.json" \
        --set 'dmd.terraces={"levels":"optimal","n":3}' >"$work/design.csv" ||
        fail "design failed"
    head -1 "$work/design.csv" | grep -q "levels optimal, values boltzmann, n 3" ||
        fail "design header: $(head -1 "$work/design.csv")"
    grep -q '^0,-[0-9.e-]*,[0-9.e-]*,0$' "$work/design.csv" || fail "terrace 0 does not carry 0"
    [ "$(grep -c '^-[0-9]*,' "$work/design.csv")" -eq 3 ] || fail "not 3 terraces in the well"
    # Explicit levels: the header names them, not the uniform design they replace.
    "$terrace" design "$src/experiments/scenes/dense-rods.json" --set 'dmd.levels=[1,2,3]' |
        head -1 | grep -q "levels explicit (3 in dmd.levels), values midpoint, model bare" ||
        fail "design header for explicit levels"
    "$terrace" design --profile --set dmd.dV=0.25 | head -1 | grep -q '^r_A,U_kJ_per_mol,V_kJ_per_mol$' ||
        fail "profile header"
    expect_error "$src/experiments/scenes/dense-rods.json" "dmd.terraces.levels" \
        --set 'dmd.terraces={"levels":"log"}'
    expect_error "$src/experiments/scenes/dense-rods.json" "dmd.values" \
        --set 'dmd.levels=[-1,1]' --set 'dmd.values=[0,0]'
    # A terracing that swallows the shallow Gay-Berne wells whole is said, with what resolves
    # them; the shipped scene's own dV resolves them.
    "$terrace" design "$src/experiments/scenes/gay-berne-liquid.json" --set dmd.dV=0.5 |
        grep -q "^# warning: dmd: terrace 0 (V = 0) holds the whole well of [1-9][0-9]* of the" ||
        fail "design: no warning of swallowed wells at dV = 0.5 kT"
    "$terrace" design "$src/experiments/scenes/gay-berne-liquid.json" | grep -q "^# warning" &&
        fail "design: the shipped Gay-Berne scene swallows a well"
    # A run on a design goes end to end.
    short_run dmd --set 'dmd.terraces={"levels":"volume","values":"virial","n":3}'
    # The run's CPU counts the building of its engine: an optimal design for rods takes about
    # 0.25 CPU s, over ten times this short production, and process_cpu_seconds is most of the
    # process's.
    python3 - "$terrace" "$src/experiments/scenes/dense-rods.json" "$work/optimal" <<'PY' ||
import json, resource, subprocess, sys
terrace, scene, out = sys.argv[1:]
subprocess.run([terrace, "run", scene, "--quiet", "--out", out, "--set", "engine=dmd",
                "--set", "state.n=108", "--set", "run.equilibrate_ps=0.045",
                "--set", "run.time_ps=0.09", "--set", 'dmd.terraces={"levels":"optimal"}'],
               check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
used = resource.getrusage(resource.RUSAGE_CHILDREN)
process = used.ru_utime + used.ru_stime
s = json.load(open(out + "/summary.json"))
assert s["process_cpu_seconds"] >= 0.8 * process, (s["process_cpu_seconds"], process)
assert s["process_cpu_seconds"] >= 5 * (s["cpu_seconds"] + s["cpu_seconds_equilibration"]), s
PY
        fail "process_cpu_seconds leaves out the optimal design's CPU"
    ;;
end_to_end_dmd)
    short_run dmd
    grep -q '"collisions_per_ps"' "$work/dmd/summary.json" || fail "DMD summary lacks collisions_per_ps"
    ;;
lengths_as_typed)
    # Lengths that are no whole number of their intervals run as typed: equilibration's last
    # rescale interval is cut short, production runs on past its last sample, unsampled.
    "$terrace" run "$src/experiments/scenes/dense-rods.json" --quiet --out "$work/typed" \
        --set state.n=216 --set run.equilibrate_ps=0.05 --set run.time_ps=0.1 >/dev/null ||
        fail "a run of 0.1 ps (11.1 samples of 9 fs) after 0.05 ps (5.6 rescales) failed"
    got=$(python3 -c 'import json, sys; s = json.load(open(sys.argv[1])); print(s["simulated_ps"], s["samples"])' \
        "$work/typed/summary.json")
    awk -v g="$got" 'BEGIN { split(g, x, " "); exit !(x[1] > 0.1 - 1e-12 && x[1] < 0.1 + 1e-12 && x[2] == 12) }' ||
        fail "typed lengths: simulated_ps and samples $got, not 0.1 and 12"
    ;;
end_to_end_smd)
    short_run smd --set smd.dt_fs=1.8
    grep -q '"neighbour_rebuilds"' "$work/smd/summary.json" || fail "SMD summary lacks neighbour_rebuilds"
    ;;
analyse_compare)
    short_run dmd --set output.trajectory_every_fs=9 # every sample: the same data both ways
    cp "$work/dmd/vacf.csv" "$work/vacf-run.csv"
    cp "$work/dmd/rdf.csv" "$work/rdf-run.csv"
    "$terrace" analyse "$work/dmd" >/dev/null || fail "analyse failed"
    # The same accumulators and settings: g(r) count for count (positions read back bit for bit),
    # the time curves to the round-off of the velocities' unit conversion.
    # (analyse has no engine: the run's back-converted g_continuous columns are not recomputed)
    cmp -s <(cut -d, -f1-3 "$work/rdf-run.csv") "$work/dmd/rdf.csv" ||
        fail "analyse gives another g(r) than the run"
    head -1 "$work/rdf-run.csv" | grep -q ',g_continuous,err_continuous$' ||
        fail "the DMD run's rdf.csv lacks g_continuous"
    paste -d, "$work/vacf-run.csv" "$work/dmd/vacf.csv" |
        awk -F, 'function abs(x) { return x < 0 ? -x : x }
            NR > 1 && (abs($1 - $4) > 1e-12 || abs($2 - $5) > 1e-12) { exit 1 }' ||
        fail "analyse gives another VACF than the run"
    "$terrace" compare "$work/vacf-run.csv" "$work/dmd/vacf.csv" >/dev/null ||
        fail "compare rejects a curve recomputed from the trajectory"
    awk -F, 'NR == 1 { print; next } { $2 = $2 + 0.5; print }' OFS=, "$work/dmd/vacf.csv" \
        >"$work/shifted.csv"
    "$terrace" compare "$work/vacf-run.csv" "$work/shifted.csv" >/dev/null &&
        fail "compare accepts a curve shifted by 0.5"
    # B the first half of A: the common points agree, but half of A would go unchecked.
    head -n $(($(wc -l <"$work/vacf-run.csv") / 2)) "$work/vacf-run.csv" >"$work/half.csv"
    err=$("$terrace" compare "$work/vacf-run.csv" "$work/half.csv" 2>&1 >/dev/null) &&
        fail "compare accepts a curve cut to half its range"
    [[ $err == "terrace: compare: the curves cover different ranges: "*" has "*" points over "* ]] ||
        fail "compare of a half curve: $err"
    err=$("$terrace" compare "$work/vacf-run.csv" "$work/vacf-run.csv" --tol-sigma inf 2>&1)
    [ $? -eq 2 ] || fail "--tol-sigma inf: exit status not 2"
    [[ $err == "terrace compare: --tol-sigma must be a finite number > 0"* ]] ||
        fail "--tol-sigma inf: $err"
    ;;
determinism)
    # The same scene and seed give the same trajectory bit for bit (DESIGN.md "Interfaces").
    for engine in dmd smd; do
        for k in 1 2; do
            "$terrace" run "$src/experiments/scenes/dense-rods.json" --quiet --out "$work/$engine-$k" \
                --set engine="$engine" --set state.n=216 --set run.equilibrate_ps=0.099 \
                --set run.time_ps=0.297 --set output.trajectory_every_fs=9 >/dev/null ||
                fail "$engine run failed"
        done
        cmp -s "$work/$engine-1/trajectory.xyz" "$work/$engine-2/trajectory.xyz" ||
            fail "$engine: two runs of one scene and seed differ"
    done
    "$terrace" run "$src/experiments/scenes/dense-rods.json" --quiet --out "$work/dmd-3" \
        --set state.n=216 --set run.equilibrate_ps=0.099 --set run.time_ps=0.297 --set seed=2 \
        --set output.trajectory_every_fs=9 >/dev/null || fail "seed 2 run failed"
    cmp -s "$work/dmd-1/trajectory.xyz" "$work/dmd-3/trajectory.xyz" &&
        fail "a different seed gave the same trajectory"
    ;;
interrupt)
    # Ctrl-C ends a long run at the next sample with valid, flushed output and exit status 130.
    "$terrace" run "$src/experiments/scenes/dense-rods.json" --quiet --out "$work/int" \
        --set state.n=216 --set run.equilibrate_ps=0 --set run.time_ps=900 \
        --set output.trajectory_every_fs=9 >/dev/null 2>&1 &
    pid=$!
    wait_frames "$work/int/trajectory.xyz" 216 4 # production has written the 4 frames analyse needs
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
overlap)
    # Two bodies half an angstrom apart: both engines name the pair before any work.
    printf '%s' '{"name": "two", "state": {"density": 0.005, "particles": [
        {"r": [1, 1, 1], "axis": [0, 0, 1]}, {"r": [1.5, 1, 1], "axis": [0, 0, 1]}]}}' >"$work/s.json"
    expect_error "$work/s.json" "state: bodies 0 and 1 overlap"
    expect_error "$work/s.json" "state: bodies 0 and 1 overlap" --set engine=smd
    ;;
thermostat)
    # Equilibration rescales every run.thermostat_fs whatever run.sample_fs is: runs sampled every
    # 9 and every 18 fs start production from the same state (it once rescaled per sample).
    for fs in 9 18; do
        "$terrace" run "$src/experiments/scenes/dense-rods.json" --quiet --out "$work/s$fs" \
            --set state.n=216 --set run.equilibrate_ps=0.18 --set run.time_ps=0.36 \
            --set run.sample_fs=$fs --set output.trajectory_every_fs=18 >/dev/null ||
            fail "run with sample_fs $fs failed"
    done
    cmp -s <(head -n 218 "$work/s9/trajectory.xyz") <(head -n 218 "$work/s18/trajectory.xyz") ||
        fail "the equilibrated state depends on run.sample_fs"
    ;;
run_help)
    "$terrace" run --help | grep -q -- "--continue" || fail "terrace run --help does not describe run"
    "$terrace" analyse --help | grep -q "terrace analyse" || fail "terrace analyse --help fails"
    ;;
existing_results)
    # A directory holding an earlier run is refused; --overwrite removes the old files first,
    # so a trajectory or thermo.csv the new run does not write cannot survive from the old one.
    short_run dmd --set output.thermo_every_fs=45
    [ -s "$work/dmd/thermo.csv" ] || fail "no thermo.csv"
    err=$("$terrace" run "$src/experiments/scenes/dense-rods.json" --quiet --out "$work/dmd" \
        --set state.n=216 --set run.equilibrate_ps=0 --set run.time_ps=0.099 2>&1 >/dev/null) &&
        fail "exit status 0 into a directory with an earlier run's results"
    [ "$(printf '%s\n' "$err" | wc -l)" -eq 1 ] || fail "error is not one line: $err"
    [[ $err == *"earlier run"*"--overwrite"* ]] || fail "error does not say what to do: $err"
    [[ $err != *"--continue"* ]] || fail "--continue offered for a finished run: $err"
    "$terrace" run "$src/experiments/scenes/dense-rods.json" --quiet --out "$work/dmd" --overwrite \
        --set state.n=216 --set run.equilibrate_ps=0 --set run.time_ps=0.099 \
        --set output.thermo_every_fs=0 >/dev/null || fail "--overwrite refused"
    [ ! -e "$work/dmd/trajectory.xyz" ] || fail "a stale trajectory.xyz survived --overwrite"
    [ ! -e "$work/dmd/thermo.csv" ] || fail "a stale thermo.csv survived --overwrite"
    grep -q '"simulated_ps": 0.09' "$work/dmd/summary.json" || fail "summary is not the new run's"
    ;;
lock)
    # Two runs into one directory at once: the second is refused while the first runs.
    "$terrace" run "$src/experiments/scenes/dense-rods.json" --quiet --out "$work/busy" \
        --set state.n=216 --set run.equilibrate_ps=0 --set run.time_ps=900 >/dev/null 2>&1 &
    pid=$!
    for _ in $(seq 1 100); do [ -e "$work/busy/scene.json" ] && break; sleep 0.05; done
    err=$("$terrace" run "$src/experiments/scenes/dense-rods.json" --quiet --out "$work/busy" \
        --overwrite --set state.n=216 --set run.time_ps=0.099 2>&1 >/dev/null)
    status=$?
    err2=$("$terrace" run --continue "$work/busy" 2>&1 >/dev/null)
    status2=$?
    err3=$("$terrace" analyse "$work/busy" 2>&1 >/dev/null)
    status3=$?
    kill -TERM $pid
    wait $pid
    [ $status -ne 0 ] || fail "a second run into a busy directory went ahead"
    [[ $err == *"another terrace run is writing into this directory"* ]] || fail "message: $err"
    [ $status2 -ne 0 ] && [[ $err2 == *"another terrace run is writing"* ]] ||
        fail "--continue into a busy directory: $err2"
    [ $status3 -ne 0 ] && [[ $err3 == *"another terrace run is writing"* ]] ||
        fail "analyse of a busy directory: $err3"
    ;;
default_name)
    # A scene name cannot send the default output outside out/.
    (cd "$work" && "$terrace" run "$src/experiments/scenes/dense-rods.json" --quiet \
        --set name=../../escaped --set state.n=216 --set run.equilibrate_ps=0 \
        --set run.time_ps=0.099 >/dev/null) || fail "run failed"
    [ -s "$work/out/_.._escaped-dmd-equilibrate_ps=0,time_ps=0.099,n=216/summary.json" ] ||
        fail "output not under out/: $(ls -R "$work")"
    [ ! -e "$work/../escaped-dmd" ] || fail "output escaped the working directory"
    ;;
unwritable)
    # An output directory that cannot be made or written: a one-line error naming it and the
    # cause. A file in the way of the path fails for everyone; a read-only directory for users
    # other than root (as root, the run is made as nobody when setpriv can).
    : >"$work/file"
    err=$("$terrace" run "$src/experiments/scenes/dense-rods.json" --quiet --out "$work/file/sub" \
        --set state.n=216 --set run.time_ps=0.099 2>&1 >/dev/null) && fail "exit status 0"
    [[ $err == "terrace: cannot create the output directory $work/file/sub: Not a directory" ]] ||
        fail "message: $err"
    mkdir "$work/ro" && chmod 555 "$work/ro" && chmod 755 "$work"
    as=() program=$terrace scene=$src/experiments/scenes/dense-rods.json
    if [ "$(id -u)" -eq 0 ]; then
        command -v setpriv >/dev/null || fail "running as root without setpriv"
        as=(setpriv --reuid=nobody --regid=nogroup --clear-groups)
        # nobody may not reach a checkout under /root (mode 700): the program and the scene are
        # copied where it can read them.
        cp "$terrace" "$work/terrace" && cp "$scene" "$work/dense-rods.json" &&
            chmod 755 "$work/terrace" && chmod 644 "$work/dense-rods.json" || fail "copy for nobody"
        program=$work/terrace scene=$work/dense-rods.json
    fi
    err=$("${as[@]}" "$program" run "$scene" --quiet \
        --out "$work/ro" --set state.n=216 --set run.time_ps=0.099 2>&1 >/dev/null) &&
        fail "exit status 0 into a read-only directory"
    [[ $err == *"$work/ro"*"Permission denied"* ]] || fail "message: $err"
    ;;
file_size_limit)
    # A write that does not fit (a file-size limit, as a full disk) ends the run with an error
    # naming the file and the cause; the trajectory keeps only whole frames.
    status=0
    err=$(ulimit -f 400 && "$terrace" run "$src/experiments/scenes/dense-rods.json" --quiet \
        --out "$work/full" --set state.n=216 --set run.equilibrate_ps=0 --set run.time_ps=0.999 \
        --set output.trajectory_every_fs=9 2>&1 >/dev/null) || status=$?
    [ $status -ne 0 ] || fail "exit status 0 after a failed write"
    [[ $err == *"cannot write $work/full/trajectory.xyz: File too large"* ]] || fail "message: $err"
    lines=$(wc -l <"$work/full/trajectory.xyz")
    [ $((lines % 218)) -eq 0 ] && [ "$lines" -gt 0 ] || fail "trajectory not whole frames: $lines lines"
    grep -q '"error": "cannot write' "$work/full/summary.json" || fail "summary does not record the error"
    ;;
signals)
    # SIGTERM and SIGHUP end a run like SIGINT: exit 128 + signal, summary naming the signal,
    # whole frames, the analysis written.
    for sig in TERM HUP; do
        "$terrace" run "$src/experiments/scenes/dense-rods.json" --quiet --out "$work/$sig" \
            --set state.n=216 --set run.equilibrate_ps=0 --set run.time_ps=900 \
            --set output.trajectory_every_fs=9 >/dev/null 2>&1 &
        pid=$!
        wait_frames "$work/$sig/trajectory.xyz" 216 5
        kill -$sig $pid
        wait $pid
        status=$?
        expected=$((128 + $(kill -l $sig)))
        [ $status -eq $expected ] || fail "exit status $status after SIG$sig, expected $expected"
        grep -q "\"interrupted_by\": \"SIG$sig\"" "$work/$sig/summary.json" ||
            fail "summary does not name SIG$sig"
        [ -s "$work/$sig/vacf.csv" ] || fail "no analysis after SIG$sig"
        frames=$(grep -c '^216$' "$work/$sig/trajectory.xyz")
        lines=$(wc -l <"$work/$sig/trajectory.xyz")
        [ "$lines" -eq $((frames * 218)) ] || fail "SIG$sig: trajectory not whole frames"
    done
    ;;
second_signal)
    # Two signals in quick succession: the run stops at the next sample and still writes its
    # analysis whole, since it was accumulated as the run went (only the files are left to write,
    # nothing slow to cancel); exit status 143.
    "$terrace" run "$src/experiments/scenes/dense-rods.json" --quiet --out "$work/two" \
        --set state.n=2744 --set run.equilibrate_ps=0 --set run.time_ps=45 \
        --set output.trajectory_every_fs=9 >/dev/null 2>&1 &
    pid=$!
    wait_frames "$work/two/trajectory.xyz" 2744 200 6000
    kill -TERM $pid
    sleep 0.5
    kill -TERM $pid
    start=$(date +%s)
    wait $pid
    status=$?
    [ $status -eq 143 ] || fail "exit status $status, expected 143"
    [ $(($(date +%s) - start)) -le 20 ] || fail "the run did not end promptly"
    grep -q '"interrupted_by": "SIGTERM"' "$work/two/summary.json" || fail "summary: not interrupted"
    grep -q '"analysis_cpu_seconds"' "$work/two/summary.json" ||
        fail "summary lacks the analysis: $(grep -A2 analysis "$work/two/summary.json")"
    for f in rdf.csv vacf.csv oacf.csv msd.csv; do
        [ -s "$work/two/$f" ] || fail "no $f after two signals"
    done
    ;;
kill_resume)
    # A run killed with SIGKILL and continued from its restart file ends with the same
    # trajectory, thermo.csv, correlation files and pressure, byte for byte, as the same run left
    # alone: DMD and SMD killed in production, DMD killed during a long equilibration (with
    # lengths that are no whole number of their intervals: its last rescale interval cut short,
    # its production's last 5 fs unsampled); and under each heat bath (its stream and energy
    # carried by restart.bin), with its summary block too; and a mixture of two masses in both
    # engines (its bodies' species carried by restart.bin); and the square-well mixture in DMD,
    # whose pairs' energies differ (its energy counted by pair of species, recounted on resuming).
    andersen='{"kind":"andersen","rate_per_ps":5}' csvr='{"kind":"csvr","tau_fs":90}'
    heavy_b='species=[{"name":"A","fraction":0.8},{"name":"B","fraction":0.2,"epsilon":0.5,"sigma":0.88,"mass":3}]'
    for case in dmd:0.2:0.9::mixture smd:0.2:0.9::mixture dmd:0.18:9 smd:0.18:9 dmd:9.005:0.905 \
        dmd:0.18:9:andersen smd:0.18:9:andersen dmd:0.18:9:csvr smd:0.18:9:csvr \
        dmd:9.005:0.905:andersen dmd:0:0::steps; do
        IFS=: read -r engine equilibrate ps bath mixture <<<"$case"
        name=$engine-$equilibrate${bath:+-$bath}${mixture:+-$mixture}
        scene=$src/experiments/scenes/dense-rods.json n=216 restart_ps=0.9 frame_fs=18
        if [ "$mixture" = mixture ]; then # its samples every 5 fs
            scene=$src/experiments/scenes/kob-andersen.json n=256 restart_ps=0.3 frame_fs=20
        fi
        args=(--quiet --set engine=$engine --set state.n=$n --set run.equilibrate_ps=$equilibrate
            --set run.time_ps=$ps --set output.trajectory_every_fs=$frame_fs
            --set output.thermo_every_fs=$((2 * frame_fs)) --set output.restart_every_ps=$restart_ps)
        [ -z "$bath" ] || args+=(--set "run.heat_bath=${!bath}")
        [ "$mixture" != mixture ] || args+=(--set "$heavy_b" --set state.density=0.85) # SMD's box: ≥ 2(r_u + skin)
        if [ "$mixture" = steps ]; then # lengths in its τ (2.155 ps)
            scene=$src/experiments/scenes/square-well-mixture.json
            args=(--quiet --set state.n=256 --set run.equilibrate=0.5 --set run.time=20
                --set run.sample=0.01 --set output.trajectory_every=0.1
                --set output.thermo_every=0.2 --set output.restart_every=2)
        fi
        "$terrace" run "$scene" --out "$work/$name-a" \
            "${args[@]}" >/dev/null || fail "$name: the uninterrupted run failed"
        "$terrace" run "$scene" --out "$work/$name-b" \
            "${args[@]}" >/dev/null 2>&1 &
        pid=$!
        for _ in $(seq 1 1000); do
            [ -e "$work/$name-b/restart.bin" ] && break
            sleep 0.01
        done
        sleep 0.15 # past the first restart point, so that the continued run cuts files back
        kill -KILL $pid
        wait $pid
        [ -e "$work/$name-b/restart.bin" ] || fail "$name: no restart file before the kill"
        [ ! -e "$work/$name-b/summary.json" ] || fail "$name: the run ended before the kill"
        if [ "$equilibrate" = 9.005 ]; then
            grep -qa equilibration "$work/$name-b/restart.bin" || fail "$name: not killed in equilibration"
            [ ! -e "$work/$name-b/trajectory.xyz" ] || fail "$name: production had begun"
            [ ! -e "$work/$name-b/thermo.csv" ] || fail "$name: thermo.csv before production"
        fi
        "$terrace" run --continue "$work/$name-b" --quiet >/dev/null ||
            fail "$name: --continue failed"
        files=(trajectory.xyz thermo.csv rdf.csv vacf.csv msd.csv)
        [ -n "$mixture" ] || files+=(oacf.csv) # spheres do not turn
        for f in "${files[@]}"; do
            cmp -s "$work/$name-a/$f" "$work/$name-b/$f" ||
                fail "$name: $f of the continued run differs from the uninterrupted run's"
        done
        pressure() { sed -n '/^  "pressure": {/,/^  }/p' "$1/summary.json"; }
        [ -n "$(pressure "$work/$name-a")" ] || fail "$name: no pressure in summary.json"
        [ "$(pressure "$work/$name-a")" = "$(pressure "$work/$name-b")" ] ||
            fail "$name: the continued run's pressure differs: $(pressure "$work/$name-b")"
        if [ -n "$bath" ]; then
            block() { sed -n '/^  "heat_bath": {/,/^  }/p' "$1/summary.json"; }
            [ -n "$(block "$work/$name-a")" ] || fail "$name: no heat_bath in summary.json"
            [ "$(block "$work/$name-a")" = "$(block "$work/$name-b")" ] ||
                fail "$name: the continued run's heat_bath differs: $(block "$work/$name-b")"
        fi
        grep -q '"continued": 1' "$work/$name-b/summary.json" || fail "$name: not marked continued"
        # The run's CPU adds up over its stretches (restart.bin keeps the first's): at least
        # what its engine spent in both, however little the continuation itself took.
        python3 - "$work/$name-b/summary.json" <<'PY' || fail "$name: process CPU of the continued run"
import json, sys
s = json.load(open(sys.argv[1]))
assert s["process_cpu_seconds"] >= s["cpu_seconds"] + s["cpu_seconds_equilibration"], s
PY
        [ ! -e "$work/$name-b/restart.bin" ] || fail "$name: restart file left after the end"
    done
    "$terrace" run --continue "$work/dmd-0.18-b" --quiet 2>/dev/null && fail "a finished run continued"
    err=$("$terrace" run --continue "$work/dmd-0.18-b" --set run.time_ps=0.9 2>&1)
    [ $? -eq 2 ] && [[ $err == *"--continue DIR takes no scene, --set"* ]] ||
        fail "--continue with --set: $err"
    ;;
heat_bath)
    # run.heat_bath "none" is NVE as without the key: every file the same, byte for byte (the
    # summary but for its CPU times). A bath's run reports it; a CSVR τ below SMD's step is refused.
    args=(--quiet --set state.n=216 --set run.equilibrate_ps=0.18 --set run.time_ps=0.9
        --set output.trajectory_every_fs=18 --set output.thermo_every_fs=36)
    for engine in dmd smd; do
        "$terrace" run "$src/experiments/scenes/dense-rods.json" --out "$work/$engine-plain" \
            "${args[@]}" --set engine=$engine >/dev/null || fail "$engine: the plain run failed"
        "$terrace" run "$src/experiments/scenes/dense-rods.json" --out "$work/$engine-none" \
            "${args[@]}" --set engine=$engine --set run.heat_bath=none >/dev/null ||
            fail "$engine: the run with heat_bath none failed"
        for f in scene.json initial.xyz trajectory.xyz thermo.csv rdf.csv vacf.csv msd.csv; do
            cmp -s "$work/$engine-plain/$f" "$work/$engine-none/$f" ||
                fail "$engine: $f differs under run.heat_bath none"
        done
        # The CPU times (SMD's phase_seconds among them) and the date vary from run to run.
        timeless() {
            grep -v -e seconds -e _per_cpu -e memory -e date_utc -e '"drift":' -e '"force":' \
                -e '"kick":' -e '"neighbour":' "$1/summary.json"
        }
        [ "$(timeless "$work/$engine-plain")" = "$(timeless "$work/$engine-none")" ] ||
            fail "$engine: summary.json differs under run.heat_bath none"
        ! grep -q heat_bath "$work/$engine-none/summary.json" || fail "$engine: a heat_bath block under none"
        "$terrace" run "$src/experiments/scenes/dense-rods.json" --out "$work/$engine-csvr" \
            "${args[@]}" --set engine=$engine --set 'run.heat_bath={"kind":"csvr","tau_fs":90}' \
            >/dev/null || fail "$engine: the CSVR run failed"
        grep -q '"degrees_of_freedom": 1077' "$work/$engine-csvr/summary.json" ||
            fail "$engine: no heat_bath block with f = 5N - 3 in summary.json"
        head -1 "$work/$engine-csvr/thermo.csv" | grep -q ',effective_total$' ||
            fail "$engine: thermo.csv lacks effective_total: $(head -1 "$work/$engine-csvr/thermo.csv")"
    done
    # A lattice start still aligned after equilibration is a warning (stderr and summary.json).
    err=$("$terrace" run "$src/experiments/scenes/dense-rods.json" --out "$work/aligned" --quiet \
        --set state.n=216 --set state.orientations=aligned --set run.equilibrate_ps=0.018 \
        --set run.time_ps=0.09 2>&1 >/dev/null) || fail "the aligned run failed"
    [[ $err == *"the lattice start has not melted after run.equilibrate_ps = 0.018 ps"*"S2 = "* ]] ||
        fail "no melt warning: $err"
    grep -q "has not melted" "$work/aligned/summary.json" || fail "no melt warning in summary.json"
    err=$("$terrace" run "$src/experiments/scenes/dense-rods.json" --out "$work/melted" --quiet \
        --set state.n=216 --set run.time_ps=0.09 2>&1 >/dev/null) || fail "the default run failed"
    [[ $err != *"has not melted"* ]] || fail "a melted start warned: $err"
    err=$("$terrace" run "$src/experiments/scenes/dense-rods.json" --out "$work/short" --set engine=smd \
        --set 'run.heat_bath={"kind":"csvr","tau_fs":1}' 2>&1) && fail "tau_fs < dt_fs accepted"
    [[ $err == *"run.heat_bath.tau_fs: 1 fs is shorter than smd.dt_fs = 1.8 fs"* ]] ||
        fail "tau_fs < dt_fs: $err"
    ;;
term_continue)
    # A run stopped by SIGTERM keeps its stop as a restart point: continued, it loses nothing and
    # ends as long as the run left alone, the same up to the stop (after it, the continued run's
    # engine was rebuilt at another instant: the same dynamics, other round-off).
    args=(--quiet --set state.n=216 --set run.equilibrate_ps=0.18 --set run.time_ps=9
        --set output.trajectory_every_fs=18 --set output.restart_every_ps=0.9)
    "$terrace" run "$src/experiments/scenes/dense-rods.json" --out "$work/a" "${args[@]}" \
        >/dev/null || fail "the uninterrupted run failed"
    "$terrace" run "$src/experiments/scenes/dense-rods.json" --out "$work/b" "${args[@]}" \
        >/dev/null 2>&1 &
    pid=$!
    # The first restart file of production (its first sample), kept to compare with the last.
    for _ in $(seq 1 6000); do
        grep -qa production "$work/b/restart.bin" 2>/dev/null && break
        sleep 0.01
    done
    cp "$work/b/restart.bin" "$work/first.bin" || fail "no restart file at production's start"
    wait_frames "$work/b/trajectory.xyz" 216 60
    kill -TERM $pid
    wait $pid
    status=$?
    [ $status -eq 143 ] || fail "exit status $status after SIGTERM"
    stopped=$(grep -c '^216$' "$work/b/trajectory.xyz")
    [ "$stopped" -lt 501 ] || fail "the run ended before the signal" # 1000 samples, every 2nd
    # The restart file holds no series of samples: after 120 samples or more it is as large as
    # after the first (3.1 MB), but for the integers that grew, the engine's counters among them
    # (from 0 at production's start: up to 8 bytes more each in CBOR; 665 bytes measured).
    first=$(stat -c %s "$work/first.bin") last=$(stat -c %s "$work/b/restart.bin")
    [ $((last - first)) -le 1024 ] && [ $((first - last)) -le 1024 ] ||
        fail "restart.bin grew from $first bytes at the first sample to $last at sample $((2 * stopped - 2))"
    "$terrace" run --continue "$work/b" --quiet >/dev/null || fail "--continue failed"
    [ "$(grep -c '^216$' "$work/b/trajectory.xyz")" -eq "$(grep -c '^216$' "$work/a/trajectory.xyz")" ] ||
        fail "the continued trajectory has another length"
    cmp -s <(head -n $((stopped * 218)) "$work/a/trajectory.xyz") \
        <(head -n $((stopped * 218)) "$work/b/trajectory.xyz") || fail "differs before the stop"
    grep -q '"continued": 1' "$work/b/summary.json" || fail "not marked continued"
    grep -q '"interrupted": false' "$work/b/summary.json" || fail "the finished run says interrupted"
    ;;
gsd_continue)
    # A GSD trajectory through SIGTERM and --continue: the continued file holds as many frames as
    # the run left alone, the same up to the stop, read by gsd; and a restart point whose GSD file
    # was replaced by another run's is refused naming the file.
    python=
    for p in ${TERRACE_PYTHON:-} /usr/bin/python3 python3; do
        if "$p" -c 'import gsd.hoomd' >/dev/null 2>&1; then python=$p; break; fi
    done
    [ -n "$python" ] || fail "no python3 with gsd (gsd.hoomd): apt-get install python3-gsd"
    args=(--quiet --set state.n=216 --set run.equilibrate_ps=0.18 --set run.time_ps=9
        --set output.trajectory_every_fs=18 --set output.trajectory_format=gsd
        --set output.restart_every_ps=0.9)
    "$terrace" run "$src/experiments/scenes/dense-rods.json" --out "$work/a" "${args[@]}" \
        >/dev/null || fail "the uninterrupted run failed"
    "$terrace" run "$src/experiments/scenes/dense-rods.json" --out "$work/b" "${args[@]}" \
        >/dev/null 2>&1 &
    pid=$!
    for _ in $(seq 1 6000); do [ -e "$work/b/restart.bin" ] && break; sleep 0.01; done
    kill -TERM $pid
    wait $pid
    status=$?
    [ $status -eq 143 ] || fail "exit status $status after SIGTERM"
    frames() { "$python" -c 'import gsd.hoomd, sys; print(len(gsd.hoomd.open(sys.argv[1], "rb")))' "$1"; }
    stopped=$(frames "$work/b/trajectory.gsd") || fail "gsd cannot read the stopped run's file"
    [ "$stopped" -lt 501 ] || fail "the run ended before the signal"
    cp -r "$work/b" "$work/c"
    "$terrace" run --continue "$work/b" --quiet >/dev/null || fail "--continue failed"
    out=$("$python" - "$work/a/trajectory.gsd" "$work/b/trajectory.gsd" "$stopped" 2>&1 <<'PY'
import sys
import numpy as np
import gsd.hoomd
a, b = (gsd.hoomd.open(p, "rb") for p in sys.argv[1:3])
stopped = int(sys.argv[3])
if len(a) != len(b):
    sys.exit(f"{len(b)} frames continued, {len(a)} left alone")
for k in range(stopped):
    fa, fb = a[k], b[k]
    if fa.configuration.step != fb.configuration.step or not np.array_equal(
            fa.particles.position, fb.particles.position) or not np.array_equal(
            fa.particles.orientation, fb.particles.orientation):
        sys.exit(f"frame {k} differs before the stop")
steps = [f.configuration.step for f in b]
if steps != sorted(steps) or len(set(steps)) != len(steps):
    sys.exit(f"steps not increasing once each: {steps[:5]}...")
PY
    ) || fail "$out"
    # The stopped copy's trajectory swapped for another run's (another seed, as many frames):
    # refused, naming the file. (The run left alone, the same up to the stop, would be taken.)
    "$terrace" run "$src/experiments/scenes/dense-rods.json" --out "$work/d" "${args[@]}" \
        --set seed=2 --set run.time_ps=1.8 >/dev/null || fail "the other seed's run failed"
    cp "$work/d/trajectory.gsd" "$work/c/trajectory.gsd"
    err=$("$terrace" run --continue "$work/c" --quiet 2>&1 >/dev/null) && fail "another run's file taken"
    [[ $err == *"trajectory.gsd"* ]] || fail "the refusal does not name trajectory.gsd: $err"
    ;;
hot_restarts)
    # A restart point rebuilds the engine from a running state: checks meant for a start (overlap)
    # are not repeated there, or a hot SMD run with restarts would fail where one without runs.
    "$terrace" run "$src/experiments/scenes/dense-rods.json" --quiet --out "$work/hot" \
        --set engine=smd --set state.n=216 --set state.temperature=3000 --set smd.dt_fs=0.05 \
        --set run.sample_fs=0.5 --set run.thermostat_fs=0.5 --set run.equilibrate_ps=0 \
        --set run.time_ps=0.1 --set output.restart_every_ps=0.0005 >/dev/null ||
        fail "a hot SMD run with restarts failed"
    ;;
partial_frame)
    # A trajectory whose last frame was cut by a kill is analysed up to its last whole frame.
    short_run dmd --set output.trajectory_every_fs=9
    size=$(stat -c %s "$work/dmd/trajectory.xyz")
    truncate -s $((size - 3000)) "$work/dmd/trajectory.xyz"
    out=$("$terrace" analyse "$work/dmd" 2>&1) || fail "analyse rejects a cut-off last frame: $out"
    [[ $out == *"warning"*"the last frame is cut short"* ]] || fail "no warning: $out"
    ;;
memory)
    # A run whose analysis cannot fit in memory is refused before it starts, with the estimate:
    # 4096 of 8000 bodies followed with 4096 lags a level over 10^9 samples (~25 GiB, under ulimit -v
    # 8 GiB). The samples are not kept (their statistics stream): 10^9 samples of the default
    # analysis need some MiB, and are not refused.
    err=$(ulimit -v 8388608; "$terrace" run "$src/experiments/scenes/dense-rods.json" --quiet \
        --out "$work/big" --set state.n=8000 --set analysis.lags_per_level=4096 \
        --set run.sample_fs=0.01 --set run.time_ps=10000 2>&1 >/dev/null) && fail "exit status 0"
    [[ $err == "terrace: run: analysis.follow_bodies, analysis.lags_per_level (4096 bodies followed, 4096 lags a level): the run needs about"*"of memory"*"available: follow fewer bodies or use fewer lags a level" ]] ||
        fail "message: $err"
    [ ! -e "$work/big" ] || fail "output written for a run refused"
    # 10^8 bodies (~50 GiB; was stopped only by an allocation failing): refused at once, before
    # anything is allocated, naming the estimate and what the process may take (under ulimit -v
    # 8 GiB, so that a machine with that much memory refuses them too); DMD at 6·10^7, below
    # the most bodies it runs, 67108863, which is refused as such.
    for case in dmd:60000000 smd:100000000 dmd:70000000; do
        engine=${case%%:*} n=${case#*:}
        start=$(date +%s%N)
        err=$(ulimit -v 8388608; "$terrace" run "$src/experiments/scenes/dense-rods.json" --quiet \
            --out "$work/huge" --set engine=$engine --set state.n=$n 2>&1 >/dev/null)
        status=$?
        elapsed=$(( ($(date +%s%N) - start) / 1000000 ))
        [ $status -eq 1 ] || fail "$engine, $n bodies: exit status $status: $err"
        [ "$(printf '%s\n' "$err" | wc -l)" -eq 1 ] || fail "not one line: $err"
        if [ "$n" = 70000000 ]; then
            [[ $err == "terrace: run: state.n = 70000000: DMD runs at most 67108863 bodies"* ]] ||
                fail "DMD beyond its limit: $err"
        else
            [[ $err == "terrace: run: state.n = $n: the run needs about "*" GiB of memory (engine "*", analysis "*") and "*" available: use fewer bodies" ]] ||
                fail "$engine, $n bodies: message: $err"
        fi
        [ "$elapsed" -lt 5000 ] || fail "$engine: the refusal took $elapsed ms"
        [ ! -e "$work/huge" ] || fail "output written for a run refused"
    done
    ;;
not_utf8)
    # Bytes that are not UTF-8 in a --set (key or value), a scene file or a sweep file: one line
    # naming the byte and where it is (the bytes shown escaped, not echoed), nothing written.
    expect_error "$src/experiments/scenes/dense-rods.json" \
        '--set dmd.\xff=1: not UTF-8 text (byte 0xff at character 5)' --set $'dmd.\xff=1'
    expect_error "$src/experiments/scenes/dense-rods.json" \
        '--set name=caf\xe9: not UTF-8 text (byte 0xe9 at character 9)' --set $'name=caf\xe9'
    printf '{"name": "caf\xe9"}' >"$work/latin1.json"
    expect_error "$work/latin1.json" 'not UTF-8 text (byte 0xe9 at line 1, column 14)'
    printf '{"scene": "%s", "set": {"dmd.\xff": 1}}' "$src/experiments/scenes/dense-rods.json" \
        >"$work/s.json"
    err=$("$terrace" sweep "$work/s.json" --out "$work/sweep" 2>&1)
    status=$?
    [ $status -eq 2 ] || fail "a sweep file that is not UTF-8: exit status $status"
    [[ $err == "terrace: $work/s.json: byte 0xff at line 1, column "*": not UTF-8 text: a sweep file is JSON, which is UTF-8" ]] ||
        fail "sweep file: $err"
    printf '{"scene": "%s"}' "$src/experiments/scenes/dense-rods.json" >"$work/s.json"
    err=$("$terrace" sweep "$work/s.json" --out "$work/sweep" --set $'name=caf\xe9' 2>&1)
    [ $? -eq 2 ] || fail "a sweep's --set that is not UTF-8: exit status not 2"
    [[ $err == *'--set name=caf\xe9: not UTF-8 text (byte 0xe9 at character 9)'* ]] ||
        fail "sweep --set: $err"
    [ ! -e "$work/sweep" ] || fail "a refused sweep wrote its directory"
    ;;
disk)
    # A trajectory beyond the free space of the output's file system (64 000 rods, a frame every
    # 9 fs for 9 ns: ~17 TB) is refused before the run, naming the estimate, the free space and
    # the key; nothing is written.
    err=$("$terrace" run "$src/experiments/scenes/dense-rods.json" --quiet --out "$work/disk" \
        --set state.n=64000 --set analysis.follow_bodies=100 --set run.time_ps=9000 \
        --set output.trajectory_every_fs=9 2>&1 >/dev/null)
    status=$?
    [ $status -eq 1 ] || fail "exit status $status: $err"
    [ "$(printf '%s\n' "$err" | wc -l)" -eq 1 ] || fail "not one line: $err"
    [[ $err == "terrace: run: output.trajectory_every_fs: the run will write about "*" TiB into $work/disk (trajectory.xyz "*") and its file system has "*" free: write less often, or choose another --out" ]] ||
        fail "message: $err"
    [ ! -e "$work/disk" ] || fail "output written for a run refused"
    # The same as GSD, a fifth of the bytes, still beyond: the message names trajectory.gsd.
    err=$("$terrace" run "$src/experiments/scenes/dense-rods.json" --quiet --out "$work/disk" \
        --set state.n=64000 --set analysis.follow_bodies=100 --set run.time_ps=9000 \
        --set output.trajectory_every_fs=9 --set output.trajectory_format=gsd 2>&1 >/dev/null) &&
        fail "gsd: exit status 0"
    [[ $err == *"output.trajectory_every_fs: the run will write about"*"(trajectory.gsd "* ]] ||
        fail "gsd: message: $err"
    [ ! -e "$work/disk" ] || fail "output written for a run refused"
    ;;
ase_read)
    # Trajectories a real client reads: ASE's extended XYZ reader loads every body kind's file,
    # and a mixture's, with the frames, bodies and positions that the file holds, and the
    # mixture's species_index column as initial.xyz has it, every species there. python3-ase is a dependency of
    # the test suite (quickstart.sh installs it): missing, the check fails rather than skips.
    python=
    for p in ${TERRACE_PYTHON:-} /usr/bin/python3 python3; do
        if "$p" -c 'import ase.io' >/dev/null 2>&1; then python=$p; break; fi
    done
    [ -n "$python" ] || fail "no python3 with ASE (ase.io): apt-get install python3-ase" \
        "(./quickstart.sh installs it), or name an interpreter that has it in TERRACE_PYTHON"
    for kind in sphere linear symmetric asymmetric mixture; do
        case $kind in # the built-in default otherwise: rod-lj, I = (1.154, 1.154, 0) g/mol Å²
        sphere) body='"kind": "sphere"}, "potential": {"kind": "lj"' ;;
        mixture) body='"kind": "sphere"}, "species": [{"name": "A", "fraction": 0.8, "epsilon": 1,
            "sigma": 1}, {"name": "B", "fraction": 0.2, "epsilon": 0.5, "sigma": 0.88}],
            "potential": {"kind": "lj"' ;;
        linear) body='"kind": "linear"' ;;
        symmetric) body='"kind": "symmetric", "inertia": [1.154, 1.154, 0.5]' ;;
        asymmetric) body='"kind": "asymmetric", "inertia": [0.8, 1.154, 0.5]' ;;
        esac
        printf '{"name": "%s", "body": {%s}, "state": {"n": 64, "density": 0.1}}' \
            "$kind" "$body" >"$work/$kind.json"
        "$terrace" run "$work/$kind.json" --quiet --out "$work/$kind" --set run.equilibrate_ps=0 \
            --set run.time_ps=0.036 --set output.trajectory_every_fs=9 >"$work/$kind.log" 2>&1 ||
            fail "$kind run failed: $(cat "$work/$kind.log")"
        out=$("$python" - "$work/$kind/trajectory.xyz" "$kind" 2>&1 <<'PY'
import sys
import numpy as np
import ase.io

path, kind = sys.argv[1], sys.argv[2]
code = {"sphere": 0, "linear": 2, "symmetric": 3, "asymmetric": 3, "mixture": 0}[kind]
# The file's own numbers, frame by frame: count, Time and positions (columns 2-4).
expected = []
with open(path) as f:
    lines = f.read().splitlines()
i = 0
while i < len(lines):
    n = int(lines[i])
    time = float(lines[i + 1].split("Time=")[1].split()[0])
    rows = [line.split() for line in lines[i + 2:i + 2 + n]]
    expected.append((n, time, np.array([[float(x) for x in r[1:4]] for r in rows])))
    i += n + 2
frames = ase.io.read(path, ":")
if len(frames) != len(expected) or len(frames) < 5:
    sys.exit(f"ASE read {len(frames)} frames, the file holds {len(expected)} (at least 5)")
for k, (atoms, (n, time, pos)) in enumerate(zip(frames, expected)):
    if len(atoms) != n:
        sys.exit(f"frame {k}: ASE read {len(atoms)} bodies, the file holds {n}")
    if not np.array_equal(atoms.positions, pos):
        sys.exit(f"frame {k}: ASE's positions differ from the file's")
    if set(atoms.get_chemical_symbols()) != {"X"}:
        sys.exit(f"frame {k}: species {set(atoms.get_chemical_symbols())}, expected X")
    if not np.all(atoms.arrays["body"] == code):
        sys.exit(f"frame {k}: body column {set(atoms.arrays['body'])}, expected {code}")
    if atoms.info["Time"] != time or not all(atoms.pbc):
        sys.exit(f"frame {k}: Time {atoms.info['Time']} (file {time}), pbc {atoms.pbc}")
    if kind == "mixture":
        start = ase.io.read(path.replace("trajectory.xyz", "initial.xyz"))
        if not np.array_equal(atoms.arrays["species_index"], start.arrays["species_index"]):
            sys.exit(f"frame {k}: species_index differs from initial.xyz's")
        if set(atoms.arrays["species_index"]) != {0, 1}:
            sys.exit(f"frame {k}: species_index {set(atoms.arrays['species_index'])}")
    elif "species_index" in atoms.arrays:
        sys.exit(f"frame {k}: a species_index column without species")
PY
        ) || fail "ASE cannot read the $kind trajectory ($python): $out"
    done
    ;;
export_refusal)
    # terrace export lammps: what LAMMPS cannot represent is refused in one line naming the key,
    # with nothing written; a usage error names the command's help.
    err=$("$terrace" export lammps "$src/experiments/scenes/dense-rods.json" "$work/rods" 2>&1 >/dev/null) &&
        fail "exit status 0 for the rod potential"
    [ "$(printf '%s\n' "$err" | wc -l)" -eq 1 ] || fail "refusal is not one line: $err"
    [[ $err == *"potential.kind: rod-lj"*"no LAMMPS pair style"* ]] || fail "refusal names no reason: $err"
    [ ! -e "$work/rods" ] || fail "files written for a refused scene"
    err=$("$terrace" export gromacs "$src/experiments/scenes/lj-liquid.json" "$work/g" 2>&1 >/dev/null) &&
        fail "exit status 0 for an unknown format"
    [[ $err == *"no format 'gromacs'"*"export --help"* ]] || fail "unknown format: $err"
    "$terrace" export --help | grep -q "terrace export lammps SCENE.json DIR" || fail "no export --help"
    "$terrace" --help | grep -q "terrace export lammps" || fail "terrace --help lacks export"
    ;;
lammps_energy)
    # The exported decks run by LAMMPS (Debian's lammps, which quickstart.sh installs; without
    # lmp the check is skipped, saying so): the potential energy of the first frame (run 0)
    # against terrace's at the same state (thermo.csv's first row of an SMD run that starts
    # production at once). LJ spheres: the model is the same (a table of g(r)·U_LJ), to 1e-6
    # relative; so are Gay–Berne and dumbbells where no pair lies in the switch band (gb-random,
    # dumbbell-band). Otherwise
    # Gay–Berne and site molecules: LAMMPS cuts or switches differently (the export's
    # notes), so LAMMPS is held to the deck's own model, which the export evaluates in terrace,
    # to 1e-6, and the export's terrace model to the run's, to 1e-9; the gap is printed.
    # TERRACE_LMP names another LAMMPS binary (lmp_serial, lmp_mpi, a build of one's own).
    lmp=${TERRACE_LMP:-lmp}
    if ! command -v "$lmp" >/dev/null; then
        echo "SKIPPED: no LAMMPS binary '$lmp' (apt-get install lammps, or ./quickstart.sh)"
        exit 77
    fi
    export OMP_NUM_THREADS=1
    for case in lj gb gb-random dumbbell dumbbell-band triatomic; do
        case $case in
        lj) # thermo every sample (9 fs, 45 steps), in the deck as in the run
            scene=lj-liquid sets=(--set state.n=256 --set output.thermo_every_fs=9) ;;
        gb) scene=gay-berne-liquid sets=() ;;
        gb-random) # random axes on a lattice whose shells (8.33, 11.78, 14.4 Å) leave the switch
            # band [12, 13.5] Å empty: there LAMMPS's cut and terrace's switch give one U
            scene=gay-berne-liquid
            sets=(--set state.orientations=random --set state.density=0.035
                --set state.lattice_aspect=1 --set 'potential.cutoff=[4.0,4.5]') ;;
        dumbbell) scene=dumbbell-liquid sets=() ;;
        dumbbell-band) # aligned dumbbells on a lattice where every pair of molecules has its
            # centre and all four site distances on one side of the band [8.08, 8.31] Å: there
            # the switch by centre distance and the one by site distance give one U
            scene=dumbbell-liquid
            sets=(--set state.density=0.2 --set state.lattice_aspect=1
                --set 'potential.cutoff=[2.44,2.51]') ;;
        triatomic) scene=triatomic-liquid sets=() ;;
        esac
        "$terrace" export lammps "$src/experiments/scenes/$scene.json" "$work/$case" "${sets[@]}" \
            >"$work/$case.export" 2>&1 || fail "$case: export failed: $(cat "$work/$case.export")"
        (cd "$work/$case" && "$lmp" -in in.terrace -var steps 0 -var equilibrate 0 -log none \
            -screen lammps.out >/dev/null 2>&1) ||
            fail "$case: LAMMPS failed: $(tail -5 "$work/$case/lammps.out")"
        pe=$(awk '/^ *Step / { getline; print $3; exit }' "$work/$case/lammps.out")
        [ -n "$pe" ] || fail "$case: no thermo row in LAMMPS's output"
        "$terrace" run "$src/experiments/scenes/$scene.json" "${sets[@]}" --set engine=smd \
            --set run.equilibrate_ps=0 --set run.sample_fs=9 --set run.time_ps=0.009 \
            --set output.thermo_every_fs=9 --quiet --out "$work/$case-run" >/dev/null 2>&1 ||
            fail "$case: terrace run failed"
        ut=$(awk -F, '$1 == "0" { print $5; exit }' "$work/$case-run/thermo.csv")
        read -r et ed <<<"$(awk '/U of the initial state/ { print $7, $11 }' "$work/$case.export")"
        # The kinetic energy too: velocities, angular momenta and masses carried over, in LAMMPS's
        # own units (its mvv2e). LAMMPS's ellipsoid has a spin, which starts at 0, and here its
        # moment across the axis is the scene's, so K is terrace's for every case.
        awk -F, -v c="$case" 'FNR == 1 { file++ }
            file == 1 && /^ *Step / { getline; split($0, w, " "); kl = w[4] * 4.184 }
            file == 2 && $1 == "0" { kt = $2 + $3 }
            END { d = (kl - kt) / kt
                  printf "%s: first frame K, LAMMPS %.12g kJ/mol, terrace %.12g: relative %.2g\n", c, kl, kt, d
                  exit !(d > -1e-6 && d < 1e-6) }' "$work/$case/lammps.out" "$work/$case-run/thermo.csv" ||
            fail "$case: kinetic energies disagree"
        awk -v pe="$pe" -v ut="$ut" -v et="$et" -v ed="$ed" -v c="$case" 'BEGIN {
            ul = pe * 4.184; d = (ul - ut) / ut; dd = (ul - ed) / ed; dt = (et - ut) / ut
            printf "%s: first frame U, LAMMPS %.12g kJ/mol, terrace %.12g: relative %.2g (the deck'"'"'s model %.12g: %.2g)\n", c, ul, ut, d, ed, dd
            if (dd < -1e-6 || dd > 1e-6) { print c ": LAMMPS differs from the deck'"'"'s model"; exit 1 }
            if (dt < -1e-9 || dt > 1e-9) { print c ": the export'"'"'s terrace U differs from the run'"'"'s"; exit 1 }
            if ((c == "lj" || c == "gb-random" || c == "dumbbell-band") && (d < -1e-6 || d > 1e-6)) {
                print c ": LAMMPS differs from terrace"; exit 1 }
        }' || fail "$case: energies disagree"
    done
    # A few steps: the LJ deck run 9 fs (45 steps of 0.2 fs, its thermo interval) against
    # terrace's SMD row at 0.009 ps; the table's forces are within its interpolation of the
    # formula's, so U stays within 1e-6 (measured: 5.6e-8).
    (cd "$work/lj" && "$lmp" -in in.terrace -var steps 45 -var equilibrate 0 -log none \
        -screen steps.out >/dev/null 2>&1) || fail "lj: LAMMPS failed over 45 steps"
    pe=$(awk '/^ *Step / { getline; getline; print $1, $3; exit }' "$work/lj/steps.out")
    ut=$(awk -F, '$1 == "0.009" { print $5; exit }' "$work/lj-run/thermo.csv")
    awk -v pe="${pe#* }" -v step="${pe% *}" -v ut="$ut" 'BEGIN {
        ul = pe * 4.184; d = (ul - ut) / ut
        printf "lj after 45 steps: U LAMMPS %.12g kJ/mol, terrace %.12g: relative %.2g\n", ul, ut, d
        exit !(step == 45 && ut != "" && d > -1e-6 && d < 1e-6) }' || fail "lj: U after 45 steps differs"
    # The deck's equilibration is terrace's: velocities rescaled to T every 9 fs (45 steps) over
    # 18 fs, then 45 steps of NVE; U at production's start and 9 fs into it, to 1e-6 each
    # (measured: 1.6e-8 and 7.6e-8).
    (cd "$work/lj" && "$lmp" -in in.terrace -var equilibrate 90 -var steps 45 -log none \
        -screen equilibrated.out >/dev/null 2>&1) || fail "lj: LAMMPS failed to equilibrate"
    "$terrace" run "$src/experiments/scenes/lj-liquid.json" --set state.n=256 --set engine=smd \
        --set run.equilibrate_ps=0.018 --set run.sample_fs=9 --set run.time_ps=0.009 \
        --set output.thermo_every_fs=9 --quiet --out "$work/lj-equilibrated" >/dev/null 2>&1 ||
        fail "lj: the equilibrated terrace run failed"
    awk -F, 'FNR == 1 { file++ }
        file == 1 && split($0, w, " ") == 6 && w[1] ~ /^[0-9]+$/ { if (w[1] == 90) l0 = w[3]; if (w[1] == 135) l1 = w[3] }
        file == 2 && $1 == "0" { t0 = $5 } file == 2 && $1 == "0.009" { t1 = $5 }
        END { d0 = (l0 * 4.184 - t0) / t0; d1 = (l1 * 4.184 - t1) / t1
              printf "lj equilibrated: U LAMMPS %.12g and %.12g kJ/mol, terrace %.12g and %.12g: relative %.2g and %.2g\n", l0 * 4.184, l1 * 4.184, t0, t1, d0, d1
              exit !(l0 != "" && l1 != "" && t0 != "" && t1 != "" && d0 > -1e-6 && d0 < 1e-6 && d1 > -1e-6 && d1 < 1e-6) }' \
        "$work/lj/equilibrated.out" "$work/lj-equilibrated/thermo.csv" || fail "lj: the equilibrated U differs"
    ;;
gsd_read)
    # GSD trajectories read by Debian's python3-gsd (gsd.hoomd), for every body kind and shape:
    # the same run written as extended XYZ and as GSD (same seed, the same trajectory), frame by
    # frame the GSD file's step, time, box, unwrapped positions (position + image·L) and axes
    # (orientation applied to the body z axis) against the XYZ file's, to single precision; the
    # type's shape and moments; tops' orientations; both engines. quickstart.sh installs
    # python3-gsd: missing, the check fails rather than skips.
    python=
    for p in ${TERRACE_PYTHON:-} /usr/bin/python3 python3; do
        if "$p" -c 'import gsd.hoomd' >/dev/null 2>&1; then python=$p; break; fi
    done
    [ -n "$python" ] || fail "no python3 with gsd (gsd.hoomd): apt-get install python3-gsd" \
        "(./quickstart.sh installs it), or name an interpreter that has it in TERRACE_PYTHON"
    for kind in sphere linear symmetric asymmetric gay-berne dumbbell; do
        engine=dmd
        case $kind in # the built-in default otherwise: rod-lj, I = (1.154, 1.154, 0) g/mol Å²
        sphere) body='"body": {"kind": "sphere"}, "potential": {"kind": "lj"}' shape=Sphere ;;
        linear) body='"body": {"kind": "linear"}' shape=ConvexPolyhedron engine=smd ;;
        symmetric) body='"body": {"kind": "symmetric", "inertia": [1.154, 1.154, 0.5]}' shape=ConvexPolyhedron ;;
        asymmetric) body='"body": {"kind": "asymmetric", "inertia": [0.8, 1.154, 0.5]}' shape=ConvexPolyhedron engine=smd ;;
        gay-berne) shape=Ellipsoid ;;
        dumbbell) shape=SphereUnion ;;
        esac
        case $kind in
        gay-berne | dumbbell) scene=$src/experiments/scenes/$kind-liquid.json ;;
        *)
            printf '{"name": "%s", %s, "state": {"n": 64, "density": 0.1}}' "$kind" "$body" \
                >"$work/$kind.json"
            scene=$work/$kind.json
            ;;
        esac
        n=64 # Gay–Berne and the dumbbell's box needs more at their density (twice r_m)
        case $kind in gay-berne | dumbbell) n=128 ;; esac
        for format in xyz gsd; do
            "$terrace" run "$scene" --quiet --out "$work/$kind-$format" --set engine=$engine \
                --set state.n=$n --set run.equilibrate_ps=0 --set run.time_ps=0.036 \
                --set output.trajectory_every_fs=9 --set output.trajectory_format=$format \
                >"$work/$kind.log" 2>&1 || fail "$kind $format run failed: $(cat "$work/$kind.log")"
        done
        [ ! -e "$work/$kind-gsd/trajectory.xyz" ] || fail "$kind: a GSD run also wrote trajectory.xyz"
        out=$("$python" - "$work/$kind-xyz/trajectory.xyz" "$work/$kind-gsd/trajectory.gsd" \
            "$shape" 2>&1 <<'PY'
import json, sys
import numpy as np
import gsd.hoomd

xyz, path, shape = sys.argv[1:]
# The XYZ file's frames: Time, box, positions and axes (a top's orientation w x y z gives it).
frames = []
with open(xyz) as f:
    lines = f.read().splitlines()
i = 0
while i < len(lines):
    n = int(lines[i])
    head = lines[i + 1]
    props = head.split("Properties=")[1].split()[0].split(":")
    cols, at = {}, 0
    for name, kind, width in zip(props[0::3], props[1::3], props[2::3]):
        cols[name] = (at, at + int(width))
        at += int(width)
    rows = np.array([[float(x) for x in l.split()[1:]] for l in lines[i + 2:i + 2 + n]])
    def col(name):
        a, b = cols[name]
        return rows[:, a - 1:b - 1]
    time = float(head.split("Time=")[1].split()[0])
    box = float(head.split('Lattice="')[1].split()[0])
    if "axis" in cols:
        axis = col("axis")
    elif "orientation" in cols:
        q = col("orientation")  # w x y z: the image of z
        w, x, y, z = q.T
        axis = np.stack([2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)], 1)
    else:
        axis = None
    frames.append((n, time, box, col("pos"), axis, col("orientation") if "orientation" in cols else None))
    i += n + 2
traj = gsd.hoomd.open(path, "rb")
if len(traj) != len(frames) or len(traj) < 5:
    sys.exit(f"gsd read {len(traj)} frames, the XYZ file holds {len(frames)} (at least 5)")
first = traj[0]
shapes = first.particles.type_shapes
if len(shapes) != 1 or shapes[0].get("type") != shape:
    sys.exit(f"type_shapes {shapes}, expected one {shape}")
for k, (f, (n, time, box, pos, axis, ori)) in enumerate(zip(traj, frames)):
    p = f.particles
    if p.N != n or f.configuration.step != k * 1:
        sys.exit(f"frame {k}: N {p.N} (file {n}), step {f.configuration.step}")
    if abs(f.log["time_ps"][0] * 1000 - time) > 1e-9 * max(1, time):
        sys.exit(f"frame {k}: time {f.log['time_ps'][0]} ps, the XYZ file {time} fs")
    if not np.allclose(f.configuration.box, [box, box, box, 0, 0, 0], rtol=1e-6):
        sys.exit(f"frame {k}: box {f.configuration.box}, expected {box}")
    if np.any(np.abs(p.position) > box / 2 + 1e-4):
        sys.exit(f"frame {k}: positions outside the box")
    unwrapped = p.position.astype(float) + p.image * box
    if not np.allclose(unwrapped, pos, atol=1e-4 * box):
        sys.exit(f"frame {k}: positions differ from the XYZ file's by {np.abs(unwrapped - pos).max()}")
    q = p.orientation.astype(float)
    if not np.allclose(np.linalg.norm(q, axis=1), 1, atol=1e-6):
        sys.exit(f"frame {k}: orientations not unit quaternions")
    if axis is not None:
        w, x, y, z = q.T
        image = np.stack([2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)], 1)
        if not np.allclose(image, axis, atol=1e-5):
            sys.exit(f"frame {k}: orientations do not carry the axes, off by {np.abs(image - axis).max()}")
    if ori is not None and not np.allclose(q, ori, atol=1e-6):
        sys.exit(f"frame {k}: a top's orientations differ from the XYZ file's")
    if k == 0 and (p.moment_inertia is None or p.mass is None):
        sys.exit("frame 0 lacks masses or moments of inertia")
PY
        ) || fail "gsd cannot read the $kind trajectory as the run wrote it ($python): $out"
    done
    ;;
thermo)
    # thermo.csv from both engines (cli/thermo.hpp): its header, a row at production's start and
    # every output.thermo_every_fs after it (0.54 ps / 36 fs + 1 = 16 rows), DMD's total energy
    # conserved to round-off and its collisions adding up to the summary's across restart points
    # (engines rebuilt every 0.18 ps); summary.json's pressure.
    names=time_ps,kinetic_translational,kinetic_rotational,potential,potential_continuous,total
    names=$names,temperature_K,pressure_bar
    for engine in dmd smd; do
        "$terrace" run "$src/experiments/scenes/dense-rods.json" --quiet --out "$work/$engine" \
            --set engine=$engine --set state.n=216 --set run.equilibrate_ps=0.09 \
            --set run.time_ps=0.54 --set output.thermo_every_fs=36 \
            --set output.restart_every_ps=0.18 >/dev/null || fail "$engine run failed"
        f=$work/$engine/thermo.csv
        expected=$names
        [ $engine = dmd ] && expected=$names,collisions
        [ "$(head -n 1 "$f")" = "$expected" ] || fail "$engine: header $(head -n 1 "$f")"
        [ "$(sed -n 2p "$f" | cut -c1)" = "#" ] || fail "$engine: no units line"
        rows=$(grep -vc '^#' "$f")
        [ $((rows - 1)) -eq 16 ] || fail "$engine: $((rows - 1)) rows, expected 16"
        # Times from the sample index on the run's grid, shown as the decimals they are.
        [ "$(tail -n 1 "$f" | cut -d, -f1)" = 0.54 ] || fail "$engine: the last row is not at 0.54 ps"
        [ "$(sed -n 9p "$f" | cut -d, -f1)" = 0.18 ] ||
            fail "$engine: the sixth row's time is $(sed -n 9p "$f" | cut -d, -f1), not 0.18"
        # Total energy: DMD's (terraced U + K) within 1e-9 of K of the first row's, SMD's within
        # 1e-2 of K (summary.json's own warning threshold).
        tol=1e-2
        [ $engine = dmd ] && tol=1e-9
        awk -F, -v tol=$tol '/^#/ || NR == 1 { next }
            !n++ { e0 = $6; k = $2 + $3 } { d = $6 - e0; if (d < 0) d = -d; if (d > m) m = d }
            END { exit !(m <= tol * k) }' "$f" || fail "$engine: total energy not conserved"
        for key in mean_bar error_bar mean_reduced error_reduced samples kinetic_term_reduced \
            virial_term_reduced; do
            grep -q "\"$key\": [-0-9]" "$work/$engine/summary.json" ||
                fail "$engine: summary.json lacks pressure.$key"
        done
    done
    # DMD: no pressure on the first row (no interval yet); collisions over the rows add up to
    # the run's. SMD: its potential is the continuous one.
    awk -F, '/^#/ || NR == 1 { next }
        !seen++ { if ($8 != "nan") exit 1; next } $8 == "nan" { exit 1 }' "$work/dmd/thermo.csv" ||
        fail "dmd: pressure_bar not nan on the first row only"
    sum=$(awk -F, '/^#/ || NR == 1 { next } { s += $9 } END { print s }' "$work/dmd/thermo.csv")
    rate=$(sed -n 's/^  "collisions_per_ps": \(.*\),$/\1/p' "$work/dmd/summary.json")
    awk -v s="$sum" -v r="$rate" 'BEGIN { d = s - r * 0.54; exit !(s > 0 && d * d < 0.25) }' ||
        fail "dmd: thermo.csv counts $sum collisions, summary.json $rate per ps over 0.54 ps"
    awk -F, '/^#/ || NR == 1 { next } $4 != $5 { exit 1 }' "$work/smd/thermo.csv" ||
        fail "smd: potential_continuous differs from potential"
    # On by default: 0.54 ps of 9 fs is 60 samples, fewer than 150, so a row at each (61 rows),
    # every time a short decimal (k · 0.009 ps, no binary round-off); off with an explicit 0.
    "$terrace" run "$src/experiments/scenes/dense-rods.json" --quiet --out "$work/default" \
        --set state.n=216 --set run.equilibrate_ps=0.09 --set run.time_ps=0.54 >/dev/null ||
        fail "default run failed"
    [ "$(grep -vc '^#' "$work/default/thermo.csv")" -eq 62 ] ||
        fail "default thermo.csv: $(grep -vc '^#' "$work/default/thermo.csv") lines, not a header and 61 rows"
    grep -q '"thermo_every_fs": 9.0' "$work/default/scene.json" || fail "scene.json lacks the interval used"
    awk -F, '/^#/ || NR == 1 { next } { if ($1 "" != sprintf("%.6g", (NR - 4) * 0.009)) exit 1 }' \
        "$work/default/thermo.csv" || fail "default thermo.csv: a time off the grid's decimals"
    "$terrace" run "$src/experiments/scenes/dense-rods.json" --quiet --out "$work/off" \
        --set state.n=216 --set run.equilibrate_ps=0.09 --set run.time_ps=0.54 \
        --set output.thermo_every_fs=0 >/dev/null || fail "run without thermo failed"
    [ ! -e "$work/off/thermo.csv" ] || fail "output.thermo_every_fs=0 wrote thermo.csv"
    ;;
sweep)
    # Six small runs, two of which the run refuses (a trajectory too large for any disk): four
    # done, the two failures recorded, exit status 1; run again, nothing runs again.
    sweep_file "$work/s.json"
    "$terrace" sweep "$work/s.json" --out "$work/out" -j 2 2>"$work/err"
    status=$?
    [ $status -eq 1 ] || fail "exit status $status for a sweep with failed runs: $(cat "$work/err")"
    [ "$(wc -l <"$work/out/sweep.csv")" -eq 7 ] || fail "sweep.csv: not a header and 6 rows"
    [ "$(grep -c ',ok,' "$work/out/sweep.csv")" -eq 4 ] || fail "not 4 runs ok: $(cat "$work/out/sweep.csv")"
    [ "$(grep -c ',failed,.*will write about .* PiB into' "$work/out/sweep.csv")" -eq 2 ] ||
        fail "the failures are not recorded: $(cat "$work/out/sweep.csv")"
    for run in dmd_seed-1 smd_seed-2; do
        for f in summary.json scene.json rdf.csv vacf.csv run.log; do
            [ -s "$work/out/$run/$f" ] || fail "$run lacks $f"
        done
    done
    grep -q 'sweep: \[6/6\]' "$work/err" || fail "no progress line: $(cat "$work/err")"
    grep -q 'ETA' "$work/err" || fail "no ETA"
    before=$(stat -c %Y "$work/out/dmd_seed-1/summary.json")
    cp "$work/out/sweep.csv" "$work/first.csv"
    sleep 1
    "$terrace" sweep "$work/s.json" --out "$work/out" -j 2 2>"$work/err"
    [ $? -eq 1 ] || fail "the sweep run again forgot its failures"
    grep -q '6 done before, 0 to run' "$work/err" || fail "runs ran again: $(cat "$work/err")"
    [ "$(stat -c %Y "$work/out/dmd_seed-1/summary.json")" = "$before" ] || fail "a finished run was run again"
    cmp -s <(cut -d, -f1-18 "$work/first.csv") <(cut -d, -f1-18 "$work/out/sweep.csv") ||
        fail "the table changed when nothing ran"
    # A bad sweep file: one line naming the run and the key, status 2, nothing written.
    printf '{"axes": [{"dmd.dv": [1]}]}' >"$work/bad.json"
    err=$("$terrace" sweep "$work/bad.json" --out "$work/bad" 2>&1)
    status=$?
    [ $status -eq 2 ] || fail "exit status $status for a bad sweep"
    [ "$(printf '%s\n' "$err" | wc -l)" -eq 1 ] || fail "error is not one line: $err"
    [[ $err == *"run dv-1"*"dmd.dv: unknown key"* ]] || fail "error does not name run and key: $err"
    [ ! -e "$work/bad" ] || fail "a bad sweep wrote its directory"
    ;;
sweep_interrupt)
    # SIGINT to a sweep: its runs end as interrupted runs do, the table stays valid, the exit
    # status is 130; the same command then finishes the sweep, continuing from restart files.
    cat >"$work/s.json" <<END
{"scene": "$src/experiments/scenes/dense-rods.json",
 "set": {"state.n": 216, "engine": "smd", "smd.dt_fs": 0.5, "run.equilibrate_ps": 0.09,
         "run.time_ps": 18, "output.restart_every_ps": 0.9},
 "seeds": [1, 2, 3]}
END
    "$terrace" sweep "$work/s.json" --out "$work/out" -j 2 2>"$work/err" &
    pid=$!
    for _ in $(seq 1 3000); do
        [ -e "$work/out/seed-1/restart.bin" ] && [ -e "$work/out/seed-2/restart.bin" ] && break
        sleep 0.01
    done
    # A second sweep into the same directory meanwhile is refused (exit status 3), touching nothing.
    "$terrace" sweep "$work/s.json" --out "$work/out" -j 2 2>"$work/err2"
    status=$?
    [ $status -eq 3 ] || fail "a second sweep into a running sweep's directory: exit status $status"
    grep -q 'another terrace sweep is running' "$work/err2" || fail "second sweep: $(cat "$work/err2")"
    kill -INT $pid
    wait $pid
    status=$?
    [ $status -eq 130 ] || fail "exit status $status after SIGINT: $(cat "$work/err")"
    [ "$(wc -l <"$work/out/sweep.csv")" -eq 4 ] || fail "sweep.csv: not a header and 3 rows"
    grep -q '^seed-1,1,interrupted,.*interrupted by SIGINT' "$work/out/sweep.csv" ||
        fail "seed-1 not interrupted: $(cat "$work/out/sweep.csv")"
    grep -q '^seed-3,3,pending,' "$work/out/sweep.csv" || fail "seed-3 was started after the signal"
    grep -q '"interrupted": true' "$work/out/seed-2/summary.json" || fail "seed-2's summary"
    grep -q 'the same command goes on' "$work/err" || fail "no word on how to go on"
    "$terrace" sweep "$work/s.json" --out "$work/out" -j 2 2>"$work/err" || fail "resumed: $(cat "$work/err")"
    [ "$(grep -c ',ok,' "$work/out/sweep.csv")" -eq 3 ] || fail "not all done: $(cat "$work/out/sweep.csv")"
    grep -q '"continued": 1' "$work/out/seed-1/summary.json" || fail "seed-1 not continued"
    ;;
sweep_kill)
    # kill -9 of a sweep: its runs end with it (the kernel sends each SIGTERM at the sweep's death:
    # it stops as at a Ctrl-C, its restart file written) rather than running on as orphans that
    # hold their directories' locks. A run directory another process holds is waited for, not
    # recorded failed; the same command then finishes the sweep.
    cat >"$work/s.json" <<END
{"scene": "$src/experiments/scenes/dense-rods.json",
 "set": {"state.n": 216, "engine": "smd", "smd.dt_fs": 0.5, "run.equilibrate_ps": 0.09,
         "run.time_ps": 4.5, "output.restart_every_ps": 0.9},
 "seeds": [1, 2]}
END
    "$terrace" sweep "$work/s.json" --out "$work/out" -j 2 2>"$work/err" &
    pid=$!
    for _ in $(seq 1 3000); do
        [ -e "$work/out/seed-1/restart.bin" ] && [ -e "$work/out/seed-2/restart.bin" ] && break
        sleep 0.01
    done
    pgrep -f -- "--out $work/out/seed-" >/dev/null || fail "no run of the sweep to outlive it"
    kill -9 $pid
    wait $pid 2>/dev/null
    for _ in $(seq 1 100); do
        pgrep -f -- "--out $work/out/seed-" >/dev/null || break
        sleep 0.01
    done
    left=$(pgrep -f -- "--out $work/out/seed-")
    [ -z "$left" ] || fail "runs outlived their sweep by a second: $left"
    for s in 1 2; do
        grep -q '"interrupted_by": "SIGTERM"' "$work/out/seed-$s/summary.json" ||
            fail "seed-$s did not stop on its sweep's death"
    done
    # seed-1's directory held by another process: the sweep waits for it, then continues it.
    hold_lock "$work/out/seed-1" "$work/err"
    "$terrace" sweep "$work/s.json" --out "$work/out" -j 2 2>"$work/err" ||
        fail "the sweep after the kill: $(cat "$work/err")"
    wait $holder
    grep -q 'seed-1: another terrace run holds its directory.s lock; waiting' "$work/err" ||
        fail "no word of waiting: $(cat "$work/err")"
    [ "$(grep -c ',ok,' "$work/out/sweep.csv")" -eq 2 ] || fail "not all done: $(cat "$work/out/sweep.csv")"
    for s in 1 2; do
        grep -q '"continued": 1' "$work/out/seed-$s/summary.json" || fail "seed-$s not continued"
    done
    ;;
sweep_mpi)
    # The same sweep under mpirun (3 ranks, rank 0 only handing out, so that every run, the failed
    # ones too, runs on another rank) and with -j 1: the same run files, the same table but for
    # the costs.
    export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
    export OMPI_MCA_btl_vader_single_copy_mechanism=none
    sweep_file "$work/s.json"
    "$terrace" sweep "$work/s.json" --out "$work/serial" -j 1 --quiet
    [ $? -eq 1 ] || fail "-j 1: not exit status 1"
    mpirun --oversubscribe -np 3 "$terrace" sweep "$work/s.json" --out "$work/mpi" -j 0 \
        >"$work/mpi.log" 2>&1
    status=$?
    [ $status -eq 1 ] || fail "mpirun: exit status $status: $(cat "$work/mpi.log")"
    grep -q '2 remote workers' "$work/mpi.log" || fail "not 2 workers: $(cat "$work/mpi.log")"
    for d in "$work/serial"/*/; do
        run=$(basename "$d")
        for f in rdf.csv vacf.csv oacf.csv msd.csv scene.json; do
            [ -e "$d/$f" ] || continue
            cmp -s "$d/$f" "$work/mpi/$run/$f" || fail "$run/$f differs under mpirun"
        done
    done
    cmp -s <(cut -d, -f1-18 "$work/serial/sweep.csv") <(cut -d, -f1-18 "$work/mpi/sweep.csv") ||
        fail "sweep.csv differs under mpirun: $(diff "$work/serial/sweep.csv" "$work/mpi/sweep.csv")"
    [ "$(grep -c ',failed,' "$work/mpi/sweep.csv")" -eq 2 ] || fail "the failures got lost under mpirun"
    # A run directory another process holds (a run of an earlier sweep still ending): rank 0
    # waits for it before handing the run out, instead of a worker's run failing on the lock.
    hold_lock "$work/held/dmd_seed-1" "$work/held.log"
    mpirun --oversubscribe -np 3 "$terrace" sweep "$work/s.json" --out "$work/held" -j 0 \
        >"$work/held.log" 2>&1
    status=$?
    wait $holder
    [ $status -eq 1 ] || fail "mpirun, a held run: exit status $status: $(cat "$work/held.log")"
    grep -q 'dmd_seed-1: another terrace run holds its directory.s lock; waiting' "$work/held.log" ||
        fail "no word of waiting under mpirun: $(cat "$work/held.log")"
    grep -q '^dmd_seed-1,.*,ok,' "$work/held/sweep.csv" ||
        fail "the held run was not run once free: $(cat "$work/held/sweep.csv")"
    [ "$(grep -c ',failed,' "$work/held/sweep.csv")" -eq 2 ] || fail "not the two refused runs failed"
    ;;
tradeoff)
    # terrace tradeoff end to end on a small LJ gas with loose tolerances: a verdict with an
    # interval and its files (--frontier: both engines' cheapest settings resolved); then the
    # chosen settings' biases re-measured by independent runs (other seeds, twice as long), each
    # found within its tolerance (not outside it at 2 sigma).
    tiny=(--set state.n=108 --set state.density=0.3 --set state.temperature=2
          --set run.equilibrate_ps=0.45 --set run.time_ps=1.8 --set smd.dt_fs=0.5)
    "$terrace" tradeoff "$src/experiments/scenes/lj-liquid.json" "${tiny[@]}" --observables u,p \
        --tolerance u=5% --tolerance p=15% --dV 0.5,0.25,0.125 --designs uniform --schemes verlet \
        --max-replicas 16 --cost-pairs 3 -j 2 --frontier --out "$work/t" --quiet \
        >"$work/verdict" 2>"$work/err" || fail "tradeoff: exit status $?: $(cat "$work/verdict" "$work/err")"
    grep -Eq 'is [0-9.]+x \([0-9.]+-[0-9.]+, 75 %\) cheaper than' "$work/verdict" ||
        fail "no verdict with an interval: $(cat "$work/verdict")"
    for f in tradeoff.json tradeoff.csv; do [ -s "$work/t/$f" ] || fail "no $f"; done
    # Bias runs take a g(r) frame at every sample, the cost windows the scene's (every 10th);
    # every run gives its whole process's CPU, which the budget counts.
    python3 - "$work/t/runs" <<'PY' || fail "tradeoff's runs: frames or process CPU"
import glob, json, os, sys
runs = glob.glob(os.path.join(sys.argv[1], "*", "scene.json"))
every = {os.path.basename(os.path.dirname(p)): json.load(open(p))["analysis"]["rdf_every"] for p in runs}
cost = {k: v for k, v in every.items() if k.startswith("cost-")}
bias = {k: v for k, v in every.items() if not k.startswith("cost-")}
assert cost and bias, every
assert set(cost.values()) == {10} and set(bias.values()) == {1}, every
for p in runs:
    summary = json.load(open(os.path.join(os.path.dirname(p), "summary.json")))
    assert summary["process_cpu_seconds"] > 0, p
    if "error" not in summary:  # a step beyond SMD's stability can fail in equilibration
        assert summary["process_cpu_seconds"] >= summary["cpu_seconds"] > 0, p
PY
    if command -v gnuplot >/dev/null; then [ -s "$work/t/tradeoff.png" ] || fail "no tradeoff.png"; fi
    python3 "$src/tests/cli/tradeoff_recheck.py" plan "$work/t/tradeoff.json" \
        "$src/experiments/scenes/lj-liquid.json" >"$work/recheck.json" || fail "cannot read the choice"
    "$terrace" sweep "$work/recheck.json" "${tiny[@]}" --set run.time_ps=3.6 --out "$work/re" -j 2 \
        --quiet || fail "the re-measuring runs failed"
    python3 "$src/tests/cli/tradeoff_recheck.py" check "$work/t/tradeoff.json" "$work/re" ||
        fail "a chosen setting's bias is outside its tolerance in independent runs"
    # Without --frontier, from the same runs: every DMD setting of the ladder was timed dearer
    # than SMD's within, none resolved outside, so the ladder's coarsest bounds DMD's cost.
    "$terrace" tradeoff "$src/experiments/scenes/lj-liquid.json" "${tiny[@]}" --observables u,p \
        --tolerance u=5% --tolerance p=15% --dV 0.5,0.25,0.125 --designs uniform --schemes verlet \
        --max-replicas 16 --cost-pairs 3 -j 2 --out "$work/t" --quiet >"$work/early" 2>"$work/err" ||
        fail "tradeoff's early stop: exit status $?: $(cat "$work/early" "$work/err")"
    grep -Eq '^SMD verlet .* is at least [0-9.]+x \([0-9.]+-[0-9.]+, 75 %\) cheaper than any DMD setting within tolerance no coarser than its ladders. coarsest at .*: DMD.s coarsest setting, DMD dV = 0.5 kT' \
        "$work/early" || fail "no early stop at the ladder's end: $(cat "$work/early")"
    grep -q '"ladder_end": true' "$work/t/tradeoff.json" || fail "tradeoff.json: no ladder_end bound"
    # No verdict says why, per engine: from the same runs (two replicas each, no new run), a
    # tolerance on u that two replicas cannot resolve.
    status=0
    "$terrace" tradeoff "$src/experiments/scenes/lj-liquid.json" "${tiny[@]}" --observables u,p \
        --tolerance u=0.001% --tolerance p=15% --dV 0.5,0.25,0.125 --designs uniform \
        --schemes verlet --max-replicas 2 --cost-pairs 3 -j 2 --out "$work/t" --quiet \
        >"$work/none" 2>"$work/err" || status=$?
    [ $status = 1 ] || fail "tradeoff without a verdict: exit status $status: $(cat "$work/err")"
    grep -Eq '^no verdict: no setting of either engine was resolved within tolerance .*; DMD: (unresolved u on [0-9]+(, p on [0-9]+)? of its [0-9]+ settings not outside, at up to 2 replicas|every setting resolved outside); SMD: ' \
        "$work/none" || fail "no verdict without its reason: $(cat "$work/none")"
    ;;
units)
    # Reduced units (docs/UNITS.md): the LJ liquid under units lj prints T*, U/N in ε beside the
    # total, and P*; summary.json has a "reduced" entry; thermo.csv and the analysis' CSVs are
    # in τ, σ and ε per body; scene.json records the units. Unit-free twins of named-unit keys
    # are read in τ under lj and unknown under real; the real run prints U/N beside <U>.
    scene=$src/experiments/scenes/lj-liquid.json
    "$terrace" run "$scene" --set units=lj --set state.temperature=2 --set output.thermo_every=0.9 \
        --set output.trajectory_every=0.9 --quiet --out "$work/lj" >"$work/lj.log" ||
        fail "lj run failed: $(cat "$work/lj.log")"
    sed -n 1p "$work/lj.log" | grep -q 'N = 256, 27 τ (τ = 100 fs) simulated' ||
        fail "no time in τ: $(cat "$work/lj.log")"
    sed -n 2p "$work/lj.log" | grep -Eq '^  T\* = [0-9.]+ \(target 2\), U/N = -[0-9.]+ ε \(U = -[0-9.e+]+ ε\)' ||
        fail "no T*, U/N in ε: $(cat "$work/lj.log")"
    sed -n 3p "$work/lj.log" | grep -Eq '^  P\* = [0-9.]+ ± [0-9.e-]+$' || fail "no P*: $(cat "$work/lj.log")"
    grep -q ' K\b\|kJ/mol\|bar' "$work/lj.log" && fail "real units in the lj line: $(cat "$work/lj.log")"
    grep -q '"units": "lj"' "$work/lj/summary.json" || fail "summary.json lacks units"
    for key in temperature_target potential_energy_per_body pressure simulated_tau einstein; do
        grep -Eq "\"$key\": [-0-9]" "$work/lj/summary.json" || fail "summary.json lacks reduced $key"
    done
    grep -q '"temperature_target": 2.0' "$work/lj/summary.json" || fail "T* target is not 2"
    grep -q '"units": "lj"' "$work/lj/scene.json" || fail "scene.json lacks units"
    for f in rdf.csv:r_sigma,g,err vacf.csv:t_tau,c,err msd.csv:t_tau,msd_sigma2,err \
        thermo.csv:time_tau,kinetic_translational_per_body; do
        head -n 1 "$work/lj/${f%%:*}" | grep -q "^${f#*:}" ||
            fail "${f%%:*} header: $(head -n 1 "$work/lj/${f%%:*}")"
    done
    # terrace analyse rewrites the CSVs in the run's units
    "$terrace" analyse "$work/lj" >/dev/null || fail "analyse failed"
    head -n 1 "$work/lj/msd.csv" | grep -q '^t_tau,msd_sigma2,err$' || fail "analyse: msd.csv in real units"
    # thermo rows every 0.9 τ, T* = 2 at production's start (the thermostat's last rescaling)
    awk -F, '/^#/ || NR == 1 { next } !n++ { exit !($1 == 0 && $7 > 1.999 && $7 < 2.001) }' \
        "$work/lj/thermo.csv" || fail "thermo.csv's first row: $(sed -n 4p "$work/lj/thermo.csv")"
    [ "$(grep -vc "^#" "$work/lj/thermo.csv")" -eq 32 ] || fail "thermo.csv: not a header and 31 rows"
    "$terrace" run "$scene" --set state.temperature=2 --set run.time_ps=0.27 --quiet \
        --out "$work/real" >"$work/real.log" || fail "real run failed"
    grep -Eq '^  T = [0-9.]+ K \(target 240.5 K\), <U>/N = -[0-9.]+ kJ/mol \(<U> = -[0-9.]+ kJ/mol\)' \
        "$work/real.log" || fail "real line: $(cat "$work/real.log")"
    expect_error "$scene" "run.time: unknown key; did you mean run.time_ps?" --set run.time=27
    expect_error "$scene" "run.time: and run.time_ps set the same value: give one of them" \
        --set units=lj --set run.time=27 --set run.time_ps=2.7
    expect_error "$scene" "(units lj: τ = 100 fs, σ = 1 Å, ε = 1 kJ/mol;" --set units=lj --set run.time=0.01
    err=$("$terrace" tradeoff "$scene" --set units=lj --out "$work/t" 2>&1) && fail "tradeoff ran under lj"
    [[ $err == *"units: terrace tradeoff measures in real units; leave units out"* ]] ||
        fail "tradeoff under lj: $err"
    [ ! -e "$work/t" ] || fail "tradeoff wrote under lj"
    ;;
*)
    fail "unknown check"
    ;;
esac
exit 0
