#pragma once
// A sphere of one of a scene's species (Scene::species): translation only, like Sphere, an index
// that a species potential reads to pick the pair's parameters (core/lj_mixture.hpp), and the
// species' own mass (BodyParams::speciesMass). The species of a body never changes.
#include "core/sphere.hpp"
#include <cstdint>

namespace terrace {

struct SpeciesSphere : Sphere {
    // Sphere's functions of the motion take this state as the Sphere state it extends.
    struct State : Sphere::State {
        std::int32_t species = 0; // index into Scene::species
    };

    static double mass(const State& s, const BodyParams& p) { return p.speciesMass[s.species]; }
};

} // namespace terrace
