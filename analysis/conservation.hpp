#pragma once
// Energy-conservation statistics of a run (DESIGN.md "Analysis", conservation monitors), from the
// total energy E(t) and potential energy U(t) recorded at times t (ps), energies in kJ/mol:
//
//   initial, final   E(t_0), E(t_last)
//   mean, std        of E over the records (std: population, 1/n)
//   maxAbsDev        max_t |E(t) − E(t_0)|: the worst excursion from the starting energy
//   relFluct         std(E) / |mean(U)|: the paper's measure (1.8 fs SMD: about 1 %, "Comparison
//                    between standard molecular dynamics and event-driven simulations");
//                    +inf when mean(U) = 0 and E fluctuates, 0 when neither does
//   driftPerPs       slope of the least-squares line E ≈ a + b t, kJ/mol per ps (0 for one record)
#include <vector>

namespace terrace::analysis {

struct EnergyStats {
    double initial, final, mean, std, maxAbsDev, relFluct, driftPerPs;
};

/// Throws std::invalid_argument for empty or unequal-length series or non-increasing times.
EnergyStats energyStats(const std::vector<double>& tPs, const std::vector<double>& total,
                        const std::vector<double>& potential);

} // namespace terrace::analysis
