#pragma once
// When a start is an overlap, not a state point: one bound and one message for both engines, so
// that DMD and SMD refuse the same starts in the same words (DESIGN.md "Bad input").
#include "core/scene.hpp"
#include <cmath>
#include <string>

namespace terrace {

/// A pair above this multiple of the well depth |U_min| at the start overlaps: far up the
/// repulsive wall, its first events or forces would be meaningless.
inline constexpr double overlapFactor = 1e4;

/// Whether a start pair with energy U (kJ/mol) overlaps, for a potential of minimum uMin.
inline bool overlapsAtStart(double U, double uMin) {
    return !std::isfinite(U) || U > overlapFactor * std::abs(uMin);
}

/// "state: bodies i and j overlap (U = ... kJ/mol)", i < j.
[[noreturn]] inline void throwOverlap(int i, int j, double U) {
    throw SceneError("state: bodies " + std::to_string(std::min(i, j)) + " and " +
                     std::to_string(std::max(i, j)) + " overlap (U = " + std::to_string(U) +
                     " kJ/mol)");
}

} // namespace terrace
