#include "cli/dispatch.hpp"
#include "cli/run_command.hpp"
#include "cli/run_driver.hpp"
#include "dmd/engine.hpp"

namespace terrace::cli {

nlohmann::json runDmd(const Scene& scene, const std::filesystem::path& outDir, bool quiet) {
    return withBodyAndPotential(scene, [&]<class K, class P>(const P& potential) {
        dmd::Engine<K, P> engine(buildInitialState<K, P>(scene, potential), scene);
        prepareOutput(outDir, scene);
        return drive(engine, scene, outDir, K::rotationalDof, quiet);
    });
}

} // namespace terrace::cli
