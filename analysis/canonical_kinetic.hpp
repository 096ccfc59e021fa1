#pragma once
// Whether a series of kinetic energies K_k (kJ/mol, equally spaced samples of one run) is
// canonical: in the canonical ensemble K of f quadratic degrees of freedom is Gamma(f/2, kT), so
//   ⟨K⟩ = (f/2) kT,   Var(K) = (f/2) (kT)².
// Both are estimated with one standard error from contiguous blocks (block_average.hpp), which
// counts the samples' correlation as long as a block is longer than it; the variance as the block
// mean of (K_k − K̄)², K̄ the whole series' mean (its bias, −Var/n, is far below the error).
#include "analysis/block_average.hpp"
#include <span>
#include <vector>

namespace terrace::analysis {

struct CanonicalKinetic {
    Estimate mean, variance;
    double canonicalMean = 0.0, canonicalVariance = 0.0;
    /// Deviations from the canonical values in units of their errors (NaN without an error).
    double meanDeviation() const { return (mean.mean - canonicalMean) / mean.err; }
    double varianceDeviation() const { return (variance.mean - canonicalVariance) / variance.err; }
};

/// The series' mean and variance against the canonical ones for f degrees of freedom at kT.
inline CanonicalKinetic canonicalKinetic(std::span<const double> kinetic, int f, double kT,
                                         int blocks) {
    CanonicalKinetic c;
    c.canonicalMean = 0.5 * f * kT;
    c.canonicalVariance = 0.5 * f * kT * kT;
    c.mean = blockMean(kinetic, blocks);
    std::vector<double> squared;
    squared.reserve(kinetic.size());
    for (const double k : kinetic)
        squared.push_back((k - c.mean.mean) * (k - c.mean.mean));
    c.variance = blockMean(squared, blocks);
    return c;
}

} // namespace terrace::analysis
