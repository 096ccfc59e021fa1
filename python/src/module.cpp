// The compiled part of the Python module terrace (python/terrace/__init__.py wraps it): the
// exceptions, and the Simulation a user advances. Scenes and runs: scene_binding.cpp; sweeps:
// sweep_binding.cpp.
#include "bindings.hpp"
#include "cli/engine_handle.hpp"
#include "cli/run_record.hpp"
#include "core/output_file.hpp"
#include "core/units.hpp"
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <stdexcept>

namespace py = pybind11;

namespace terrace::python {

namespace {

/// One engine built from a scene (cli/engine_handle.hpp); its units are the engines' own, and the
/// binding turns times into ps.
using Simulation = cli::EngineHandle;

/// An n×columns float64 array that owns `values` (moved, not copied).
py::array_t<double> ownedArray(std::vector<double>&& values, std::size_t columns) {
    auto* held = new std::vector<double>(std::move(values));
    const py::capsule owner(held, [](void* p) { delete static_cast<std::vector<double>*>(p); });
    const auto rows = py::ssize_t(held->size() / columns);
    return py::array_t<double>({rows, py::ssize_t(columns)}, held->data(), owner);
}

/// Three-vectors as an n×3 array, each component times `scale` (a unit conversion).
py::array_t<double> vectors(const std::vector<Vec3>& v, double scale) {
    std::vector<double> flat(3 * v.size());
    for (std::size_t i = 0; i < v.size(); ++i)
        for (int k = 0; k < 3; ++k)
            flat[3 * i + std::size_t(k)] = v[i][k] * scale;
    return ownedArray(std::move(flat), 3);
}

/// Orientations as n×4 quaternions (w, x, y, z), body to lab: a top's own; a linear rotor's
/// rotation of least angle taking the body z axis to its axis (its spin is immaterial), as the
/// GSD trajectory writes it (core/gsd_frame.cpp); a sphere's axis is z, so its is the identity.
py::array_t<double> quaternions(const Snapshot& s) {
    std::vector<double> flat(4 * std::size_t(s.size()));
    for (int i = 0; i < s.size(); ++i) {
        const Quat q = s.orientation.empty() ? Quat::FromTwoVectors(Vec3::UnitZ(), s.axis[i])
                                             : s.orientation[i];
        const double wxyz[4] = {q.w(), q.x(), q.y(), q.z()};
        std::copy(wxyz, wxyz + 4, flat.begin() + 4 * i);
    }
    return ownedArray(std::move(flat), 4);
}

/// The engine with what the binding adds: the scene, and where the last advance began (DMD's
/// pressure is a mean over an interval, core/pressure.hpp).
struct PySimulation {
    std::unique_ptr<Simulation> sim;
    Scene scene;
    int bodies = 0;
    double sampleInterval = 0.0; // time units, as the CLI's run plan has it
    double intervalStart = 0.0;  // time units
    double virialAtStart = 0.0;
    // True while advance runs with the GIL released. Read and written with the GIL held only, so
    // another thread's call meanwhile sees it and is refused instead of racing the engine.
    bool advancing = false;
};

/// `p`, refused while another thread advances it.
const PySimulation& idle(const PySimulation& p) {
    if (p.advancing)
        throw std::runtime_error("this Simulation is being advanced by another thread: one "
                                 "thread at a time");
    return p;
}
PySimulation& idle(PySimulation& p) {
    idle(static_cast<const PySimulation&>(p));
    return p;
}

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

/// Advances by `ps` in chunks that end on the scene's sample grid (k · run.sample_fs from the
/// start, the instants at which `terrace run` samples a run without equilibration), checking for
/// Ctrl-C between chunks with the GIL held. A target within round-off of a grid point is that
/// point, so that ten advances of one sample end where one of ten samples does, bit for bit.
void advance(PySimulation& p, double ps) {
    if (!(ps >= 0.0) || !std::isfinite(ps))
        throw std::invalid_argument("advance: ps must be a finite time >= 0, got " +
                                    std::to_string(ps));
    Simulation& sim = *idle(p).sim;
    p.advancing = true;
    struct Done {
        bool& flag;
        ~Done() { flag = false; }
    } done{p.advancing};
    p.intervalStart = sim.time();
    p.virialAtStart = sim.virial();
    const double grid = p.sampleInterval;
    double target = sim.time() + units::fromPs(ps);
    const double k = std::round(target / grid);
    if (std::abs(target / grid - k) < 1e-9 * std::max(1.0, k)) target = k * grid;
    while (sim.time() < target) {
        const double next = std::min(target, (std::floor(sim.time() / grid + 1e-6) + 1.0) * grid);
        {
            const py::gil_scoped_release free;
            sim.advanceTo(next);
        }
        if (PyErr_CheckSignals() != 0) throw py::error_already_set();
        if (next == target) break; // SMD stops on its own grid, at or past the target
    }
}

/// P in bar: SMD's at the instant; DMD's over the last advance (NaN before one).
double pressureBar(const PySimulation& p) {
    const Simulation& sim = *idle(p).sim;
    const double volume = std::pow(p.scene.boxLength(), 3);
    double w = sim.virial();
    if (sim.virialKind() == VirialKind::Impulse) {
        if (!(sim.time() > p.intervalStart)) return nan;
        w = impulseVirialOver(p.virialAtStart, w, p.intervalStart, sim.time());
    }
    return units::bar(virialPressure(sim.translationalKineticEnergy(), w, volume));
}

py::dict energies(const Simulation& sim) {
    const ContinuousSums c = sim.continuousSums();
    py::dict d;
    d["kinetic"] = sim.kineticEnergy();
    d["kinetic_translational"] = sim.translationalKineticEnergy();
    d["potential"] = sim.potentialEnergy();
    d["potential_continuous"] = c.potential;
    d["total"] = sim.kineticEnergy() + sim.potentialEnergy();
    return d;
}

py::dict state(const Snapshot& s) {
    py::dict d;
    d["time_ps"] = units::toPs(s.time);
    d["box_angstrom"] = s.boxLength;
    d["positions"] = vectors(s.position, 1.0);
    d["velocities"] = vectors(s.velocity, 1.0 / units::psPerTimeUnit);
    d["orientations"] = quaternions(s);
    d["angular_velocities"] = vectors(s.omega, 1.0 / units::psPerTimeUnit);
    // A mixture's species of each body (an index into the scene's species); None without.
    if (s.species.empty())
        d["species"] = py::none();
    else
        d["species"] = py::array_t<std::int32_t>(py::ssize_t(s.species.size()), s.species.data());
    return d;
}

} // namespace

void bindSimulation(py::module_& m) {
    py::class_<PySimulation>(m, "_Simulation")
        .def(py::init([](const ResolvedScene& s) {
                 PySimulation p{cli::makeEngineHandle(s.scene), s.scene};
                 p.bodies = p.sim->positions().size();
                 p.sampleInterval = cli::planRun(s.scene).sampleInterval;
                 return p;
             }),
             py::arg("scene"))
        .def("advance", &advance, py::arg("ps"))
        .def_property_readonly(
            "time_ps", [](const PySimulation& p) { return units::toPs(idle(p).sim->time()); })
        .def("state", [](const PySimulation& p) { return state(idle(p).sim->snapshot()); })
        .def("positions",
             [](const PySimulation& p) { return vectors(idle(p).sim->positions().position, 1.0); })
        .def("energies", [](const PySimulation& p) { return energies(*p.sim); })
        .def("pressure_bar", &pressureBar)
        .def("temperature_K",
             [](const PySimulation& p) {
                 const double dof = idle(p).sim->degreesOfFreedom();
                 return units::kelvin(2.0 * idle(p).sim->kineticEnergy() / dof);
             })
        .def("rescale_temperature",
             [](PySimulation& p, std::optional<double> kelvin) {
                 idle(p).sim->rescaleTemperature(kelvin ? *kelvin * units::kB : p.scene.kT());
             })
        .def("momentum",
             [](const PySimulation& p) {
                 const Vec3 v = idle(p).sim->totalMomentum() / units::psPerTimeUnit;
                 return std::vector<double>{v.x(), v.y(), v.z()};
             })
        .def("statistics", [](const PySimulation& p) { return idle(p).sim->statistics().dump(); });
}

} // namespace terrace::python

