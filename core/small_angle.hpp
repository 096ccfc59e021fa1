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
    const double x2 = x * x;
    double s = detail::sinSeries[7], c = detail::cosSeries[8];
    for (int k = 6; k >= 0; --k)
        s = s * x2 + detail::sinSeries[k];
    for (int k = 7; k >= 0; --k)
        c = c * x2 + detail::cosSeries[k];
    return {x * s, c};
}

} // namespace terrace
