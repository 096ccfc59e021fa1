#include "cli/dispatch.hpp"
#include "cli/run_command.hpp"
#include "smd/engine.hpp"

namespace terrace::cli {

RunOutcome runSmd(const Scene& scene, const RunTarget& target) {
    return withBodyAndPotential(scene, [&]<class K, class P>(const P& potential) {
        return buildAndDrive<smd::Engine, K>(scene, sceneModel(scene, potential, false), target);
    });
}

} // namespace terrace::cli