PYBIND11_MODULE(_terrace, m) {
    using namespace terrace;
    m.doc() = "The compiled part of terrace; use the package terrace, which wraps it.";
    // Python's exceptions carry the CLI's messages (cli/main.cpp prints them after "terrace: ").
    static py::exception<SceneError> sceneError(m, "SceneError", PyExc_ValueError);
    static py::exception<IoError> ioError(m, "IoError", PyExc_OSError);
    static py::exception<std::exception> terraceError(m, "TerraceError", PyExc_RuntimeError);
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const py::builtin_exception&) {
            throw; // pybind11's own (a failed cast), translated by pybind11
        } catch (const std::bad_alloc&) {
            PyErr_SetString(PyExc_MemoryError, "out of memory (the system refused an allocation)");
        } catch (const std::invalid_argument& e) {
            PyErr_SetString(PyExc_ValueError, e.what());
        } catch (const SceneError& e) {
            sceneError(e.what());
        } catch (const IoError& e) {
            ioError(e.what());
        } catch (const std::filesystem::filesystem_error& e) {
            ioError(("cannot access " + e.path1().string() + ": " + e.code().message()).c_str());
        } catch (const nlohmann::json::exception& e) {
            PyErr_SetString(PyExc_ValueError, e.what());
        } catch (const std::exception& e) { // an engine's failure, a refused resource, ...
            terraceError(e.what());
        }
    });
    python::bindScene(m);
    python::bindSweep(m);
    python::bindSimulation(m);
}
