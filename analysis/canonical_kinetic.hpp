#pragma once
// Whether a run's kinetic energies K_k (kJ/mol, equally spaced samples) are canonical: in the
// canonical ensemble K of f quadratic degrees of freedom is Gamma(f/2, kT), so
//   ⟨K⟩ = (f/2) kT,   Var(K) = (f/2) (kT)².
// Both are estimated with one standard error from contiguous blocks (block_average.hpp), which
// counts the samples' correlation as long as a block is longer than it; the variance as the block
// mean of (K_k − K̄)², K̄ the whole series' mean (its bias, −Var/n, is far below the error).
//
// A run keeps no series (cli/sample_statistics.hpp), so the blocks come as sums taken sample by
// sample (fixed_blocks.hpp): of K, and of (K − c)² with c = (f/2) kT known before the run. Each
// block's Σ (K − K̄)² follows from them once K̄ is known,
//   Σ_b (K − K̄)² = Σ_b (K − c)² − 2 (K̄ − c) Σ_b (K − c) + n_b (K̄ − c)²,
// and the shift by c keeps the sums of squares near Var K rather than ⟨K⟩², which at 10⁶ bodies
// would cost six of the sixteen digits.
#include "analysis/block_average.hpp"
#include "analysis/fixed_blocks.hpp"
#include <cstddef>
#include <stdexcept>
#include <vector>

namespace terrace::analysis {

struct CanonicalKinetic {
    Estimate mean, variance;
    double canonicalMean = 0.0, canonicalVariance = 0.0;
    /// Deviations from the canonical values in units of their errors (NaN without an error).
    double meanDeviation() const { return (mean.mean - canonicalMean) / mean.err; }
    double varianceDeviation() const { return (variance.mean - canonicalVariance) / variance.err; }
};

/// The canonical values for f degrees of freedom at kT: the c that shiftedSquares subtracts.
inline double canonicalKineticMean(int f, double kT) {
    return 0.5 * f * kT;
}

/// ⟨K⟩ and Var K from blocks of K and of (K − canonicalKineticMean(f, kT))² laid over the same
/// samples; std::invalid_argument when the two disagree on their blocks, or before a sample.
inline CanonicalKinetic canonicalKinetic(const FixedBlocks& kinetic,
                                         const FixedBlocks& shiftedSquares, int f, double kT) {
    if (kinetic.blocks() != shiftedSquares.blocks() || kinetic.count() != shiftedSquares.count() ||
        kinetic.weights() != shiftedSquares.weights())
        throw std::invalid_argument("canonicalKinetic: K and (K − c)² over different blocks");
    CanonicalKinetic c;
    c.canonicalMean = canonicalKineticMean(f, kT);
    c.canonicalVariance = 0.5 * f * kT * kT;
    c.mean = kinetic.estimate();
    const double shift = c.mean.mean - c.canonicalMean; // K̄ − c
    std::vector<double> centred(kinetic.sums().size());
    for (std::size_t b = 0; b < centred.size(); ++b) {
        const double n = kinetic.weights()[b];
        const double linear = kinetic.sums()[b] - c.canonicalMean * n; // Σ_b (K − c)
        centred[b] = shiftedSquares.sums()[b] - 2.0 * shift * linear + n * shift * shift;
    }
    c.variance = blockRatio(centred, kinetic.weights());
    return c;
}

} // namespace terrace::analysis
