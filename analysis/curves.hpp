#pragma once
// Correlation curves with block error bars, and the diffusion coefficients drawn from them:
// what the product's streaming analysis (streaming_correlations.hpp) and the all-samples
// reference (reference/direct_correlations.hpp) share.
//
//   VACF   c(t)  = ⟨v(0)·v(t)⟩ / ⟨v²⟩                       centre-of-mass velocity, normalised
//   OACF   c1(t) = ⟨s(0)·s(t)⟩,  c2(t) = ⟨P₂(s(0)·s(t))⟩    unit long axis s, P₂(x) = (3x² − 1)/2
//   MSD    Δ²(t) = ⟨|r(t) − r(0)|²⟩                         unwrapped centres of mass, Å²
//   D      = slope of Δ²(t) / 6 over the fit window          Å²/ps (Einstein relation)
//
// Error bars. The time origins of a run of T samples are cut into F = 4B fine blocks, fine
// block f holding origins [⌊fT/F⌋, ⌊(f+1)T/F⌋). At each lag k, the fine blocks that still have
// origins (t0 + k < T) are regrouped, in time order, into B coarse blocks of about equal numbers
// of origins, and the error is the block error of those B estimates (block_average.hpp).
// Regrouping per lag keeps B blocks, hence B − 1 degrees of freedom of the error, out to the
// longest lags; fixed blocks of origins would leave only the first few blocks at long lags, and
// error bars that scatter far more than their own size suggests (compare.hpp relies on the
// degrees of freedom being B − 1).
// The MSD is the exception: the displacements r(t0 + k) − r(t0) of neighbouring origins share
// most of their path once k exceeds a block, so blocks of origins scatter far less than the
// estimate does (a re-run then "disagrees"). Its B blocks are groups of bodies instead, each with
// every time origin; bodies move nearly independently (correlations O(1/N) from the fixed centre
// of mass), so their spread is an honest error at every lag, including the diffusion fit. In a
// run at fixed total energy the kinetic energy of each group fluctuates while the total does
// not, so at short (ballistic, Δ² ≈ ⟨v²⟩t²) lags this error is conservative.
// Normalised curves are normalised fine block by fine block (each by its own ⟨v²⟩), so that
// c(0) = 1 with zero error. Curves are in ps.
#include <vector>

namespace terrace::analysis {

struct SampledCurve {
    std::vector<double> tPs, value, err;
    int blocks = 0;                              // B: coarse blocks behind err
    std::vector<std::vector<double>> fineValue;  // [fine block][lag], for derived error bars
    std::vector<std::vector<double>> fineWeight; // [fine block][lag]: its origins at the lag
                                                 // (MSD: origins × bodies of the group)
};

struct OrientationalCorrelation {
    SampledCurve c1, c2;
};

/// Fine origin blocks used for B coarse blocks and T samples.
inline constexpr int fineBlocksPerBlock = 4;
int fineBlockCount(long samples, int blocks);
/// First origin of block b when T origins are cut into B contiguous blocks: ⌊bT/B⌋.
inline long blockBegin(long b, long samples, int blocks) {
    return (b * samples) / blocks;
}
/// The fine block (of F over T planned samples) that origin t belongs to; beyond the plan: the
/// last one.
int fineBlockOfSample(long t, long plannedSamples, int fineBlocks);

/// Coarse block (0 … B−1) of each fine block, from the fine blocks' origin counts at one lag:
/// in time order, by the midpoint of its origins within all origins; −1 for empty fine blocks.
std::vector<int> coarseBlocks(const std::vector<double>& fineWeights, int blocks);

/// Pools a curve's fine values into value (all origins) and err (its B coarse blocks, regrouped
/// lag by lag from the fine blocks' weights at that lag).
void poolFineBlocks(SampledCurve& c);
/// The OACF from its fine sums of s(0)·s(t) (c1) and (s(0)·s(t))² (c2): c2 turned into
/// ⟨P₂(s(0)·s(t))⟩, linear in each block's mean, then both pooled.
void finishOrientational(OrientationalCorrelation& c);

/// Largest lag (in samples) allowed for T samples and B blocks (at least two blocks of origins
/// reach it), and the lag for a request in ps (requestPs ≤ 0: half the sampled span), clipped
/// to that limit.
int largestLag(long samples, int blocks);
int lagFor(double requestPs, double sampleIntervalPs, long samples, int blocks);

struct Diffusion {
    double coefficient = 0.0; // Å²/ps
    double err = 0.0;
    double fromPs = 0.0, toPs = 0.0; // fit window
};

/// Least-squares slope of the MSD over lags [t_max/4, 3·t_max/4] (by time; on a uniform grid of
/// K lags, ⌊K/4⌋ … ⌊3K/4⌋) (past the ballistic and caging regime, short of the longest lags
/// with the fewest origins), divided by 6; the error from the slopes of the B blocks (of
/// bodies, see above). NaN when the window holds fewer than two lags.
Diffusion diffusionFromMsd(const SampledCurve& msd);

/// Green–Kubo D = (1/3) ∫₀^tmax ⟨v(0)·v(t)⟩ dt (trapezoid rule over the curve's lags, truncated
/// at the last one), Å²/ps, from the normalised VACF and ⟨v²⟩ in Å² per time unit²; the error
/// from the block curves, grouped as of the last lag and integrated whole. fromPs is 0.
Diffusion greenKuboDiffusion(const SampledCurve& vacf, double meanSquareVelocity);

} // namespace terrace::analysis
