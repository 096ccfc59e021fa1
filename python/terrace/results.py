"""A run directory (or a sweep's) read back as NumPy arrays and dicts."""

import csv
import json
import os

import numpy as np

from ._terrace import IoError


def _table(path):
    """A CSV file of a run (first line the column names, '#' lines comments) as a NumPy
    structured array, one field per column; None when the run did not write it."""
    if not os.path.exists(path):
        return None
    table = np.genfromtxt(path, delimiter=",", names=True, comments="#", dtype=np.float64,
                          deletechars="")
    return np.atleast_1d(table)


class Result:
    """A run's directory read back (terrace.load, terrace.run). Every table is a NumPy
    structured array read from the run's CSV (exact: the files carry 17 significant digits),
    one field per column, with the columns the files have:

    rdf     r_angstrom, g, err (one standard error); DMD adds g_continuous, err_continuous
    vacf    t_ps, c, err       velocity autocorrelation, normalised
    oacf    t_ps, c1, c1_err, c2, c2_err   orientational autocorrelations of the long axis,
            first and second Legendre order (None for spheres)
    msd     t_ps, msd_angstrom2, err
    thermo  time_ps, kinetic_translational, ..., pressure_bar (None when
            output.thermo_every_fs was 0)

    These are the columns under units "real". A run under units "lj" names them in reduced
    units (r_sigma, t_tau, msd_sigma2, time_tau, temperature_reduced, ...; docs/UNITS.md).

    summary is summary.json as a dict (pressure, temperature_K, energy, the engine's counters,
    cpu_seconds, provenance, ...); scene is the resolved scene the run ran (scene.json).
    An interrupted run (Ctrl-C, a time limit) reads the same, with summary["interrupted"] true
    and its analysis up to where it stopped; terrace.resume(dir) takes it on.
    """

    def __init__(self, directory):
        self.dir = os.fspath(directory)
        path = os.path.join(self.dir, "summary.json")
        if not os.path.isfile(path):
            if os.path.isfile(os.path.join(self.dir, "restart.bin")):
                raise IoError(f"{self.dir}: no summary.json, but a restart file: the run was "
                              "killed before it wrote its summary; terrace.resume(dir) takes "
                              "it on")
            raise IoError(f"{self.dir}: no summary.json: not a terrace run directory, or a run "
                          "still in progress")
        with open(path, encoding="utf-8") as f:
            self.summary = json.load(f)
        self._cache = {}

    def _csv(self, name):
        if name not in self._cache:
            self._cache[name] = _table(os.path.join(self.dir, name + ".csv"))
        return self._cache[name]

    rdf = property(lambda self: self._csv("rdf"), doc="g(r) with its error columns")
    vacf = property(lambda self: self._csv("vacf"), doc="the velocity autocorrelation")
    oacf = property(lambda self: self._csv("oacf"), doc="the orientational autocorrelation")
    msd = property(lambda self: self._csv("msd"), doc="the mean squared displacement, Å²")
    thermo = property(lambda self: self._csv("thermo"), doc="the thermo time series")

    @property
    def scene(self):
        """The resolved scene the run ran, as a dict (scene.json)."""
        with open(os.path.join(self.dir, "scene.json"), encoding="utf-8") as f:
            return json.load(f)

    @property
    def interrupted(self):
        """Whether a signal stopped the run before its end."""
        return bool(self.summary.get("interrupted", False))

    @property
    def trajectory(self):
        """The trajectory file's path (trajectory.gsd or trajectory.xyz), or None."""
        for name in ("trajectory.gsd", "trajectory.xyz"):
            path = os.path.join(self.dir, name)
            if os.path.exists(path):
                return path
        return None

    def __repr__(self):
        s = self.summary
        return (f"terrace.Result({self.dir!r}: {s.get('engine')}, N = {s.get('n_bodies')}, "
                f"{s.get('simulated_ps')} ps{', interrupted' if self.interrupted else ''})")


def load(directory):
    """Reads a finished or interrupted run directory (terrace.Result)."""
    return Result(directory)


class SweepResult:
    """A sweep's directory (terrace.sweep): status is the exit status of ``terrace sweep``
    (0 every run done, 1 some failed); table is sweep.csv as a list of dicts, one per run
    (numbers as floats, the rest as strings); runs maps a run's name to its Result (runs that
    failed before writing a summary are left out; their row says why)."""

    def __init__(self, directory, status=0):
        self.dir = os.fspath(directory)
        self.status = status
        with open(os.path.join(self.dir, "sweep.csv"), encoding="utf-8", newline="") as f:
            rows = [r for r in csv.reader(f) if r and not r[0].startswith("#")]
        header, body = rows[0], rows[1:]

        def value(text):
            try:
                return float(text)
            except ValueError:
                return text
        self.table = [dict(zip(header, map(value, row))) for row in body]

    @property
    def runs(self):
        found = {}
        for entry in sorted(os.scandir(self.dir), key=lambda e: e.name):
            if entry.is_dir() and os.path.isfile(os.path.join(entry.path, "summary.json")):
                found[entry.name] = Result(entry.path)
        return found

    def __repr__(self):
        return f"terrace.SweepResult({self.dir!r}: {len(self.table)} runs, status {self.status})"
