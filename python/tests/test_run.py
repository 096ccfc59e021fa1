"""terrace.run and terrace.load: the CLI's run, bit for bit, read back as NumPy."""

import json
import math
import os
import shutil

import numpy as np
import pytest

import terrace
from conftest import DENSE_RODS, SMALL, cli_run, cli_sets


def comparable(summary):
    """The summary without what differs between two runs of one scene: the clocks (CPU seconds,
    SMD's seconds per phase) and the provenance (time, host)."""
    if isinstance(summary, dict):
        return {k: comparable(v) for k, v in summary.items()
                if "cpu" not in k and "seconds" not in k and k != "provenance"}
    return summary


@pytest.fixture(scope="module", params=["dmd", "smd"])
def both(request, tmp_path_factory, executable):
    """The same small scene run by the CLI and by terrace.run, per engine."""
    engine = request.param
    work = tmp_path_factory.mktemp(engine)
    overrides = dict(SMALL, **{"output.thermo_every_fs": 18, "seed": 7})
    status, err = cli_run(executable, work / "cli", DENSE_RODS, *cli_sets(overrides),
                          "--set", f"engine={engine}")
    assert status == 0, err
    scene = terrace.Scene(DENSE_RODS, overrides, engine=engine)
    result = terrace.run(scene, out=work / "py", progress=False)
    return engine, work / "cli", result


def test_numbers_equal_the_cli_bit_for_bit(both):
    engine, cli, result = both
    with open(cli / "summary.json") as f:
        expected = json.load(f)
    assert expected["engine"] == engine
    assert comparable(result.summary) == comparable(expected)
    for name in ("scene.json", "rdf.csv", "vacf.csv", "oacf.csv", "msd.csv", "thermo.csv",
                 "initial.xyz"):
        with open(cli / name, "rb") as a, open(os.path.join(result.dir, name), "rb") as b:
            assert a.read() == b.read(), name


def test_tables_shapes_and_units(both):
    engine, _, r = both
    sigma = r.scene["potential"]["sigma"]
    assert r.rdf.dtype.names[:3] == ("r_angstrom", "g", "err")
    assert r.rdf.ndim == 1 and len(r.rdf) > 10
    # Bins of analysis.rdf_bin_angstrom out to analysis.rdf_max σ (at most half the box).
    bin_width = r.scene["analysis"]["rdf_bin_angstrom"]
    assert np.allclose(np.diff(r.rdf["r_angstrom"]), bin_width)
    assert r.rdf["r_angstrom"][-1] <= r.scene["analysis"]["rdf_max"] * sigma + bin_width
    if engine == "dmd":
        assert "g_continuous" in r.rdf.dtype.names
    assert r.oacf.dtype.names == ("t_ps", "c1", "c1_err", "c2", "c2_err")
    for table, names in ((r.vacf, ("c", "err")), (r.oacf, ("c1", "c1_err")),
                         (r.msd, ("msd_angstrom2", "err"))):
        assert table.dtype.names[:3] == ("t_ps",) + names
        assert table["t_ps"][0] == 0.0
        assert np.all(np.diff(table["t_ps"]) > 0)
        assert table["t_ps"][-1] <= r.summary["simulated_ps"] + 1e-12
    assert r.vacf["c"][0] == pytest.approx(1.0)
    assert r.oacf["c1"][0] == pytest.approx(1.0) and r.oacf["c2"][0] == pytest.approx(1.0)
    assert r.msd["msd_angstrom2"][0] == 0.0 and np.all(r.msd["msd_angstrom2"][1:] > 0)
    assert len(r.thermo) == 11  # rows every 18 fs over 180 fs, and one at the start
    assert r.summary["n_bodies"] == 144
    assert math.isfinite(r.summary["pressure"]["mean_bar"])
    assert not r.interrupted and r.trajectory is None


def test_load_reads_the_same(both):
    _, _, r = both
    again = terrace.load(r.dir)
    assert again.summary == r.summary
    for name in r.rdf.dtype.names:
        assert np.array_equal(again.rdf[name], r.rdf[name], equal_nan=True)
    assert "144" in repr(again)


def test_existing_results_are_refused_as_by_the_cli(both, executable, tmp_path):
    engine, cli, _ = both
    scene = terrace.Scene(DENSE_RODS, SMALL, engine=engine)
    with pytest.raises(terrace.IoError) as caught:
        terrace.run(scene, out=cli, progress=False)
    status, err = cli_run(executable, cli, DENSE_RODS, *cli_sets(SMALL), "--set",
                          f"engine={engine}")
    assert status != 0 and err.strip() == "terrace: " + str(caught.value)


def test_out_none_is_a_fresh_temporary_directory():
    r = terrace.run(terrace.Scene(DENSE_RODS, dict(SMALL, **{"run.equilibrate_ps": 0}),
                                  engine="smd"), progress=False)
    try:
        assert os.path.basename(r.dir).startswith("terrace-dense-rods-smd-")
        assert r.rdf.shape[0] > 10
    finally:  # the directory is the caller's to remove
        shutil.rmtree(r.dir)


def test_load_refuses_what_is_no_run(tmp_path):
    with pytest.raises(terrace.IoError, match="no summary.json"):
        terrace.load(tmp_path)


def test_resume_without_a_restart_file_raises_the_cli_message(tmp_path, executable):
    import subprocess
    with pytest.raises(terrace.IoError) as caught:
        terrace.resume(tmp_path, progress=False)
    p = subprocess.run([str(executable), "run", "--continue", str(tmp_path)],
                       capture_output=True, text=True)
    assert p.returncode != 0 and p.stderr.strip() == "terrace: " + str(caught.value)


def test_an_engine_failure_raises_with_the_output_written(tmp_path, executable):
    """An unstable SMD step (9 fs steps): TerraceError with the CLI's message; the summary
    records the error, as the CLI's does."""
    sets = dict(SMALL, **{"smd.dt_fs": 9})
    with pytest.raises(terrace.TerraceError) as caught:
        terrace.run(terrace.Scene(DENSE_RODS, sets, engine="smd"), out=tmp_path / "py",
                    progress=False)
    assert "smd: the integration became unstable" in str(caught.value)
    status, err = cli_run(executable, tmp_path / "cli", DENSE_RODS, *cli_sets(sets), "--set",
                          "engine=smd")
    assert status == 1
    cli_message = err.strip().splitlines()[-1][len("terrace: "):]
    assert str(caught.value) == cli_message.replace(str(tmp_path / "cli"), str(tmp_path / "py"))
    r = terrace.load(tmp_path / "py")
    assert r.summary["error"] in str(caught.value)
