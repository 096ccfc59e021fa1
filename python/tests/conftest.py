"""Shared pieces of the Python module's tests: the build's terrace executable, the repository,
and a scene small enough that a run of either engine takes about a second."""

import json
import os
import pathlib
import subprocess

import pytest

import terrace

SOURCE = pathlib.Path(__file__).resolve().parents[2]
DENSE_RODS = SOURCE / "experiments" / "scenes" / "dense-rods.json"
# 144 rods (the fewest SMD's cell list takes at this density), 45 fs of equilibration and
# 180 fs of production (20 samples of 9 fs).
SMALL = {"state.n": 144, "run.equilibrate_ps": 0.045, "run.time_ps": 0.18,
         "analysis.rdf_every": 2}


def build_dir():
    """TERRACE_BUILD (ctest sets it), else the build tree the module was imported from."""
    chosen = os.environ.get("TERRACE_BUILD")
    return pathlib.Path(chosen) if chosen else pathlib.Path(terrace.__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def executable():
    path = build_dir() / "terrace"
    if not path.exists():
        pytest.fail(f"{path}: the terrace executable is not built (cmake --build build "
                    "--target terrace)")
    return path


def cli_run(executable, out, *args):
    """`terrace run ARGS --out OUT --quiet`; returns (exit status, standard error)."""
    p = subprocess.run([str(executable), "run", *map(str, args), "--out", str(out), "--quiet"],
                       capture_output=True, text=True)
    return p.returncode, p.stderr


def cli_sets(overrides):
    """The --set options of a dict of overrides, values as JSON (as terrace.Scene passes them)."""
    args = []
    for key, value in overrides.items():
        args += ["--set", f"{key}={json.dumps(value)}"]
    return args
