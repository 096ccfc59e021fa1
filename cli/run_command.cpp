#include "cli/run_command.hpp"
#include "cli/dispatch.hpp"
#include "core/xyz.hpp"
#include <fstream>

namespace terrace::cli {

Scene resolveScene(const RunRequest& request) {
    if (request.scenePath.empty())
        return sceneFromJson(toJson(defaultScene()), "<built-in default scene>", request.overrides);
    return loadScene(request.scenePath, request.overrides);
}

void prepareOutput(const std::filesystem::path& dir, const Scene& scene) {
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "scene.json") << toJson(scene).dump(2) << '\n';
}

nlohmann::json runScene(const Scene& scene, const std::filesystem::path& outDir, bool quiet) {
    return scene.engine == "smd" ? runSmd(scene, outDir, quiet) : runDmd(scene, outDir, quiet);
}

} // namespace terrace::cli
