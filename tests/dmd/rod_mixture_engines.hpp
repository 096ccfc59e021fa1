#pragma once
// Rods among spheres (core/species_rotor.hpp, core/rod_mixture.hpp) as the DMD tests run them:
// the engines' types, and the scene (tests/rods_among_spheres_scene.hpp) with both engines'
// sections (each test adds what it varies).
#include "core/initial_state.hpp"
#include "core/rod_mixture.hpp"
#include "core/smoothed_potential.hpp"
#include "core/species_rotor.hpp"
#include "dmd/scene_engine.hpp"
#include "smd/scene_engine.hpp"
#include "tests/rods_among_spheres_scene.hpp"
#include <nlohmann/json.hpp>

namespace terrace::rod_mixture_tests {

using Model = Smoothed<RodMixture>;
using RodSystem = System<SpeciesRotor, Model>;
using DmdRods = dmd::SceneEngine<SpeciesRotor, Model>;
using SmdRods = smd::SceneEngine<SpeciesRotor, Model>;

/// The tests' rods among spheres (tests/rods_among_spheres_scene.hpp) cut on [2.5, 3] σ, DMD on
/// the smoothed model at ΔV = dVInKT kT, SMD at dtFs.
inline nlohmann::json rodsAmongSpheres(int n, double density, double temperature, double dVInKT,
                                       double dtFs = 0.9) {
    nlohmann::json j = rodsAmongSpheresDocument(n, density, temperature);
    j["potential"]["cutoff"] = {2.5, 3.0};
    j["dmd"] = {{"model", "smoothed"}, {"dV", dVInKT}};
    j["smd"] = {{"dt_fs", dtFs}};
    return j;
}

inline RodSystem rodSystem(const Scene& s) {
    return buildInitialState<SpeciesRotor>(s, Model{rodMixture(s), sceneCutoff(s)});
}

} // namespace terrace::rod_mixture_tests
