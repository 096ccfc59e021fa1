#pragma once
// What the pair-potential tests share (test_potentials, test_gay_berne, test_site_potential):
// the finite-difference stencil their analytic derivatives are checked against, the relative
// comparison with a floor where a quantity vanishes, and random unit vectors.
#include "core/vec.hpp"
#include <algorithm>
#include <gtest/gtest.h>
#include <random>

namespace terrace::pairchecks {

/// f'(0) by the fourth-order central stencil [8(f(h) − f(−h)) − (f(2h) − f(−2h))] / 12h.
template <class Fn> double centralDerivative(Fn&& f, double h) {
    return (8.0 * (f(h) - f(-h)) - (f(2.0 * h) - f(-2.0 * h))) / (12.0 * h);
}

/// |a − b| ≤ tol · max(|b|, floor): relative error, with a floor where b vanishes.
inline ::testing::AssertionResult closeRelative(const Vec3& a, const Vec3& b, double tol,
                                                double floor) {
    const double err = (a - b).norm(), scale = std::max(b.norm(), floor);
    if (err <= tol * scale) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "got (" << a.transpose() << "), expected ("
                                         << b.transpose() << "), relative error " << err / scale;
}
inline ::testing::AssertionResult closeRelative(double a, double b, double tol, double floor) {
    return closeRelative(Vec3(a, 0, 0), Vec3(b, 0, 0), tol, floor);
}

/// Uniform on the sphere: a normalised Gaussian vector.
inline Vec3 randomUnit(std::mt19937_64& rng) {
    std::normal_distribution<double> gauss;
    const Vec3 g(gauss(rng), gauss(rng), gauss(rng));
    return g / g.norm();
}

} // namespace terrace::pairchecks
