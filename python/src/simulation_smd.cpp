#include "cli/dispatch.hpp"
#include "simulation.hpp"
#include "smd/engine.hpp"

namespace terrace::python {

// As cli/run_smd.cpp builds a fresh run's engine.
std::unique_ptr<Simulation> makeSmdSimulation(const Scene& scene) {
    return cli::withBodyAndPotential(
        scene, [&]<class K, class P>(const P& potential) -> std::unique_ptr<Simulation> {
            const auto model = cli::sceneModel(scene, potential, false);
            using M = std::remove_const_t<decltype(model)>;
            using E = smd::Engine<K, M>;
            const smd::SmdSettings settings =
                smd::smdSettings(scene, scene.boxLength(), model.range());
            return std::make_unique<EngineSimulation<E, K::rotationalDof>>(
                std::make_unique<E>(buildInitialState<K, M>(scene, model), settings));
        });
}

std::unique_ptr<Simulation> makeSimulation(const Scene& scene) {
    return scene.engine == "smd" ? makeSmdSimulation(scene) : makeDmdSimulation(scene);
}

} // namespace terrace::python
