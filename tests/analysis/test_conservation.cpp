// Energy-conservation statistics on synthetic series with known answers.
#include "analysis/conservation.hpp"
#include <cmath>
#include <gtest/gtest.h>
#include <random>

namespace test_conservation {

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

namespace {

/// The statistics by two passes about the mean in extended precision (long double: 64-bit
/// mantissa, x87), the reference the streamed ones are judged against.
EnergyStats twoPass(const std::vector<double>& t, const std::vector<double>& e,
                    const std::vector<double>& u) {
    using real = long double;
    const real n = real(e.size());
    real tm = 0, em = 0, um = 0;
    for (std::size_t k = 0; k < e.size(); ++k)
        tm += t[k], em += e[k], um += u[k];
    tm /= n, em /= n, um /= n;
    real see = 0, stt = 0, ste = 0, suu = 0;
    for (std::size_t k = 0; k < e.size(); ++k) {
        see += (e[k] - em) * (e[k] - em), stt += (t[k] - tm) * (t[k] - tm);
        ste += (t[k] - tm) * (e[k] - em), suu += (u[k] - um) * (u[k] - um);
    }
    EnergyStats s{};
    s.mean = double(em), s.std = double(std::sqrt(see / n)), s.driftPerPs = double(ste / stt);
    s.potentialMean = double(um), s.potentialStd = double(std::sqrt(suu / n));
    return s;
}

} // namespace

// Record by record, the running centred sums give what two passes in extended precision give, to
// round-off, on a series whose drift (1e-6 per ps) is tiny beside its energy (1e5) and its
// fluctuations (1e-3): raw sums of squares would lose it all, and running sums about the running
// mean alone lose 8 of the 16 digits of the spread (measured: 4e-9 of it, 4e-6 of the slope).
TEST(EnergyStats, StreamedAsAccurateAsTwoPasses) {
    std::mt19937_64 rng(3);
    std::normal_distribution<double> noise(0.0, 1e-3);
    std::vector<double> t, e, u;
    for (int k = 0; k < 20000; ++k) {
        t.push_back(0.005 * k);
        e.push_back(1e5 + 1e-6 * t.back() + noise(rng));
        u.push_back(-2e5 + 50.0 * noise(rng));
    }
    const EnergyStats s = energyStats(t, e, u), r = twoPass(t, e, u);
    // The means are plain sums of 2·10⁴ terms (their round-off, ~1e-14); the spreads and the
    // slope keep the digits of the fluctuations.
    EXPECT_NEAR(s.mean, r.mean, 1e-13 * 1e5);
    EXPECT_NEAR(s.potentialMean, r.potentialMean, 1e-13 * 2e5);
    EXPECT_NEAR(s.std, r.std, 1e-12 * r.std);
    EXPECT_NEAR(s.potentialStd, r.potentialStd, 1e-12 * r.potentialStd);
    EXPECT_NEAR(s.driftPerPs, r.driftPerPs, 1e-10 * r.driftPerPs);
    EXPECT_NEAR(s.driftPerPs, 1e-6, 5.0 * 1e-3 * std::sqrt(12.0) / (100.0 * std::sqrt(2e4)));
}

// Its state, written after some records and read back, goes on to the same bits as the
// accumulator that never stopped, and is the same size after 1 record as after 10⁴.
TEST(EnergyStats, TheAccumulatorsStateGoesOnToTheSameBits) {
    std::mt19937_64 rng(9);
    std::normal_distribution<double> noise(0.0, 0.5);
    EnergyAccumulator whole, stopped;
    for (int k = 0; k < 10000; ++k) {
        const double t = 0.01 * k, e = -800.0 + noise(rng), u = -1500.0 + noise(rng);
        whole.add(t, e, u), stopped.add(t, e, u);
        if (k == 4321) { // through its bytes into a new accumulator
            StateWriter out;
            stopped.write(out);
            const auto bytes = out.take();
            stopped = EnergyAccumulator();
            StateReader in(bytes);
            stopped.read(in);
            in.finish();
        }
    }
    StateWriter a, b;
    whole.write(a), stopped.write(b);
    const auto x = a.take(), y = b.take();
    EXPECT_EQ(x, y);
    StateWriter one;
    EnergyAccumulator single;
    single.add(0.0, 1.0, 1.0);
    single.write(one);
    EXPECT_EQ(one.take().size(), x.size());
    EXPECT_THROW(EnergyAccumulator().stats(), std::invalid_argument);
}

} // namespace test_conservation
