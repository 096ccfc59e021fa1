"""terrace.Simulation: the engine advanced from Python, its state as NumPy arrays."""

import math
import signal

import numpy as np
import pytest

import terrace
from conftest import DENSE_RODS, SMALL


@pytest.fixture(params=["dmd", "smd"])
def scene(request):
    return terrace.Scene(DENSE_RODS, SMALL, engine=request.param)


def test_state_shapes_and_units(scene):
    sim = terrace.Simulation(scene)
    s = sim.state()
    n = 144
    assert s.positions.shape == (n, 3) and s.velocities.shape == (n, 3)
    assert s.orientations.shape == (n, 4) and s.angular_velocities.shape == (n, 3)
    assert all(a.dtype == np.float64 for a in s[2:6])
    assert s.species is None  # one kind of body
    assert np.allclose(np.linalg.norm(s.orientations, axis=1), 1.0)
    assert s.time_ps == 0.0 and sim.time == 0.0
    # ρ* = Nσ³/L³ fixes the box; the positions start inside it.
    r = scene.resolved()
    box = (n / r["state"]["density"]) ** (1 / 3) * r["potential"]["sigma"]
    assert s.box_angstrom == pytest.approx(box, rel=1e-12)
    assert np.all(np.abs(s.positions) <= box)
    # Velocities in Å/ps: the kinetic temperature of the start is the scene's (T* ε / k_B).
    target = r["state"]["temperature"] * r["potential"]["epsilon"] / 0.0083144626
    assert sim.temperature == pytest.approx(target, rel=1e-9)
    mass = r["body"]["mass"]
    kinetic = 0.5 * mass * np.sum(s.velocities ** 2) / 100.0  # (Å/ps)² g/mol = 0.01 kJ/mol
    assert kinetic == pytest.approx(sim.energies()["kinetic_translational"], rel=1e-12)
    # A rod's orientation takes z to its axis: ω is perpendicular to the axis for a linear rotor.
    q = s.orientations
    w, x, y, z = q.T
    axis = np.stack([2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)], axis=1)
    assert np.allclose(np.einsum("ij,ij->i", axis, s.angular_velocities), 0.0, atol=1e-9)
    assert np.array_equal(sim.positions(), s.positions)
    # The arrays are the caller's: changing one changes nothing in the engine.
    s.positions[:] = 0.0
    assert not np.array_equal(sim.positions(), s.positions)


def test_advance_energies_pressure_counters(scene):
    sim = terrace.Simulation(scene)
    engine = scene.engine
    if engine == "dmd":
        assert math.isnan(sim.pressure)  # a mean over the last advance, and there was none
    e0 = sim.energies()
    sim.advance(0.09)
    assert sim.time == pytest.approx(0.09, abs=1e-12)
    e1 = sim.energies()
    assert set(e1) == {"kinetic", "kinetic_translational", "potential", "potential_continuous",
                       "total"}
    if engine == "dmd":  # its (terraced) total energy is conserved to round-off
        assert e1["total"] == pytest.approx(e0["total"], rel=1e-9)
    assert math.isfinite(sim.pressure)
    assert np.allclose(sim.momentum, 0.0, atol=1e-8)
    counters = sim.counters
    assert isinstance(counters, dict) and counters
    sim.rescale_temperature(300.0)
    assert sim.temperature == pytest.approx(300.0, rel=1e-9)
    sim.rescale_temperature()
    target = scene.resolved()["state"]["temperature"] * scene.resolved()["potential"]["epsilon"]
    assert sim.temperature == pytest.approx(target / 0.0083144626, rel=1e-9)


def test_advance_equals_the_cli_run(scene, tmp_path, executable):
    """A Simulation advanced over the sample grid is the CLI's run without equilibration: its
    energies, temperature and pressure at 90 fs are thermo.csv's row there, bit for bit."""
    from conftest import cli_run, cli_sets
    sets = dict(SMALL, **{"run.equilibrate_ps": 0, "output.thermo_every_fs": 90})
    status, err = cli_run(executable, tmp_path / "cli", DENSE_RODS, *cli_sets(sets),
                          "--set", f"engine={scene.engine}")
    assert status == 0, err
    thermo = terrace.load(tmp_path / "cli").thermo
    sim = terrace.Simulation(terrace.Scene(DENSE_RODS, sets, engine=scene.engine))
    for _ in range(10):
        sim.advance(0.009)
    row = thermo[1]
    assert row["time_ps"] == pytest.approx(sim.time, abs=1e-15)
    e = sim.energies()
    assert row["kinetic_translational"] == e["kinetic_translational"]
    assert row["kinetic_rotational"] == e["kinetic"] - e["kinetic_translational"]
    assert row["potential"] == e["potential"]
    assert row["potential_continuous"] == e["potential_continuous"]
    assert row["total"] == e["total"]
    assert row["temperature_K"] == sim.temperature
    # The pressure over the last advance (DMD: 9 fs) against the row's (DMD: over 90 fs).
    if scene.engine == "smd":
        assert row["pressure_bar"] == sim.pressure


