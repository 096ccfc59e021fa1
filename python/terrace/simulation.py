"""terrace.Simulation: a scene's engine, advanced and read from Python."""

import json
from collections import namedtuple

from . import _terrace
from .scene import Scene

State = namedtuple("State", "time_ps box_angstrom positions velocities orientations "
                            "angular_velocities species")
State.__doc__ = """The bodies at one instant, in the scene's numbering (NumPy float64 arrays):
positions (N, 3) unwrapped centres of mass, Å; velocities (N, 3) Å/ps; orientations (N, 4) unit
quaternions (w, x, y, z), body to lab (a linear rotor's: the least rotation taking z to its
axis; a sphere's: the identity); angular_velocities (N, 3) in the lab frame, rad/ps;
box_angstrom the periodic cube's edge; time_ps the engine's time; species, for a mixture, (N,)
int32 indices into the scene's species (scene.resolved()["species"]), else None."""


class Simulation:
    """A scene's engine (scene.engine: DMD or SMD) on the scene's initial state, built as
    ``terrace run`` builds it, which the caller advances in time and reads.

    Nothing happens unless asked: no equilibration (rescale_temperature() is the CLI's
    thermostat step), no sampling, no analysis, no files. For those, terrace.run().

        sim = terrace.Simulation(terrace.Scene(engine="smd", overrides={"state.n": 216}))
        for _ in range(100):
            sim.advance(0.009)           # ps
            e = sim.energies()["total"]

    advance() goes in chunks that end on the scene's sample grid (run.sample_fs), the instants
    at which ``terrace run`` samples, and checks for Ctrl-C between chunks (KeyboardInterrupt,
    the engine left at the end of the last chunk). A DMD engine synchronises its bodies at each
    chunk's end, so its path depends on those instants only, not on how advance() was called
    between them; SMD advances in whole steps of smd.dt_fs, stopping at the first step at or
    past the target.

    State is read as copies (state(), positions()): an engine keeps its bodies in an order of its
    own and in its internal units, so the arrays are made per call, in the scene's numbering and
    in Å, ps; each array owns its memory (no second copy is made for NumPy).

    One thread at a time: advance() lets other Python threads run while the engine works, and a
    call on the same Simulation from one of them meanwhile raises RuntimeError. Runs and sweeps
    (terrace.run, terrace.sweep) go one at a time in a process, each waiting for the last: they
    hold the process's signal handlers for their duration.
    """

    def __init__(self, scene=None):
        if not isinstance(scene, Scene):
            scene = Scene(scene)
        self.scene = scene
        self._sim = _terrace._Simulation(scene._scene)

    def advance(self, ps):
        """Advances the engine by `ps` picoseconds (see the class's note on chunks)."""
        self._sim.advance(float(ps))

    @property
    def time(self):
        """The engine's time, ps (0 at the start)."""
        return self._sim.time_ps

    def state(self):
        """Positions, velocities, orientations and angular velocities now (a State)."""
        return State(**self._sim.state())

    def positions(self):
        """The bodies' unwrapped centres of mass now, (N, 3), Å (cheaper than state())."""
        return self._sim.positions()

    def energies(self):
        """The whole system's energies now, kJ/mol: kinetic, kinetic_translational, potential
        (the engine's own: DMD the terraced one, SMD the continuous), potential_continuous
        (the continuous model's U on this configuration) and total (kinetic + potential, which
        DMD conserves to round-off)."""
        return self._sim.energies()

    @property
    def pressure(self):
        """P in bar from the molecular virial: SMD at this instant; DMD the mean over the last
        advance() (impulse virial), nan before the first."""
        return self._sim.pressure_bar()

    @property
    def temperature(self):
        """The kinetic temperature 2K / (dof k_B), K, dof = 3N + R − 3, R the bodies' rotational
        degrees of freedom together (2 per rod, none per sphere among rods)."""
        return self._sim.temperature_K()

    @property
    def momentum(self):
        """The total momentum, g/mol Å/ps (three numbers)."""
        return self._sim.momentum()

    @property
    def counters(self):
        """The engine's counters as a dict (DMD: events by kind; SMD: steps, list rebuilds,
        ...), the keys of summary.json's engine section."""
        return json.loads(self._sim.statistics())

    def rescale_temperature(self, kelvin=None):
        """Scales velocities and angular velocities to `kelvin` (default: the scene's
        temperature), as one thermostat step of the CLI's equilibration."""
        self._sim.rescale_temperature(None if kelvin is None else float(kelvin))

    def __repr__(self):
        return f"terrace.Simulation({self.scene!r}, t = {self.time} ps)"
