#pragma once
// Time correlations of rigid bodies from samples equally spaced in time, averaged over bodies and
// all time origins (FFT sums of time_correlation.hpp), with block errors over origin blocks:
//
//   VACF   c(t)  = ⟨v(0)·v(t)⟩ / ⟨v²⟩                       centre-of-mass velocity, normalised
//   OACF   c1(t) = ⟨s(0)·s(t)⟩,  c2(t) = ⟨P₂(s(0)·s(t))⟩    unit long axis s, P₂(x) = (3x² − 1)/2
//   MSD    Δ²(t) = ⟨|r(t) − r(0)|²⟩                         unwrapped centres of mass, Å²
//   D      = slope of Δ²(t) / 6 over the fit window          Å²/ps (Einstein relation)
//
// ⟨(s(0)·s(t))²⟩ = Σ_ab Q_ab(0) Q_ab(t) with Q_ab = s_a s_b, so c2 is the autocorrelation of the
// six independent products (the three off-diagonal ones counted twice). The MSD uses
// Δ²(t0, k) = |r(t0+k)|² + |r(t0)|² − 2 r(t0)·r(t0+k): FFT for the cross term, prefix sums for the
// squares (G. R. Kneller et al., Comput. Phys. Commun. 91, 191 (1995), nMoldyn), with each body's
// mean position subtracted first so that the squares stay small and cancellation harmless.
// Normalised curves are normalised block by block (each block by its own ⟨v²⟩), so that c(0) = 1
// with zero error. Times: samples in 100 fs units (core/units.hpp), curves in ps.
#include "core/snapshot.hpp"
#include <vector>

namespace terrace::analysis {

struct SampledCurve {
    std::vector<double> tPs, value, err;
    std::vector<std::vector<double>> blockValue;  // [block][lag], for derived error bars
    std::vector<std::vector<double>> blockWeight; // [block][lag]: origins of the block at the lag
};

/// The sample interval in ps; throws std::invalid_argument unless there are ≥ 2 samples, equally
/// spaced in time, with the same number of bodies and one velocity per body in each.
double sampleIntervalPs(const std::vector<Snapshot>& samples);

/// Axes vary in time for some body (otherwise orientational correlations are meaningless).
bool axesRotate(const std::vector<Snapshot>& samples);

/// Curves for lags 0 … maxLag samples, from `blocks` blocks of time origins. maxLag must leave at
/// least two blocks with an origin at the longest lag (maxLag ≤ T − 1 − ⌊T/B⌋).
SampledCurve velocityAutocorrelation(const std::vector<Snapshot>& samples, int maxLag, int blocks,
                                     double* meanSquareVelocity = nullptr); // Å² per time unit²
struct OrientationalCorrelation {
    SampledCurve c1, c2;
};
OrientationalCorrelation orientationalAutocorrelation(const std::vector<Snapshot>& samples,
                                                      int maxLag, int blocks);
SampledCurve meanSquaredDisplacement(const std::vector<Snapshot>& samples, int maxLag, int blocks);

/// Largest lag (in samples) allowed for T samples and B blocks, and the lag for a request in ps
/// (requestPs ≤ 0: half the sampled span), clipped to that limit.
int largestLag(int samples, int blocks);
int lagFor(double requestPs, double sampleIntervalPs, int samples, int blocks);

struct Diffusion {
    double coefficient = 0.0; // Å²/ps
    double err = 0.0;
    double fromPs = 0.0, toPs = 0.0; // fit window
};
/// Least-squares slope of the MSD over lags [maxLag/4, 3·maxLag/4] (past the ballistic and caging
/// regime, short of the longest lags that only few origin blocks reach), divided by 6; the error
/// from the slopes of the origin blocks. NaN when the window holds fewer than two lags.
Diffusion diffusionFromMsd(const SampledCurve& msd);

} // namespace terrace::analysis
