#pragma once
// The linear lags k = 0 … W − 1 of the VACF, OACF and MSD sums, over every time origin, as the
// samples arrive, by FFTW on overlapping windows (the classic windowed FFT correlation; M. P.
// Allen and D. J. Tildesley, Computer Simulation of Liquids, 2nd ed., OUP 2017, sec. 8.3):
//
//   the samples are cut into blocks of W; the W origins of block j are correlated against the
//   2W-sample window of blocks j and j + 1, zero-padded to 2W points,
//   IFFT(conj(A_j)·X_j)[k] = Σ_{t0 ∈ block j} a(t0) x(t0 + k),  k < W.
//
// The padding keeps t0 + k from wrapping round (k < W ≤ 2W − (W − 1)), and every origin meets
// each lag 0 … W − 1 exactly once, in the window of its own block.
//
// One forward transform per block and series, no inverse as the samples arrive: with A_j the
// 2W-point transform of block j alone (zero-padded), the window [block j | block j + 1] is
// A_j + (−1)^f A_{j+1} by the shift theorem (a shift by W of 2W points multiplies bin f by
// e^{−iπf}). So once block j + 1 is transformed, conj(A_j)·(A_j + (−1)^f A_{j+1}) is block j's
// cross-spectrum, and, the inverse being linear, the cross-spectra are summed in frequency space
// over bodies and blocks (one sum per fine block of origins and quantity, one per group of bodies
// for the MSD); the inverse transforms run only when the sums are read. Each body keeps its last
// block's transform until the next block's is made.
//
// At the end of a run (or whenever the sums are read) the last complete block and the partial
// block after it are correlated against windows that stop at the last sample: the zeros beyond
// it leave exactly the pairs t0 + k ≤ T − 1, so a run's last partial block is exact too.
//
// Series per body (15): v_a and s_a (VACF, OACF c1), Q_ab = s_a s_b (c2: ⟨(s(0)·s(t))²⟩ =
// Σ_ab Q_ab(0) Q_ab(t), off-diagonal pairs counted twice), and x_a = r_a − r_a(t_j) for the MSD,
// Δ²(t0, k) = |x(t0 + k)|² + |x(t0)|² − 2 x(t0)·x(t0 + k), the cross term by FFT, the squares
// by direct sums over the window (G. R. Kneller et al., Comput. Phys. Commun. 91, 191 (1995)).
// Positions are taken relative to each body's position at its window's first sample t_j, so
// the squares stay of the size of a displacement over two blocks and their difference loses
// nothing to cancellation. Block j + 1 is transformed relative to t_j, the window it closes, and
// kept relative to t_{j+1} for the window it opens: x shifts by the constant
// δ = r(t_{j+1}) − r(t_j) over its W samples, which takes δ·U from its transform, U that of W
// ones (exact but for round-off).
//
// Two real series that add to the same sum with the same weight travel as one complex series
// z = a + ib in one complex transform (v_x + i v_y, s_x + i s_y, Q00 + i Q11, Q01 + i Q02,
// x_x + i x_y): Re Σ conj(z(t0)) z(t0 + k) = Σ a(t0) a(t0 + k) + b(t0) b(t0 + k), the cross terms
// being imaginary, and the real part of an inverse is the inverse of the spectrum's Hermitian
// part. The five left (v_z, s_z, Q22, Q12, x_z) go alone, with W + 1 of their bins kept. Ten
// complex transforms of 2W points cost less than fifteen real ones: FFTW's complex codelets are
// vectorised, its real ones not.
//
// Origins are split where a block straddles the boundary of a fine block of origins (the raw
// material of the error bars, curves.hpp), each part transformed on its own against the shared
// window, so the sums per fine block are those of the direct sums. The MSD's blocks are groups of
// bodies.
//
// Memory: 2W samples × 9 doubles and one block's transforms (5 × 2W + 5 × (W + 1) complex) per
// followed body, and the sums' spectra; independent of the run's length. Work per block and
// body: ten complex FFTs of 2W points and the products over their bins, against 3 + 3 + 1 + 3
// products per lag and sample for the direct sums over the same lags
// (reference/direct_correlations.hpp). At W = 16 the two come out close, and what decides is
// the glue around the transforms: bodies are taken four at a time, their samples gathered and
// their cross-spectra summed four doubles to a vector (AVX where the processor has it, chosen at
// run time, the same sums to the last bit as the SSE2 loops), so that bench/bench_analysis.cpp
// puts the time correlations' cost per sample 2–14 % below the direct sums' at N 512 and
// 3–10 % below at 32 768 (4096 followed bodies). There the kept transforms, twice the size
// of the samples they stand for, stream from L3 at every block (16 MB read and written per 16
// samples) and the products wait on them: that, with FFTW's ten transforms, is the floor.
#include "analysis/state_bytes.hpp"
#include "core/snapshot.hpp"
#include <complex>
#include <cstddef>
#include <memory>
#include <utility>
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
    long samples() const { return seen_; }
    /// What each followed body holds for a window of W samples: its 2W samples in the ring and
    /// its last block's kept transforms (bytes; the memory check before a run).
    static std::size_t bytesPerBody(int window);
    /// Everything later samples add to (state_bytes.hpp): the ring of samples, the last block's
    /// kept transforms, the summed spectra and squares; restore() takes them into a correlation
    /// built with the same settings. FFTW's buffers are scratch, refilled before every use.
    void save(StateWriter& out) const;
    void restore(StateReader& in);

