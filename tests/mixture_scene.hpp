#pragma once
// Kob–Andersen's binary Lennard-Jones mixture (W. Kob and H. C. Andersen, Phys. Rev. E 51, 4626
// (1995): 80 % A, 20 % B, ε_AB 1.5, σ_AB 0.8, ε_BB 0.5, σ_BB 0.88) as a scene document, in units
// where ε = 1 kJ/mol, σ = 1 Å and m = 1 g/mol (τ = 100 fs), for the mixture tests; each adds the
// sections it needs (lattice, engines, run).
#include <nlohmann/json.hpp>

namespace terrace::mixture_tests {

inline nlohmann::json kobAndersen(int n, double density, double temperature) {
    return {{"body", {{"kind", "sphere"}, {"mass", 1.0}}},
            {"potential",
             {{"kind", "lj"},
              {"epsilon", 1.0},
              {"sigma", 1.0},
              {"cutoff", {2.5, 3.0}},
              {"pairs", {{{"between", {"A", "B"}}, {"epsilon", 1.5}, {"sigma", 0.8}}}}}},
            {"species",
             {{{"name", "A"}, {"fraction", 0.8}, {"epsilon", 1.0}, {"sigma", 1.0}},
              {{"name", "B"}, {"fraction", 0.2}, {"epsilon", 0.5}, {"sigma", 0.88}}}},
            {"state", {{"n", n}, {"density", density}, {"temperature", temperature}}}};
}

} // namespace terrace::mixture_tests
