#include "analysis/windowed_correlation.hpp"
#include "analysis/curves.hpp"
#include <algorithm>
#include <fftw3.h>
#include <stdexcept>

namespace terrace::analysis {

namespace {

using Complex = std::complex<double>;

constexpr int rows = 9;      // v, s, r: three components each, per sample and body
constexpr int channels = 10; // complex series per body: five pairs, then five real ones
constexpr int pairs = 5;
constexpr int chunk = 4; // bodies transformed together: one AVX vector; the scratch stays in L1
/// The channels' sums: vv, ss, s2 (per fine block), msd (per group), and their weights. Pairs:
/// v_x + i v_y, s_x + i s_y, Q00 + i Q11, Q01 + i Q02, x_x + i x_y; then v_z, s_z, Q22, Q12, x_z
/// (Q_ab = s_a s_b; Σ_ab Q_ab(0) Q_ab(t) counts the off-diagonal pairs twice).
constexpr int quantityOf[channels] = {0, 1, 2, 2, 3, 0, 1, 2, 2, 3};
constexpr double weightOf[channels] = {1.0, 1.0, 1.0, 2.0, 1.0, 1.0, 1.0, 1.0, 2.0, 1.0};
constexpr int msdPair = 4, msdSingle = 9;

/// Two doubles, one complex number (re, im): SSE2 on x86-64, NEON on AArch64.
typedef double Pair __attribute__((vector_size(16)));

Pair load(const double* p) {
    Pair v;
    __builtin_memcpy(&v, p, sizeof v);
    return v;
}
void store(double* p, Pair v) {
    __builtin_memcpy(p, &v, sizeof v);
}
Pair swapped(Pair v) {
    return Pair{v[1], v[0]};
}

/// conj(a)·y summed into (re·re, im·im) and (re·im, im·re) products per bin, so that the sums
/// run on whole vectors: Re = s1[0] + s1[1], Im = s2[0] − s2[1] (Spectra::complexAt).
void addProduct(const Complex* a, const Complex* y, int bins, double weight, double* s1,
                double* s2) {
    const double* as = reinterpret_cast<const double*>(a);
    const double* ys = reinterpret_cast<const double*>(y);
    for (int b = 0; b < 2 * bins; b += 2) {
        const Pair p = load(as + b), v = load(ys + b);
        store(s1 + b, load(s1 + b) + weight * (p * v));
        store(s2 + b, load(s2 + b) + weight * (p * swapped(v)));
    }
}

/// The MSD's next kept transform is made relative to the window's first sample t_j and kept
/// relative to its own, t_{j+1}: A ← A − δ·U, δ = r(t_{j+1}) − r(t_j) = dr + i di per body, U
/// and i·U interleaved (re, im) per bin.
struct Shift {
    const double *dr, *di, *u, *iu;
};

/// Block j's window, its cross-spectrum and the next kept transform in one pass over a channel,
/// for the `count` bodies of a chunk that add to the same sums (kept and next: one body's channel
/// every `stride` doubles): y = A_j + (−1)^f A_{j+1}, sums += weight · Σ_bodies conj(A_j)·y,
/// A_j ← A_{j+1} (less δ·U when shifted). The bodies' products are summed first; two bins at a
/// time, (−1)^f = +1 and −1.
template <int count, bool shifted>
void addWindows(double* kept, std::size_t keptStride, const double* next, std::size_t nextStride,
                int bins, double weight, double* s1, double* s2, const Shift& shift) {
    const auto keep = [&](double* k, Pair q, int c, int b) {
        if constexpr (shifted)
            q = q - (shift.dr[c] * load(shift.u + b) + shift.di[c] * load(shift.iu + b));
        store(k, q);
    };
    int b = 0;
    for (; b + 4 <= 2 * bins; b += 4) {
        Pair e1 = {0.0, 0.0}, e2 = e1, o1 = e1, o2 = e1;
#pragma GCC unroll 8
        for (int c = 0; c < count; ++c) {
            double* k = kept + c * keptStride + b;
            const double* q = next + c * nextStride + b;
            const Pair pe = load(k), qe = load(q), po = load(k + 2), qo = load(q + 2);
            const Pair ve = pe + qe, vo = po - qo;
            e1 += pe * ve, e2 += pe * swapped(ve), o1 += po * vo, o2 += po * swapped(vo);
            keep(k, qe, c, b), keep(k + 2, qo, c, b + 2);
        }
        store(s1 + b, load(s1 + b) + weight * e1), store(s2 + b, load(s2 + b) + weight * e2);
        store(s1 + b + 2, load(s1 + b + 2) + weight * o1);
        store(s2 + b + 2, load(s2 + b + 2) + weight * o2);
    }
    if (b < 2 * bins) { // an odd number of bins: the last one even
        Pair e1 = {0.0, 0.0}, e2 = e1;
        for (int c = 0; c < count; ++c) {
            double* k = kept + c * keptStride + b;
            const Pair p = load(k), q = load(next + c * nextStride + b), v = p + q;
            e1 += p * v, e2 += p * swapped(v);
            keep(k, q, c, b);
        }
        store(s1 + b, load(s1 + b) + weight * e1), store(s2 + b, load(s2 + b) + weight * e2);
    }
}

#if defined(__x86_64__) && defined(__GNUC__) && !defined(TERRACE_NO_AVX2)
/// Four doubles, two complex bins (an even one and the odd one after it): AVX, chosen at run
/// time (addWindowsFast). AVX alone, not FMA: every lane rounds as addWindows' do, so the sums
/// are the same to the last bit on any processor.
typedef double Quad __attribute__((vector_size(32)));
typedef long long QuadIndex __attribute__((vector_size(32)));

// Lane permutations: GCC's __builtin_shuffle takes the lanes as a vector, clang's
// __builtin_shufflevector as constants (the sanitiser tier builds with clang); the same permute.
__attribute__((target("avx"), always_inline)) inline Quad swapPairs(Quad v) {
#ifdef __clang__
    return __builtin_shufflevector(v, v, 1, 0, 3, 2);
#else
    return __builtin_shuffle(v, QuadIndex{1, 0, 3, 2});
#endif
}
__attribute__((target("avx"), always_inline)) inline Quad interleaveLow(Quad a, Quad b) {
#ifdef __clang__
    return __builtin_shufflevector(a, b, 0, 4, 1, 5);
#else
    return __builtin_shuffle(a, b, QuadIndex{0, 4, 1, 5});
#endif
}
__attribute__((target("avx"), always_inline)) inline Quad interleaveHigh(Quad a, Quad b) {
#ifdef __clang__
    return __builtin_shufflevector(a, b, 2, 6, 3, 7);
#else
    return __builtin_shuffle(a, b, QuadIndex{2, 6, 3, 7});
#endif
}

__attribute__((target("avx"), always_inline)) inline Quad load4(const double* p) {
    Quad v;
    __builtin_memcpy(&v, p, sizeof v);
    return v;
}
__attribute__((target("avx"), always_inline)) inline void store4(double* p, Quad v) {
    __builtin_memcpy(p, &v, sizeof v);
}

/// addWindows over whole pairs of bins, four doubles at a time; an odd last bin by addWindows.
template <int count, bool shifted>
__attribute__((target("avx"))) void
addWindowsAvx(double* kept, std::size_t keptStride, const double* next, std::size_t nextStride,
              int bins, double weight, double* s1, double* s2, const Shift& shift) {
    const Quad sign = {1.0, 1.0, -1.0, -1.0}; // (−1)^f: exact, p + (−q) rounds as p − q
    int b = 0;
    for (; b + 4 <= 2 * bins; b += 4) {
        Quad e1 = {0.0, 0.0, 0.0, 0.0}, e2 = e1;
#pragma GCC unroll 8
        for (int c = 0; c < count; ++c) {
            double* k = kept + c * keptStride + b;
            // The four bodies' streams 512 B ahead: at M in the thousands the kept transforms
            // come from L3.
            __builtin_prefetch(k + 64, 1);
            const Quad p = load4(k);
            Quad q = load4(next + c * nextStride + b);
            const Quad v = p + sign * q;
            e1 += p * v, e2 += p * swapPairs(v);
            if constexpr (shifted)
                q = q - (shift.dr[c] * load4(shift.u + b) + shift.di[c] * load4(shift.iu + b));
            store4(k, q);
        }
        store4(s1 + b, load4(s1 + b) + weight * e1), store4(s2 + b, load4(s2 + b) + weight * e2);
    }
    if (b < 2 * bins) {
        const Shift rest{shift.dr, shift.di, shift.u + b, shift.iu + b};
        addWindows<count, shifted>(kept + b, keptStride, next + b, nextStride, 1, weight, s1 + b,
                                   s2 + b, rest);
    }
}
#endif

/// A chunk's samples over a block, from the ring into the transforms' input, with the MSD's
/// squares: positions relative to r0 (the window's first sample), squares relative to p0 (the
/// block's own first sample, into `mine`) and to r0 (into `later`).
struct Gather {
    const double* ring;
    const std::size_t* slot; // [t]: the chunk's first body's row 0 of the block's sample t
    std::size_t m;           // doubles from one row to the next
    double* in;              // [channel][point][body], complex
    int z, from, to, count;  // z: doubles from one channel to the next
    bool oneGroup;
    double r0[3][chunk], p0[3][chunk];
    double *mine[chunk], *later[chunk];
};

/// Sample by sample, the chunk's bodies side by side (each line of the ring read once), every
/// value read into a scalar of its own, so that no store is read back through memory.
template <bool squares> void gather(const Gather& g) {
    const std::size_t m = g.m;
    const int z = g.z;
    for (int t = g.from; t < g.to; ++t) {
        const double* row = g.ring + g.slot[t];
        double own[chunk], later[chunk];
        for (int c = 0; c < g.count; ++c) {
            const double vx = row[c], vy = row[c + m], vz = row[c + 2 * m];
            const double sx = row[c + 3 * m], sy = row[c + 4 * m], sz = row[c + 5 * m];
            const double qx = row[c + 6 * m], qy = row[c + 7 * m], qz = row[c + 8 * m];
            const double xx = qx - g.r0[0][c], xy = qy - g.r0[1][c], xz = qz - g.r0[2][c];
            double* __restrict out = g.in + 2 * (t * chunk + c);
            out[0] = vx, out[1] = vy, out[5 * z] = vz;
            out[z] = sx, out[z + 1] = sy, out[6 * z] = sz;
            out[2 * z] = sx * sx, out[2 * z + 1] = sy * sy, out[7 * z] = sz * sz;
            out[3 * z] = sx * sy, out[3 * z + 1] = sx * sz, out[8 * z] = sy * sz;
            out[4 * z] = xx, out[4 * z + 1] = xy, out[9 * z] = xz;
            if constexpr (squares) {
                const double dx = qx - g.p0[0][c], dy = qy - g.p0[1][c], dz = qz - g.p0[2][c];
                own[c] = dx * dx + dy * dy + dz * dz;
                later[c] = xx * xx + xy * xy + xz * xz;
            }
        }
        if constexpr (squares)
            for (int c = 0; c < g.count; ++c) {
                g.mine[c][t] += own[c];
                g.later[c][t] += later[c];
            }
    }
}

#if defined(__x86_64__) && defined(__GNUC__) && !defined(TERRACE_NO_AVX2)
/// (re, im) of four bodies, in their order.
__attribute__((target("avx"), always_inline)) inline void put(double* out, Quad re, Quad im) {
    store4(out, interleaveLow(re, im));
    store4(out + 4, interleaveHigh(re, im));
}

/// Adds body c's square at sample t (lane c) into the sums of its group: in the bodies' order,
/// as gather does, and as one running sum where they share a group.
__attribute__((target("avx"), always_inline)) inline void sumSquares(double* const* sums, int t,
                                                                     Quad square, bool oneGroup) {
    if (oneGroup) {
        sums[0][t] = sums[0][t] + square[0] + square[1] + square[2] + square[3];
        return;
    }
    for (int c = 0; c < chunk; ++c)
        sums[c][t] += square[c];
}

/// gather for a whole chunk, its four bodies in one vector: the same operations lane by lane.
template <bool squares> __attribute__((target("avx"))) void gatherAvx(const Gather& g) {
    static_assert(chunk == 4);
    // Everything the loop reads besides the samples in locals: the stores into the input could
    // alias g, which would be read again after each of them.
    const double* const ring = g.ring;
    const std::size_t* const slot = g.slot;
    const std::size_t m = g.m;
    double* const in = g.in;
    const int z = g.z, from = g.from, to = g.to;
    const bool oneGroup = g.oneGroup;
    double* const mine[chunk] = {g.mine[0], g.mine[1], g.mine[2], g.mine[3]};
    double* const later[chunk] = {g.later[0], g.later[1], g.later[2], g.later[3]};
    const Quad zero = {0.0, 0.0, 0.0, 0.0};
    const Quad r0x = load4(g.r0[0]), r0y = load4(g.r0[1]), r0z = load4(g.r0[2]);
    const Quad p0x = load4(g.p0[0]), p0y = load4(g.p0[1]), p0z = load4(g.p0[2]);
    for (int t = from; t < to; ++t) {
        const double* row = ring + slot[t];
        const Quad vx = load4(row), vy = load4(row + m), vz = load4(row + 2 * m);
        const Quad sx = load4(row + 3 * m), sy = load4(row + 4 * m), sz = load4(row + 5 * m);
        const Quad qx = load4(row + 6 * m), qy = load4(row + 7 * m), qz = load4(row + 8 * m);
        // The lines of the chunk after next, asked for a chunk ahead: the prefetcher does not
        // follow nine rows a slot apart.
        for (int a = 0; a < rows; ++a)
            __builtin_prefetch(row + a * m + 2 * chunk);
        const Quad xx = qx - r0x, xy = qy - r0y, xz = qz - r0z;
        double* out = in + 2 * t * chunk;
        put(out, vx, vy), put(out + 5 * z, vz, zero);
        put(out + z, sx, sy), put(out + 6 * z, sz, zero);
        put(out + 2 * z, sx * sx, sy * sy), put(out + 7 * z, sz * sz, zero);
        put(out + 3 * z, sx * sy, sx * sz), put(out + 8 * z, sy * sz, zero);
        put(out + 4 * z, xx, xy), put(out + 9 * z, xz, zero);
        if constexpr (squares) {
            const Quad dx = qx - p0x, dy = qy - p0y, dz = qz - p0z;
            const Quad d2 = dx * dx + dy * dy + dz * dz, x2 = xx * xx + xy * xy + xz * xz;
            sumSquares(mine, t, d2, oneGroup), sumSquares(later, t, x2, oneGroup);
        }
    }
}
#endif

/// gather, by AVX where the processor has it and the chunk is whole.
template <bool squares> void gatherFast(const Gather& g) {
#if defined(__x86_64__) && defined(__GNUC__) && !defined(TERRACE_NO_AVX2)
    static const bool avx = __builtin_cpu_supports("avx");
    if (avx && g.count == chunk) return gatherAvx<squares>(g);
#endif
    gather<squares>(g);
}

/// addWindows, by AVX where the processor has it.
template <int count, bool shifted>
void addWindowsFast(double* kept, std::size_t keptStride, const double* next,
                    std::size_t nextStride, int bins, double weight, double* s1, double* s2,
                    const Shift& shift) {
#if defined(__x86_64__) && defined(__GNUC__) && !defined(TERRACE_NO_AVX2)
    static const bool avx = __builtin_cpu_supports("avx");
    if (avx)
        return addWindowsAvx<count, shifted>(kept, keptStride, next, nextStride, bins, weight, s1,
                                             s2, shift);
#endif
    addWindows<count, shifted>(kept, keptStride, next, nextStride, bins, weight, s1, s2, shift);
}

} // namespace

struct WindowedCorrelation::Spectra {
    // [fine block or group]: the pairs' spectra over n bins, then the real series' over W + 1
    // bins (their spectra are Hermitian); each bin as two sums of products (addProduct), all
    // bins' first sums, then all bins' second.
    std::vector<std::vector<double>> vv, ss, s2, msd;
    static Complex complexAt(const std::vector<double>& sums, int bin) {
        const std::size_t second = sums.size() / 2;
        return {sums[2 * bin] + sums[2 * bin + 1],
                sums[second + 2 * bin] - sums[second + 2 * bin + 1]};
    }
    std::vector<std::vector<double>> squares; // [group][lag]: |x(t0 + k)|² + |x(t0)|²
    std::vector<std::vector<double>> origins; // [fine block][lag]
    std::vector<double> msdOrigins;           // [lag]
};

struct WindowedCorrelation::Fft {
    int n, bins, kept; // kept: complex numbers kept per body, n per pair and W + 1 per real series
    fftw_complex* in;  // channels × n × chunk: samples at 0 … W − 1, zeros beyond
    fftw_complex* out; // their transforms
    fftw_complex* y;   // chunk × kept: a window's transforms
    fftw_complex* a;   // chunk × kept: a block's transforms, kept while parts use out
    fftw_complex* sum; // one accumulated spectrum, to invert
    double* lagSums;   // its inverse
    fftw_plan forward, backward;
    std::vector<double> sign; // (−1)^f per bin: the shift by W of the window's second block
    std::vector<Complex> ones, iOnes; // U: the transform of W ones at 0 … W − 1; and i·U
    std::vector<std::vector<double>> squares; // [group][t]: Σ over the group's bodies of |x|²
    std::vector<std::vector<double>> own;     // [group][t]: the same over the last block alone
    std::vector<std::size_t> slot;            // [t]: where a block's samples sit in the ring
    Fft(int w, int groups)
        : n(2 * w), bins(w + 1), kept(pairs * n + (channels - pairs) * bins),
          in(fftw_alloc_complex(std::size_t(chunk) * channels * n)),
          out(fftw_alloc_complex(std::size_t(chunk) * channels * n)),
          y(fftw_alloc_complex(std::size_t(chunk) * kept)),
          a(fftw_alloc_complex(std::size_t(chunk) * kept)), sum(fftw_alloc_complex(bins)),
          lagSums(fftw_alloc_real(n)), sign(n), ones(n), iOnes(n),
          squares(groups, std::vector<double>(n, 0.0)), own(groups, std::vector<double>(w, 0.0)),
          slot(w) {
        Complex* z = reinterpret_cast<Complex*>(in);
        std::fill(z, z + std::size_t(chunk) * channels * n, Complex(0.0));
        // FFTW_ESTIMATE plans in microseconds without touching the buffers; at these small
        // lengths FFTW runs one hard-coded codelet either way. Complex transforms, two real
        // series each: FFTW's complex codelets are vectorised, its real ones not, and at 2W = 32
        // one complex transform cost less than one real one here (about 70 against 110 ns).
        // In: [channel][point][body], so that a chunk's bodies, side by side in the ring, are
        // written side by side; out: [body][channel][bin], each body's channels read in turn.
        // FFTW transposes on the way (its n2fv codelets, as fast as the contiguous n1fv).
        fftw_iodim length{n, chunk, 1};
        fftw_iodim many[2] = {{channels, n * chunk, n}, {chunk, 1, channels * n}};
        forward = fftw_plan_guru_dft(1, &length, 2, many, in, out, FFTW_FORWARD, FFTW_ESTIMATE);
        backward = fftw_plan_dft_c2r_1d(n, sum, lagSums, FFTW_ESTIMATE);
        for (int f = 0; f < n; ++f)
            sign[f] = f % 2 == 0 ? 1.0 : -1.0;
        // U by the same transform as the samples', so that δ·U rounds as their shift would.
        for (int t = 0; t < w; ++t)
            z[t * chunk] = 1.0;
        fftw_execute(forward);
        std::copy(reinterpret_cast<const Complex*>(out), reinterpret_cast<const Complex*>(out) + n,
                  ones.begin());
        for (int f = 0; f < n; ++f)
            iOnes[f] = Complex(-ones[f].imag(), ones[f].real());
        for (int t = 0; t < w; ++t)
            z[t * chunk] = 0.0;
    }
    ~Fft() {
        fftw_destroy_plan(forward);
        fftw_destroy_plan(backward);
        fftw_free(in), fftw_free(out), fftw_free(y), fftw_free(a), fftw_free(sum);
        fftw_free(lagSums);
    }
    Fft(const Fft&) = delete;
    Fft& operator=(const Fft&) = delete;

