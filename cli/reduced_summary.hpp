#pragma once
// summary.json's "reduced" entry under the scene's units lj (core/unit_system.hpp): the run's
// results in σ, ε, m, τ, with the energies per body. The summary's other entries stay in real
// units whatever the scene's units, since the commands that read summaries (compare, sweep,
// tradeoff) and the experiments' scripts read them there.
//
//   scale                      sigma_angstrom, epsilon_kj_per_mol, mass_g_per_mol, tau_fs
//   simulated_tau, sample_tau, cpu_seconds_per_tau
//   temperature, temperature_err, temperature_target                        T* = k_B T/ε
//   potential_energy_per_body, _err, _std; total_energy_per_body            ε
//   energy_drift_per_tau_per_body, energy_rel_fluct                         ε/τ; a ratio
//   pressure, pressure_err                                                  P* = Pσ³/ε
//   configurational: potential_energy_per_body, _err, pressure, pressure_err
//   diffusion: einstein, einstein_err, green_kubo, green_kubo_err           σ²/τ
//     and for a mixture species: {A: {the same four}, …}
//   collisions_per_tau, collisions_per_tau_err                              DMD
// A quantity the summary lacks, or holds as null, is left out or null.
#include "core/unit_system.hpp"
#include <nlohmann/json.hpp>

namespace terrace::cli {

/// The "reduced" entry of `summary` (a run's, in real units) under `u` (reduced()).
nlohmann::json reducedSummary(const nlohmann::json& summary, const UnitSystem& u);

} // namespace terrace::cli