def test_path_does_not_depend_on_how_advance_is_called(scene):
    one, many = terrace.Simulation(scene), terrace.Simulation(scene)
    one.advance(0.09)
    for _ in range(10):
        many.advance(0.009)
    a, b = one.state(), many.state()
    for x, y in zip(a[2:], b[2:]):
        assert np.array_equal(x, y)


def test_bad_advance_raises(scene):
    sim = terrace.Simulation(scene)
    with pytest.raises(ValueError, match="advance"):
        sim.advance(-1.0)
    with pytest.raises(ValueError, match="advance"):
        sim.advance(float("inf"))


def test_ctrl_c_interrupts_advance(scene):
    """A signal whose Python handler raises (as SIGINT's does) stops advance() between chunks."""
    def interrupt(signum, frame):
        raise KeyboardInterrupt
    sim = terrace.Simulation(scene)
    previous = signal.signal(signal.SIGALRM, interrupt)
    try:
        signal.setitimer(signal.ITIMER_REAL, 0.3)
        with pytest.raises(KeyboardInterrupt):
            sim.advance(1e6)  # a million ps: far longer than the test could wait
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)
    assert 0.0 < sim.time < 1e6
    sim.advance(0.009)  # usable afterwards


def test_another_thread_is_refused_while_one_advances():
    """advance() releases the GIL; a call from another thread meanwhile is refused, not raced."""
    import threading
    sim = terrace.Simulation(terrace.Scene(DENSE_RODS, SMALL, engine="dmd"))
    worker = threading.Thread(target=sim.advance, args=(20.0,))
    worker.start()
    refused = None
    while worker.is_alive() and refused is None:
        try:
            sim.state()
        except RuntimeError as e:
            refused = str(e)
    worker.join()
    assert refused is not None and "another thread" in refused
    assert sim.time == pytest.approx(20.0)
    sim.state()  # usable again once the advance has ended


def test_help_shows_docstrings():
    assert "advance" in terrace.Simulation.__doc__
    assert "bit for bit" in terrace.run.__doc__
    assert "SceneError" in terrace.Scene.__doc__


# gas-rods' DMD levels leave out the well, which the scene's reader warns of (as the CLI does).
@pytest.mark.filterwarnings("ignore:dmd.dV")
@pytest.mark.parametrize("name", ["lj-liquid", "gay-berne-liquid", "dumbbell-liquid",
                                  "triatomic-liquid", "gas-rods"])
@pytest.mark.parametrize("engine", ["dmd", "smd"])
def test_every_body_kind(name, engine):
    """Spheres, linear rotors (Gay–Berne, dumbbells, rods) and asymmetric tops (triatomics):
    the same arrays, unit quaternions; a sphere's orientation is the identity and its ω zero."""
    from conftest import SOURCE
    scene = terrace.Scene(SOURCE / "experiments" / "scenes" / f"{name}.json", engine=engine)
    sim = terrace.Simulation(scene)
    sim.advance(0.009)
    s = sim.state()
    n = scene.resolved()["state"]["n"]
    assert s.positions.shape == (n, 3) and s.orientations.shape == (n, 4)
    assert np.allclose(np.linalg.norm(s.orientations, axis=1), 1.0)
    assert np.all(np.isfinite(s.velocities)) and np.all(np.isfinite(s.angular_velocities))
    if scene.resolved()["body"]["kind"] == "sphere":
        assert np.array_equal(s.orientations, np.tile([1.0, 0.0, 0.0, 0.0], (n, 1)))
        assert not np.any(s.angular_velocities)
    else:
        assert np.any(s.angular_velocities)


def test_a_mixtures_species_and_masses():
    """A mixture's state names each body's species, and each body moves with its species' mass:
    ½ Σ m_s v² over the bodies is the engine's translational kinetic energy."""
    from conftest import SOURCE
    for engine in ("dmd", "smd"):
        scene = terrace.Scene(SOURCE / "experiments" / "scenes" / "kob-andersen.json",
                              {"state.n": 256, "state.density": 0.85}, engine=engine)
        resolved = scene.resolved()
        resolved["species"][1]["mass"] = 3.0
        sim = terrace.Simulation(terrace.Scene(resolved))
        sim.advance(0.02)
        s = sim.state()
        assert s.species.dtype == np.int32 and s.species.shape == (256,)
        assert np.bincount(s.species).tolist() == [205, 51]  # 80 %, 20 % by largest remainder
        mass = resolved["body"]["mass"] * np.where(s.species == 1, 3.0, 1.0)
        # (Å/ps)² g/mol = 0.01 kJ/mol
        kinetic = 0.5 * np.sum(mass[:, None] * s.velocities ** 2) / 100.0
        assert kinetic == pytest.approx(sim.energies()["kinetic_translational"], rel=1e-12)
