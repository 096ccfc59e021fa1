#pragma once
// An SMD engine built from a scene, as tests, benchmarks and tools build one: its settings read
// from the scene (smd/parameters.hpp: smdSettings) for the bodies' box and the model's range. The
// engine itself takes its settings and knows no scene; a run reads them once and builds every
// engine of the run from them (cli/run_smd.cpp).
#include "core/scene.hpp"
#include "core/system.hpp"
#include "smd/engine.hpp"
#include "smd/parameters.hpp"
#include <nlohmann/json.hpp>
#include <utility>

namespace terrace::smd {

template <BodyKind K, PairPotential P> class SceneEngine : public Engine<K, P> {
public:
    SceneEngine(System<K, P> initial, const Scene& scene)
        : SceneEngine(initial, settingsOf(scene, initial)) {}
    /// Resumed from a checkpoint (smd::Engine's).
    SceneEngine(System<K, P> initial, const Scene& scene, const nlohmann::json& checkpoint)
        : SceneEngine(initial, settingsOf(scene, initial), checkpoint) {}

private:
    static SmdSettings settingsOf(const Scene& scene, const System<K, P>& s) {
        return smdSettings(scene, s.box.length, s.potential.range());
    }
    // `s` is moved from only once the settings have been read from it.
    template <class... Checkpoint>
    SceneEngine(System<K, P>& s, SmdSettings settings, const Checkpoint&... c)
        : Engine<K, P>(std::move(s), std::move(settings), c...) {}
};

} // namespace terrace::smd
