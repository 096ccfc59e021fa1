#!/usr/bin/env python3
"""Both engines on one scene, side by side: g(r) and the velocity autocorrelation of DMD and SMD,
and a GSD trajectory of each for OVITO.

    PYTHONPATH=build/python /usr/bin/python3 examples/two_engines.py [OUT]

writes OUT/dmd/, OUT/smd/ (run directories, each with trajectory.gsd) and OUT/two_engines.png
(OUT defaults to out/two_engines). Some 10 s on one core.
"""

import os
import sys

import matplotlib

matplotlib.use("Agg")  # files only, no display needed
import matplotlib.pyplot as plt

import terrace

out = sys.argv[1] if len(sys.argv) > 1 else os.path.join("out", "two_engines")

# The paper's dense rods (512 rods, ρ* 0.5, T* 1.4; 1.8 ps of equilibration, 9 ps sampled), with a
# GSD frame every 90 fs (orientations and shapes included: OVITO draws the rods).
scene = terrace.Scene({
    "name": "two-engines",
    "state": {"n": 512, "density": 0.5, "temperature": 1.4},
    "run": {"equilibrate_ps": 1.8, "time_ps": 9.0},
    "output": {"trajectory_every_fs": 90, "trajectory_format": "gsd"},
})

results = {}
for engine in ("dmd", "smd"):
    results[engine] = terrace.run(terrace.Scene(scene, engine=engine),
                                  out=os.path.join(out, engine), overwrite=True)
    s = results[engine].summary
    print(f"{engine}: {s['cpu_seconds']:.2f} CPU s, T = {s['temperature_K']:.1f} K, "
          f"P = {s['pressure']['mean_bar']:.0f} ± {s['pressure']['error_bar']:.0f} bar, "
          f"trajectory {results[engine].trajectory}")

fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
for engine, r in results.items():
    left.errorbar(r.rdf["r_angstrom"], r.rdf["g"], yerr=r.rdf["err"], label=engine.upper(),
                  lw=1, elinewidth=0.5)
    right.errorbar(r.vacf["t_ps"], r.vacf["c"], yerr=r.vacf["err"], label=engine.upper(),
                   lw=1, elinewidth=0.5)
left.set(xlabel="r (Å)", ylabel="g(r)", title="pair distribution of the centres")
right.set(xlabel="t (ps)", ylabel="C_v(t)", title="velocity autocorrelation")
for ax in (left, right):
    ax.legend()
fig.tight_layout()
figure = os.path.join(out, "two_engines.png")
fig.savefig(figure, dpi=120)
print(f"figure: {figure}")
