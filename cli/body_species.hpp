#pragma once
// A mixture's species labels for the analysis (analysis/species_labels.hpp): the names from the
// scene, body i's species as the engine's samples give it (Snapshot::species).
//
// Why from the engine's samples and not recomputed from the scene: a body's species is dealt
// once, by core/initial_state.hpp, from the scene's seed, and travels with the body's state from
// then on (into restart files and back); both engines hand out samples in the scene's numbering
// whatever order they keep their bodies in (DMD's Morton order, SMD's cell order: their
// snapshot(bodies) maps scene numbers to their own), so the labels read once at the start hold
// for every later sample, of a fresh run or of a continued one. A copy of the dealing here could
// drift from the engines' own. The labels are read a slice of bodies at a time: a whole sample
// of a large system is never held beside the engine.
#include "analysis/species_labels.hpp"
#include "core/engine.hpp"
#include "core/scene.hpp"
#include <algorithm>
#include <numeric>
#include <span>
#include <stdexcept>
#include <vector>

namespace terrace::cli {

/// The labels' names, and for rods among spheres which species never turn (kind sphere), from
/// the scene; the bodies' species are left to the caller.
inline analysis::SpeciesLabels speciesNames(const Scene& scene) {
    analysis::SpeciesLabels labels;
    for (const auto& s : scene.species)
        labels.names.push_back(s.name);
    const bool kinds = std::any_of(scene.species.begin(), scene.species.end(),
                                   [](const SpeciesSpec& s) { return s.kind == "sphere"; });
    if (kinds)
        for (const auto& s : scene.species)
            labels.fixedAxis.push_back(s.kind == "sphere");
    return labels;
}

/// The scene's species names and each body's species from `engine` (n bodies); empty labels for
/// a scene without species.
template <class E> analysis::SpeciesLabels bodySpecies(const E& engine, const Scene& scene, int n) {
    if (scene.species.empty()) return {};
    analysis::SpeciesLabels labels = speciesNames(scene);
    labels.ofBody.reserve(static_cast<std::size_t>(n));
    constexpr int slice = 1 << 16;
    std::vector<int> bodies;
    for (int begin = 0; begin < n; begin += slice) {
        bodies.resize(static_cast<std::size_t>(std::min(slice, n - begin)));
        std::iota(bodies.begin(), bodies.end(), begin);
        const Snapshot s = engine.snapshot(std::span<const int>(bodies));
        if (s.species.size() != bodies.size())
            throw std::logic_error("species: the engine's samples carry no species for a "
                                   "mixture scene");
        labels.ofBody.insert(labels.ofBody.end(), s.species.begin(), s.species.end());
    }
    labels.check(n);
    return labels;
}

} // namespace terrace::cli
