// summary.json's statistics of the samples taken one by one (cli/sample_statistics.hpp): on a run
// that takes its planned samples they are the block means and errors of the whole series, bit for
// bit; their state, a fixed size, goes on to the same summary; a state of another plan is refused.
#include "analysis/block_average.hpp"
#include "analysis/canonical_kinetic.hpp"
#include "analysis/conservation.hpp"
#include "cli/sample_statistics.hpp"
#include "cli/thermo.hpp"
#include "core/units.hpp"
#include <cmath>
#include <gtest/gtest.h>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace test_sample_statistics {

using namespace terrace;
using cli::SampleRecord;
using cli::VirialKind;

namespace {

constexpr double volume = 27000.0, sigma = 3.035, epsilon = 3.0;

/// A DMD-like series: energies that fluctuate, a growing impulse virial and collision count, the
/// continuous sums on every third sample (the g(r) frames).
std::vector<SampleRecord> series(int n, unsigned seed) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> d(0.0, 1.0);
    std::vector<SampleRecord> s(static_cast<std::size_t>(n));
    double w = 0.0, c = 0.0;
    for (int k = 0; k < n; ++k) {
        SampleRecord& e = s[std::size_t(k)];
        e.time = 0.09 * (k + 1), e.tPs = units::toPs(0.09 * k);
        e.kinetic = 800.0 + 20.0 * d(rng), e.kineticTranslational = 500.0 + 15.0 * d(rng);
        e.potential = -1200.0 + 20.0 * d(rng), e.total = e.kinetic + e.potential;
        e.virial = w += 300.0 + 40.0 * d(rng);
        e.collisions = c += std::round(1000.0 + 30.0 * d(rng));
        if (k % 3 == 0)
            e.continuousPotential = -1180.0 + 25.0 * d(rng), e.continuousVirial = -700.0 + d(rng);
    }
    return s;
}

double err(const analysis::Estimate& e) {
    return e.err;
}

} // namespace

// A run that takes its 50 planned samples: every block mean and error as computed from the whole
// series in 8 contiguous blocks (the configurational ones over the 17 g(r) frames).
TEST(SampleStatistics, AWholeRunGivesTheBlockStatisticsOfItsSeries) {
    const auto s = series(50, 1);
    const cli::SamplePlan plan{50, 17, VirialKind::Impulse, volume, 9 * 64 - 3};
    cli::SampleStatistics stats(plan);
    for (const auto& e : s)
        stats.add(e);
    nlohmann::json j;
    stats.summarise(j, sigma, epsilon);
    std::vector<double> kinetic, potential, pressure, kin, vir, collisions, u, p;
    for (std::size_t k = 0; k < s.size(); ++k) {
        kinetic.push_back(s[k].kinetic), potential.push_back(s[k].potential);
        if (k > 0) {
            const auto t = cli::pressureTerms(s[k], s[k - 1], VirialKind::Impulse, volume);
            pressure.push_back(t.kinetic + t.virial), kin.push_back(t.kinetic);
            vir.push_back(t.virial);
            collisions.push_back(s[k].collisions - s[k - 1].collisions);
        }
        if (std::isfinite(s[k].continuousPotential)) {
            u.push_back(s[k].continuousPotential);
            p.push_back(virialPressure(s[k].kineticTranslational, s[k].continuousVirial, volume));
        }
    }
    const auto blocks = [](const std::vector<double>& x) {
        return analysis::blockMean(x, cli::pressureBlocks);
    };
    EXPECT_EQ(j["temperature_err_K"].get<double>(),
              units::kelvin(2.0 * err(blocks(kinetic)) / plan.dof));
    EXPECT_EQ(j["potential_energy_err"].get<double>(), err(blocks(potential)));
    EXPECT_EQ(j["pressure"]["mean_bar"].get<double>(), units::bar(blocks(pressure).mean));
    EXPECT_EQ(j["pressure"]["error_bar"].get<double>(), units::bar(err(blocks(pressure))));
    EXPECT_EQ(j["pressure"]["samples"], 49);
    double kinSum = 0.0;
    for (double x : kin)
        kinSum += x;
    EXPECT_EQ(j["pressure"]["kinetic_term_reduced"].get<double>(),
              reducedPressure(kinSum / 49.0, sigma, epsilon));
    EXPECT_EQ(j["configurational"]["frames"], 17);
    EXPECT_EQ(j["configurational"]["blocks"], 8);
    EXPECT_EQ(j["configurational"]["potential_energy_mean"].get<double>(), blocks(u).mean);
    EXPECT_EQ(j["configurational"]["potential_energy_err"].get<double>(), err(blocks(u)));
    EXPECT_EQ(j["configurational"]["pressure_err_bar"].get<double>(), units::bar(err(blocks(p))));
    const double dtPs = 0.125;
    EXPECT_EQ(stats.collisionRateError(dtPs).get<double>(), err(blocks(collisions)) / dtPs);
    EXPECT_NEAR(j["energy"]["initial"].get<double>(), s.front().total, 0.0);
    EXPECT_NEAR(j["energy"]["final"].get<double>(), s.back().total, 0.0);
    EXPECT_EQ(stats.count(), 50);
}

