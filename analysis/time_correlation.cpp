#include "analysis/time_correlation.hpp"
#include <algorithm>
#include <fftw3.h>
#include <stdexcept>
#include <string>

namespace terrace::analysis {

std::vector<double> crossCorrelationDirect(std::span<const double> a, std::span<const double> b,
                                           int maxLag) {
    const int n = static_cast<int>(a.size());
    if (b.size() != a.size() || maxLag < 0 || maxLag >= n)
        throw std::invalid_argument("crossCorrelationDirect: need equal lengths and lag < length");
    std::vector<double> c(maxLag + 1, 0.0);
    for (int k = 0; k <= maxLag; ++k)
        for (int t = 0; t + k < n; ++t)
            c[k] += a[t] * b[t + k];
    return c;
}

std::vector<double> autocorrelationFft(std::span<const double> x, int maxLag) {
    BlockedAutocorrelation acf(static_cast<int>(x.size()), maxLag, 1);
    acf.add(x);
    return acf.sums().front();
}

int OriginBlocks::origins(int b, int k) const {
    // Origins t0 with t0 + k ≤ T − 1, i.e. t0 < T − k, clipped to the block.
    const int last = std::min(begin(b + 1), samples - k);
    return std::max(0, last - begin(b));
}

namespace {

/// Smallest 2^a 3^b 5^c ≥ n: lengths FFTW transforms fastest.
int fastFftLength(int n) {
    for (int m = std::max(n, 1);; ++m) {
        int r = m;
        for (int f : {2, 3, 5})
            while (r % f == 0)
                r /= f;
        if (r == 1) return m;
    }
}

} // namespace

struct BlockedAutocorrelation::Fft {
    int length;
    double* real;
    fftw_complex* signal;
    fftw_complex* block;
    fftw_plan forward;  // real → signal
    fftw_plan backward; // block → real
    explicit Fft(int m)
        : length(m), real(fftw_alloc_real(m)), signal(fftw_alloc_complex(m / 2 + 1)),
          block(fftw_alloc_complex(m / 2 + 1)) {
        // FFTW_ESTIMATE leaves the buffers untouched and plans in microseconds; the sizes here
        // are small enough that measuring plans would cost more than it saves.
        forward = fftw_plan_dft_r2c_1d(m, real, signal, FFTW_ESTIMATE);
        backward = fftw_plan_dft_c2r_1d(m, block, real, FFTW_ESTIMATE);
    }
    ~Fft() {
        fftw_destroy_plan(forward);
        fftw_destroy_plan(backward);
        fftw_free(real);
        fftw_free(signal);
        fftw_free(block);
    }
    Fft(const Fft&) = delete;
    Fft& operator=(const Fft&) = delete;
};

BlockedAutocorrelation::BlockedAutocorrelation(int samples, int maxLag, int blocks)
    : blocks_{samples, maxLag, blocks} {
    if (samples < 2 || blocks < 1 || blocks > samples || maxLag < 0 || maxLag >= samples)
        throw std::invalid_argument(
            "BlockedAutocorrelation: need 2 ≤ samples, 1 ≤ blocks ≤ samples, 0 ≤ lag < samples "
            "(samples " +
            std::to_string(samples) + ", lag " + std::to_string(maxLag) + ", blocks " +
            std::to_string(blocks) + ")");
    fft_ = std::make_unique<Fft>(fastFftLength(samples + maxLag));
    spectra_.assign(blocks, std::vector<std::complex<double>>(fft_->length / 2 + 1, 0.0));
}

BlockedAutocorrelation::~BlockedAutocorrelation() = default;

int BlockedAutocorrelation::paddedLength() const {
    return fft_->length;
}

void BlockedAutocorrelation::add(std::span<const double> x, double weight) {
    const int n = blocks_.samples, m = fft_->length;
    if (static_cast<int>(x.size()) != n)
        throw std::invalid_argument("BlockedAutocorrelation::add: series of the wrong length");
    std::fill(fft_->real, fft_->real + m, 0.0);
    std::copy(x.begin(), x.end(), fft_->real);
    fftw_execute(fft_->forward);
    const int bins = m / 2 + 1;
    std::vector<std::complex<double>> whole(bins);
    for (int f = 0; f < bins; ++f)
        whole[f] = {fft_->signal[f][0], fft_->signal[f][1]};
    for (int b = 0; b < blocks_.blocks; ++b) {
        auto& spectrum = spectra_[b];
        if (blocks_.blocks == 1) { // the masked series is the series itself
            for (int f = 0; f < bins; ++f)
                spectrum[f] += weight * std::norm(whole[f]);
            continue;
        }
        std::fill(fft_->real, fft_->real + m, 0.0);
        std::copy(x.begin() + blocks_.begin(b), x.begin() + blocks_.begin(b + 1),
                  fft_->real + blocks_.begin(b));
        fftw_execute(fft_->forward);
        for (int f = 0; f < bins; ++f)
            spectrum[f] += weight *
                           std::conj(std::complex<double>(fft_->signal[f][0], fft_->signal[f][1])) *
                           whole[f];
    }
}

std::vector<std::vector<double>> BlockedAutocorrelation::sums() const {
    const int m = fft_->length, bins = m / 2 + 1;
    std::vector<std::vector<double>> out(blocks_.blocks);
    for (int b = 0; b < blocks_.blocks; ++b) {
        for (int f = 0; f < bins; ++f) {
            fft_->block[f][0] = spectra_[b][f].real();
            fft_->block[f][1] = spectra_[b][f].imag();
        }
        fftw_execute(fft_->backward); // unnormalised: divide by m
        out[b].assign(fft_->real, fft_->real + blocks_.maxLag + 1);
        for (double& c : out[b])
            c /= m;
    }
    return out;
}

} // namespace terrace::analysis
