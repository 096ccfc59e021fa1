#include "cli/dispatch.hpp"
#include "cli/engine_handle.hpp"
#include "cli/run_command.hpp"
#include "smd/engine.hpp"

namespace terrace::cli {
namespace {

/// Calls fn.template operator()<K>(model) with the scene's body kind K and the model SMD
/// integrates, returning R. SMD has nothing to integrate in a step table (its forces are impulses
/// at the radii): the scene is refused before it gets here (core/scene.cpp), and no SMD engine is
/// compiled for one.
template <class R, class Fn> R withSmdModel(const Scene& scene, Fn&& fn) {
    return withBodyAndPotential(scene, [&]<class K, class P>(const P& potential) -> R {
        if constexpr (isSteppedModel<P>)
            throw SceneError("engine: smd cannot integrate potential.kind steps: use engine dmd");
        else
            return fn.template operator()<K>(sceneModel(scene, potential, false));
    });
}

} // namespace

RunOutcome runSmd(const Scene& scene, const RunTarget& target) {
    return withSmdModel<RunOutcome>(scene, [&]<class K, class M>(const M& model) {
        using E = smd::Engine<K, M>;
        // Read once: every engine of the run (restart points rebuild it) takes a copy.
        const smd::SmdSettings settings = smd::smdSettings(scene, scene.boxLength(), model.range());
        auto make = [&settings](System<K, M>&& system, nlohmann::json* checkpoint) {
            if (!checkpoint) return std::make_unique<E>(std::move(system), settings);
            return std::make_unique<E>(std::move(system), settings, *checkpoint);
        };
        return buildAndDrive<E, K>(scene, model, target, make);
    });
}

std::unique_ptr<EngineHandle> makeSmdHandle(const Scene& scene) {
    return withSmdModel<std::unique_ptr<EngineHandle>>(
        scene, [&]<class K, class M>(const M& model) -> std::unique_ptr<EngineHandle> {
            using E = smd::Engine<K, M>;
            System<K, M> start = buildInitialState<K, M>(scene, model);
            const int dof = degreesOfFreedom(start);
            return std::make_unique<EngineHandleOf<E>>(
                std::make_unique<E>(std::move(start),
                                    smd::smdSettings(scene, scene.boxLength(), model.range())),
                dof);
        });
}

std::unique_ptr<EngineHandle> makeEngineHandle(const Scene& scene) {
    return scene.engine == "smd" ? makeSmdHandle(scene) : makeDmdHandle(scene);
}

} // namespace terrace::cli