    /// The offset of a channel among a body's kept transforms, and how many bins it keeps.
    int offset(int channel) const {
        return channel < pairs ? channel * n : pairs * n + (channel - pairs) * bins;
    }
    int length(int channel) const { return channel < pairs ? n : bins; }
    /// The lag sums (unnormalised c2r, divided by n) of an accumulated spectrum: Re IFFT of the
    /// pairs' part, whose Hermitian part (P[f] + conj P[−f])/2 it is, plus the real series'.
    const double* invert(const std::vector<double>& spectrum) {
        Complex* h = reinterpret_cast<Complex*>(sum);
        for (int f = 0; f < bins; ++f)
            h[f] = 0.5 * (Spectra::complexAt(spectrum, f) +
                          std::conj(Spectra::complexAt(spectrum, (n - f) % n))) +
                   Spectra::complexAt(spectrum, n + f);
        fftw_execute(backward);
        for (int k = 0; k < n; ++k)
            lagSums[k] /= n;
        return lagSums;
    }
    std::size_t bytes() const {
        return std::size_t(chunk) * (2 * channels * n + 2 * kept) * sizeof(Complex) +
               (bins + 2 * n) * sizeof(Complex) + squares.size() * (n + n / 2) * sizeof(double) +
               n * sizeof(double);
    }
};

WindowedCorrelation::WindowedCorrelation(int followed, int window, int lags, long plannedSamples,
                                         int fineBlocks, int groups)
    : m_(followed), w_(window), lags_(lags), fine_(fineBlocks), groups_(groups),
      stride_((std::size_t(followed) + 7) / 8 * 8 + 8), planned_(plannedSamples) {
    if (followed < 1 || window < 1 || lags < 1 || lags > window || fineBlocks < 1 || groups < 1 ||
        groups > followed || plannedSamples < 1)
        throw std::invalid_argument("windowed correlation: need bodies, 1 ≤ lags ≤ W, fine "
                                    "blocks and 1 ≤ groups ≤ bodies");
    ring_.assign(std::size_t(2 * w_) * rows * stride_, 0.0);
    for (int k = 0; k < m_; ++k) // group b holds bodies ⌊bM/G⌋ … ⌊(b+1)M/G⌋ − 1
        group_.push_back(static_cast<int>((long(k) * groups_ + groups_ - 1) / m_));
    groupBegin_.assign(groups_ + 1, m_);
    for (int k = m_ - 1; k >= 0; --k)
        groupBegin_[group_[k]] = k;
    fft_ = std::make_unique<Fft>(w_, groups_);
    spectrum_.assign(std::size_t(m_) * fft_->kept, Complex(0.0));
    sums_ = std::make_unique<Spectra>();
    Spectra& s = *sums_;
    s.vv.assign(fine_, std::vector<double>(4 * std::size_t(fft_->n + fft_->bins), 0.0));
    s.ss = s.s2 = s.vv;
    s.msd.assign(groups_, std::vector<double>(4 * std::size_t(fft_->n + fft_->bins), 0.0));
    s.squares.assign(groups_, std::vector<double>(lags_, 0.0));
    s.origins.assign(fine_, std::vector<double>(lags_, 0.0));
    s.msdOrigins.assign(lags_, 0.0);
}

WindowedCorrelation::~WindowedCorrelation() = default;

std::size_t WindowedCorrelation::at(long t, int k) const {
    return std::size_t(t % (2 * w_)) * rows * stride_ + k;
}

void WindowedCorrelation::add(const Snapshot& frame, const int* index) {
    double* row = ring_.data() + at(seen_, 0);
    for (int k = 0; k < m_; ++k) {
        const int i = index ? index[k] : k;
        for (int a = 0; a < 3; ++a) {
            row[(0 + a) * stride_ + k] = frame.velocity[i][a];
            row[(3 + a) * stride_ + k] = frame.axis[i][a];
            row[(6 + a) * stride_ + k] = frame.position[i][a];
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

void WindowedCorrelation::transform(int first, int count, long begin, long from, long to, long ref,
                                    long own) const {
    Fft& f = *fft_;
    const int n = f.n, z = 2 * n * chunk; // z: doubles from one channel to the next
    const int inFrom = static_cast<int>(std::clamp(from - begin, 0L, long(w_))),
              inTo = static_cast<int>(std::clamp(to - begin, long(inFrom), long(w_)));
    double* in = reinterpret_cast<double*>(f.in);
    // The real series' imaginary parts and the points W … n − 1 stay zero.
    for (int t = 0; t < w_; ++t)
        if (t < inFrom || t >= inTo)
            for (int ch = 0; ch < channels; ++ch)
                std::fill(in + ch * z + 2 * t * chunk, in + ch * z + 2 * (t + 1) * chunk, 0.0);
    // Rows of the block's samples, and of the references, found once for every body (at()
    // divides).
    Gather g;
    for (int t = inFrom; t < inTo; ++t)
        f.slot[t] = at(begin + t, 0) + first;
    g.ring = ring_.data(), g.slot = f.slot.data(), g.m = stride_, g.in = in, g.z = z;
    g.from = inFrom, g.to = inTo;
    const std::size_t origin = at(ref, first), start = at(std::max(own, 0L), first);
    for (int c = 0; c < chunk; ++c) {
        const int k = first + std::min(c, count - 1);
        for (int a = 0; a < 3; ++a)
            g.r0[a][c] = ring_[origin + c + (6 + a) * stride_],
            g.p0[a][c] = ring_[start + c + (6 + a) * stride_];
        g.mine[c] = f.own[group_[k]].data(), g.later[c] = f.squares[group_[k]].data() + w_;
    }
    g.count = count, g.oneGroup = group_[first] == group_[first + count - 1];
    if (own >= 0)
        gatherFast<true>(g);
    else
        gatherFast<false>(g);
    fftw_execute(f.forward);
}

void WindowedCorrelation::keep(const Complex* full, int count, Complex* kept) const {
    const Fft& f = *fft_;
    for (int c = 0; c < count; ++c)
        for (int ch = 0; ch < channels; ++ch) {
            const Complex* from = full + (std::size_t(c) * channels + ch) * f.n;
            std::copy(from, from + f.length(ch), kept + std::size_t(c) * f.kept + f.offset(ch));
        }
}

std::pair<double*, double*> WindowedCorrelation::sumsOf(Spectra& to, int channel, int fine,
                                                        int group) const {
    const int q = quantityOf[channel];
    std::vector<double>& sums = q == 0   ? to.vv[fine]
                                : q == 1 ? to.ss[fine]
                                : q == 2 ? to.s2[fine]
                                         : to.msd[group];
    double* s1 = sums.data() + (channel < pairs ? 0 : 2 * fft_->n);
    return {s1, s1 + sums.size() / 2};
}

void WindowedCorrelation::addOrigins(int first, int count, const std::vector<Part>& parts, long ref,
                                     const Complex* a, const Complex* y, Spectra& to) const {
    Fft& f = *fft_;
    const auto target = [&](int ch, int fine, int c) {
        return sumsOf(to, ch, fine, group_[first + c]);
    };
    // The MSD's sums are per group of bodies, not per fine block: the whole block's origins.
    for (int c = 0; c < count; ++c)
        for (const int ch : {msdPair, msdSingle}) {
            const std::size_t at = std::size_t(c) * f.kept + f.offset(ch);
            const auto [s1, s2] = target(ch, 0, c);
            addProduct(a + at, y + at, f.length(ch), weightOf[ch], s1, s2);
        }
    // origins: kept layout (f.kept per body) or FFTW's (channels × n per body).
    const auto correlations = [&](const Complex* origins, bool full, int fine) {
        for (int c = 0; c < count; ++c)
            for (int ch = 0; ch < channels; ++ch) {
                if (ch == msdPair || ch == msdSingle) continue;
                const std::size_t at = std::size_t(c) * f.kept + f.offset(ch);
                const Complex* o =
                    full ? origins + (std::size_t(c) * channels + ch) * f.n : origins + at;
                const auto [s1, s2] = target(ch, fine, c);
                addProduct(o, y + at, f.length(ch), weightOf[ch], s1, s2);
            }
    };
    if (parts.size() == 1) {
        correlations(a, false, parts.front().fine);
        return;
    }
    // A block that straddles fine blocks: each part's origins transformed alone, against the
    // whole window.
    const long begin = parts.front().begin;
    for (const Part& part : parts) {
        transform(first, count, begin, part.begin, part.end, ref);
        correlations(reinterpret_cast<const Complex*>(f.out), true, part.fine);
    }
}

void WindowedCorrelation::ringSquares(long ref, long windowEnd) const {
    Fft& f = *fft_;
    const int span = static_cast<int>(windowEnd - ref);
    for (int t = 0; t < span; ++t) {
        for (int g = 0; g < groups_; ++g) {
            double x2 = 0.0;
            for (int k = groupBegin_[g]; k < groupBegin_[g + 1]; ++k)
                for (int a = 6; a < 9; ++a) {
                    const double x =
                        ring_[at(ref + t, k) + a * stride_] - ring_[at(ref, k) + a * stride_];
                    x2 += x * x;
                }
            f.squares[g][t] = x2;
        }
    }
}

void WindowedCorrelation::addSquares(const std::vector<Part>& parts, long ref, long windowEnd,
                                     Spectra& to) const {
    Fft& f = *fft_;
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
    const int n = f.n;
    const long begin = j * w_, previous = begin - w_;
    const std::vector<Part> cut = j >= 1 ? parts(previous, begin) : std::vector<Part>{};
    Spectra& to = *sums_;
    const std::size_t now = at(begin, 0), then = at(std::max(previous, 0L), 0);
    // The MSD's squares over block j − 1's window relative to its first sample: block j − 1's
    // own, kept from its transform, then block j's, made with its transform.
    for (int g = 0; g < groups_; ++g) {
        std::copy(f.own[g].begin(), f.own[g].end(), f.squares[g].begin());
        std::fill(f.own[g].begin(), f.own[g].end(), 0.0);
        std::fill(f.squares[g].begin() + w_, f.squares[g].end(), 0.0);
    }
    const double* u = reinterpret_cast<const double*>(f.ones.data());
    const double* iu = reinterpret_cast<const double*>(f.iOnes.data());
    const std::size_t keptStride = 2 * std::size_t(f.kept),
                      nextStride = 2 * std::size_t(channels) * n;
    for (int first = 0; first < m_; first += chunk) {
        const int count = std::min(chunk, m_ - first);
        // Block j's positions relative to block j − 1's first sample, that of the window they
        // join; kept relative to their own (less δ·U).
        transform(first, count, begin, begin, begin + w_, j >= 1 ? previous : begin, begin);
        const Complex* out = reinterpret_cast<const Complex*>(f.out);
        Complex* kept = spectrum_.data() + std::size_t(first) * f.kept;
        if (j == 0) {
            keep(out, count, kept);
            continue;
        }
        double dr[chunk], di[chunk], dz[chunk], zero[chunk] = {}; // δ = r(t_j) − r(t_{j−1})
        for (int c = 0; c < count; ++c) {
            const std::size_t k = std::size_t(first + c);
            dr[c] = ring_[now + k + 6 * stride_] - ring_[then + k + 6 * stride_];
            di[c] = ring_[now + k + 7 * stride_] - ring_[then + k + 7 * stride_];
            dz[c] = ring_[now + k + 8 * stride_] - ring_[then + k + 8 * stride_];
        }
        if (cut.size() == 1) { // one pass: window, cross-spectrum, kept transform
            const int fine = cut.front().fine;
            const bool oneGroup = group_[first] == group_[first + count - 1];
            for (int ch = 0; ch < channels; ++ch) {
                double* p = reinterpret_cast<double*>(kept + f.offset(ch));
                const double* q = reinterpret_cast<const double*>(out + std::size_t(ch) * n);
                const bool msd = ch == msdPair || ch == msdSingle;
                const Shift shift{ch == msdPair ? dr : dz, ch == msdPair ? di : zero, u, iu};
                if (count == chunk && (!msd || oneGroup)) {
                    const auto [s1, s2] = sumsOf(to, ch, fine, group_[first]);
                    if (msd)
                        addWindowsFast<chunk, true>(p, keptStride, q, nextStride, f.length(ch),
                                                    weightOf[ch], s1, s2, shift);
                    else
                        addWindowsFast<chunk, false>(p, keptStride, q, nextStride, f.length(ch),
                                                     weightOf[ch], s1, s2, shift);
                    continue;
                }
                for (int c = 0; c < count; ++c) {
                    const auto [s1, s2] = sumsOf(to, ch, fine, group_[first + c]);
                    const Shift own{shift.dr + c, shift.di + c, u, iu};
                    if (msd)
                        addWindowsFast<1, true>(p + c * keptStride, 0, q + c * nextStride, 0,
                                                f.length(ch), weightOf[ch], s1, s2, own);
                    else
                        addWindowsFast<1, false>(p + c * keptStride, 0, q + c * nextStride, 0,
                                                 f.length(ch), weightOf[ch], s1, s2, own);
                }
            }
            continue;
        }
        Complex* a = reinterpret_cast<Complex*>(f.a);
        Complex* y = reinterpret_cast<Complex*>(f.y);
        for (int c = 0; c < count; ++c)
            for (int ch = 0; ch < channels; ++ch) {
                const std::size_t at = std::size_t(c) * f.kept + f.offset(ch);
                const Complex* q = out + (std::size_t(c) * channels + ch) * n;
                for (int b = 0; b < f.length(ch); ++b)
                    y[at + b] = kept[at + b] + f.sign[b] * q[b];
            }
        std::copy(kept, kept + std::size_t(count) * f.kept, a);
        keep(out, count, kept);
        for (int c = 0; c < count; ++c) // the MSD's kept transforms relative to t_j
            for (const int ch : {msdPair, msdSingle}) {
                const double r = ch == msdPair ? dr[c] : dz[c], i = ch == msdPair ? di[c] : 0.0;
                Complex* k = kept + std::size_t(c) * f.kept + f.offset(ch);
                for (int b = 0; b < f.length(ch); ++b)
                    k[b] -= r * f.ones[b] + i * f.iOnes[b];
            }
        addOrigins(first, count, cut, previous, a, y, to);
    }
    if (j >= 1) addSquares(cut, previous, begin + w_, to);
}

LagSums WindowedCorrelation::sums() const {
    Spectra total = *sums_;
    Fft& f = *fft_;
    const long complete = seen_ / w_, tail = complete * w_;
    // The last complete block's window stops at the last sample, as does the partial block's;
    // both relative to the first sample of the earlier.
    const long ref = complete >= 1 ? tail - w_ : 0;
    const std::vector<Part> last = complete >= 1 ? parts(ref, tail) : std::vector<Part>{},
                            partial = parts(tail, seen_);
    if (last.empty() && partial.empty()) return invert(total);
    for (int first = 0; first < m_; first += chunk) {
        const int count = std::min(chunk, m_ - first);
        const std::size_t size = std::size_t(count) * f.kept;
        Complex* a = reinterpret_cast<Complex*>(f.a);
        Complex* y = reinterpret_cast<Complex*>(f.y);
        // The partial block (zeros when there is none) relative to ref.
        transform(first, count, tail, tail, seen_, ref);
        keep(reinterpret_cast<const Complex*>(f.out), count, a);
        if (!last.empty()) {
            const Complex* kept = spectrum_.data() + std::size_t(first) * f.kept;
            for (std::size_t r = 0; r < size; ++r) {
                const int bin = static_cast<int>(r % f.kept),
                          channel = bin < pairs * f.n ? bin / f.n : pairs;
                const int b = channel < pairs ? bin % f.n : (bin - pairs * f.n) % f.bins;
                y[r] = kept[r] + f.sign[b] * a[r];
            }
            addOrigins(first, count, last, ref, kept, y, total);
        }
        if (!partial.empty()) addOrigins(first, count, partial, ref, a, a, total);
    }
    ringSquares(ref, seen_);
    if (!last.empty()) addSquares(last, ref, seen_, total);
    if (!partial.empty()) addSquares(partial, ref, seen_, total);
    return invert(total);
}

LagSums WindowedCorrelation::invert(const Spectra& s) const {
    Fft& f = *fft_;
    LagSums out;
    out.origins = s.origins;
    out.msdOrigins = s.msdOrigins;
    const auto lagsOf = [&](const std::vector<double>& spectrum) {
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

std::size_t WindowedCorrelation::bytesPerBody(int window) {
    const std::size_t n = 2 * std::size_t(window), bins = std::size_t(window) + 1;
    return n * rows * sizeof(double) + (pairs * n + (channels - pairs) * bins) * sizeof(Complex);
}

std::size_t WindowedCorrelation::bytes() const {
    const std::size_t spectra = (3 * std::size_t(fine_) + groups_) * 2 * (fft_->n + fft_->bins) *
                                sizeof(Complex),
                      table = (std::size_t(fine_) + groups_ + 1) * lags_ * sizeof(double);
    return ring_.size() * sizeof(double) + (group_.size() + groupBegin_.size()) * sizeof(int) +
           spectrum_.size() * sizeof(Complex) + spectra + table + fft_->bytes();
}

void WindowedCorrelation::save(StateWriter& out) const {
    out.value(std::int64_t(seen_));
    out.doubles(ring_);
    out.doubles(spectrum_);
    const Spectra& s = *sums_;
    for (const auto* sums : {&s.vv, &s.ss, &s.s2, &s.msd, &s.squares, &s.origins})
        out.nested(*sums);
    out.doubles(s.msdOrigins);
    // The MSD's squares of the last complete block, made with its transform, that the next
    // block's window begins with.
    out.nested(fft_->own);
}

void WindowedCorrelation::restore(StateReader& in) {
    const auto seen = in.value<std::int64_t>("FFT correlation's samples");
    if (seen < 0) throw std::invalid_argument("analysis state: a negative number of samples");
    seen_ = long(seen);
    in.doubles(ring_, "FFT correlation's ring of samples");
    in.doubles(spectrum_, "FFT correlation's kept transforms");
    Spectra& s = *sums_;
    in.nested(s.vv, "FFT correlation's VACF spectra");
    in.nested(s.ss, "FFT correlation's OACF spectra");
    in.nested(s.s2, "FFT correlation's P2 spectra");
    in.nested(s.msd, "FFT correlation's MSD spectra");
    in.nested(s.squares, "FFT correlation's MSD squares");
    in.nested(s.origins, "FFT correlation's origin counts");
    in.doubles(s.msdOrigins, "FFT correlation's MSD origin counts");
    in.nested(fft_->own, "FFT correlation's last block's squares");
}

} // namespace terrace::analysis
