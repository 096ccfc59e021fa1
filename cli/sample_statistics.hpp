#pragma once
// What summary.json says of a run's production samples (energies, temperature, pressure, the
// configurational estimators, the collision rate), accumulated sample by sample in a state whose
// size is fixed before the run starts: a run keeps no series of its samples, and its restart
// file (cli/restart.hpp) holds this state, about a kilobyte, whatever the run's length.
//
//   energy          analysis::EnergyAccumulator: initial, final, mean, spreads, the drift's
//                   least-squares slope, the largest excursion
//   blocks          analysis::FixedBlocks of pressureBlocks (8) blocks laid over the planned
//                   samples: K (temperature_err_K), U (potential_energy_err), P (pressure), the
//                   collisions per interval (collisions_per_ps_err), and the configurational U
//                   and P over the planned g(r) frames (at most 8 blocks, one frame each below)
//   previous        the last sample: DMD's pressure and collisions are taken over the interval
//                   that ends at a sample
//   heat bath       the effective energy H + (energy the bath removed) as a second
//                   EnergyAccumulator, blocks of (K − (f/2) kT)² beside those of K for Var K
//                   (analysis/canonical_kinetic.hpp), and the bath's count at the first sample;
//                   kept whether or not the scene has a bath, so the state's size is the plan's
//
// A run that takes the samples it planned reports the block errors of 8 contiguous blocks of
// equal length (±1), as when they were computed from the whole series at the end. A run stopped
// for good before its end has its later blocks part-filled or empty, each counting by its number
// of samples (analysis/block_average.hpp), where the series used to be cut into 8 blocks of its
// own length: the same mean, an error from another grouping (docs/RUNS.md).
#include "analysis/canonical_kinetic.hpp"
#include "analysis/conservation.hpp"
#include "analysis/fixed_blocks.hpp"
#include "cli/restart.hpp"
#include "core/pressure.hpp"
#include <cstdint>
#include <nlohmann/json.hpp>
#include <span>
#include <vector>

namespace terrace::cli {

/// What the statistics are laid out for: the samples and g(r) frames the run plans, what its
/// virial holds, the box volume (Å³) and the temperature's degrees of freedom.
struct SamplePlan {
    long samples = 0, frames = 0;
    VirialKind virialKind = VirialKind::Instantaneous;
    double volume = 0.0;
    int dof = 0;
    double kT = 0.0;       // kJ/mol: the canonical kinetic energy's reference, (dof/2) kT
    bool heatBath = false; // H is not conserved, so its wander is no warning (the effective
                           // energy's is, cli/heat_bath_summary.hpp)
};

class SampleStatistics {
public:
    SampleStatistics() = default;
    explicit SampleStatistics(const SamplePlan& plan);

    /// Production's next sample; std::out_of_range beyond the plan, std::invalid_argument when
    /// its time does not follow the last one's.
    void add(const SampleRecord& e);
    long count() const { return energy_.count(); }

    /// summary.json's entries from the samples so far: temperature_K and its error,
    /// potential_energy_* and energy (with a warning, also on stderr, when the total energy
    /// wandered without a heat bath), pressure and configurational; nothing before the first
    /// sample. σ in Å, ε in kJ/mol.
    void summarise(nlohmann::json& summary, double sigma, double epsilon) const;
    /// One standard error of the collisions per ps (DMD), from the collisions of each sample
    /// interval; null below three samples or two blocks.
    nlohmann::json collisionRateError(double sampleIntervalPs) const;

    /// What the heat bath's block of summary.json reads (cli/heat_bath_summary.hpp): the
    /// effective energy's statistics (std::invalid_argument before a sample), the energy the bath
    /// took out since production's first sample (kJ/mol), and ⟨K⟩, Var K against the canonical.
    analysis::EnergyStats effectiveEnergy() const { return effective_.stats(); }
    double bathEnergyRemoved() const { return count() == 0 ? 0.0 : previous_.bath - firstBath_; }
    analysis::CanonicalKinetic canonicalKinetic() const {
        return analysis::canonicalKinetic(kinetic_, kineticShiftedSquares_, plan_.dof, plan_.kT);
    }

    /// The state as raw bytes (analysis/state_bytes.hpp), its size fixed by the plan.
    std::vector<std::uint8_t> state() const;
    /// The state of statistics of the same plan; std::invalid_argument for any other.
    void restore(std::span<const std::uint8_t> bytes);

private:
    nlohmann::json configurational(double sigma, double epsilon) const;

    SamplePlan plan_;
    analysis::EnergyAccumulator energy_;
    analysis::FixedBlocks kinetic_, potential_, pressure_, collisions_;
    analysis::FixedBlocks continuousU_, continuousP_;
    double pressureKinetic_ = 0.0, pressureVirial_ = 0.0; // Σ over the samples with a pressure
    analysis::EnergyAccumulator effective_;               // H + bath
    analysis::FixedBlocks kineticShiftedSquares_; // (K − (dof/2) kT)², over kinetic_'s blocks
    double firstBath_ = 0.0;                      // the bath's energy at the first sample
    SampleRecord previous_;
};

} // namespace terrace::cli
