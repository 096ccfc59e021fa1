// VACF, OACF and MSD of samples whose correlations are known exactly or analytically.
#include "analysis/dynamic_correlations.hpp"
#include "analysis/time_correlation.hpp"
#include "synthetic_samples.hpp"
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>
#include <gtest/gtest.h>

using namespace terrace;
using namespace terrace::analysis;

namespace {

/// Exact identities (VACF of free flight, averages the code must reproduce sample by sample):
/// round-off of FFT sums over a few thousand terms.
constexpr double roundOff = 1e-12;
/// MSD of free flight: |r(t) − r(0)|² from unwrapped positions of ~100 Å loses ~1e-14 relative
/// to cancellation, amplified by the FFT; 1e-9 relative still catches any wrong lag or weight.
constexpr double msdRelativeTolerance = 1e-9;
/// Statistical check of an average over N bodies of a quantity bounded by 1 in magnitude:
/// 5 standard errors of the mean (its standard deviation is at most 1).
constexpr double boundedSigmas = 5.0;
/// Estimated D against the true one, in units of the block error (7 degrees of freedom: a
/// Student-t beyond 4.5 happens with probability ~0.3 %).
constexpr double diffusionSigmas = 4.5;
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

TEST(DynamicCorrelations, VacfOfFreeParticlesIsOne) {
    const auto samples = synthetic::freeRotors(60, 40, 0.1, 30.0, kT, mass, inertia, 1);
    const auto vacf = velocityAutocorrelation(samples, 29, 4);
    for (std::size_t k = 0; k < vacf.value.size(); ++k) {
        EXPECT_NEAR(vacf.value[k], 1.0, roundOff) << "lag " << k;
        EXPECT_NEAR(vacf.err[k], 0.0, roundOff);
        EXPECT_NEAR(vacf.tPs[k], k * 0.01, 1e-15); // 0.1 time units = 10 fs
    }
}

TEST(DynamicCorrelations, MsdOfFreeFlightIsMeanSquareSpeedTimesTimeSquared) {
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

TEST(DynamicCorrelations, MsdEqualsDirectSumOverOriginsAndBodies) {
    const int t = 80, n = 12, maxLag = 39, blocks = 4;
    const auto samples = synthetic::randomWalk(t, n, 0.1, 20.0, 0.3, 3);
    const auto msd = meanSquaredDisplacement(samples, maxLag, blocks);
    const OriginBlocks o{t, maxLag, blocks};
    for (int k = 0; k <= maxLag; ++k) {
        double sum = 0.0;
        for (int t0 = 0; t0 + k < t; ++t0)
            for (int i = 0; i < n; ++i)
                sum += (samples[t0 + k].position[i] - samples[t0].position[i]).squaredNorm();
        // Pooled over blocks with origin weights = all origins at once.
        EXPECT_NEAR(msd.value[k], sum / ((t - k) * n), roundOff * (1.0 + sum / ((t - k) * n)));
        for (int b = 0; b < blocks; ++b)
            EXPECT_EQ(msd.blockWeight[b][k], o.origins(b, k));
    }
}

TEST(DynamicCorrelations, DiffusionCoefficientOfARandomWalk) {
    const double d = 0.05; // Å² per time unit = 0.5 Å²/ps
    const auto samples = synthetic::randomWalk(400, 200, 0.1, 40.0, d, 4);
    const auto msd = meanSquaredDisplacement(samples, 199, 8);
    const Diffusion fit = diffusionFromMsd(msd);
    const double exact = d / units::toPs(1.0);
    EXPECT_GT(fit.err, 0.0);
    EXPECT_NEAR(fit.coefficient, exact, diffusionSigmas * fit.err);
    EXPECT_LT(fit.err, 0.05 * exact); // 200 bodies × 400 samples pin D to a few per cent
    EXPECT_NEAR(fit.fromPs, 49 * 0.01, 1e-12);
    EXPECT_NEAR(fit.toPs, 149 * 0.01, 1e-12);
}

TEST(DynamicCorrelations, RotorCurveClosedFormMatchesRayleighQuadrature) {
    for (double x : {0.0, 0.3, 1.0, 1.7, 2.5, 4.0, 6.0})
        EXPECT_NEAR(rotorCos(x), rotorCosQuadrature(x), 1e-9) << "x = " << x;
    EXPECT_LT(rotorCos(2.5), 0.0); // the anti-correlation of free rotors
}

TEST(DynamicCorrelations, OacfOfFreeRotorsEqualsTheirSampleAverageExactly) {
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

TEST(DynamicCorrelations, OacfOfMaxwellBoltzmannRotorsMatchesAnalyticForm) {
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

TEST(DynamicCorrelations, SpheresDoNotRotateRodsDo) {
    auto samples = synthetic::emptySamples(10, 3, 0.1, 10.0);
    EXPECT_FALSE(axesRotate(samples));
    EXPECT_TRUE(axesRotate(synthetic::freeRotors(10, 3, 0.1, 10.0, kT, mass, inertia, 7)));
}

TEST(DynamicCorrelations, RejectsUnequalSpacingAndTooLongLags) {
    auto samples = synthetic::freeRotors(20, 3, 0.1, 10.0, kT, mass, inertia, 8);
    EXPECT_THROW(velocityAutocorrelation(samples, largestLag(20, 4) + 1, 4), std::invalid_argument);
    EXPECT_THROW(velocityAutocorrelation(samples, 5, 1), std::invalid_argument);
    EXPECT_EQ(lagFor(10.0, 0.01, 20, 4), largestLag(20, 4));
    samples[7].time += 0.01;
    EXPECT_THROW(sampleIntervalPs(samples), std::invalid_argument);
}
