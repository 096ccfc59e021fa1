#pragma once
// sin and cos together, by their Taylor series where the angle is small and by the library
// elsewhere. The DMD searches rotate bodies through a few hundredths of a radian per sample
// (|ω| ~ 3 rad per 100 fs for the paper's rods, samples ≤ 4 fs apart), where two short
// polynomials cost a fraction of a library sincos (which must reduce any argument).
// On |x| ≤ π/4 the first omitted terms, x¹⁷/17! and x¹⁸/18!, are below 5e-17: the series is
// correct to round-off there (Abramowitz & Stegun 4.3.65-66).
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
} // namespace detail

inline SinCos sinCos(double x) {
    constexpr double seriesLimit = 0.7853981633974483; // π/4
    if (!(std::abs(x) <= seriesLimit)) return {std::sin(x), std::cos(x)};
    using detail::cosSeries, detail::sinSeries;
    // Estrin's scheme in y = x²: pairs first, so the chain of dependent multiplications is three
    // deep instead of eight.
    const double y = x * x, y2 = y * y, y4 = y2 * y2;
    const double s01 = sinSeries[0] + sinSeries[1] * y, s23 = sinSeries[2] + sinSeries[3] * y,
                 s45 = sinSeries[4] + sinSeries[5] * y, s67 = sinSeries[6] + sinSeries[7] * y;
    const double c01 = cosSeries[0] + cosSeries[1] * y, c23 = cosSeries[2] + cosSeries[3] * y,
                 c45 = cosSeries[4] + cosSeries[5] * y, c67 = cosSeries[6] + cosSeries[7] * y;
    const double s = (s01 + s23 * y2) + (s45 + s67 * y2) * y4;
    const double c = (c01 + c23 * y2) + (c45 + c67 * y2) * y4 + cosSeries[8] * (y4 * y4);
    return {x * s, c};
}

} // namespace terrace
