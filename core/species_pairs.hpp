#pragma once
// One value per pair of a mixture's species (Scene::species), symmetric: what the pair (a, b) of
// a species potential takes, its ε, σ or switch (core/lj_mixture.hpp, core/step_mixture.hpp).
#include "core/body_kind.hpp"
#include <array>

namespace terrace {

template <class T> class SpeciesPairTable {
public:
    const T& operator()(int a, int b) const { return value_[a * maxSpecies + b]; }
    bool operator==(const SpeciesPairTable&) const = default;
    /// Sets the pair (a, b) and its mirror (b, a).
    void set(int a, int b, const T& v) {
        value_[a * maxSpecies + b] = value_[b * maxSpecies + a] = v;
    }

private:
    std::array<T, maxSpecies * maxSpecies> value_{};
};

} // namespace terrace
