// Scenes and runs: the CLI's own functions (cli/run_command.hpp), called as `terrace run` calls
// them (cli/main.cpp runMain), so that a run from Python is the same run, bit for bit.
#include "bindings.hpp"
#include "cli/engine_keys.hpp"
#include "cli/run_command.hpp"
#include "cli/scene_check.hpp"
#include <pybind11/stl.h>

namespace py = pybind11;

namespace terrace::python {

namespace {

/// From a scene file (`path`), a scene as JSON text (`text`, what Python's dict became) or
/// neither (the built-in default scene), with the overrides applied as --set applies them.
ResolvedScene resolve(const std::string& path, const std::string& text,
                      const std::vector<std::string>& overrides, bool strict) {
    ResolvedScene r;
    r.overrides = overrides;
    if (text.empty()) {
        r.scene = cli::resolveScene(cli::RunRequest{path, overrides, true});
    } else {
        const std::string origin = "<scene dict>";
        r.scene = sceneFromJson(nlohmann::json::parse(text), origin, overrides);
        cli::resolveEngineSections(r.scene, origin);
    }
    // As runMain: the keys the engine does not read are warnings the run records, or refused.
    for (std::string& w : cli::judgeOverrides(overrides, r.scene.engine,
                                              "the run's engine, " + r.scene.engine + ",", strict))
        r.scene.warnings.push_back(std::move(w));
    return r;
}

} // namespace

void bindScene(py::module_& m) {
    py::class_<ResolvedScene>(m, "_Scene")
        .def_property_readonly("json",
                               [](const ResolvedScene& s) { return toJson(s.scene).dump(); })
        .def_property_readonly("warnings", [](const ResolvedScene& s) { return s.scene.warnings; })
        .def_property_readonly("overrides", [](const ResolvedScene& s) { return s.overrides; })
        .def_property_readonly("default_output", [](const ResolvedScene& s) {
            return cli::defaultOutput(s.scene, s.overrides).string();
        });
    m.def("resolve_scene", &resolve, py::arg("path"), py::arg("text"), py::arg("overrides"),
          py::arg("strict"));
    m.def(
        "run_scene",
        [](const ResolvedScene& s, const std::string& dir, bool overwrite, bool quiet) {
            cli::RunTarget target;
            target.dir = dir;
            target.mode = overwrite ? cli::OutputMode::Overwrite : cli::OutputMode::Fresh;
            target.quiet = quiet;
            // The run installs its own signal handlers (cli/interrupt.hpp) for its duration.
            const py::gil_scoped_release free;
            const std::lock_guard one(runLock());
            return cli::runScene(s.scene, target);
        },
        py::arg("scene"), py::arg("dir"), py::arg("overwrite"), py::arg("quiet"));
    m.def(
        "resume_run",
        [](const std::string& dir, bool quiet) {
            Scene scene;
            const py::gil_scoped_release free;
            const std::lock_guard one(runLock());
            return cli::continueRun(dir, quiet, scene);
        },
        py::arg("dir"), py::arg("quiet"));
    py::class_<cli::RunOutcome>(m, "_RunOutcome")
        .def_property_readonly("summary", [](const cli::RunOutcome& o) { return o.summary.dump(); })
        .def_readonly("exit_status", &cli::RunOutcome::exitStatus);
}

} // namespace terrace::python
