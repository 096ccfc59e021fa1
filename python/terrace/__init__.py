"""terrace from Python: event-driven (DMD) and standard (SMD) rigid-body dynamics on one scene.

The module drives the same C++ code as the ``terrace`` command line: a scene is read and checked
by the CLI's reader (same keys, same one-line messages), and a run goes through the same run path
as ``terrace run``, so its numbers equal the command line's bit for bit for the same scene and seed.

    import terrace
    scene = terrace.Scene("experiments/scenes/dense-rods.json", engine="smd",
                          overrides={"state.n": 216, "run.time_ps": 0.9})
    r = terrace.run(scene)             # a run directory, read back as NumPy
    r.rdf["g"], r.vacf["c"], r.summary["pressure"]["mean_bar"]

    sim = terrace.Simulation(scene)    # the engine alone, advanced by hand
    sim.advance(0.09)
    sim.state().positions              # (N, 3) array, Å

Units: Å, g/mol, kJ/mol, K, ps (times), bar (pressure), as in the run directories' files.

Errors are exceptions carrying the CLI's message: SceneError (a ValueError) for a refused scene
or sweep file, IoError (an OSError) for a file or directory, TerraceError (a RuntimeError) for an
engine's failure or a refused resource. python/README.md says more.
"""

from ._terrace import IoError, SceneError, TerraceError
from .results import Result, SweepResult, load
from .runs import resume, run, sweep
from .scene import Scene
from .simulation import Simulation, State

__all__ = ["Scene", "run", "resume", "load", "sweep", "Simulation", "State", "Result",
           "SweepResult", "SceneError", "IoError", "TerraceError"]
