#!/usr/bin/env python3
"""terrace SMD versus LAMMPS on the same input, timed in one run, alternating the two codes.

Input (both codes): Lennard-Jones spheres, N = 512 from an 8^3 simple cubic lattice, rho* = 0.5,
T* = 1.4, smoothed between 2.5 and 3.0 sigma, NVE, dt = 0.005 tau, Verlet skin 0.3 sigma checked
every step, 500 untimed steps to melt the lattice, then the timed production steps.
LAMMPS: in.lj-smooth (pair_style lj/smooth 2.5 3.0, fix nve), serial `lmp`.
terrace: bench_smd's ljLammpsInput benchmark (same state point and parameters).

Each code runs `--rounds` times, alternately, so that a change in machine load hits both; the
best round of each is compared (the usual way to time on a shared machine). Reported: steps/s and
atom-steps/s by CPU time (LAMMPS: loop time x its reported CPU use) and by wall time.

Usage: side_by_side.py [--bench BUILD/bench/bench_smd] [--lmp lmp] [--steps 5000] [--rounds 3]
"""
import argparse
import json
import os
import re
import subprocess
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
N_ATOMS = 512


def run_lammps(lmp, steps):
    with tempfile.TemporaryDirectory() as tmp:
        out = subprocess.run(
            [lmp, "-in", os.path.join(HERE, "in.lj-smooth"), "-log", "none", "-var", "steps",
             str(steps)], cwd=tmp, capture_output=True, text=True, check=True).stdout
    # The last "Loop time" / "CPU use" pair belongs to the production run.
    loop = re.findall(r"Loop time of ([0-9.eE+-]+) on 1 procs for (\d+) steps", out)[-1]
    cpu = re.findall(r"([0-9.]+)% CPU use", out)[-1]
    wall = float(loop[0])
    n = int(loop[1])
    return {"steps": n, "wall_s": wall, "cpu_s": wall * float(cpu) / 100.0}


def run_terrace(bench, steps):
    out = subprocess.run(
        [bench, "--benchmark_filter=ljLammpsInput", "--benchmark_format=json",
         "--benchmark_min_time=%g" % max(0.5, steps / 3000.0)],
        capture_output=True, text=True, check=True).stdout
    b = json.loads(out)["benchmarks"][0]
    scale = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}[b["time_unit"]]
    n = int(b["iterations"])  # one iteration = one step
    return {"steps": n, "wall_s": b["real_time"] * scale * n, "cpu_s": b["cpu_time"] * scale * n,
            "pair_evals_per_s": b["pair_evals/s"]}


def rate(r, key):
    return r["steps"] / r[key]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bench", default=os.path.join(HERE, "../../build/bench/bench_smd"))
    ap.add_argument("--lmp", default="lmp")
    ap.add_argument("--steps", type=int, default=5000)
    ap.add_argument("--rounds", type=int, default=3)
    a = ap.parse_args()
    lammps, terrace = [], []
    for k in range(a.rounds):
        lammps.append(run_lammps(a.lmp, a.steps))
        terrace.append(run_terrace(a.bench, a.steps))
        print("round %d: LAMMPS %.0f steps/s cpu (%.0f wall), terrace %.0f steps/s cpu (%.0f wall)"
              % (k + 1, rate(lammps[-1], "cpu_s"), rate(lammps[-1], "wall_s"),
                 rate(terrace[-1], "cpu_s"), rate(terrace[-1], "wall_s")))
    result = {}
    for key in ("cpu_s", "wall_s"):
        l = max(rate(r, key) for r in lammps)
        t = max(rate(r, key) for r in terrace)
        result[key.replace("_s", "")] = {
            "lammps_steps_per_s": l, "terrace_steps_per_s": t,
            "lammps_atom_steps_per_s": l * N_ATOMS, "terrace_atom_steps_per_s": t * N_ATOMS,
            "ratio_terrace_over_lammps": t / l}
    print(json.dumps(result, indent=2))


if __name__ == "__main__":
    main()
