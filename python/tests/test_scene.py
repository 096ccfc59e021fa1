"""terrace.Scene: read by the CLI's reader, with its messages; resolved() round trips."""

import json
import subprocess
import warnings

import pytest

import terrace
from conftest import DENSE_RODS, SMALL


def cli_error(executable, tmp_path, *args):
    """The message `terrace run` prints for a refused scene (without "terrace: ")."""
    p = subprocess.run([str(executable), "run", *map(str, args), "--out", str(tmp_path / "o")],
                       capture_output=True, text=True)
    assert p.returncode != 0
    line = p.stderr.strip().splitlines()[-1]
    assert line.startswith("terrace: ")
    return line[len("terrace: "):]


def test_resolved_round_trip():
    scene = terrace.Scene(DENSE_RODS, overrides=SMALL, engine="smd")
    resolved = scene.resolved()
    assert resolved["engine"] == "smd"
    assert resolved["state"]["n"] == 144
    # The resolved scene read back is the same scene, key for key and bit for bit.
    again = terrace.Scene(resolved)
    assert again.resolved() == resolved
    assert json.dumps(again.resolved(), sort_keys=True) == json.dumps(resolved, sort_keys=True)


def test_resolved_equals_the_run_scene_json(tmp_path, executable):
    from conftest import cli_run, cli_sets
    status, err = cli_run(executable, tmp_path / "cli", DENSE_RODS, *cli_sets(SMALL),
                          "--set", "engine=smd")
    assert status == 0, err
    with open(tmp_path / "cli" / "scene.json") as f:
        recorded = json.load(f)
    assert terrace.Scene(DENSE_RODS, SMALL, engine="smd").resolved() == recorded


def test_scene_from_a_scene_keeps_its_overrides():
    base = terrace.Scene(DENSE_RODS, {"state.n": 144})
    derived = terrace.Scene(base, engine="smd")
    assert derived.resolved()["state"]["n"] == 144
    assert derived.engine == "smd"
    assert derived.overrides == ['state.n=144', 'engine="smd"']
    assert derived.cli_arguments() == [str(DENSE_RODS), "--set", "state.n=144", "--set",
                                       'engine="smd"']


def test_default_scene_and_default_output():
    scene = terrace.Scene(engine="smd")
    assert scene.name == "dense-rods"
    assert scene.default_output == "out/dense-rods-smd"
    assert terrace.Scene(None, {"state.n": 64}).default_output == "out/dense-rods-dmd-n=64"


@pytest.mark.parametrize("overrides, key", [
    ({"smd.bogus": 1}, "smd.bogus"),
    ({"dmd.dV": -1}, "dmd.dV"),
    ({"engine": "smd", "run.time_ps": 2}, "run.time_ps"),  # between two SMD steps
    ({"state.temp": 2}, "state.temp"),
])
def test_bad_values_raise_the_cli_message(tmp_path, executable, overrides, key):
    from conftest import cli_sets
    with pytest.raises(terrace.SceneError) as caught:
        terrace.Scene(DENSE_RODS, overrides)
    assert key in str(caught.value)
    assert str(caught.value) == cli_error(executable, tmp_path, DENSE_RODS, *cli_sets(overrides))


def test_a_start_refused_as_the_run_begins_raises_the_cli_message(tmp_path, executable):
    """A density that overlaps the lattice is found when the initial state is built."""
    from conftest import cli_sets
    scene = terrace.Scene(DENSE_RODS, {"state.density": 5})
    with pytest.raises(terrace.SceneError) as caught:
        terrace.run(scene, out=tmp_path / "py", progress=False)
    assert str(caught.value).startswith("state.density: 5.000000 puts lattice neighbours")
    assert str(caught.value) == cli_error(executable, tmp_path, DENSE_RODS,
                                          *cli_sets({"state.density": 5}))
    assert not (tmp_path / "py" / "summary.json").exists()


def test_bad_file_raises(tmp_path, executable):
    bad = tmp_path / "s.json"
    bad.write_text('{ not json')
    with pytest.raises(terrace.SceneError) as caught:
        terrace.Scene(bad)
    assert str(caught.value) == cli_error(executable, tmp_path, bad)
    with pytest.raises(terrace.SceneError, match="cannot open"):
        terrace.Scene(tmp_path / "missing.json")


def test_bad_dict_names_the_dict():
    with pytest.raises(terrace.SceneError, match=r"^<scene dict>: dmd.dv: unknown key"):
        terrace.Scene({"name": "x", "dmd": {"dv": 1}})
    with pytest.raises(TypeError):
        terrace.Scene(3)
    with pytest.raises(ValueError):  # JSON has no NaN
        terrace.Scene(None, {"state.density": float("nan")})


def test_other_engine_key_warns_or_is_refused():
    with pytest.warns(UserWarning, match="smd.dt_fs"):
        terrace.Scene(DENSE_RODS, {"smd.dt_fs": 1.8})
    with pytest.raises(terrace.SceneError, match="smd.dt_fs"):
        terrace.Scene(DENSE_RODS, {"smd.dt_fs": 1.8}, strict=True)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        terrace.Scene(DENSE_RODS, {"smd.dt_fs": 1.8}, engine="smd")


def test_numpy_values_are_accepted():
    np = pytest.importorskip("numpy")
    scene = terrace.Scene(None, {"state.n": np.int64(64), "state.density": np.float64(0.4)})
    assert scene.resolved()["state"]["n"] == 64
    assert scene.resolved()["state"]["density"] == 0.4
