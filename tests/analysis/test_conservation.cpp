// Energy-conservation statistics on synthetic series with known answers.
#include "analysis/conservation.hpp"
#include <cmath>
#include <gtest/gtest.h>
#include <random>

using namespace terrace::analysis;

namespace {

/// Sums of a few hundred terms of size ~1e3: round-off.
constexpr double roundOff = 1e-10;

} // namespace

TEST(EnergyStats, LinearDriftIsTheSlope) {
    std::vector<double> t, e, u;
    for (int k = 0; k <= 100; ++k) { // t = 0 … 10 ps
        t.push_back(0.1 * k);
        e.push_back(-1200.0 + 0.25 * t.back());
        u.push_back(-2000.0);
    }
    const EnergyStats s = energyStats(t, e, u);
    EXPECT_NEAR(s.driftPerPs, 0.25, roundOff);
    EXPECT_DOUBLE_EQ(s.initial, -1200.0);
    EXPECT_NEAR(s.final, -1197.5, roundOff);
    EXPECT_NEAR(s.mean, -1198.75, roundOff);
    EXPECT_NEAR(s.maxAbsDev, 2.5, roundOff);
    // std of an equally spaced ramp of n points and step δ: δ √((n² − 1)/12)
    const double std = 0.025 * std::sqrt((101.0 * 101.0 - 1.0) / 12.0);
    EXPECT_NEAR(s.std, std, roundOff);
    EXPECT_NEAR(s.relFluct, std / 2000.0, roundOff);
}

TEST(EnergyStats, NoiseWithoutTrendHasNoDrift) {
    std::mt19937_64 rng(5);
    std::normal_distribution<double> noise(0.0, 0.5);
    std::vector<double> t, e, u;
    for (int k = 0; k < 10000; ++k) {
        t.push_back(0.01 * k);
        e.push_back(-800.0 + noise(rng));
        u.push_back(-1500.0 + 10.0 * noise(rng));
    }
    const EnergyStats s = energyStats(t, e, u);
    // Slope error of white noise σ over n points spanning T: σ √12 / (T √n) ≈ 0.0017 per ps.
    EXPECT_LT(std::abs(s.driftPerPs), 5.0 * 0.5 * std::sqrt(12.0) / (100.0 * 100.0));
    EXPECT_NEAR(s.std, 0.5, 0.02);               // 10⁴ draws: std known to ~0.7 %
    EXPECT_NEAR(s.relFluct, 0.5 / 1500.0, 2e-5); // the paper's ratio, std(E)/|⟨U⟩|
    EXPECT_GT(s.maxAbsDev, 3.0 * 0.5);           // 10⁴ normal draws reach beyond 3σ
}

TEST(EnergyStats, ConstantEnergyAndZeroPotential) {
    const EnergyStats s = energyStats({0.0, 1.0, 2.0}, {5.0, 5.0, 5.0}, {0.0, 0.0, 0.0});
    EXPECT_EQ(s.std, 0.0);
    EXPECT_EQ(s.relFluct, 0.0);
    EXPECT_EQ(s.driftPerPs, 0.0);
    const EnergyStats g = energyStats({0.0, 1.0}, {5.0, 6.0}, {0.0, 0.0});
    EXPECT_TRUE(std::isinf(g.relFluct)); // an ideal gas has no potential energy to compare with
    const EnergyStats one = energyStats({0.0}, {5.0}, {-1.0});
    EXPECT_EQ(one.driftPerPs, 0.0);
}

TEST(EnergyStats, RejectsMismatchedOrEmptySeries) {
    EXPECT_THROW(energyStats({}, {}, {}), std::invalid_argument);
    EXPECT_THROW(energyStats({0.0, 1.0}, {1.0}, {1.0, 1.0}), std::invalid_argument);
    EXPECT_THROW(energyStats({1.0, 1.0}, {1.0, 1.0}, {1.0, 1.0}), std::invalid_argument);
}
