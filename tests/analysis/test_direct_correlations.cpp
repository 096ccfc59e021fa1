// The reference VACF, OACF and MSD (direct sums over every origin) on samples whose correlations
// are known exactly or analytically, and the block and diffusion arithmetic of curves.hpp. The
// product's streaming curves are tested against this reference (test_streaming_analysis.cpp).
#include "analysis/curves.hpp"
#include "analysis/reference/direct_correlations.hpp"
#include "synthetic_samples.hpp"
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>
#include <gtest/gtest.h>

namespace test_direct_correlations {

using namespace terrace;
using namespace terrace::analysis;
using namespace terrace::analysis::reference;

namespace {

/// Exact identities (VACF of free flight, averages the code must reproduce sample by sample):
/// round-off of sums over a few thousand terms.
constexpr double roundOff = 1e-12;
/// MSD of free flight: |r(t) − r(0)|² from unwrapped positions of ~100 Å loses ~1e-14 relative
/// to cancellation; 1e-9 relative still catches any wrong lag or weight.
constexpr double msdRelativeTolerance = 1e-9;
/// Statistical check of an average over N bodies of a quantity bounded by 1 in magnitude:
/// 5 standard errors of the mean (its standard deviation is at most 1).
constexpr double boundedSigmas = 5.0;
/// Estimated D against the true one, in units of the block error (7 degrees of freedom: a
/// Student-t beyond 4.5 happens with probability ~0.3 %).
constexpr double diffusionSigmas = 4.5;
/// ⟨z²⟩ of Student-t (7 dof) deviates averaged over a few hundred strongly correlated lags of
/// four runs: it scatters by ~0.3 about 1.4 (var t² = 7.8 per point, ~40 independent groups).
constexpr double tDistributionSpread = 0.5;
/// Quadrature accuracy for the analytic rotor curves.
constexpr double quadratureTolerance = 1e-10;

// Rods of the paper (DESIGN.md): m = 18 g/mol, I = 1.154 g/mol Å², kT = 4.2 kJ/mol.
constexpr double mass = 18.0, inertia = 1.154, kT = 4.2;

/// Dawson's integral F(y) = e^{−y²} ∫₀^y e^{t²} dt = ∫₀^y e^{t² − y²} dt.
double dawson(double y) {
    if (y == 0.0) return 0.0;
    return boost::math::quadrature::gauss_kronrod<double, 61>::integrate(
        [y](double t) { return std::exp(t * t - y * y); }, 0.0, y, 15, quadratureTolerance);
}

/// ⟨cos(|ω| t)⟩ for |ω| Rayleigh-distributed with σ² = kT/I (2-D Maxwell–Boltzmann, ω ⟂ s),
/// x = t √(kT/I): 1 − x √(π/2) e^{−x²/2} erfi(x/√2) = 1 − √2 x F(x/√2), F Dawson's integral.
double rotorCos(double x) {
    return 1.0 - std::sqrt(2.0) * x * dawson(x / std::sqrt(2.0));
}

/// The same average by direct quadrature over the Rayleigh density u e^{−u²/2}, u = |ω|/σ.
double rotorCosQuadrature(double x) {
    return boost::math::quadrature::gauss_kronrod<double, 61>::integrate(
        [x](double u) { return u * std::exp(-0.5 * u * u) * std::cos(u * x); }, 0.0, 14.0, 15,
        quadratureTolerance);
}

/// ⟨P₂(cos |ω|t)⟩ = (3⟨cos²⟩ − 1)/2 = 1/4 + (3/4)⟨cos 2|ω|t⟩.
double rotorP2(double x) {
    return 0.25 + 0.75 * rotorCos(2.0 * x);
}

} // namespace

TEST(DirectCorrelations, VacfOfFreeParticlesIsOne) {
    const auto samples = synthetic::freeRotors(60, 40, 0.1, 30.0, kT, mass, inertia, 1);
    const auto vacf = velocityAutocorrelation(samples, 29, 4);
    for (std::size_t k = 0; k < vacf.value.size(); ++k) {
        EXPECT_NEAR(vacf.value[k], 1.0, roundOff) << "lag " << k;
        EXPECT_NEAR(vacf.err[k], 0.0, roundOff);
        EXPECT_NEAR(vacf.tPs[k], k * 0.01, 1e-15); // 0.1 time units = 10 fs
    }
}

TEST(DirectCorrelations, MsdOfFreeFlightIsMeanSquareSpeedTimesTimeSquared) {
    const auto samples = synthetic::freeRotors(50, 30, 0.2, 30.0, kT, mass, inertia, 2);
    double v2 = 0.0; // Å²/ps²
    for (const Vec3& v : samples[0].velocity)
        v2 += v.squaredNorm() / units::toPs(1.0) / units::toPs(1.0);
    v2 /= samples[0].size();
    const auto msd = meanSquaredDisplacement(samples, 24, 5);
    for (std::size_t k = 0; k < msd.value.size(); ++k) {
        const double exact = v2 * msd.tPs[k] * msd.tPs[k];
        EXPECT_NEAR(msd.value[k], exact, msdRelativeTolerance * (exact + 1.0)) << "lag " << k;
    }
}

TEST(DirectCorrelations, MsdEqualsDirectSumOverOriginsAndBodies) {
    const int t = 80, n = 12, maxLag = 39, blocks = 4;
    const auto samples = synthetic::randomWalk(t, n, 0.1, 20.0, 0.3, 3);
    const auto msd = meanSquaredDisplacement(samples, maxLag, blocks);

    for (int k = 0; k <= maxLag; ++k) {
        double sum = 0.0;
        for (int t0 = 0; t0 + k < t; ++t0)
            for (int i = 0; i < n; ++i)
                sum += (samples[t0 + k].position[i] - samples[t0].position[i]).squaredNorm();
        // Pooled over blocks of bodies weighted by their origins: all origins at once.
        EXPECT_NEAR(msd.value[k], sum / ((t - k) * n), roundOff * (1.0 + sum / ((t - k) * n)));
        for (int g = 0; g < blocks; ++g) // blocks of n/B = 3 bodies, all origins
            EXPECT_EQ(msd.fineWeight[g][k], 3.0 * (t - k));
    }
}

TEST(DirectCorrelations, DiffusionCoefficientOfARandomWalk) {
    const double d = 0.05; // Å² per time unit = 0.5 Å²/ps
    const auto samples = synthetic::randomWalk(400, 200, 0.1, 40.0, d, 4);
    const auto msd = meanSquaredDisplacement(samples, 199, 8);
    const Diffusion fit = diffusionFromMsd(msd);
    const double exact = d / units::toPs(1.0);
    EXPECT_GT(fit.err, 0.0);
    EXPECT_NEAR(fit.coefficient, exact, diffusionSigmas * fit.err);
    EXPECT_LT(fit.err, 0.1 * exact); // 200 bodies × 400 samples pin D to better than 10 %
    EXPECT_NEAR(fit.fromPs, 49 * 0.01, 1e-12);
    EXPECT_NEAR(fit.toPs, 149 * 0.01, 1e-12);
}

TEST(DirectCorrelations, RotorCurveClosedFormMatchesRayleighQuadrature) {
    for (double x : {0.0, 0.3, 1.0, 1.7, 2.5, 4.0, 6.0})
        EXPECT_NEAR(rotorCos(x), rotorCosQuadrature(x), 1e-9) << "x = " << x;
    EXPECT_LT(rotorCos(2.5), 0.0); // the anti-correlation of free rotors
}

TEST(DirectCorrelations, OacfOfFreeRotorsEqualsTheirSampleAverageExactly) {
    const int t = 40, n = 50;
    const double h = 0.05;
    const auto samples = synthetic::freeRotors(t, n, h, 30.0, kT, mass, inertia, 5);
    const auto oacf = orientationalAutocorrelation(samples, 19, 4);
    for (int k = 0; k <= 19; ++k) {
        double c1 = 0.0, c2 = 0.0; // free rotors: s(0)·s(t) = cos(|ω| t) from any origin
        for (int i = 0; i < n; ++i) {
            const double c = std::cos(samples[0].omega[i].norm() * k * h);
            c1 += c / n, c2 += 0.5 * (3.0 * c * c - 1.0) / n;
        }
        EXPECT_NEAR(oacf.c1.value[k], c1, roundOff) << "lag " << k;
        EXPECT_NEAR(oacf.c2.value[k], c2, roundOff) << "lag " << k;
    }
    EXPECT_NEAR(oacf.c1.value[0], 1.0, roundOff);
    EXPECT_NEAR(oacf.c2.value[0], 1.0, roundOff);
}

TEST(DirectCorrelations, OacfOfMaxwellBoltzmannRotorsMatchesAnalyticForm) {
    const int t = 100, n = 20000;
    const double h = 0.05; // 5 fs; x reaches 49 · 0.05 · 1.91 ≈ 4.7, past the minimum
    const auto samples = synthetic::freeRotors(t, n, h, 60.0, kT, mass, inertia, 6);
    const int maxLag = lagFor(0.0, units::toPs(h), t, 2);
    ASSERT_EQ(maxLag, 49);
    const auto oacf = orientationalAutocorrelation(samples, maxLag, 2);
    const double tolerance = boundedSigmas / std::sqrt(n);
    for (int k = 0; k <= maxLag; ++k) {
        const double x = k * h * std::sqrt(kT / inertia);
        EXPECT_NEAR(oacf.c1.value[k], rotorCos(x), tolerance) << "x = " << x;
        EXPECT_NEAR(oacf.c2.value[k], rotorP2(x), tolerance) << "x = " << x;
    }
}

TEST(DirectCorrelations, CoarseBlocksHaveEqualOriginsInTimeOrder) {
    // Fine blocks of 10 origins, the last three empty at this lag: 5 valid → groups 0,0,1,1,1?
    // Midpoints 5, 15, 25, 35, 45 of 50 origins, two coarse blocks: 0, 0, 1, 1, 1.
    const std::vector<int> two = coarseBlocks({10, 10, 10, 10, 10, 0, 0, 0}, 2);
    EXPECT_EQ(two, (std::vector<int>{0, 0, 1, 1, 1, -1, -1, -1}));
    const std::vector<int> four = coarseBlocks({10, 10, 10, 10, 10, 10, 10, 4}, 4);
    EXPECT_EQ(four, (std::vector<int>{0, 0, 1, 1, 2, 2, 3, 3}));
}

TEST(DirectCorrelations, ErrorBarsAreHonestOutToTheLongestLag) {
    // Ornstein–Uhlenbeck velocities, VACF e^{−γt} exactly known. With B blocks, (c − exact)/err
    // is Student-t with B − 1 degrees of freedom: ⟨z²⟩ = (B − 1)/(B − 3) = 1.4 for B = 8, at
    // short and at long lags alike (fixed blocks of origins give ~2 beyond one block length).
    const double rate = 0.5, h = 0.1;
    double shortLags = 0.0, longLags = 0.0;
    int nShort = 0, nLong = 0;
    for (std::uint64_t seed = 1; seed <= 4; ++seed) {
        const auto samples = synthetic::ornsteinUhlenbeck(1000, 60, h, 30.0, kT, mass, rate, seed);
        const auto vacf = velocityAutocorrelation(samples, 499, 8);
        for (int k = 1; k <= 499; ++k) {
            const double z = (vacf.value[k] - std::exp(-rate * h * k)) / vacf.err[k];
            if (k < 125)
                shortLags += z * z, ++nShort;
            else
                longLags += z * z, ++nLong;
        }
    }
    EXPECT_NEAR(shortLags / nShort, 1.4, tDistributionSpread);
    EXPECT_NEAR(longLags / nLong, 1.4, tDistributionSpread);
}

TEST(DirectCorrelations, SpheresDoNotRotateRodsDo) {
    auto samples = synthetic::emptySamples(10, 3, 0.1, 10.0);
    EXPECT_FALSE(axesRotate(samples));
    EXPECT_TRUE(axesRotate(synthetic::freeRotors(10, 3, 0.1, 10.0, kT, mass, inertia, 7)));
}

TEST(DirectCorrelations, RejectsUnequalSpacingAndTooLongLags) {
    auto samples = synthetic::freeRotors(20, 3, 0.1, 10.0, kT, mass, inertia, 8);
    EXPECT_THROW(velocityAutocorrelation(samples, largestLag(20, 4) + 1, 4), std::invalid_argument);
    EXPECT_THROW(velocityAutocorrelation(samples, 5, 1), std::invalid_argument);
    EXPECT_EQ(lagFor(10.0, 0.01, 20, 4), largestLag(20, 4));
    samples[7].time += 0.01;
    EXPECT_THROW(sampleIntervalPs(samples), std::invalid_argument);
}

} // namespace test_direct_correlations
