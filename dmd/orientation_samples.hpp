#pragma once
// The relative orientations a terrace design (dmd/pair_energy_density.hpp) and the well check
// (dmd/well_coverage.hpp) sample of a pair potential: random attitudes of the kind the potential
// reads (a unit axis, or a frame) and, for a mixture of rods and spheres, a species pair with
// them, taken in turn over every pair a ≤ b of its species so that each is sampled alike (the
// rods' anisotropic pairs as often as the solvent's round ones). A design is a pure function of
// its inputs: the draws come from the caller's fixed stream, in the order they always had.
#include "core/body_orientation.hpp"
#include "core/initial_state.hpp"
#include "core/pair_potential.hpp"
#include <random>
#include <utility>
#include <vector>

namespace terrace::dmd {

/// The species of a mixture's potential (its bare potential's, under a smoothed cutoff); 1 for a
/// potential of one kind of body.
template <class P> int mixtureSpecies(const P& p) {
    if constexpr (requires { p.bare.species; })
        return p.bare.species;
    else if constexpr (requires { p.species; })
        return p.species;
    else
        return 1;
}

/// Every pair of species a ≤ b of p, in order.
template <class P> std::vector<std::pair<int, int>> speciesPairsOf(const P& p) {
    std::vector<std::pair<int, int>> pairs;
    const int species = mixtureSpecies(p);
    for (int a = 0; a < species; ++a)
        for (int b = a; b < species; ++b)
            pairs.emplace_back(a, b);
    return pairs;
}

/// The k-th sampled orientation pair of an orientational potential p (isOrientational<P>),
/// random from rng; a mixture of rods and spheres takes its species pair k modulo their number.
template <PairPotential P>
std::pair<typename P::Orientation, typename P::Orientation>
sampledOrientations(const P& p, int k, std::mt19937_64& rng) {
    static_assert(isOrientational<P>);
    if constexpr (P::attitude == AttitudeUse::Frame) {
        const Mat3 qi = terrace::detail::randomRotation(rng);
        return {qi, terrace::detail::randomRotation(rng)};
    } else if constexpr (P::attitude == AttitudeUse::SpeciesAxis) {
        const auto pairs = speciesPairsOf(p);
        const auto [a, b] = pairs[static_cast<std::size_t>(k) % pairs.size()];
        const Vec3 si = terrace::detail::randomUnitVector(rng);
        return {SpeciesAxis{si, a}, SpeciesAxis{terrace::detail::randomUnitVector(rng), b}};
    } else {
        const Vec3 si = terrace::detail::randomUnitVector(rng);
        return {si, terrace::detail::randomUnitVector(rng)};
    }
}

} // namespace terrace::dmd
