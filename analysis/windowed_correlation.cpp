#include "analysis/windowed_correlation.hpp"
#include "analysis/curves.hpp"
#include <algorithm>
#include <fftw3.h>
#include <stdexcept>

namespace terrace::analysis {

namespace {

using Complex = std::complex<double>;

constexpr int rows = 9;    // v, s, r: three components each, per sample and body
constexpr int series = 15; // v_a, s_a, Q_ab (six), x_a
constexpr int chunk = 4;    // bodies transformed together: the scratch stays near L1
constexpr int firstQ = 6, firstX = 12;
/// Weight of Q_ab in Σ_ab Q_ab(0) Q_ab(t), in the order Q00 Q01 Q02 Q11 Q12 Q22.
constexpr double qWeight[6] = {1.0, 2.0, 2.0, 1.0, 2.0, 1.0};

} // namespace

struct WindowedCorrelation::Fft {
    int n, bins;
    double* window;    // chunk × series × n: the window's samples, zero beyond its end
    double* origins;   // the same, zero outside the origins of one part of the block
    fftw_complex* x;   // transforms of window
    fftw_complex* a;   // transforms of origins
    fftw_complex* sum; // one accumulated spectrum, to invert
    double* lagSums;   // its inverse
    fftw_plan forwardWindow, forwardOrigins, backward;
    std::vector<std::vector<double>> squares; // [group][t]: Σ over the group's bodies of |x|²
    std::vector<std::vector<Complex>> msd;    // [group][bin]: Σ conj(A)·X of the x_a
    Fft(int w, int groups)
        : n(2 * w), bins(w + 1), window(fftw_alloc_real(std::size_t(chunk) * series * n)),
          origins(fftw_alloc_real(std::size_t(chunk) * series * n)),
          x(fftw_alloc_complex(std::size_t(chunk) * series * bins)),
          a(fftw_alloc_complex(std::size_t(chunk) * series * bins)), sum(fftw_alloc_complex(bins)),
          lagSums(fftw_alloc_real(n)), squares(groups, std::vector<double>(n, 0.0)),
          msd(groups, std::vector<Complex>(bins, 0.0)) {
        std::fill(window, window + std::size_t(chunk) * series * n, 0.0);
        std::fill(origins, origins + std::size_t(chunk) * series * n, 0.0);
        // FFTW_ESTIMATE plans in microseconds without touching the buffers; at these small
        // lengths FFTW runs one hard-coded codelet either way.
        const int length[1] = {n};
        forwardWindow = fftw_plan_many_dft_r2c(1, length, chunk * series, window, nullptr, 1, n, x,
                                               nullptr, 1, bins, FFTW_ESTIMATE);
        forwardOrigins = fftw_plan_many_dft_r2c(1, length, chunk * series, origins, nullptr, 1, n,
                                                a, nullptr, 1, bins, FFTW_ESTIMATE);
        backward = fftw_plan_dft_c2r_1d(n, sum, lagSums, FFTW_ESTIMATE);
    }
    ~Fft() {
        fftw_destroy_plan(forwardWindow);
        fftw_destroy_plan(forwardOrigins);
        fftw_destroy_plan(backward);
        fftw_free(window), fftw_free(origins), fftw_free(x), fftw_free(a), fftw_free(sum);
        fftw_free(lagSums);
    }
    Fft(const Fft&) = delete;
    Fft& operator=(const Fft&) = delete;

