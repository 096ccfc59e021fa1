#include "cli/dispatch.hpp"
#include "cli/engine_handle.hpp"
#include "cli/run_command.hpp"
#include "dmd/engine.hpp"
#include "dmd/scene_engine.hpp"

namespace terrace::cli {
namespace {

/// Calls fn.template operator()<K>(model, settings) with the scene's body kind K, the model DMD
/// terraces and its settings (run.heat_bath among them), returning R.
template <class R, class Fn> R withDmdModel(const Scene& scene, Fn&& fn) {
    return withBodyAndPotential(scene, [&]<class K, class P>(const P& potential) -> R {
        const auto model = sceneModel(scene, potential, true);
        return fn.template operator()<K>(
            model, dmd::sceneSettings(scene, model, scene.kT(), scene.boxLength()));
    });
}

} // namespace

RunOutcome runDmd(const Scene& scene, const RunTarget& target) {
    return withDmdModel<RunOutcome>(scene, [&]<class K, class M>(const M& model,
                                                                 const dmd::DmdSettings& settings) {
        using E = dmd::Engine<K, M>;
        // Read once: every engine of the run (restart points rebuild it) takes a copy.
        auto make = [&settings, seed = scene.seed](System<K, M>&& system,
                                                   nlohmann::json* checkpoint) {
            if (!checkpoint) return std::make_unique<E>(std::move(system), settings, seed);
            return std::make_unique<E>(std::move(system), settings, seed, std::move(*checkpoint));
        };
        return buildAndDrive<E, K>(scene, model, target, make);
    });
}

std::unique_ptr<EngineHandle> makeDmdHandle(const Scene& scene) {
    return withDmdModel<std::unique_ptr<EngineHandle>>(
        scene,
        [&]<class K, class M>(const M& model,
                              const dmd::DmdSettings& settings) -> std::unique_ptr<EngineHandle> {
            using E = dmd::Engine<K, M>;
            System<K, M> start = buildInitialState<K, M>(scene, model);
            const int dof = degreesOfFreedom(start);
            return std::make_unique<EngineHandleOf<E>>(
                std::make_unique<E>(std::move(start), settings, scene.seed), dof);
        });
}

} // namespace terrace::cli
