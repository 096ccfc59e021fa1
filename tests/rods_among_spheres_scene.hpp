#pragma once
// Rods among spheres (core/species_rotor.hpp, core/rod_mixture.hpp) as a scene document, for the
// tests of the scene, the engines and their agreement: a quarter of the bodies the paper's rods
// (ε 3 kJ/mol, σ 3.035 Å, ζ 1 Å, 18 g/mol, I 1.154 g/mol Å²), the rest spheres of 0.6 ε, 1.1 σ
// and 2.2 times the rods' mass, unlike pairs by Lorentz–Berthelot (as
// experiments/scenes/rods-in-solvent.json). Each test adds what it varies.
#include <nlohmann/json.hpp>

namespace terrace::rod_mixture_tests {

inline nlohmann::json rodsAmongSpheresDocument(int n, double density, double temperature) {
    return {{"body", {{"kind", "linear"}, {"mass", 18.0}, {"inertia", {1.154, 1.154, 0.0}}}},
            {"potential", {{"kind", "rod-lj"}, {"epsilon", 3.0}, {"sigma", 3.035}, {"zeta", 1.0}}},
            {"species",
             {{{"name", "rod"}, {"fraction", 0.25}, {"kind", "linear"}},
              {{"name", "solvent"},
               {"fraction", 0.75},
               {"kind", "sphere"},
               {"epsilon", 0.6},
               {"sigma", 1.1},
               {"mass", 2.2}}}},
            {"state", {{"n", n}, {"density", density}, {"temperature", temperature}}}};
}

} // namespace terrace::rod_mixture_tests
