"""terrace.sweep (the CLI's sweep machinery) and a run stopped by Ctrl-C."""

import json
import os
import signal
import subprocess
import sys
import time

import pytest

import terrace
from conftest import DENSE_RODS, SMALL, build_dir


def test_sweep_runs_each_run_as_the_cli(tmp_path, executable):
    sweep = tmp_path / "seeds.json"
    sweep.write_text(json.dumps({"scene": str(DENSE_RODS), "set": dict(SMALL, engine="smd"),
                                 "seeds": [1, 2]}))
    result = terrace.sweep(sweep, out=tmp_path / "py", jobs=2, progress=False)
    assert result.status == 0
    assert len(result.table) == 2
    assert sorted(result.runs) == ["seed-1", "seed-2"]
    # Each run equals `terrace run` of the same scene and seed.
    p = subprocess.run([str(executable), "sweep", str(sweep), "--out", str(tmp_path / "cli"),
                        "--quiet"], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    for seed in ("seed-1", "seed-2"):
        for name in ("rdf.csv", "vacf.csv", "msd.csv"):
            with open(tmp_path / "cli" / seed / name, "rb") as a, \
                    open(tmp_path / "py" / seed / name, "rb") as b:
                assert a.read() == b.read()
    # Done runs are found done: the same call runs nothing again.
    again = terrace.sweep(sweep, out=tmp_path / "py", progress=False)
    def numbers(table):  # without the wall clock; repr, so that nan equals nan
        return repr([{k: v for k, v in row.items() if "seconds" not in k} for row in table])
    assert again.status == 0 and numbers(again.table) == numbers(result.table)


def test_bad_sweep_file_raises_the_cli_message(tmp_path, executable):
    sweep = tmp_path / "bad.json"
    sweep.write_text(json.dumps({"scene": str(DENSE_RODS), "axes": [{"state.n": []}]}))
    with pytest.raises(terrace.SceneError) as caught:
        terrace.sweep(sweep, out=tmp_path / "o")
    p = subprocess.run([str(executable), "sweep", str(sweep), "--out", str(tmp_path / "o")],
                       capture_output=True, text=True)
    assert p.returncode == 2 and p.stderr.strip() == "terrace: " + str(caught.value)


def test_ctrl_c_stops_a_run_with_its_output(tmp_path):
    """SIGINT during terrace.run: the run writes its output and KeyboardInterrupt is raised;
    terrace.load reads it."""
    out = tmp_path / "run"
    script = (
        "import terrace, sys\n"
        f"s = terrace.Scene({str(DENSE_RODS)!r}, {{'state.n': 144, 'run.equilibrate_ps': 0,"
        " 'run.time_ps': 900, 'output.restart_every_ps': 9}, engine='smd')\n"
        "print('started', flush=True)\n"
        "try:\n"
        f"    terrace.run(s, out={str(out)!r}, progress=False)\n"
        "except KeyboardInterrupt as e:\n"
        "    print('KeyboardInterrupt:', e, flush=True)\n"
        "    sys.exit(7)\n")
    env = dict(os.environ, PYTHONPATH=str(build_dir() / "python"))
    p = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, text=True,
                         stderr=subprocess.PIPE, env=env)
    assert p.stdout.readline().strip() == "started"
    deadline = time.time() + 60
    while not (out / "scene.json").exists():  # written as the run starts
        if time.time() > deadline or p.poll() is not None:
            break
        time.sleep(0.05)
    time.sleep(0.5)
    p.send_signal(signal.SIGINT)
    stdout, stderr = p.communicate(timeout=120)
    assert p.returncode == 7, stderr
    assert "interrupted" in stdout
    r = terrace.load(out)
    assert r.interrupted and r.summary["interrupted_by"] == "SIGINT"
    assert r.vacf is not None and 0 < r.summary["simulated_ps"] < 900