    /// IFFT of an accumulated spectrum, divided by n: the lag sums (unnormalised c2r).
    const double* invert(const std::vector<Complex>& spectrum) {
        std::copy(spectrum.begin(), spectrum.end(), reinterpret_cast<Complex*>(sum));
        fftw_execute(backward);
        for (int k = 0; k < n; ++k)
            lagSums[k] /= n;
        return lagSums;
    }
    std::size_t bytes() const {
        return std::size_t(chunk) * series * (2 * n * sizeof(double) + 2 * bins * sizeof(Complex)) +
               squares.size() * n * sizeof(double) + msd.size() * bins * sizeof(Complex);
    }
};

WindowedCorrelation::WindowedCorrelation(int followed, int window, int lags, long plannedSamples,
                                         int fineBlocks, int groups)
    : m_(followed), w_(window), lags_(lags), fine_(fineBlocks), groups_(groups),
      planned_(plannedSamples) {
    if (followed < 1 || window < 1 || lags < 1 || lags > window || fineBlocks < 1 || groups < 1 ||
        groups > followed || plannedSamples < 1)
        throw std::invalid_argument("windowed correlation: need bodies, 1 ≤ lags ≤ W, fine "
                                    "blocks and 1 ≤ groups ≤ bodies");
    ring_.assign(std::size_t(2 * w_) * rows * m_, 0.0);
    for (int k = 0; k < m_; ++k) // group b holds bodies ⌊bM/G⌋ … ⌊(b+1)M/G⌋ − 1
        group_.push_back(static_cast<int>((long(k) * groups_ + groups_ - 1) / m_));
    sums_.vv.assign(fine_, std::vector<double>(lags_, 0.0));
    sums_.ss = sums_.s2 = sums_.origins = sums_.vv;
    sums_.msd.assign(groups_, std::vector<double>(lags_, 0.0));
    sums_.msdOrigins.assign(lags_, 0.0);
    fft_ = std::make_unique<Fft>(w_, groups_);
}

WindowedCorrelation::~WindowedCorrelation() = default;

void WindowedCorrelation::add(const Snapshot& frame, const int* index) {
    double* row = ring_.data() + std::size_t(seen_ % (2 * w_)) * rows * m_;
    for (int k = 0; k < m_; ++k) {
        const int i = index ? index[k] : k;
        for (int a = 0; a < 3; ++a) {
            row[(0 + a) * m_ + k] = frame.velocity[i][a];
            row[(3 + a) * m_ + k] = frame.axis[i][a];
            row[(6 + a) * m_ + k] = frame.position[i][a];
        }
    }
    ++seen_;
    // Block j + 1 complete: the origins of block j meet their whole window.
    if (seen_ % w_ == 0 && seen_ >= 2 * w_) correlate(seen_ - 2 * w_, seen_ - w_, seen_, sums_);
}

LagSums WindowedCorrelation::sums() const {
    LagSums out = sums_;
    const long complete = seen_ / w_, rest = seen_ % w_;
    // The last complete block's window stops at the last sample, as does the partial block's.
    if (complete >= 1) correlate((complete - 1) * w_, complete * w_, seen_, out);
    if (rest > 0) correlate(complete * w_, seen_, seen_, out);
    return out;
}

void WindowedCorrelation::fillWindow(int first, int count, long begin, long windowEnd) const {
    Fft& f = *fft_;
    const int n = f.n, span = static_cast<int>(windowEnd - begin);
    const double* start = ring_.data() + std::size_t(begin % n) * rows * m_ + first;
    // Sample by sample, so that each row of the ring is read along consecutive bodies.
    for (int t = 0; t < span; ++t) {
        const double* row = ring_.data() + std::size_t((begin + t) % n) * rows * m_ + first;
        for (int c = 0; c < count; ++c) {
            double* out = f.window + std::size_t(c) * series * n + t;
            double s[3], x2 = 0.0;
            for (int a = 0; a < 3; ++a) {
                out[a * n] = row[a * m_ + c];
                s[a] = out[(3 + a) * n] = row[(3 + a) * m_ + c];
                const double x = row[(6 + a) * m_ + c] - start[(6 + a) * m_ + c];
                out[(firstX + a) * n] = x;
                x2 += x * x;
            }
            int q = firstQ;
            for (int a = 0; a < 3; ++a)
                for (int b = a; b < 3; ++b)
                    out[q++ * n] = s[a] * s[b];
            f.squares[group_[first + c]][t] += x2;
        }
    }
    for (int c = 0; c < count; ++c)
        for (int s = 0; s < series; ++s) {
            double* out = f.window + (std::size_t(c) * series + s) * n;
            std::fill(out + span, out + n, 0.0);
        }
}

void WindowedCorrelation::correlate(long begin, long end, long windowEnd, LagSums& sums) const {
    Fft& f = *fft_;
    const int n = f.n, bins = f.bins;
    // The block's origins in parts of one fine block each (usually one part).
    struct Part {
        long begin, end;
        int fine;
        std::vector<Complex> vv, ss, s2;
    };
    std::vector<Part> parts;
    for (long t = begin; t < end; ++t) {
        const int fine = fineBlockOfSample(t, planned_, fine_);
        if (parts.empty() || parts.back().fine != fine)
            parts.push_back({t, t, fine, std::vector<Complex>(bins, 0.0),
                             std::vector<Complex>(bins, 0.0), std::vector<Complex>(bins, 0.0)});
        parts.back().end = t + 1;
    }
    for (auto& s : f.squares)
        std::fill(s.begin(), s.end(), 0.0);
    for (auto& s : f.msd)
        std::fill(s.begin(), s.end(), Complex(0.0));

    for (int first = 0; first < m_; first += chunk) {
        const int count = std::min(chunk, m_ - first);
        fillWindow(first, count, begin, windowEnd);
        fftw_execute(f.forwardWindow);
        const auto* x = reinterpret_cast<const Complex*>(f.x);
        const auto* a = reinterpret_cast<const Complex*>(f.a);
        for (auto& part : parts) {
            const int from = static_cast<int>(part.begin - begin),
                      to = static_cast<int>(part.end - begin);
            for (int row = 0; row < count * series; ++row) {
                const double* in = f.window + std::size_t(row) * n;
                double* out = f.origins + std::size_t(row) * n;
                std::fill(out, out + n, 0.0);
                std::copy(in + from, in + to, out + from);
            }
            fftw_execute(f.forwardOrigins);
            for (int c = 0; c < count; ++c) {
                const Complex* ac = a + std::size_t(c) * series * bins;
                const Complex* xc = x + std::size_t(c) * series * bins;
                // conj(A)·X written out: std::complex's product checks for infinities and NaNs
                // (C99 Annex G) at every bin, which costs more than the product itself.
                auto add = [&](std::vector<Complex>& to, int s, double weight) {
                    const double* as = reinterpret_cast<const double*>(ac + s * bins);
                    const double* xs = reinterpret_cast<const double*>(xc + s * bins);
                    double* sum = reinterpret_cast<double*>(to.data());
                    for (int k = 0; k < 2 * bins; k += 2) {
                        sum[k] += weight * (as[k] * xs[k] + as[k + 1] * xs[k + 1]);
                        sum[k + 1] += weight * (as[k] * xs[k + 1] - as[k + 1] * xs[k]);
                    }
                };
                for (int s = 0; s < 3; ++s)
                    add(part.vv, s, 1.0), add(part.ss, 3 + s, 1.0);
                for (int q = 0; q < 6; ++q)
                    add(part.s2, firstQ + q, qWeight[q]);
                const int g = group_[first + c];
                for (int s = 0; s < 3; ++s)
                    add(f.msd[g], firstX + s, 1.0);
            }
        }
    }

    const auto partners = [windowEnd](long from, long to, int k) { // origins with t0 + k in reach
        return double(std::max(0L, std::min(to, windowEnd - k) - from));
    };
    for (const auto& part : parts) {
        const double* vv = f.invert(part.vv);
        for (int k = 0; k < lags_; ++k)
            sums.vv[part.fine][k] += vv[k];
        const double* ss = f.invert(part.ss);
        for (int k = 0; k < lags_; ++k)
            sums.ss[part.fine][k] += ss[k];
        const double* s2 = f.invert(part.s2);
        for (int k = 0; k < lags_; ++k)
            sums.s2[part.fine][k] += s2[k];
        for (int k = 0; k < lags_; ++k)
            sums.origins[part.fine][k] += partners(part.begin, part.end, k);
    }
    for (int g = 0; g < groups_; ++g) {
        const double* cross = f.invert(f.msd[g]);
        const std::vector<double>& q = f.squares[g];
        // Lag 0 adds nothing: every displacement is exactly zero there.
        for (int k = 1; k < lags_; ++k) {
            double squares = 0.0;
            for (long t0 = begin; t0 < end && t0 + k < windowEnd; ++t0)
                squares += q[t0 - begin + k] + q[t0 - begin];
            sums.msd[g][k] += squares - 2.0 * cross[k];
        }
    }
    for (int k = 0; k < lags_; ++k)
        sums.msdOrigins[k] += partners(begin, end, k);
}

std::size_t WindowedCorrelation::bytes() const {
    const std::size_t table = (4 * std::size_t(fine_) + groups_ + 1) * lags_ * sizeof(double);
    return ring_.size() * sizeof(double) + group_.size() * sizeof(int) + table + fft_->bytes();
}

} // namespace terrace::analysis
