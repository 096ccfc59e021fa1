#pragma once
// The linear lags k = 0 … W − 1 of the VACF, OACF and MSD sums, over every time origin, as the
// samples arrive, by FFTW on overlapping windows (the classic windowed FFT correlation; M. P.
// Allen and D. J. Tildesley, Computer Simulation of Liquids, 2nd ed., OUP 2017, sec. 8.3):
//
//   the samples are cut into blocks of W; once block j + 1 is complete, the W origins of block j
//   are correlated against the 2W-sample window of blocks j and j + 1, both zero-padded to 2W
//   points, IFFT(conj(A)·X)[k] = Σ_{t0 ∈ block j} a(t0) x(t0 + k),  k < W.
//
// The padding keeps t0 + k from wrapping round (k < W ≤ 2W − (W − 1)), and every origin meets
// each lag 0 … W − 1 exactly once, in the window of its own block. At the end of a run (or
// whenever the sums are read) the last complete block and the partial block after it are
// correlated against windows that stop at the last sample: the zeros beyond it leave exactly the
// pairs t0 + k ≤ T − 1, so a run's last partial block is exact too.
//
// Series per body (15): v_a and s_a (VACF, OACF c1), Q_ab = s_a s_b (c2: ⟨(s(0)·s(t))²⟩ =
// Σ_ab Q_ab(0) Q_ab(t), off-diagonal pairs counted twice), and r_a − r_a(t_w) for the MSD,
// Δ²(t0, k) = |x(t0 + k)|² + |x(t0)|² − 2 x(t0)·x(t0 + k), the cross term by FFT, the squares
// by direct sums over the window (G. R. Kneller et al., Comput. Phys. Commun. 91, 191 (1995)).
// Positions are taken relative to each body's position at the window's first sample t_w, so the
// squares stay of the size of a displacement and their difference loses nothing to cancellation.
//
// Origins are split where a block straddles the boundary of a fine block of origins (the raw
// material of the error bars, curves.hpp), each part with its own transform, so the sums per
// fine block are those of the direct sums. The MSD's blocks are groups of bodies.
//
// Memory: 2W samples × 9 doubles per followed body, and a fixed scratch for a few bodies at a
// time; independent of the run's length. Work per sample and body: two real FFTs of 2W points
// for each of the 15 series per W samples, O(log W), against O(W) for the direct sums over the
// same lags (reference/direct_correlations.hpp). The constant is large: 15 transforms, where
// the direct sums need 3 + 3 + 1 + 3 products per lag; at a window of 16 the direct sums are
// the cheaper, and the transforms pay only for windows several times wider
// (bench/bench_analysis.cpp measures the product's cost per sample).
#include "core/snapshot.hpp"
#include <complex>
#include <cstddef>
#include <memory>
#include <vector>

namespace terrace::analysis {

/// Sums over origins for lags 0 … lags − 1: [fine block][lag] for the VACF and OACF numerators
/// and their origin counts, [group of bodies][lag] for the MSD (every origin).
struct LagSums {
    std::vector<std::vector<double>> vv, ss, s2, origins;
    std::vector<std::vector<double>> msd;
    std::vector<double> msdOrigins;
};

class WindowedCorrelation {
public:
    /// `followed` bodies, windows of W samples, sums for lags < `lags` (≤ W); the fine blocks of
    /// origins over `plannedSamples` (curves.hpp fineBlockOfSample), `groups` groups of bodies.
    WindowedCorrelation(int followed, int window, int lags, long plannedSamples, int fineBlocks,
                        int groups);
    ~WindowedCorrelation();
    WindowedCorrelation(const WindowedCorrelation&) = delete;
    WindowedCorrelation& operator=(const WindowedCorrelation&) = delete;

    /// The next sample: frame's entry for followed body k is index[k], or k when index is null.
    void add(const Snapshot& frame, const int* index);
    /// The sums over every origin of the samples added so far (the last blocks included).
    LagSums sums() const;
    std::size_t bytes() const;

private:
    struct Fft; // FFTW plans and aligned scratch
    /// Correlates origins [begin, end) against the window [begin, windowEnd) into sums.
    void correlate(long begin, long end, long windowEnd, LagSums& sums) const;
    void fillWindow(int first, int count, long begin, long windowEnd) const;

    int m_, w_, lags_, fine_, groups_;
    long planned_, seen_ = 0;
    std::vector<double> ring_; // 2W slots × 9 rows (v, s, r) × M bodies
    std::vector<int> group_;   // the MSD's group of each followed body
    LagSums sums_;             // of the origin blocks whose windows are complete
    std::unique_ptr<Fft> fft_;
};

} // namespace terrace::analysis
