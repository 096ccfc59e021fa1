#pragma once
// The pieces of the compiled module _terrace, one function per concept (module.cpp calls them).
#include "core/scene.hpp"
#include <mutex>
#include <pybind11/pybind11.h>
#include <string>
#include <vector>

namespace terrace::python {

/// A scene resolved as `terrace run` resolves it, with the overrides ("key=value", as --set
/// takes them) that name its default output directory.
struct ResolvedScene {
    Scene scene;
    std::vector<std::string> overrides;
};

/// A Python UserWarning (an exception where warnings are made errors).
void warn(const std::string& text);

/// Held by a run or sweep for its duration: one at a time in the process, since each installs
/// the process's signal handlers (cli/interrupt.hpp) and counts the signals in one place. Taken
/// with the GIL released, so that a second thread waits without holding it.
inline std::mutex& runLock() {
    static std::mutex lock;
    return lock;
}

void bindScene(pybind11::module_& m);      // _Scene, resolve_scene, run_scene, resume_run
void bindSweep(pybind11::module_& m);      // run_sweep
void bindSimulation(pybind11::module_& m); // _Simulation

} // namespace terrace::python
