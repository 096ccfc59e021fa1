#include "cli/run_command.hpp"
#include "cli/dispatch.hpp"
#include "cli/output_dir.hpp"
#include "cli/restart.hpp"
#include "cli/scene_check.hpp"
#include "core/output_file.hpp"
#include <cstdio>
#include <fstream>
#include <sstream>
#include <unistd.h>

namespace terrace::cli {

Scene resolveScene(const RunRequest& request) {
    const std::string origin =
        request.scenePath.empty() ? "<built-in default scene>" : request.scenePath;
    // The built-in scene is no key at all: some defaults follow other keys (analysis.rdf_max
    // the box), which the default scene written out would pin.
    Scene scene = request.scenePath.empty()
                      ? sceneFromJson(nlohmann::json::object(), origin, request.overrides)
                      : loadScene(request.scenePath, request.overrides);
    resolveEngineSections(scene, origin);
    return scene;
}

std::filesystem::path defaultOutput(const Scene& scene, const std::vector<std::string>& overrides) {
    return std::filesystem::path("out") /
           nameWithOverrides(sanitisedName(scene.name + "-" + scene.engine), overrides);
}

namespace {

/// Memory this machine can give a process now (MemAvailable), in bytes; 0 if unknown.
double availableMemory() {
    std::ifstream meminfo("/proc/meminfo");
    std::string key;
    double kib = 0.0;
    std::string unit;
    while (meminfo >> key >> kib >> unit)
        if (key == "MemAvailable:") return kib * 1024.0;
    const long pages = sysconf(_SC_AVPHYS_PAGES), size = sysconf(_SC_PAGESIZE);
    return pages > 0 && size > 0 ? double(pages) * double(size) : 0.0;
}

} // namespace

void checkSampleMemory(const Scene& scene) {
    const double need = analysisBytes(scene);
    const double have = availableMemory();
    if (have > 0.0 && need > have) {
        char text[512];
        std::snprintf(text, sizeof text,
                      "run: the analysis of the %.0f samples of this run (run.time_ps / "
                      "run.sample_fs) would take %.3g GiB of memory, more than the %.3g GiB "
                      "available: use fewer analysis.follow_bodies or a longer run.sample_fs",
                      double(planRun(scene).productionSamples) + 1.0, need / (1 << 30),
                      have / (1 << 30));
        throw SceneError(text);
    }
}

RunOutcome runScene(const Scene& scene, const RunTarget& target) {
    checkSampleMemory(scene);
    return scene.engine == "smd" ? runSmd(scene, target) : runDmd(scene, target);
}

RunOutcome continueRun(const std::filesystem::path& dir, bool quiet, Scene& scene) {
    // The lock first: the restart file read is the one no other run can change meanwhile.
    const OutputDirectory output(dir, OutputMode::Continue);
    nlohmann::json restart = readRestart(dir);
    checkRunIdentity(dir, restart); // before anything is cut back or run
    try {
        nlohmann::json recorded = restart.at("scene");
        // A restart file records the resolved scene; one that names the queue "auto" ran on the
        // tree, which is what "auto" chose, and goes on with it.
        if (recorded.contains("dmd") && recorded["dmd"].value("queue", "") == "auto")
            recorded["dmd"]["queue"] = "tree";
        const std::string origin = (dir / "restart.bin").string();
        scene = sceneFromJson(recorded, origin);
        resolveEngineSections(scene, origin);
        checkSampleMemory(scene);
        RunTarget target{dir, OutputMode::Continue, quiet, &restart};
        return scene.engine == "smd" ? runSmd(scene, target) : runDmd(scene, target);
    } catch (const nlohmann::json::exception& e) {
        throw damagedRestart(dir, e);
    }
}

} // namespace terrace::cli
