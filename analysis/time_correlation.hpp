#pragma once
// Time correlations summed over time origins, by FFT (Wiener–Khinchin) with zero padding:
//
//     C_b(k) = Σ_{t0 ∈ block b, t0 + k < T} a(t0) x(t0 + k),   k = 0 … maxLag,
//
// where a = x restricted to the origins of block b. With A = FFT(a), X = FFT(x) on M ≥ T + maxLag
// points, IFFT(conj(A)·X)[k] is exactly this sum: the zero padding keeps t0 + k from wrapping
// round onto the start of the series (the circular-correlation artefact). Cost O(M log M) per
// series instead of O(T·maxLag) (M. P. Allen and D. J. Tildesley, Computer Simulation of Liquids,
// 2nd ed., OUP 2017, sec. 8.3).
//
// The blocks of time origins here are the raw material of the error bars: block b's sums use
// only its own origins, while t0 + k may run past the block. dynamic_correlations.hpp regroups
// them, lag by lag, into the blocks whose spread gives the error (block_average.hpp).
//
// crossCorrelationDirect is the slow, obviously right O(T²) sum the FFT path is tested against.
#include <complex>
#include <memory>
#include <span>
#include <vector>

namespace terrace::analysis {

/// Σ_{t=0}^{T-1-k} a[t] b[t+k] for k = 0 … maxLag (a and b of equal length T), directly.
std::vector<double> crossCorrelationDirect(std::span<const double> a, std::span<const double> b,
                                           int maxLag);

/// The same sums for a = b = x, by FFT over one block holding all origins.
std::vector<double> autocorrelationFft(std::span<const double> x, int maxLag);

/// Contiguous blocks of time origins 0 … T-1: block b holds origins [begin(b), begin(b+1)).
struct OriginBlocks {
    int samples = 0; // T
    int maxLag = 0;
    int blocks = 1; // B

    int begin(int b) const { return static_cast<int>((static_cast<long>(b) * samples) / blocks); }
    /// Number of origins of block b that have a partner k samples later.
    int origins(int b, int k) const;
};

/// Accumulates Σ over many series (bodies, vector components) of the per-block autocorrelation
/// sums C_b(k) above, in the frequency domain, so that only B inverse transforms are needed.
class BlockedAutocorrelation {
public:
    /// Requires samples ≥ 2, 1 ≤ blocks ≤ samples and 0 ≤ maxLag < samples.
    BlockedAutocorrelation(int samples, int maxLag, int blocks);
    ~BlockedAutocorrelation();
    BlockedAutocorrelation(const BlockedAutocorrelation&) = delete;
    BlockedAutocorrelation& operator=(const BlockedAutocorrelation&) = delete;

    /// Adds weight · C_b(k) of the series x (length T) to every block's sums.
    void add(std::span<const double> x, double weight = 1.0);
    /// sums[b][k]: the accumulated C_b(k), b = 0 … B-1, k = 0 … maxLag.
    std::vector<std::vector<double>> sums() const;
    const OriginBlocks& blocks() const { return blocks_; }
    int paddedLength() const;

private:
    struct Fft; // FFTW plans and aligned buffers
    OriginBlocks blocks_;
    std::unique_ptr<Fft> fft_;
    std::vector<std::vector<std::complex<double>>> spectra_; // Σ conj(A_b)·X per block
};

} // namespace terrace::analysis
