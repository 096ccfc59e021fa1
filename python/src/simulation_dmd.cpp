#include "cli/dispatch.hpp"
#include "dmd/engine.hpp"
#include "simulation.hpp"

namespace terrace::python {

// As cli/run_dmd.cpp builds a fresh run's engine.
std::unique_ptr<Simulation> makeDmdSimulation(const Scene& scene) {
    return cli::withBodyAndPotential(
        scene, [&]<class K, class P>(const P& potential) -> std::unique_ptr<Simulation> {
            const auto model = cli::sceneModel(scene, potential, true);
            using M = std::remove_const_t<decltype(model)>;
            using E = dmd::Engine<K, M>;
            dmd::DmdSettings settings =
                dmd::readDmdSettings(scene.dmd, model, scene.kT(), scene.boxLength());
            settings.bath = heatBathOf(scene); // run.heat_bath, as the command line's runs
            return std::make_unique<EngineSimulation<E, K::rotationalDof>>(
                std::make_unique<E>(buildInitialState<K, M>(scene, model), settings, scene.seed));
        });
}

} // namespace terrace::python
