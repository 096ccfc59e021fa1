#pragma once
// VACF, OACF and MSD accumulated sample by sample as a run goes, on a multiple-tau lag grid, so
// that memory and time per sample grow only with the logarithm of the longest lag, never with
// the run's length:
//
//   level 0   lags 0, 1, …, p−1, every time origin: by FFT over overlapping windows of p
//             samples (windowed_correlation.hpp)
//   level l   every 2^l-th sample, the last p of them; lags j·2^l, j = p/2 … p−1
//             (time origins every 2^l samples), by direct sums as the samples arrive
//
// The lag grid is that of the multiple-tau correlator of J. Ramírez, S. K. Sukumaran,
// B. Vorselaars and A. E. Likhtman, J. Chem. Phys. 133, 154103 (2010), but the coarser levels
// keep every 2^l-th sample (decimation) instead of the mean of 2^l samples. Why: averaging
// biases every quadratic observable — for the MSD of a diffusing body by −2D·2^l per level, up to
// 1/(3j) ≈ 4 % of the value at p = 16 — while decimation leaves each correlation an exact sum
// over a subset of the time origins: unbiased, equal within round-off to the all-origins sums
// (reference/direct_correlations.hpp) at lags below p, and within their error bars beyond, with
// fewer origins at long lags where neighbouring origins carry little new information anyway.
//
// Sums per lag: Σ_i v_i(t0)·v_i(t0+k), Σ_i s_i(t0)·s_i(t0+k), Σ_i (s_i(t0)·s_i(t0+k))² (the
// P₂ correlation) and Σ_i |r_i(t0+k) − r_i(t0)|² over the followed bodies. Error bars as in
// curves.hpp: the time origins fall into 4B fine blocks of the planned run (so that a run of the
// planned length gives the same blocks as the reference analysis of its samples), regrouped lag
// by lag into B coarse blocks; the MSD's B blocks are groups of bodies.
//
// Large systems: the time correlations follow at most `followBodies` bodies, evenly spread over
// the index range (all when N is no larger), so that their memory stays fixed as N grows. The
// curves are then averages over those bodies, and their block errors say what that leaves.
// Memory: (levels − 1) × p × 9 doubles per followed body, and for the FFT windows 2p × 9 and
// one block's transforms (windowed_correlation.hpp).
#include "analysis/curves.hpp"
#include "analysis/windowed_correlation.hpp"
#include "core/snapshot.hpp"
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace terrace::analysis {

struct StreamingCorrelationPlan {
    long samples = 0;      // T planned (the lags and fine blocks are set by it)
    int maxLag = 0;        // samples, ≤ largestLag(T, blocks)
    int blocks = 8;        // B
    int lagsPerLevel = 16; // p, even, ≥ 4
    int followBodies = 0;  // 0: all
    // The bodies to follow, ascending and distinct, in place of followBodies' even spread (a
    // mixture's, spread over each species: followedPerSpecies); empty: followBodies decides.
    std::vector<int> follow;
};

/// For a mixture (speciesOf[i]: body i's species, S species): the bodies the time correlations
/// follow when at most `followBodies` are (0: all), in ascending order. Each species gets its
/// share, at least one body, evenly spread over its own bodies in index order, so that every
/// species has curves of its own however few its bodies. With followBodies ≥ N: every body.
std::vector<int> followedPerSpecies(const std::vector<std::int32_t>& speciesOf, int species,
                                    int followBodies);

class StreamingCorrelations {
public:
    StreamingCorrelations(int bodies, double sampleIntervalPs,
                          const StreamingCorrelationPlan& plan);

    /// The next sample (time must follow the previous one by the sample interval).
    void add(const Snapshot& frame);
    /// The next sample, given as the followed bodies alone (followedBodies(), in that order).
    void addFollowed(const Snapshot& followed);
    /// The bodies followed (indices into a whole sample), in order.
    const std::vector<int>& followedBodies() const { return follow_; }
    int followed() const { return static_cast<int>(follow_.size()); }
    int levels() const { return levels_; }
    long samples() const { return seen_; }

    /// Some body's axis changed since the first sample (orientational curves mean something).
    bool rotating() const { return rotating_; }
    /// Curves over the grid's lags that have origins; throws std::invalid_argument with fewer
    /// than two samples or with all velocities zero.
    SampledCurve velocity(double* meanSquareVelocity = nullptr) const;
    OrientationalCorrelation orientation() const;
    SampledCurve displacement() const;
    std::size_t bytes() const;
    /// Everything later samples add to (state_bytes.hpp): the samples seen, the first axes, each
    /// level's ring and the sums, and level 0's windows; restore() takes them into correlations
    /// built with the same settings.
    void save(StateWriter& out) const;
    void restore(StateReader& in);

private:
    /// frame's entry for followed body k: index[k], or k when index is null.
    void record(const Snapshot& frame, const int* index);
    void correlate(int level, int slot, int originSlot, int lagIndex);
    /// The sums of every lag: the linear lags from the windows, the coarser levels from tau_.
    LagSums sums() const;
    /// The grid's lags that have origins, in ps.
    SampledCurve emptyCurve(const LagSums& sums) const;

    int bodies_, p_, levels_ = 1, fine_, blocks_, groups_;
    long planned_;
    double dtPs_;
    std::vector<int> follow_;                       // followed body indices
    std::vector<int> lag_, lagLevel_, lagJ_;        // grid
    std::vector<int> firstLagOfLevel_;              // index into the grid
    std::unique_ptr<WindowedCorrelation> windowed_; // level 0, by FFT
    // ring_[level ≥ 1]: p slots × 9 rows × M followed bodies, structure of arrays per slot
    // (vx vy vz sx sy sz rx ry rz), so the sums over bodies stream through memory.
    std::vector<std::vector<double>> ring_;
    std::vector<std::vector<int>> slotFine_; // fine block of the sample in each slot
    LagSums tau_;                            // the coarser levels' sums (level 0's unused)
    std::vector<Vec3> firstAxis_;
    double firstTime_ = 0.0, dtUnits_ = 0.0;
    long seen_ = 0;
    bool rotating_ = false;
};

} // namespace terrace::analysis
