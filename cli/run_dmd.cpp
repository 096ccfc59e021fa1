#include "cli/dispatch.hpp"
#include "cli/run_command.hpp"
#include "dmd/engine.hpp"

namespace terrace::cli {

RunOutcome runDmd(const Scene& scene, const RunTarget& target) {
    return withBodyAndPotential(scene, [&]<class K, class P>(const P& potential) {
        return buildAndDrive<dmd::Engine, K>(scene, sceneModel(scene, potential, true), target);
    });
}

} // namespace terrace::cli
