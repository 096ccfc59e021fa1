#!/usr/bin/env bash
# The training of the profile-guided build (cli/CMakeLists.txt, TERRACE_PROFILE): an instrumented
# terrace runs short pieces of the scenes users run most — the paper's dense rods with DMD at
# ΔV = ¼ … 2 kT and with SMD, and the rod gas with both — and records how the engines' branches
# and calls go. A path no piece takes (tops, spheres, explicit levels) is compiled as without a
# profile (-fprofile-partial-training), so it is not slower than before.
#   experiments/train-profile.sh TERRACE WORKDIR
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
terrace=$1 work=$2
rm -rf "$work"
mkdir -p "$work"
scenes=$root/experiments/scenes
# Lengths in whole 9 fs samples and thermostat intervals, as terrace requires.
short=(--quiet --set run.equilibrate_ps=0.198 --set run.sample_fs=9)
k=0
piece() { # scene, production ps, then --set options
    local scene=$1 ps=$2
    shift 2
    k=$((k + 1))
    "$terrace" run "$scenes/$scene.json" "${short[@]}" --set run.time_ps="$ps" "$@" \
        --out "$work/piece-$k" >/dev/null
}
for dV in 0.25 0.5 1 2; do
    piece dense-rods 0.495 --set engine=dmd --set dmd.dV="$dV"
done
piece dense-rods 0.495 --set engine=smd
piece gas-rods 4.995 --set engine=dmd
piece gas-rods 0.999 --set engine=smd
