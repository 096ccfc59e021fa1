#pragma once
// Standard error of an estimate from the spread of independent block (or replica) estimates
// (H. Flyvbjerg and H. G. Petersen, J. Chem. Phys. 91, 461 (1989)). Block b contributes the value
// v_b with weight w_b (its number of time origins, frames, …); with W = Σ w_b over the B' blocks
// that have w_b > 0 and the pooled value v̄,
//
//     err² = B'/(B' − 1) · Σ_b (w_b/W)² (v_b − v̄)².
//
// For equal weights this is the familiar Σ (v_b − v̄)² / (B'(B' − 1)); for unequal weights it is
// the linearised (delta-method) variance of a ratio estimator Σ s_b / Σ w_b, the right error when
// blocks near the end of a run have fewer origins at long lags. Dimensionless bookkeeping only.
#include <cmath>
#include <limits>
#include <span>
#include <stdexcept>
#include <vector>

namespace terrace::analysis {

struct Estimate {
    double mean = 0.0;
    double err = 0.0; // one standard error
    // Degrees of freedom of err: B' − 1 for B' blocks or replicas. With a handful of replicas the
    // error is itself a rough estimate, and a deviation in units of it follows Student's t, not a
    // normal law (tradeoff_stats.hpp). Infinity: err is known exactly.
    double dof = std::numeric_limits<double>::infinity();
    int samples = 0; // blocks or replicas behind the estimate
};

/// The weighted error above around the given pooled value; NaN when fewer than two blocks count.
inline double blockError(std::span<const double> values, std::span<const double> weights,
                         double pooled) {
    if (values.size() != weights.size())
        throw std::invalid_argument("blockError: one weight per block value");
    double total = 0.0;
    int counted = 0;
    for (double w : weights)
        if (w > 0.0) total += w, ++counted;
    if (counted < 2) return std::numeric_limits<double>::quiet_NaN();
    double sum = 0.0;
    for (std::size_t b = 0; b < values.size(); ++b)
        if (weights[b] > 0.0) {
            const double d = (weights[b] / total) * (values[b] - pooled);
            sum += d * d;
        }
    return std::sqrt(sum * counted / (counted - 1));
}

/// Pooled mean Σ s_b / Σ w_b of block sums s_b over block weights w_b, with its block error.
inline Estimate blockRatio(std::span<const double> sums, std::span<const double> weights) {
    if (sums.size() != weights.size())
        throw std::invalid_argument("blockRatio: one weight per block sum");
    double s = 0.0, w = 0.0;
    int counted = 0;
    for (std::size_t b = 0; b < sums.size(); ++b) {
        s += sums[b], w += weights[b];
        if (weights[b] > 0.0) ++counted;
    }
    if (w <= 0.0) throw std::invalid_argument("blockRatio: no block has any weight");
    const double pooled = s / w;
    std::vector<double> values(sums.size(), 0.0);
    for (std::size_t b = 0; b < sums.size(); ++b)
        if (weights[b] > 0.0) values[b] = sums[b] / weights[b];
    return {pooled, blockError(values, weights, pooled), double(counted - 1), counted};
}

/// Mean of a time series with its error from `blocks` contiguous blocks of about equal numbers of
/// samples (a block holds samples ⌊bn/B⌋ … ⌊(b+1)n/B⌋ − 1; with fewer samples than blocks, some
/// blocks are empty and do not count). The series must not be empty.
inline Estimate blockMean(std::span<const double> series, int blocks) {
    if (series.empty() || blocks < 1)
        throw std::invalid_argument("blockMean: need samples and at least one block");
    const std::size_t n = series.size(), b = std::size_t(blocks);
    std::vector<double> sums(b, 0.0), weights(b, 0.0);
    for (std::size_t k = 0; k < b; ++k)
        for (std::size_t i = k * n / b; i < (k + 1) * n / b; ++i)
            sums[k] += series[i], weights[k] += 1.0;
    return blockRatio(sums, weights);
}

} // namespace terrace::analysis
