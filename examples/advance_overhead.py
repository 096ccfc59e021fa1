#!/usr/bin/env python3
"""What driving an engine from Python costs: the same run (a scene's production, no
equilibration) by `terrace run` and by a Python loop of Simulation.advance, in CPU seconds.

    PYTHONPATH=build/python /usr/bin/python3 examples/advance_overhead.py [ENGINE] [STEPS]

The CLI's figure is its summary's cpu_seconds (the engine's advances alone) and the whole
process's CPU time; the loop's is time.process_time() around STEPS calls of advance(run.sample_fs),
bare, and again reading energies() and state() after each (what a sampling loop does); and
the fixed cost of one call (advance(0)).
"""

import os
import resource
import subprocess
import sys
import tempfile
import time

import terrace

engine = sys.argv[1] if len(sys.argv) > 1 else "smd"
steps = int(sys.argv[2]) if len(sys.argv) > 2 else 100
sample_ps = 0.009
sets = {"run.equilibrate_ps": 0, "run.time_ps": steps * sample_ps}
scene = terrace.Scene("experiments/scenes/dense-rods.json", sets, engine=engine)

executable = os.environ.get("TERRACE_EXECUTABLE",
                            os.path.join(os.path.dirname(terrace.__file__), "..", "..",
                                         "terrace"))
with tempfile.TemporaryDirectory() as out:
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run([executable, "run", *scene.cli_arguments(), "--out", out, "--quiet"],
                   check=True, stdout=subprocess.DEVNULL)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cli_process = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    cli_engine = terrace.load(out).summary["cpu_seconds"]


def loop(read):
    sim = terrace.Simulation(scene)
    start = time.process_time()
    for _ in range(steps):
        sim.advance(sample_ps)
        if read:
            sim.energies()
            sim.state()
    return time.process_time() - start


bare, reading = loop(False), loop(True)
# The fixed cost of a call: advance(0) moves nothing.
sim = terrace.Simulation(scene)
start = time.process_time()
for _ in range(100000):
    sim.advance(0.0)
per_call = (time.process_time() - start) / 100000
n = scene.resolved()["state"]["n"]
print(f"{engine}, N = {n}, {steps} x {sample_ps} ps:")
print(f"  terrace run: engine {cli_engine:.3f} CPU s, whole process {cli_process:.3f} CPU s")
print(f"  Python loop, advance only:            {bare:.3f} CPU s ({bare / cli_engine:.3f} x "
      "the CLI's engine)")
print(f"  Python loop, + energies() + state():  {reading:.3f} CPU s ({reading / cli_engine:.3f} x)")
print(f"  one call of advance(0): {per_call * 1e6:.2f} CPU µs")
