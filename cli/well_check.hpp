#pragma once
// The warning a DMD scene gets when its terracing swallows a well of the potential in some pair
// orientation (dmd/well_coverage.hpp): `terrace run` and `terrace design` show it.
#include "core/scene.hpp"

namespace terrace::cli {

/// Wells shallower than this many kT are not reported.
inline constexpr double significantWellInKT = 0.1;

/// Adds to scene.warnings, for a DMD scene whose terraces swallow the whole well of some sampled
/// pair orientations, one line naming the share, the deepest such well in kT and what resolves
/// it. A scene whose terraces cannot be built is left alone: the run reports that itself.
void warnOfSwallowedWells(Scene& scene);

} // namespace terrace::cli
