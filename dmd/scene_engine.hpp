#pragma once
// A DMD engine built from a scene, as tests, benchmarks and tools build one: its settings read
// from the scene's dmd section (dmd/settings.hpp) for the bodies' potential, kT and box, and the
// scene's seed. The engine itself takes its settings and a seed and knows no scene; a run reads
// the settings once and builds every engine of the run from them (cli/run_dmd.cpp).
#include "core/scene.hpp"
#include "core/system.hpp"
#include "dmd/engine.hpp"
#include "dmd/settings.hpp"
#include <nlohmann/json.hpp>
#include <utility>

namespace terrace::dmd {

/// The DMD settings of `scene` for `model` at kT (kJ/mol) in a box of edge boxLength (Å): its
/// dmd section and run.heat_bath (as smd::smdSettings is SMD's).
template <PairPotential P>
DmdSettings sceneSettings(const Scene& scene, const P& model, double kT, double boxLength) {
    DmdSettings settings = readDmdSettings(scene.dmd, model, kT, boxLength);
    settings.bath = heatBathOf(scene);
    return settings;
}

template <BodyKind K, PairPotential P>
DmdSettings settingsFor(const Scene& scene, const System<K, P>& s) {
    return sceneSettings(scene, s.potential, s.kT, s.box.length);
}

template <BodyKind K, PairPotential P> class SceneEngine : public Engine<K, P> {
public:
    SceneEngine(System<K, P> initial, const Scene& scene)
        : SceneEngine(initial, settingsFor(scene, initial), scene.seed) {}
    /// Resumed from a checkpoint (dmd::Engine's), kept or spent.
    SceneEngine(System<K, P> initial, const Scene& scene, const nlohmann::json& checkpoint)
        : SceneEngine(initial, settingsFor(scene, initial), scene.seed, checkpoint) {}
    SceneEngine(System<K, P> initial, const Scene& scene, nlohmann::json&& checkpoint)
        : SceneEngine(initial, settingsFor(scene, initial), scene.seed, std::move(checkpoint)) {}

private:
    // `s` is moved from only once the settings have been read from it.
    template <class... Checkpoint>
    SceneEngine(System<K, P>& s, DmdSettings settings, std::uint64_t seed, Checkpoint&&... c)
        : Engine<K, P>(std::move(s), std::move(settings), seed, std::forward<Checkpoint>(c)...) {}
};

} // namespace terrace::dmd