// Stopped after 23 samples, its state read back into statistics of the same plan goes on to the
// same summary, byte for byte, as the statistics that never stopped; the state is as large after
// 1 sample as after 49.
TEST(SampleStatistics, ItsStateGoesOnToTheSameSummary) {
    const auto s = series(50, 2);
    const cli::SamplePlan plan{50, 17, VirialKind::Impulse, volume, 100};
    cli::SampleStatistics whole(plan), first(plan);
    first.add(s[0]);
    const std::size_t size = first.state().size();
    for (std::size_t k = 1; k < 23; ++k)
        first.add(s[k]);
    EXPECT_EQ(first.state().size(), size);
    cli::SampleStatistics second(plan);
    second.restore(first.state());
    EXPECT_EQ(second.count(), 23);
    for (std::size_t k = 0; k < s.size(); ++k) {
        whole.add(s[k]);
        if (k >= 23) second.add(s[k]);
    }
    EXPECT_EQ(second.state().size(), size);
    nlohmann::json a, b;
    whole.summarise(a, sigma, epsilon), second.summarise(b, sigma, epsilon);
    EXPECT_EQ(a.dump(), b.dump());
    EXPECT_EQ(whole.collisionRateError(0.125).dump(), second.collisionRateError(0.125).dump());
    EXPECT_LT(size, 2048u) << "the state of 50 samples";
}

// Under a heat bath: the effective energy H + bath is the whole series' (the same accumulator),
// the bath's energy removed is its last value less its first, and ⟨K⟩, Var K with their errors are
// those of 8 contiguous blocks of K and of (K − K̄)² over the whole series, though K̄ is known only
// at the end. The wander warned about is the conserved energy's: not H's under the bath, which
// takes up H's fluctuation here, but H's without it, and the effective energy's when it drifts.
TEST(SampleStatistics, UnderAHeatBathTheEffectiveEnergyAndVarianceAreThoseOfTheWholeSeries) {
    auto s = series(50, 4);
    // The bath takes up H's fluctuation (effective energy within 0.1 kJ/mol of its start); the
    // drifting copy adds 0.7 kJ/mol a sample, 34 kJ/mol in all against 1 % of ⟨K⟩, 8 kJ/mol.
    auto drifting = s;
    for (std::size_t k = 0; k < s.size(); ++k) {
        s[k].bath = 3.0 - (s[k].total - s[0].total) + 0.1 * std::sin(double(k));
        drifting[k].bath = s[k].bath + 0.7 * double(k);
    }
    const double kT = 16.0; // (f/2) kT = 800 = ⟨K⟩
    const cli::SamplePlan plan{50, 17, VirialKind::Impulse, volume, 100, kT, true};
    cli::SampleStatistics stats(plan), drift(plan),
        nve(cli::SamplePlan{50, 17, VirialKind::Impulse, volume, 100, kT, false});
    for (const auto& e : drifting)
        drift.add(e);
    std::vector<double> t, effective, potential, kinetic;
    for (const auto& e : s) {
        stats.add(e), nve.add(e);
        t.push_back(e.tPs), effective.push_back(e.total + e.bath);
        potential.push_back(e.potential), kinetic.push_back(e.kinetic);
    }
    const analysis::EnergyStats want = analysis::energyStats(t, effective, potential);
    const analysis::EnergyStats got = stats.effectiveEnergy();
    EXPECT_EQ(got.initial, want.initial);
    EXPECT_EQ(got.final, want.final);
    EXPECT_EQ(got.std, want.std);
    EXPECT_EQ(got.maxAbsDev, want.maxAbsDev);
    EXPECT_EQ(got.driftPerPs, want.driftPerPs);
    EXPECT_DOUBLE_EQ(stats.bathEnergyRemoved(), s.back().bath - s.front().bath);

    const analysis::Estimate mean = analysis::blockMean(kinetic, 8);
    std::vector<double> squared;
    for (const double k : kinetic)
        squared.push_back((k - mean.mean) * (k - mean.mean));
    const analysis::Estimate variance = analysis::blockMean(squared, 8);
    const analysis::CanonicalKinetic c = stats.canonicalKinetic();
    EXPECT_EQ(c.mean.mean, mean.mean);
    EXPECT_EQ(c.mean.err, mean.err);
    EXPECT_NEAR(c.variance.mean, variance.mean, 1e-10 * variance.mean);
    EXPECT_NEAR(c.variance.err, variance.err, 1e-8 * variance.err);
    EXPECT_DOUBLE_EQ(c.canonicalMean, 800.0);
    EXPECT_DOUBLE_EQ(c.canonicalVariance, 50.0 * kT * kT);

    nlohmann::json bath, plain, drifted;
    stats.summarise(bath, sigma, epsilon), nve.summarise(plain, sigma, epsilon);
    drift.summarise(drifted, sigma, epsilon);
    EXPECT_FALSE(bath.contains("warnings")) << bath["warnings"].dump();
    ASSERT_TRUE(plain.contains("warnings"));
    EXPECT_NE(plain["warnings"][0].get<std::string>().find("total energy wandered"),
              std::string::npos);
    ASSERT_TRUE(drifted.contains("warnings"));
    EXPECT_NE(drifted["warnings"][0].get<std::string>().find("effective energy (H + the energy "
                                                             "the heat bath removed) wandered"),
              std::string::npos);
}

