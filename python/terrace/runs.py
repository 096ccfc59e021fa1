"""terrace.run, terrace.resume and terrace.sweep: the command line's run and sweep, from Python."""

import os
import signal
import tempfile

from . import _terrace
from .results import Result, SweepResult
from .scene import Scene, _json_value


def _ended(status, what, directory):
    """Raises what the command line's exit status 128 + signal means here: KeyboardInterrupt
    for Ctrl-C, SystemExit(status) for a termination (SIGTERM, SIGHUP); the output is written."""
    if status == 128 + signal.SIGINT:
        raise KeyboardInterrupt(f"{what} interrupted; its output is in {directory} (terrace.load, "
                                "terrace.resume)")
    if status > 128:
        raise SystemExit(status)


def run(scene, out=None, progress=True, overwrite=False):
    """Runs a scene as ``terrace run`` does, through the same C++ run path, and returns its
    Result (NumPy tables, summary dict). The numbers equal those of
    ``terrace run SCENE --set ... --out DIR`` bit for bit for the same scene and seed.

    scene      a terrace.Scene, or what Scene() takes (a path, a dict; None: the default scene)
    out        the run's directory; None: a new temporary directory (tempfile.mkdtemp, named
               terrace-<name>-<engine>-*, kept after the run: Result.dir says where), not the
               CLI's out/<name>-<engine>, so that a script can run the same scene twice
    progress   the CLI's progress lines on stderr (--quiet when False)
    overwrite  replace an earlier run's files in out (--overwrite); otherwise a directory that
               holds them is refused with IoError, as by the CLI

    Ctrl-C stops the run at the next sample, as for the CLI: the restart file (with
    output.restart_every_ps), the summary and the analysis are written, then KeyboardInterrupt
    is raised (terrace.load(dir) reads what was done). An engine's failure (an unstable SMD
    step, ...) writes what was gathered and raises TerraceError with the CLI's message.
    """
    if not isinstance(scene, Scene):
        scene = Scene(scene)
    resolved = scene.resolved()
    if out is None:
        out = tempfile.mkdtemp(prefix=f"terrace-{resolved['name']}-{resolved['engine']}-")
    out = os.fspath(out)
    outcome = _terrace.run_scene(scene._scene, out, overwrite, not progress)
    _ended(outcome.exit_status, "the run", out)
    return Result(out)


def resume(directory, progress=True):
    """Continues the run in `directory` from its restart file, as ``terrace run --continue``;
    returns its Result. Refused (IoError) where there is no restart file."""
    directory = os.fspath(directory)
    outcome = _terrace.resume_run(directory, not progress)
    _ended(outcome.exit_status, "the run", directory)
    return Result(directory)


def sweep(file, out=None, jobs=1, overrides=None, progress=True, retry_failed=False,
          strict=False):
    """Runs a sweep file as ``terrace sweep`` does (locally; MPI is the CLI's), each run a child
    ``terrace run`` process of this build's executable (or $TERRACE_EXECUTABLE).

    file          the sweep file (JSON, cli/sweep_plan.hpp's format)
    out           the sweep's directory; None: out/<sweep file's stem>[-<overrides>], as the CLI
    jobs          runs at once (-j)
    overrides     a dict of dotted keys every run gets after the file's "set" (--set)
    progress      one line on stderr per run that ends (--quiet when False)
    retry_failed  run again the runs whose failure is recorded (--retry-failed)
    strict        refuse keys a run's engine does not read (--strict); else UserWarnings

    Returns a SweepResult (status 0: every run done, 1: some failed, their rows say why).
    A bad sweep file raises SceneError before anything runs; Ctrl-C stops the sweep as the
    CLI's (running runs write their output) and raises KeyboardInterrupt; the same call later
    goes on where it stopped.
    """
    file = os.fspath(file)
    sets = [f"{k}={_json_value(v)}" for k, v in (overrides or {}).items()]
    if out is None:
        out = _terrace.sweep_default_output(file, sets)
    out = os.fspath(out)
    status = _terrace.run_sweep(file, sets, out, jobs, not progress, retry_failed, strict)
    _ended(status, "the sweep", out)
    return SweepResult(out, status)
