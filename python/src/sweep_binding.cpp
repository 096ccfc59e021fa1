// terrace.sweep(): the sweep of `terrace sweep` (cli/main.cpp sweepMain, without MPI), its runs
// started as `terrace run` children of this build's executable (cli/run_process.hpp).
#include "bindings.hpp"
#include "cli/engine_keys.hpp"
#include "cli/output_dir.hpp"
#include "cli/run_process.hpp"
#include "cli/sweep_runner.hpp"
#include <cstdlib>
#include <pybind11/stl.h>

namespace py = pybind11;

namespace terrace::python {

namespace {

/// TERRACE_EXECUTABLE when set, else the executable built beside this module (python/CMakeLists).
std::filesystem::path terraceExecutable() {
    const char* chosen = std::getenv("TERRACE_EXECUTABLE");
    return chosen != nullptr && *chosen != '\0' ? chosen : TERRACE_EXECUTABLE;
}

} // namespace

void warn(const std::string& text) {
    if (PyErr_WarnEx(PyExc_UserWarning, text.c_str(), 2) != 0) throw py::error_already_set();
}

void bindSweep(py::module_& m) {
    m.def(
        "sweep_default_output",
        [](const std::string& file, const std::vector<std::string>& sets) {
            return (std::filesystem::path("out") /
                    cli::nameWithOverrides(
                        cli::sanitisedName(std::filesystem::path(file).stem().string()), sets))
                .string();
        },
        py::arg("file"), py::arg("sets"));
    m.def(
        "run_sweep",
        [](const std::string& file, const std::vector<std::string>& sets, const std::string& out,
           int jobs, bool quiet, bool retryFailed, bool strict) {
            cli::SweepOptions options;
            options.out = out;
            options.jobs = jobs;
            options.quiet = quiet;
            options.retryFailed = retryFailed;
            options.strict = strict;
            if (jobs < 1) throw std::invalid_argument("jobs must be at least 1");
            cli::SweepPlan plan = cli::loadSweep(file, sets);
            if (strict) cli::refuseIgnoredKeys(plan);
            for (const std::string& note : plan.ignoredKeys)
                warn(cli::asWarning(note));
            const std::filesystem::path executable = terraceExecutable();
            if (!std::filesystem::exists(executable))
                throw std::runtime_error(executable.string() +
                                         ": the terrace executable a sweep's runs need is not "
                                         "there (build the target terrace, or set "
                                         "TERRACE_EXECUTABLE)");
            cli::setRunExecutable(executable);
            const py::gil_scoped_release free;
            const std::lock_guard one(runLock());
            return cli::runSweep(plan, options);
        },
        py::arg("file"), py::arg("sets"), py::arg("out"), py::arg("jobs"), py::arg("quiet"),
        py::arg("retry_failed"), py::arg("strict"));
}

} // namespace terrace::python
