#include "cli/run_command.hpp"
#include "cli/dispatch.hpp"
#include "cli/output_dir.hpp"
#include "cli/resource_check.hpp"
#include "cli/restart.hpp"
#include "cli/scene_check.hpp"
#include "cli/well_check.hpp"
#include "core/output_file.hpp"
#include <cstdio>
#include <sstream>

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
    warnOfSwallowedWells(scene);
    return scene;
}

std::filesystem::path defaultOutput(const Scene& scene, const std::vector<std::string>& overrides) {
    return std::filesystem::path("out") /
           nameWithOverrides(sanitisedName(scene.name + "-" + scene.engine), overrides);
}

RunOutcome runScene(const Scene& scene, const RunTarget& target) {
    checkResources(scene, target.dir, false);
    return scene.engine == "smd" ? runSmd(scene, target) : runDmd(scene, target);
}

RunOutcome continueRun(const std::filesystem::path& dir, bool quiet, Scene& scene) {
    const double cpuAtStart = CpuClock::now(); // the checks below may build the engine's terraces
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
        warnOfSwallowedWells(scene); // as the run it continues said
        checkResources(scene, dir, true);
        RunTarget target{dir, OutputMode::Continue, quiet, &restart, cpuAtStart};
        return scene.engine == "smd" ? runSmd(scene, target) : runDmd(scene, target);
    } catch (const nlohmann::json::exception& e) {
        throw damagedRestart(dir, e);
    }
}

} // namespace terrace::cli
