#pragma once
// Rods among spheres (core/species_rotor.hpp, core/rod_mixture.hpp) as the DMD tests run them:
// the engines' types and the scene, the paper's rods (species "rod") in a Lennard-Jones solvent of
// heavier, weaker spheres, with both engines' sections (each test adds what it varies).
#include "core/initial_state.hpp"
#include "core/rod_mixture.hpp"
#include "core/smoothed_potential.hpp"
#include "core/species_rotor.hpp"
#include "dmd/scene_engine.hpp"
#include "smd/scene_engine.hpp"
#include <nlohmann/json.hpp>

namespace terrace::rod_mixture_tests {

using Model = Smoothed<RodMixture>;
using RodSystem = System<SpeciesRotor, Model>;
using DmdRods = dmd::SceneEngine<SpeciesRotor, Model>;
using SmdRods = smd::SceneEngine<SpeciesRotor, Model>;

/// A quarter of the bodies the paper's rods (ε 3 kJ/mol, σ 3.035 Å, ζ 1 Å, 18 g/mol, I 1.154
/// g/mol Å²), the rest spheres of ε 0.6 ε, σ 1.1 σ and 2.2 times the rods' mass; unlike pairs by
/// Lorentz–Berthelot; DMD on the smoothed model at ΔV = dVInKT kT, SMD at dtFs.
inline nlohmann::json rodsAmongSpheres(int n, double density, double temperature, double dVInKT,
                                       double dtFs = 0.9) {
    return {{"body", {{"kind", "linear"}, {"mass", 18.0}, {"inertia", {1.154, 1.154, 0.0}}}},
            {"potential",
             {{"kind", "rod-lj"},
              {"epsilon", 3.0},
              {"sigma", 3.035},
              {"zeta", 1.0},
              {"cutoff", {2.5, 3.0}}}},
            {"species",
             {{{"name", "rod"}, {"fraction", 0.25}, {"kind", "linear"}},
              {{"name", "solvent"},
               {"fraction", 0.75},
               {"kind", "sphere"},
               {"epsilon", 0.6},
               {"sigma", 1.1},
               {"mass", 2.2}}}},
            {"state", {{"n", n}, {"density", density}, {"temperature", temperature}}},
            {"dmd", {{"model", "smoothed"}, {"dV", dVInKT}}},
            {"smd", {{"dt_fs", dtFs}}}};
}

inline RodSystem rodSystem(const Scene& s) {
    return buildInitialState<SpeciesRotor>(s, Model{rodMixture(s), sceneCutoff(s)});
}

} // namespace terrace::rod_mixture_tests
