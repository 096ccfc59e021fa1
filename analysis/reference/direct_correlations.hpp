#pragma once
// REFERENCE, for tests and benchmarks only (not linked by the product): VACF, OACF and MSD of a
// whole run held in memory, by the direct sums over every time origin,
//
//     C_f(k) = Σ_{t0 ∈ fine block f, t0 + k < T} Σ_i x_i(t0) · x_i(t0 + k),   k = 0 … maxLag,
//
// O(T · maxLag) per body: slow and obviously right, the oracle that the product's streaming
// correlations (streaming_correlations.hpp: FFT windows for the linear lags, multiple-tau
// beyond) are tested against. Curves, blocks and errors are those of curves.hpp; c2 uses
// (s(0)·s(t))² directly, the MSD |r(t0 + k) − r(t0)|² directly.
#include "analysis/curves.hpp"
#include "core/snapshot.hpp"
#include <vector>

namespace terrace::analysis::reference {

/// The sample interval in ps; throws std::invalid_argument unless there are ≥ 2 samples, equally
/// spaced in time, with the same number of bodies and one velocity per body in each.
double sampleIntervalPs(const std::vector<Snapshot>& samples);

/// Axes vary in time for some body (otherwise orientational correlations are meaningless).
bool axesRotate(const std::vector<Snapshot>& samples);

/// Curves for lags 0 … maxLag samples from `blocks` blocks of time origins (4B fine blocks over
/// the T samples); maxLag ≤ largestLag(T, blocks).
SampledCurve velocityAutocorrelation(const std::vector<Snapshot>& samples, int maxLag, int blocks,
                                     double* meanSquareVelocity = nullptr); // Å² per time unit²
OrientationalCorrelation orientationalAutocorrelation(const std::vector<Snapshot>& samples,
                                                      int maxLag, int blocks);
/// MSD: blocks are groups of bodies (1 ≤ blocks ≤ N; one block gives NaN errors), maxLag < T.
SampledCurve meanSquaredDisplacement(const std::vector<Snapshot>& samples, int maxLag, int blocks);

} // namespace terrace::analysis::reference
