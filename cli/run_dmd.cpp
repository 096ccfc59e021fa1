#include "cli/dispatch.hpp"
#include "cli/engine_handle.hpp"
#include "cli/run_command.hpp"
#include "dmd/engine.hpp"

namespace terrace::cli {
namespace {

template <class M> dmd::DmdSettings dmdSettingsOf(const Scene& scene, const M& model) {
    dmd::DmdSettings s = dmd::readDmdSettings(scene.dmd, model, scene.kT(), scene.boxLength());
    s.bath = heatBathOf(scene);
    return s;
}

} // namespace

RunOutcome runDmd(const Scene& scene, const RunTarget& target) {
    return withBodyAndPotential(scene, [&]<class K, class P>(const P& potential) {
        const auto model = sceneModel(scene, potential, true);
        using M = std::remove_const_t<decltype(model)>;
        using E = dmd::Engine<K, M>;
        // Read once: every engine of the run (restart points rebuild it) takes a copy.
        const dmd::DmdSettings settings = dmdSettingsOf(scene, model);
        auto make = [&settings, seed = scene.seed](System<K, M>&& system,
                                                   nlohmann::json* checkpoint) {
            if (!checkpoint) return std::make_unique<E>(std::move(system), settings, seed);
            return std::make_unique<E>(std::move(system), settings, seed, std::move(*checkpoint));
        };
        return buildAndDrive<E, K>(scene, model, target, make);
    });
}

std::unique_ptr<EngineHandle> makeDmdHandle(const Scene& scene) {
    return withBodyAndPotential(
        scene, [&]<class K, class P>(const P& potential) -> std::unique_ptr<EngineHandle> {
            const auto model = sceneModel(scene, potential, true);
            using M = std::remove_const_t<decltype(model)>;
            using E = dmd::Engine<K, M>;
            return std::make_unique<EngineHandleOf<E, K::rotationalDof>>(std::make_unique<E>(
                buildInitialState<K, M>(scene, model), dmdSettingsOf(scene, model), scene.seed));
        });
}

} // namespace terrace::cli
