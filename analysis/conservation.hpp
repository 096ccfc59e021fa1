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
//   potentialMean, potentialStd   of U (std: population, 1/n)
//
// They are accumulated record by record (EnergyAccumulator) in a state of a dozen numbers, so a
// run keeps no series and its restart file does not grow with it. The spreads and the slope use
// running centred sums (B. P. Welford, Technometrics 4, 419 (1962), and its two-variable form for
// the co-moment of t and E) of the values less the first record's: as accurate as two passes
// about the mean when E is large and its drift tiny, where raw sums of squares would cancel.
#include "analysis/state_bytes.hpp"
#include <vector>

namespace terrace::analysis {

struct EnergyStats {
    double initial, final, mean, std, maxAbsDev, relFluct, driftPerPs;
    double potentialMean, potentialStd;
};

class EnergyAccumulator {
public:
    /// The next record; std::invalid_argument when its time is not later than the last one's.
    void add(double tPs, double total, double potential);
    long count() const { return n_; }
    /// std::invalid_argument before the first record.
    EnergyStats stats() const;

    void write(StateWriter& out) const;
    void read(StateReader& in);

private:
    long n_ = 0;
    double initial_ = 0.0, firstT_ = 0.0, firstU_ = 0.0; // the first record: E, t, U
    double final_ = 0.0, lastT_ = 0.0, maxDev_ = 0.0;
    double sumE_ = 0.0, sumU_ = 0.0;   // plain sums: the means, as Σx/n
    double meanT_ = 0.0, meanE_ = 0.0; // running means behind the centred sums
    double meanU_ = 0.0, m2U_ = 0.0;   // Σ (U − ⟨U⟩)²
    double m2T_ = 0.0, m2E_ = 0.0, coTE_ = 0.0; // Σ (t − ⟨t⟩)², Σ (E − ⟨E⟩)², Σ (t − ⟨t⟩)(E − ⟨E⟩)
};

/// The statistics of whole series, through EnergyAccumulator. Throws std::invalid_argument for
/// empty or unequal-length series or non-increasing times.
EnergyStats energyStats(const std::vector<double>& tPs, const std::vector<double>& total,
                        const std::vector<double>& potential);

} // namespace terrace::analysis