private:
    struct Fft;     // FFTW plans and aligned scratch
    struct Spectra; // the cross-spectra summed so far, and the MSD's squares and origin counts
    struct Part {   // origins [begin, end) of one block within one fine block
        long begin, end;
        int fine;
    };
    std::vector<Part> parts(long begin, long end) const;
    /// Block j is complete: its transforms are made, and block j − 1's window is whole.
    void completeBlock(long j);
    /// Transforms, for bodies first … first + count − 1, samples [from, to) of the block that
    /// starts at `begin` (at points from − begin …, zeros elsewhere), positions relative to
    /// sample `ref`. With own ≥ 0, adds the MSD's squares of the block relative to sample own
    /// (the block's first, for its own window) and to ref (for the window before).
    void transform(int first, int count, long begin, long from, long to, long ref,
                   long own = -1) const;
    /// Copies the transforms of `count` bodies from FFTW's layout into the kept one.
    void keep(const std::complex<double>* full, int count, std::complex<double>* kept) const;
    /// Adds the cross-spectra of a block's origins (spectra a, whole block) against its window's
    /// spectra y, for bodies first … first + count − 1.
    void addOrigins(int first, int count, const std::vector<Part>& parts, long ref,
                    const std::complex<double>* a, const std::complex<double>* y,
                    Spectra& to) const;
    /// The MSD's squares of the window from sample ref to windowEnd, relative to sample ref.
    void ringSquares(long ref, long windowEnd) const;
    /// Adds the MSD's squares (of the window from sample ref to windowEnd, made by transform or
    /// ringSquares) and the origin counts of a block's origins.
    void addSquares(const std::vector<Part>& parts, long ref, long windowEnd, Spectra& to) const;
    LagSums invert(const Spectra& s) const;
    /// Index in ring_ of sample t's row 0 for body k (rows every stride_ doubles).
    std::size_t at(long t, int k) const;
    /// The two sums of products (addProduct) that a channel adds to.
    std::pair<double*, double*> sumsOf(Spectra& to, int channel, int fine, int group) const;

    int m_, w_, lags_, fine_, groups_;
    /// Doubles from one row of the ring to the next: M and a cache line, so that the rows of a
    /// block (M a power of two, their distance a multiple of 4 KiB) do not share L1's sets.
    std::size_t stride_;
    long planned_, seen_ = 0;
    std::vector<double> ring_; // 2W slots × 9 rows (v, s, r) × stride: a sample in one stretch
    std::vector<int> group_, groupBegin_;        // the MSD's group of each body; group starts
    std::vector<std::complex<double>> spectrum_; // M × kept: the last complete block's
    std::unique_ptr<Spectra> sums_;              // of the blocks whose windows are complete
    std::unique_ptr<Fft> fft_;
};

} // namespace terrace::analysis
