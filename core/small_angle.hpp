#pragma once
// sin and cos together, by their Taylor series where the angle is small and by the library
// elsewhere. The DMD searches rotate bodies through a few hundredths of a radian per sample
// (|ω| ~ 3 rad per 100 fs for the paper's rods, samples ≤ 4 fs apart), where two short
// polynomials cost a fraction of a library sincos (which must reduce any argument).
// On |x| ≤ π/4 the first omitted terms, x¹⁷/17! and x¹⁸/18!, are below 5e-17: the series is
// correct to round-off there (Abramowitz & Stegun 4.3.65-66).
#include <array>
#include <cmath>

namespace terrace {

struct SinCos {
    double sin, cos;
};

namespace detail {
// Taylor coefficients in x²: (−1)ᵏ/(2k+1)! for sin x / x and (−1)ᵏ/(2k)! for cos x.
inline constexpr double sinSeries[] = {1.0,
                                       -1.0 / 6.0,
                                       1.0 / 120.0,
                                       -1.0 / 5040.0,
                                       1.0 / 362880.0,
                                       -1.0 / 39916800.0,
                                       1.0 / 6227020800.0,
                                       -1.0 / 1307674368000.0};
inline constexpr double cosSeries[] = {1.0,
                                       -1.0 / 2.0,
                                       1.0 / 24.0,
                                       -1.0 / 720.0,
                                       1.0 / 40320.0,
                                       -1.0 / 3628800.0,
                                       1.0 / 479001600.0,
                                       -1.0 / 87178291200.0,
                                       1.0 / 20922789888000.0};

/// The series of sin x and cos x for |x| ≤ π/4; T is double or a packed vector of angles.
/// Estrin's scheme in y = x²: pairs first, so the chain of dependent multiplications is three
/// deep instead of eight.
template <class T> void sinCosSeries(const T& x, T& sin, T& cos) {
    const T y = x * x, y2 = y * y, y4 = y2 * y2;
    const T s01 = sinSeries[0] + sinSeries[1] * y, s23 = sinSeries[2] + sinSeries[3] * y,
            s45 = sinSeries[4] + sinSeries[5] * y, s67 = sinSeries[6] + sinSeries[7] * y;
    const T c01 = cosSeries[0] + cosSeries[1] * y, c23 = cosSeries[2] + cosSeries[3] * y,
            c45 = cosSeries[4] + cosSeries[5] * y, c67 = cosSeries[6] + cosSeries[7] * y;
    sin = x * ((s01 + s23 * y2) + (s45 + s67 * y2) * y4);
    cos = (c01 + c23 * y2) + (c45 + c67 * y2) * y4 + cosSeries[8] * (y4 * y4);
}
inline constexpr double seriesLimit = 0.7853981633974483; // π/4
} // namespace detail

inline SinCos sinCos(double x) {
    if (!(std::abs(x) <= detail::seriesLimit)) return {std::sin(x), std::cos(x)};
    SinCos r;
    detail::sinCosSeries(x, r.sin, r.cos);
    return r;
}

/// sin and cos of two angles at once: both series in one pass of packed (two-wide) arithmetic,
/// the same values as sinCos(a) and sinCos(b) (a DMD pair sample turns both of its bodies).
inline std::array<SinCos, 2> sinCosPair(double a, double b) {
    if (!(std::abs(a) <= detail::seriesLimit && std::abs(b) <= detail::seriesLimit))
        return {sinCos(a), sinCos(b)};
    // A GCC vector of two doubles: one SSE2 register, scalars broadcast in mixed arithmetic.
    using Double2 = double __attribute__((vector_size(16)));
    Double2 sin, cos;
    detail::sinCosSeries(Double2{a, b}, sin, cos);
    return {SinCos{sin[0], cos[0]}, SinCos{sin[1], cos[1]}};
}

} // namespace terrace
