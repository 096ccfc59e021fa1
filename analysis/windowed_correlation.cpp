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
constexpr int chunk = 4;   // bodies transformed together: the scratch stays near L1
constexpr int firstS = 3, firstQ = 6, firstX = 12;
/// Weight of Q_ab in Σ_ab Q_ab(0) Q_ab(t), in the order Q00 Q01 Q02 Q11 Q12 Q22.
constexpr double qWeight[6] = {1.0, 2.0, 2.0, 1.0, 2.0, 1.0};

/// sum += weight · conj(a)·y over `bins` bins, written out: std::complex's product checks for
/// infinities and NaNs (C99 Annex G) at every bin, which costs more than the product itself.
void addProduct(const Complex* a, const Complex* y, int bins, double weight, Complex* sum) {
    const double* as = reinterpret_cast<const double*>(a);
    const double* ys = reinterpret_cast<const double*>(y);
    double* s = reinterpret_cast<double*>(sum);
    for (int k = 0; k < 2 * bins; k += 2) {
        s[k] += weight * (as[k] * ys[k] + as[k + 1] * ys[k + 1]);
        s[k + 1] += weight * (as[k] * ys[k + 1] - as[k + 1] * ys[k]);
    }
}

} // namespace

struct WindowedCorrelation::Spectra {
    std::vector<std::vector<Complex>> vv, ss, s2; // [fine block][bin]
    std::vector<std::vector<Complex>> msd;        // [group][bin]: the cross term x(t0)·x(t0 + k)
    std::vector<std::vector<double>> squares;     // [group][lag]: |x(t0 + k)|² + |x(t0)|²
    std::vector<std::vector<double>> origins;     // [fine block][lag]
    std::vector<double> msdOrigins;               // [lag]
};

