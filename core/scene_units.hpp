#pragma once
// A scene's "units" (core/unit_system.hpp) and how its keys are read under them (docs/UNITS.md):
//
//   A key whose name carries a unit (run.time_ps, smd.dt_fs, analysis.rdf_bin_angstrom, ...) is
//   read in that unit, whatever the scene's units: a scene written for real units means the same
//   run under lj, only its results are written in reduced units.
//   Each such key has a unit-free twin (run.time, smd.dt, analysis.rdf_bin, ...: unitTwins), read
//   in the scene's units, τ or σ under lj; under real, which has two time units, the twins do
//   not exist (an unknown key, "did you mean run.time_ps?"). A scene gives one of the two; an
//   override (--set) of either replaces the other (keepOverriddenTwins).
//   Keys with no unit in their names are read in the scene's units: under lj, dmd.levels and
//   dmd.values in ε, state.particles[].r in σ, .v in σ/τ, .omega in 1/τ.
//   The model's own parameters (body.*, potential.*) define the scale and stay in real units;
//   state.temperature (T*) and state.density (ρ*) are reduced in both systems.
//
// The readers and the engines only ever see real units: sceneKeysToReal rewrites the JSON before
// they read it, and the resolved scene written back (toJson) gives every named-unit key in its
// unit and every unit-free one in the scene's units again (sceneKeysFromReal, exact for values
// read through sceneKeysToReal).
#include "core/scene.hpp"
#include "core/unit_system.hpp"
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace terrace {

/// The units of the scene's keys and results: real, or lj on potential.sigma, potential.epsilon
/// and body.mass.
UnitSystem unitSystem(const Scene& s);

/// A key with a unit in its name and its unit-free twin, "section.key".
struct UnitTwin {
    const char* section;
    const char* named; // in the unit its name gives (real)
    const char* free;  // in the scene's units (lj only)
    Dimension dimension;
};
/// Every twin, in the order docs/UNITS.md lists them.
const std::vector<UnitTwin>& unitTwins();

/// Under lj, after the overrides (`overriddenKeys`, dotted) are applied: of a pair of twins that
/// the scene gives both, the one no override set is removed, so that an override of either
/// replaces the one the scene file gave.
void keepOverriddenTwins(nlohmann::json& scene, const std::vector<std::string>& overriddenKeys);

/// Rewrites a whole scene's JSON into real units for the readers: unit-free twins become their
/// named keys, unit-free keys are scaled; under real, nothing changes. Both of a pair under lj
/// is a SceneError naming the key ("<origin>: run.time: ..."). Values of the wrong type are
/// left for the readers.
void sceneKeysToReal(nlohmann::json& scene, const UnitSystem& u, const std::string& origin);
/// The unit-free keys of a resolved scene back in `u` (a no-op under real).
void sceneKeysFromReal(nlohmann::json& scene, const UnitSystem& u);

/// What a refusal under reduced units adds: the scale, and that unit-free keys were converted.
std::string reducedNote(const UnitSystem& u);

} // namespace terrace