// Kinetic energies drawn from the canonical Gamma(f/2, kT) are found canonical: ⟨K⟩ and Var K
// within 3 errors of (f/2) kT and (f/2)(kT)²; drawn at 1.1 kT they are not, by many errors. At
// ⟨K⟩ ~ 10⁶ kJ/mol (10⁶ bodies) the variance keeps its digits.
TEST(SampleStatistics, CanonicalKineticEnergiesAreFoundCanonical) {
    for (const double scale : {1.0, 1.1}) {
        for (const int f : {597, 3000000}) {
            const double kT = 2.5;
            const long n = 4000;
            std::mt19937_64 rng(11);
            std::gamma_distribution<double> gamma(0.5 * f, scale * kT);
            cli::SampleStatistics stats(
                cli::SamplePlan{n, 0, VirialKind::Instantaneous, volume, f, kT, true});
            for (long k = 0; k < n; ++k) {
                SampleRecord e;
                e.tPs = 0.01 * double(k), e.kinetic = gamma(rng), e.total = e.kinetic;
                stats.add(e);
            }
            const analysis::CanonicalKinetic c = stats.canonicalKinetic();
            SCOPED_TRACE("f " + std::to_string(f) + ", kT × " + std::to_string(scale));
            if (scale == 1.0) {
                EXPECT_LT(std::abs(c.meanDeviation()), 3.0);
                EXPECT_LT(std::abs(c.varianceDeviation()), 3.0);
            } else {
                EXPECT_GT(c.meanDeviation(), 10.0);
                EXPECT_GT(c.varianceDeviation(), 5.0);
            }
        }
    }
}

// A state written for another plan (more samples, other frames), cut short or grown is refused;
// a sample beyond the plan is refused.
TEST(SampleStatistics, AStateOfAnotherPlanIsRefused) {
    const auto s = series(10, 3);
    cli::SampleStatistics stats(cli::SamplePlan{10, 4, VirialKind::Impulse, volume, 100});
    for (const auto& e : s)
        stats.add(e);
    SampleRecord beyond = s.back();
    beyond.tPs += 1.0, beyond.time += 1.0;
    EXPECT_THROW(stats.add(beyond), std::out_of_range);
    const auto bytes = stats.state();
    cli::SampleStatistics longer(cli::SamplePlan{20, 4, VirialKind::Impulse, volume, 100});
    EXPECT_THROW(longer.restore(bytes), std::invalid_argument);
    cli::SampleStatistics otherFrames(cli::SamplePlan{10, 5, VirialKind::Impulse, volume, 100});
    EXPECT_THROW(otherFrames.restore(bytes), std::invalid_argument);
    cli::SampleStatistics same(cli::SamplePlan{10, 4, VirialKind::Impulse, volume, 100});
    auto cut = bytes;
    cut.pop_back();
    EXPECT_THROW(same.restore(cut), std::invalid_argument);
    auto grown = bytes;
    grown.push_back(0);
    EXPECT_THROW(same.restore(grown), std::invalid_argument);
    same.restore(bytes);
    EXPECT_EQ(same.count(), 10);
}

// No sample: nothing but the configurational frames (0) is reported.
TEST(SampleStatistics, NoSampleReportsNothing) {
    cli::SampleStatistics stats(cli::SamplePlan{5, 0, VirialKind::Instantaneous, volume, 100});
    nlohmann::json j = nlohmann::json::object();
    stats.summarise(j, sigma, epsilon);
    EXPECT_EQ(j.dump(), R"({"configurational":{"frames":0}})");
    EXPECT_TRUE(stats.collisionRateError(0.1).is_null());
}

} // namespace test_sample_statistics