struct WindowedCorrelation::Fft {
    int n, bins;
    double* in;        // chunk × series × n: samples at 0 … W − 1, zeros beyond
    fftw_complex* out; // their transforms
    fftw_complex* y;   // chunk × series × bins: a window's transforms
    fftw_complex* a;   // chunk × series × bins: a block's transforms, kept while parts use out
    fftw_complex* sum; // one accumulated spectrum, to invert
    double* lagSums;   // its inverse
    fftw_plan forward, backward;
    std::vector<double> sign;  // (−1)^f per bin: the shift by W of the window's second block
    std::vector<Complex> ones; // U: the transform of W ones at 0 … W − 1
    std::vector<std::vector<double>> squares; // [group][t]: Σ over the group's bodies of |x|²
    Fft(int w, int groups)
        : n(2 * w), bins(w + 1), in(fftw_alloc_real(std::size_t(chunk) * series * n)),
          out(fftw_alloc_complex(std::size_t(chunk) * series * bins)),
          y(fftw_alloc_complex(std::size_t(chunk) * series * bins)),
          a(fftw_alloc_complex(std::size_t(chunk) * series * bins)), sum(fftw_alloc_complex(bins)),
          lagSums(fftw_alloc_real(n)), sign(bins), ones(bins),
          squares(groups, std::vector<double>(n, 0.0)) {
        std::fill(in, in + std::size_t(chunk) * series * n, 0.0);
        // FFTW_ESTIMATE plans in microseconds without touching the buffers; at these small
        // lengths FFTW runs one hard-coded codelet either way.
        const int length[1] = {n};
        forward = fftw_plan_many_dft_r2c(1, length, chunk * series, in, nullptr, 1, n, out, nullptr,
                                         1, bins, FFTW_ESTIMATE);
        backward = fftw_plan_dft_c2r_1d(n, sum, lagSums, FFTW_ESTIMATE);
        for (int f = 0; f < bins; ++f)
            sign[f] = f % 2 == 0 ? 1.0 : -1.0;
        // U by the same transform as the samples', so that δ·U rounds as their shift would.
        std::fill(in, in + w, 1.0);
        fftw_execute(forward);
        std::copy(reinterpret_cast<const Complex*>(out),
                  reinterpret_cast<const Complex*>(out) + bins, ones.begin());
        std::fill(in, in + w, 0.0);
    }
    ~Fft() {
        fftw_destroy_plan(forward);
        fftw_destroy_plan(backward);
        fftw_free(in), fftw_free(out), fftw_free(y), fftw_free(a), fftw_free(sum);
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
        return std::size_t(chunk) * series * (n * sizeof(double) + 3 * bins * sizeof(Complex)) +
               (bins + n) * sizeof(Complex) + squares.size() * n * sizeof(double) +
               2 * bins * sizeof(double) + bins * sizeof(Complex);
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
    groupBegin_.assign(groups_ + 1, m_);
    for (int k = m_ - 1; k >= 0; --k)
        groupBegin_[group_[k]] = k;
    spectrum_.assign(std::size_t(m_) * series * (w_ + 1), Complex(0.0));
    sums_ = std::make_unique<Spectra>();
    Spectra& s = *sums_;
    s.vv.assign(fine_, std::vector<Complex>(w_ + 1, 0.0));
    s.ss = s.s2 = s.vv;
    s.msd.assign(groups_, std::vector<Complex>(w_ + 1, 0.0));
    s.squares.assign(groups_, std::vector<double>(lags_, 0.0));
    s.origins.assign(fine_, std::vector<double>(lags_, 0.0));
    s.msdOrigins.assign(lags_, 0.0);
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
    if (seen_ % w_ == 0) completeBlock(seen_ / w_ - 1);
}

std::vector<WindowedCorrelation::Part> WindowedCorrelation::parts(long begin, long end) const {
    std::vector<Part> out;
    for (long t = begin; t < end; ++t) {
        const int fine = fineBlockOfSample(t, planned_, fine_);
        if (out.empty() || out.back().fine != fine) out.push_back({t, t, fine});
        out.back().end = t + 1;
    }
    return out;
}

void WindowedCorrelation::transform(int first, int count, long begin, long from, long to,
                                    long ref) const {
    Fft& f = *fft_;
    const int n = f.n;
    const double* origin = ring_.data() + std::size_t(ref % n) * rows * m_ + first;
    // Sample by sample, so that each row of the ring is read along consecutive bodies.
    for (int t = 0; t < w_; ++t) {
        const long sample = begin + t;
        const bool inside = sample >= from && sample < to;
        const double* row = ring_.data() + std::size_t(sample % n) * rows * m_ + first;
        for (int c = 0; c < count; ++c) {
            double* out = f.in + std::size_t(c) * series * n + t;
            if (!inside) {
                for (int s = 0; s < series; ++s)
                    out[s * n] = 0.0;
                continue;
            }
            double s[3];
            for (int a = 0; a < 3; ++a) {
                out[a * n] = row[a * m_ + c];
                s[a] = out[(firstS + a) * n] = row[(3 + a) * m_ + c];
                out[(firstX + a) * n] = row[(6 + a) * m_ + c] - origin[(6 + a) * m_ + c];
            }
            int q = firstQ;
            for (int a = 0; a < 3; ++a)
                for (int b = a; b < 3; ++b)
                    out[q++ * n] = s[a] * s[b];
        }
    }
    fftw_execute(f.forward);
}

void WindowedCorrelation::addOrigins(int first, int count, const std::vector<Part>& parts, long ref,
                                     const Complex* a, const Complex* y, Spectra& to) const {
    Fft& f = *fft_;
    const int bins = f.bins;
    const auto at = [bins](const Complex* base, int c, int s) {
        return base + (std::size_t(c) * series + s) * bins;
    };
    // The MSD's sums are per group of bodies, not per fine block: the whole block's origins.
    for (int c = 0; c < count; ++c)
        for (int s = firstX; s < series; ++s)
            addProduct(at(a, c, s), at(y, c, s), bins, 1.0, to.msd[group_[first + c]].data());
    const auto correlations = [&](const Complex* origins, int fine) {
        for (int c = 0; c < count; ++c) {
            for (int s = 0; s < 3; ++s) {
                addProduct(at(origins, c, s), at(y, c, s), bins, 1.0, to.vv[fine].data());
                addProduct(at(origins, c, firstS + s), at(y, c, firstS + s), bins, 1.0,
                           to.ss[fine].data());
            }
            for (int q = 0; q < 6; ++q)
                addProduct(at(origins, c, firstQ + q), at(y, c, firstQ + q), bins, qWeight[q],
                           to.s2[fine].data());
        }
    };
    if (parts.size() == 1) {
        correlations(a, parts.front().fine);
        return;
    }
    // A block that straddles fine blocks: each part's origins transformed alone, against the
    // whole window.
    const long begin = parts.front().begin;
    for (const Part& part : parts) {
        transform(first, count, begin, part.begin, part.end, ref);
        correlations(reinterpret_cast<const Complex*>(f.out), part.fine);
    }
}

void WindowedCorrelation::addSquares(const std::vector<Part>& parts, long ref, long windowEnd,
                                     Spectra& to) const {
    Fft& f = *fft_;
    const int n = f.n, span = static_cast<int>(windowEnd - ref);
    const double* origin = ring_.data() + std::size_t(ref % n) * rows * m_;
    for (int t = 0; t < span; ++t) {
        const double* row = ring_.data() + std::size_t((ref + t) % n) * rows * m_;
        for (int g = 0; g < groups_; ++g) {
            double x2 = 0.0;
            for (int k = groupBegin_[g]; k < groupBegin_[g + 1]; ++k)
                for (int a = 6; a < 9; ++a) {
                    const double x = row[a * m_ + k] - origin[a * m_ + k];
                    x2 += x * x;
                }
            f.squares[g][t] = x2;
        }
    }
    const auto partners = [windowEnd](long from, long to, int k) { // origins with t0 + k in reach
        return double(std::max(0L, std::min(to, windowEnd - k) - from));
    };
    for (const Part& part : parts)
        for (int k = 0; k < lags_; ++k) {
            to.origins[part.fine][k] += partners(part.begin, part.end, k);
            to.msdOrigins[k] += partners(part.begin, part.end, k);
        }
    const long begin = parts.front().begin, end = parts.back().end;
    for (int g = 0; g < groups_; ++g) {
        const std::vector<double>& q = f.squares[g];
        // Lag 0 adds nothing: every displacement is exactly zero there.
        for (int k = 1; k < lags_; ++k) {
            double squares = 0.0;
            for (long t0 = begin; t0 < end && t0 + k < windowEnd; ++t0)
                squares += q[t0 - ref + k] + q[t0 - ref];
            to.squares[g][k] += squares;
        }
    }
}

void WindowedCorrelation::completeBlock(long j) {
    Fft& f = *fft_;
    const int bins = f.bins;
    const long begin = j * w_, previous = begin - w_;
    const std::vector<Part> cut = j >= 1 ? parts(previous, begin) : std::vector<Part>{};
    Spectra& to = *sums_;
    const double* now = ring_.data() + std::size_t(begin % f.n) * rows * m_;
    const double* then = ring_.data() + std::size_t((begin + w_) % f.n) * rows * m_; // = previous
    for (int first = 0; first < m_; first += chunk) {
        const int count = std::min(chunk, m_ - first);
        transform(first, count, begin, begin, begin + w_, begin);
        const Complex* out = reinterpret_cast<const Complex*>(f.out);
        Complex* kept = spectrum_.data() + std::size_t(first) * series * bins;
        const std::size_t size = std::size_t(count) * series * bins;
        if (j == 0) {
            std::copy(out, out + size, kept);
            continue;
        }
        // Block j − 1's window: A_{j−1} + (−1)^f (A_j + δ·U for the x_a), then A_j is kept.
        Complex* a = reinterpret_cast<Complex*>(f.a);
        Complex* y = reinterpret_cast<Complex*>(f.y);
        for (int c = 0; c < count; ++c)
            for (int s = 0; s < series; ++s) {
                const std::size_t row = (std::size_t(c) * series + s) * bins;
                const double delta = s < firstX ? 0.0
                                                : now[(6 + s - firstX) * m_ + first + c] -
                                                      then[(6 + s - firstX) * m_ + first + c];
                const double* p = reinterpret_cast<const double*>(kept + row);
                const double* q = reinterpret_cast<const double*>(out + row);
                const double* u = reinterpret_cast<const double*>(f.ones.data());
                double* ys = reinterpret_cast<double*>(y + row);
                for (int b = 0; b < bins; ++b) {
                    ys[2 * b] = p[2 * b] + f.sign[b] * (q[2 * b] + delta * u[2 * b]);
                    ys[2 * b + 1] =
                        p[2 * b + 1] + f.sign[b] * (q[2 * b + 1] + delta * u[2 * b + 1]);
                }
            }
        std::copy(kept, kept + size, a);
        std::copy(out, out + size, kept);
        addOrigins(first, count, cut, previous, a, y, to);
    }
    if (j >= 1) addSquares(cut, previous, begin + w_, to);
}

LagSums WindowedCorrelation::sums() const {
    Spectra total = *sums_;
    Fft& f = *fft_;
    const int bins = f.bins;
    const long complete = seen_ / w_, tail = complete * w_;
    // The last complete block's window stops at the last sample, as does the partial block's;
    // both relative to the first sample of the earlier.
    const long ref = complete >= 1 ? tail - w_ : 0;
    const std::vector<Part> last = complete >= 1 ? parts(ref, tail) : std::vector<Part>{},
                            partial = parts(tail, seen_);
    if (last.empty() && partial.empty()) return invert(total);
    for (int first = 0; first < m_; first += chunk) {
        const int count = std::min(chunk, m_ - first);
        const std::size_t size = std::size_t(count) * series * bins;
        Complex* a = reinterpret_cast<Complex*>(f.a);
        Complex* y = reinterpret_cast<Complex*>(f.y);
        // The partial block (zeros when there is none) relative to ref.
        transform(first, count, tail, tail, seen_, ref);
        std::copy(reinterpret_cast<const Complex*>(f.out),
                  reinterpret_cast<const Complex*>(f.out) + size, a);
        if (!last.empty()) {
            const Complex* kept = spectrum_.data() + std::size_t(first) * series * bins;
            for (std::size_t r = 0; r < size; r += bins)
                for (int b = 0; b < bins; ++b)
                    y[r + b] = kept[r + b] + f.sign[b] * a[r + b];
            addOrigins(first, count, last, ref, kept, y, total);
        }
        if (!partial.empty()) addOrigins(first, count, partial, ref, a, a, total);
    }
    if (!last.empty()) addSquares(last, ref, seen_, total);
    if (!partial.empty()) addSquares(partial, ref, seen_, total);
    return invert(total);
}

LagSums WindowedCorrelation::invert(const Spectra& s) const {
    Fft& f = *fft_;
    LagSums out;
    out.origins = s.origins;
    out.msdOrigins = s.msdOrigins;
    const auto lagsOf = [&](const std::vector<Complex>& spectrum) {
        const double* sums = f.invert(spectrum);
        return std::vector<double>(sums, sums + lags_);
    };
    for (int b = 0; b < fine_; ++b) {
        out.vv.push_back(lagsOf(s.vv[b]));
        out.ss.push_back(lagsOf(s.ss[b]));
        out.s2.push_back(lagsOf(s.s2[b]));
    }
    for (int g = 0; g < groups_; ++g) {
        const double* cross = f.invert(s.msd[g]);
        std::vector<double> msd(lags_, 0.0); // lag 0: every displacement is exactly zero
        for (int k = 1; k < lags_; ++k)
            msd[k] = s.squares[g][k] - 2.0 * cross[k];
        out.msd.push_back(std::move(msd));
    }
    return out;
}

std::size_t WindowedCorrelation::bytes() const {
    const std::size_t spectra = (3 * std::size_t(fine_) + groups_) * (w_ + 1) * sizeof(Complex),
                      table = (std::size_t(fine_) + groups_ + 1) * lags_ * sizeof(double);
    return ring_.size() * sizeof(double) + (group_.size() + groupBegin_.size()) * sizeof(int) +
           spectrum_.size() * sizeof(Complex) + spectra + table + fft_->bytes();
}

} // namespace terrace::analysis
