#pragma once
// A body's orientation as a potential reads it (core/pair_potential.hpp AttitudeUse): the unit
// axis K::axis, or the frame K::frame (rotation body -> lab) of a kind that has one. Only tops
// carry a full frame; a linear rotor has an axis alone, so a frame potential on rods is a compile
// error rather than a silent use of half an attitude. Also the same choice from an attitude of
// a free orbit (core/free_orbit.hpp), which the DMD search samples.
#include "core/body_kind.hpp"
#include "core/pair_potential.hpp"
#include "core/species_sphere.hpp"

namespace terrace {

template <PairPotential P, BodyKind K>
typename P::Orientation orientationOf(const typename K::State& b) {
    if constexpr (P::attitude == AttitudeUse::Frame) {
        static_assert(
            requires { K::frame(b); }, "a frame potential needs a body kind with a frame");
        return K::frame(b);
    } else if constexpr (P::attitude == AttitudeUse::Species) {
        static_assert(
            requires { b.species; }, "a species potential needs a body kind with a species");
        return b.species;
    } else if constexpr (P::attitude == AttitudeUse::SpeciesAxis) {
        static_assert(
            requires { b.species; }, "a species potential needs a body kind with a species");
        return SpeciesAxis{K::axis(b), b.species};
    } else {
        return K::axis(b);
    }
}

/// The orientation carried by a free orbit's Attitude (its axis, its frame, its species): a
/// reference to the attitude's own member, or, for an axis with a species, the pair of them.
template <PairPotential P, class Attitude> decltype(auto) orientationOf(const Attitude& a) {
    if constexpr (P::attitude == AttitudeUse::Frame) {
        static_assert(
            requires { a.frame; }, "a frame potential needs a body kind with a frame");
        return (a.frame);
    } else if constexpr (P::attitude == AttitudeUse::Species) {
        static_assert(
            requires { a.species; }, "a species potential needs a body kind with a species");
        return (a.species);
    } else if constexpr (P::attitude == AttitudeUse::SpeciesAxis) {
        static_assert(
            requires { a.species; }, "a species potential needs a body kind with a species");
        return SpeciesAxis{a.axis, a.species};
    } else {
        return (a.axis);
    }
}

/// The orientation handed to a potential that never reads it (AttitudeUse::None).
template <PairPotential P> typename P::Orientation unusedOrientation() {
    if constexpr (P::attitude == AttitudeUse::Frame)
        return Mat3::Identity();
    else if constexpr (P::attitude == AttitudeUse::Species)
        return 0; // the first species: what a design or a coverage check samples of a mixture
    else if constexpr (P::attitude == AttitudeUse::SpeciesAxis)
        return SpeciesAxis{}; // ẑ, the first species
    else
        return Vec3::UnitZ();
}

} // namespace terrace
