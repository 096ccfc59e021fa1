#pragma once
// summary.json's "heat_bath", written when run.heat_bath is set (core/heat_bath.hpp):
//   kind, rate_per_ps or tau_fs      the bath as the scene set it
//   degrees_of_freedom               f of the kinetic energy: (3 + r) N for Andersen, which does
//                                    not keep the momentum, (3 + r) N − 3 for CSVR
//   energy_removed                   kinetic energy the bath took out over production, kJ/mol
//   effective_energy                 H + the energy the bath removed since the run began, the
//                                    quantity a thermostatted run conserves (Bussi et al. 2007):
//                                    initial, final, std, max_abs_dev, drift_per_ps (kJ/mol)
//   kinetic_energy                   ⟨K⟩ and Var(K) with block errors beside the canonical (f/2) kT
//                                    and (f/2)(kT)² (analysis/canonical_kinetic.hpp), and each
//                                    deviation in errors
// An effective energy that wanders by more than 1 % of ⟨K⟩ is a warning, as the total energy's is
// under NVE (cli/sample_statistics.cpp). In DMD it is conserved to round-off; in SMD it carries the
// integrator's error, which the bath's draws turn from a bounded fluctuation of H into a drift
// (Sivak, Chodera & Crooks, Phys. Rev. X 3, 011007 (2013)): for the rods at 1.8 fs, 0.002 kJ/mol/ps
// under CSVR (τ 50 fs) but 0.44 kJ/mol/ps under Andersen at 20/ps, which resamples every body every
// 50 fs.
#include "cli/sample_statistics.hpp"
#include "core/scene.hpp"
#include <nlohmann/json.hpp>

namespace terrace::cli {

/// The block, from the production samples' statistics (the effective energy's wander is warned
/// about with the total energy's, SampleStatistics::summarise).
nlohmann::json heatBathSummary(const Scene& scene, const SampleStatistics& samples, int dof);

} // namespace terrace::cli
