// The adaptive search against brute force on random smooth indicators (validation tier): sums of
// three cosines, resolved by the 4 fs grid (ω Δt ≤ 0.8), with the lower level placed from 1e-2 to
// 1e-9 above or below the true minimum over the window. A crossing must be found exactly when the
// minimum dips below the level — grazing or not — and it must be the first one.
#include "dmd/root_search.hpp"
#include <cmath>
#include <gtest/gtest.h>
#include <random>

namespace test_search_random {

using namespace terrace::dmd;

namespace {

struct Waves {
    double A[3], omega[3], phase[3];
    PairSample operator()(double t) const {
        double u = 0.0, d = 0.0;
        for (int k = 0; k < 3; ++k) {
            u += A[k] * std::cos(omega[k] * t + phase[k]);
            d -= A[k] * omega[k] * std::sin(omega[k] * t + phase[k]);
        }
        return {t, u, d};
    }
};

constexpr double window = 0.5;      // time units (50 fs)
constexpr int denseSamples = 20000; // brute-force grid over the window
constexpr double rootSlack = 1e-12; // time units: a root refined past the level, by round-off
constexpr std::uint64_t kSeed = 4242;

/// The true minimum of f over (0, window]: the dense grid, then golden-section refinement.
double trueMinimum(const Waves& f) {
    double tmin = 0.0, umin = INFINITY;
    for (int k = 1; k <= denseSamples; ++k) {
        const double t = window * k / denseSamples;
        if (f(t).U < umin) umin = f(t).U, tmin = t;
    }
    double a = std::max(0.0, tmin - window / denseSamples);
    double b = std::min(window, tmin + window / denseSamples);
    for (int it = 0; it < 100; ++it) {
        const double m1 = a + 0.381966 * (b - a), m2 = a + 0.618034 * (b - a);
        if (f(m1).U < f(m2).U)
            b = m2;
        else
            a = m1;
    }
    return std::min(umin, f(0.5 * (a + b)).U);
}

} // namespace

TEST(SearchAgainstBruteForce, FindsExactlyTheCrossingsThatExistAndTheFirstOne) {
    SearchSettings s;
    s.maxStep = 0.04;
    s.nudge = 0.04 / 32;
    s.grazeWindow = 0.25;
    s.levelTolerance = 1e-12;
    std::mt19937_64 rng(kSeed);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    int cases = 0, crossings = 0;
    while (cases < 2000) {
        Waves f{};
        for (int k = 0; k < 3; ++k) {
            f.A[k] = 0.2 + 0.8 * uniform(rng);
            f.omega[k] = 1.0 + 19.0 * uniform(rng);
            f.phase[k] = 2.0 * M_PI * uniform(rng);
        }
        const double margin = std::pow(10.0, -2.0 - 7.0 * uniform(rng)); // 1e-2 … 1e-9
        const bool crossing = uniform(rng) < 0.5;
        const double lower = trueMinimum(f) + (crossing ? margin : -margin);
        if (!(f(0.0).U > lower + 1e-3)) continue; // the start must be inside, clear of the level
        ++cases;
        crossings += crossing;
        const SearchResult r = findTerraceExit(f, f(0.0), lower, f(0.0).U + 100.0, window, s);
        ASSERT_EQ(r.side == ExitSide::Lower, crossing)
            << "case " << cases << ": level " << (crossing ? "above" : "below")
            << " the minimum by " << margin;
        if (!crossing) continue;
        EXPECT_LE(f(r.t).U, lower); // reported on or past the level
        double first = window;
        for (int k = 1; k <= denseSamples; ++k)
            if (f(window * k / denseSamples).U < lower) {
                first = window * k / denseSamples;
                break;
            }
        EXPECT_LE(r.t, first + rootSlack) << "case " << cases << ": a later crossing was returned";
    }
    EXPECT_GT(crossings, 800);
}

} // namespace test_search_random
