#include "cli/dispatch.hpp"
#include "cli/engine_handle.hpp"
#include "cli/run_command.hpp"
#include "smd/engine.hpp"

namespace terrace::cli {
namespace {

/// SMD has nothing to integrate in a step table (its forces are impulses at the radii); the scene
/// is refused before it gets here (core/scene.cpp), and no SMD engine is compiled for one.
[[noreturn]] void refuseSteps() {
    throw SceneError("engine: smd cannot integrate potential.kind steps: use engine dmd");
}

} // namespace

RunOutcome runSmd(const Scene& scene, const RunTarget& target) {
    return withBodyAndPotential(scene, [&]<class K, class P>(const P& potential) -> RunOutcome {
        if constexpr (isSteppedModel<P>) {
            refuseSteps();
        } else {
            const auto model = sceneModel(scene, potential, false);
            using M = std::remove_const_t<decltype(model)>;
            using E = smd::Engine<K, M>;
            // Read once: every engine of the run (restart points rebuild it) takes a copy.
            const smd::SmdSettings settings =
                smd::smdSettings(scene, scene.boxLength(), model.range());
            auto make = [&settings](System<K, M>&& system, nlohmann::json* checkpoint) {
                if (!checkpoint) return std::make_unique<E>(std::move(system), settings);
                return std::make_unique<E>(std::move(system), settings, *checkpoint);
            };
            return buildAndDrive<E, K>(scene, model, target, make);
        }
    });
}

std::unique_ptr<EngineHandle> makeSmdHandle(const Scene& scene) {
    return withBodyAndPotential(
        scene, [&]<class K, class P>(const P& potential) -> std::unique_ptr<EngineHandle> {
            if constexpr (isSteppedModel<P>) {
                refuseSteps();
            } else {
                const auto model = sceneModel(scene, potential, false);
                using M = std::remove_const_t<decltype(model)>;
                using E = smd::Engine<K, M>;
                return std::make_unique<EngineHandleOf<E, K::rotationalDof>>(
                    std::make_unique<E>(buildInitialState<K, M>(scene, model),
                                        smd::smdSettings(scene, scene.boxLength(), model.range())));
            }
        });
}

std::unique_ptr<EngineHandle> makeEngineHandle(const Scene& scene) {
    return scene.engine == "smd" ? makeSmdHandle(scene) : makeDmdHandle(scene);
}

} // namespace terrace::cli
