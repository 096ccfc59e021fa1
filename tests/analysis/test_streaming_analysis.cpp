// The product's streaming analysis against the reference (all samples in memory, every pair,
// direct sums over every origin): g(r) count for count, the time correlations within round-off
// on the lags where both use every origin (the FFT windows), exact sums over the origins they
// use on the coarser multiple-tau levels, and agreement within error of what both estimate.
#include "analysis/csv.hpp"
#include "analysis/rdf_accumulator.hpp"
#include "analysis/reference/all_pairs_rdf.hpp"
#include "analysis/reference/direct_correlations.hpp"
#include "analysis/run_analysis.hpp"
#include "analysis/streaming_correlations.hpp"
#include "core/units.hpp"
#include "synthetic_samples.hpp"
#include <cmath>
#include <gtest/gtest.h>
#include <map>
#include <unistd.h>

namespace test_streaming_analysis {

using namespace terrace;
using namespace terrace::analysis;
using namespace terrace::analysis::reference;
namespace fs = std::filesystem;

namespace {

/// Sums of the same terms in another order, or by FFT.
constexpr double roundOff = 1e-12;
/// Block errors are spreads of nearly equal block values: round-off of the values, amplified.
constexpr double errRoundOff = 1e-9;
/// CSV values against the reference's: 17 digits written, each side's round-off as above.
constexpr double fileRoundOff = 1e-9;
/// MSD by FFT of displacements (Å, from the window's first sample) against direct sums, Å².
constexpr double msdRoundOff = 1e-9;

bool near(double a, double b, double relative) {
    return std::abs(a - b) <= relative * std::max({1.0, std::abs(a), std::abs(b)});
}

StreamingCorrelations fed(const std::vector<Snapshot>& samples, int maxLag, int blocks,
                          int lagsPerLevel = 16, int follow = 0) {
    StreamingCorrelationPlan plan;
    plan.samples = static_cast<long>(samples.size());
    plan.maxLag = maxLag;
    plan.blocks = blocks;
    plan.lagsPerLevel = lagsPerLevel;
    plan.followBodies = follow;
    StreamingCorrelations c(samples.front().size(), sampleIntervalPs(samples), plan);
    for (const auto& s : samples)
        c.add(s);
    return c;
}

struct ScratchDirectory {
    fs::path path;
    explicit ScratchDirectory(const std::string& name)
        : path(fs::temp_directory_path() /
               ("terrace_streaming_" + name + "_" + std::to_string(::getpid()))) {
        fs::remove_all(path);
    }
    ~ScratchDirectory() { fs::remove_all(path); }
};

} // namespace

TEST(RdfAccumulator, OutToHalfTheBoxCountsWhatTheReferenceCounts) {
    const auto samples = synthetic::freeRotors(40, 300, 0.1, 20.0, 4.2, 18.0, 1.154, 3);
    const RadialDistribution allPairs = radialDistribution(samples, 0.1, 8);
    RdfAccumulator acc(300, 20.0, 0.1, 10.0, 40, 8);
    for (const auto& s : samples)
        acc.add(s);
    const RadialDistribution streamed = acc.result();
    ASSERT_EQ(streamed.r.size(), allPairs.r.size());
    for (std::size_t k = 0; k < allPairs.r.size(); ++k) {
        EXPECT_EQ(streamed.g[k], allPairs.g[k]) << "bin " << k;
        EXPECT_EQ(streamed.err[k], allPairs.err[k]) << "bin " << k;
    }
}

TEST(RdfAccumulator, CellListFindsEveryPairWithinItsRange) {
    // r_max = L/5: five cells per side, so pairs are found through neighbouring cells only;
    // every bin must hold what the all-pairs count puts there.
    const auto samples = synthetic::freeRotors(12, 2000, 0.1, 30.0, 4.2, 18.0, 1.154, 5);
    const RadialDistribution all = radialDistribution(samples, 0.05, 4);
    RdfAccumulator acc(2000, 30.0, 0.05, 6.0, 12, 4);
    for (const auto& s : samples)
        acc.add(s);
    const RadialDistribution near6 = acc.result();
    ASSERT_EQ(near6.r.size(), 120u);
    EXPECT_DOUBLE_EQ(acc.rMax(), 6.0);
    for (std::size_t k = 0; k < near6.r.size(); ++k) {
        EXPECT_TRUE(near(near6.g[k], all.g[k], roundOff)) << "bin " << k;
        EXPECT_TRUE(near(near6.err[k], all.err[k], errRoundOff)) << "bin " << k;
    }
}

TEST(RdfAccumulator, FramesBeyondThoseCountedLeaveLaterBlocksOut) {
    const auto samples = synthetic::freeRotors(8, 100, 0.1, 15.0, 4.2, 18.0, 1.154, 7);
    RdfAccumulator acc(100, 15.0, 0.1, 7.5, 16, 4); // planned 16 frames, 8 arrive: 2 blocks
    for (const auto& s : samples)
        acc.add(s);
    const RadialDistribution part = acc.result();
    const RadialDistribution allPairs = radialDistribution(samples, 0.1, 2);
    for (std::size_t k = 0; k < part.r.size(); ++k)
        EXPECT_TRUE(near(part.g[k], allPairs.g[k], roundOff)) << "bin " << k;
    EXPECT_THROW(RdfAccumulator(100, 15.0, 0.1, 7.6, 16, 4), std::invalid_argument);
    EXPECT_THROW(RdfAccumulator(100, 15.0, 0.0, 7.0, 16, 4), std::invalid_argument);
    EXPECT_THROW(RdfAccumulator(100, 15.0, 0.1, 7.0, 3, 4), std::invalid_argument);
}

TEST(StreamingCorrelations, LagsBelowTheFirstLevelMatchTheDirectSumsToRoundOff) {
    const auto samples = synthetic::freeRotors(120, 50, 0.05, 25.0, 4.2, 18.0, 1.154, 21);
    const int maxLag = 59, blocks = 4;
    const auto streamed = fed(samples, maxLag, blocks);
    double v2a = 0.0, v2b = 0.0;
    const SampledCurve vacf = streamed.velocity(&v2a),
                       vacfRef = velocityAutocorrelation(samples, maxLag, blocks, &v2b);
    const auto oacf = streamed.orientation();
    const auto oacfRef = orientationalAutocorrelation(samples, maxLag, blocks);
    const SampledCurve msd = streamed.displacement(),
                       msdRef = meanSquaredDisplacement(samples, maxLag, blocks);
    EXPECT_TRUE(near(v2a, v2b, roundOff));
    ASSERT_TRUE(streamed.rotating());
    for (int k = 0; k < 16; ++k) {
        EXPECT_DOUBLE_EQ(vacf.tPs[k], vacfRef.tPs[k]);
        EXPECT_TRUE(near(vacf.value[k], vacfRef.value[k], roundOff)) << "lag " << k;
        EXPECT_TRUE(near(vacf.err[k], vacfRef.err[k], errRoundOff)) << "lag " << k;
        EXPECT_TRUE(near(oacf.c1.value[k], oacfRef.c1.value[k], roundOff)) << "lag " << k;
        EXPECT_TRUE(near(oacf.c2.value[k], oacfRef.c2.value[k], roundOff)) << "lag " << k;
        EXPECT_TRUE(near(oacf.c2.err[k], oacfRef.c2.err[k], errRoundOff)) << "lag " << k;
        // The windows' MSD goes through FFTs of displacements of a few Å: round-off ~1e-15 Å².
        EXPECT_NEAR(msd.value[k], msdRef.value[k], msdRoundOff) << "lag " << k;
        EXPECT_TRUE(near(msd.err[k], msdRef.err[k], errRoundOff)) << "lag " << k;
    }
}

TEST(StreamingCorrelations, CoarseLevelsAreExactSumsOverEveryTwoToTheLthOrigin) {
    const auto samples = synthetic::freeRotors(200, 30, 0.05, 25.0, 4.2, 18.0, 1.154, 8);
    const int p = 8, maxLag = 99;
    const auto streamed = fed(samples, maxLag, 4, p);
    const auto oacf = streamed.orientation();
    const SampledCurve msd = streamed.displacement();
    const double dtPs = sampleIntervalPs(samples);
    ASSERT_EQ(std::lround(oacf.c1.tPs.back() / dtPs), 96); // level 4: j·16, j = 4 … 7 up to 99
    for (std::size_t g = 0; g < oacf.c1.tPs.size(); ++g) {
        const int k = static_cast<int>(std::lround(oacf.c1.tPs[g] / dtPs));
        int level = 0;
        while (k >= (p << level))
            ++level;
        const int stride = 1 << level;
        double c1 = 0.0, d2 = 0.0, count = 0.0;
        for (int t0 = 0; t0 + k < 200; t0 += stride) {
            for (int i = 0; i < 30; ++i) {
                c1 += samples[t0].axis[i].dot(samples[t0 + k].axis[i]);
                d2 += (samples[t0 + k].position[i] - samples[t0].position[i]).squaredNorm();
            }
            count += 30.0;
        }
        EXPECT_TRUE(near(oacf.c1.value[g], c1 / count, roundOff)) << "lag " << k;
        EXPECT_TRUE(near(msd.value[g], d2 / count, roundOff)) << "lag " << k;
    }
}

TEST(StreamingCorrelations, DiffusionAgreesWithTheReferenceEstimateWithinError) {
    // Brownian walkers, D = 0.5 Å² per time unit: the Einstein fit of both analyses must agree
    // with each other and with D within their block errors.
    const double d = 0.5, h = 0.1;
    const auto samples = synthetic::randomWalk(800, 200, h, 40.0, d, 13);
    const int blocks = 8, maxLag = lagFor(0.0, units::toPs(h), 800, blocks);
    const auto streamed = fed(samples, maxLag, blocks);
    const Diffusion a = diffusionFromMsd(streamed.displacement());
    const Diffusion b = diffusionFromMsd(meanSquaredDisplacement(samples, maxLag, blocks));
    const double expected = d / units::psPerTimeUnit; // Å²/ps
    EXPECT_GT(a.err, 0.0);
    EXPECT_NEAR(a.coefficient, expected, 4.0 * a.err);
    EXPECT_NEAR(a.coefficient, b.coefficient, 4.0 * std::hypot(a.err, b.err));
}

TEST(StreamingCorrelations, GreenKuboDiffusionHasAnErrorBarThatCoversTheKnownValue) {
    // Ornstein–Uhlenbeck velocities: ∫ c dt = 1/γ, so D = kT/(mγ) exactly.
    const double kT = 2.0, mass = 18.0, gamma = 2.0, h = 0.05;
    const auto samples = synthetic::ornsteinUhlenbeck(2000, 100, h, 30.0, kT, mass, gamma, 17);
    const int blocks = 8;
    const auto streamed = fed(samples, 200, blocks);
    double v2 = 0.0;
    const SampledCurve vacf = streamed.velocity(&v2);
    const Diffusion gk = greenKuboDiffusion(vacf, v2);
    const double expected = 3.0 * kT / mass /
                            (gamma * units::psPerTimeUnit * units::psPerTimeUnit) *
                            units::psPerTimeUnit / 3.0; // ⟨v²⟩/3 · 1/γ in Å²/ps
    EXPECT_GT(gk.err, 0.0);
    EXPECT_LT(gk.err, 0.2 * expected);
    EXPECT_NEAR(gk.coefficient, expected, 4.0 * gk.err);
}

TEST(StreamingCorrelations, MemoryDoesNotGrowWithTheSamplesAddedAndFollowsTheCap) {
    const auto samples = synthetic::freeRotors(300, 500, 0.05, 25.0, 4.2, 18.0, 1.154, 2);
    StreamingCorrelationPlan plan{300, 100, 4, 16, 64, {}};
    StreamingCorrelations c(500, sampleIntervalPs(samples), plan);
    const std::size_t before = c.bytes();
    for (const auto& s : samples)
        c.add(s);
    EXPECT_EQ(c.bytes(), before);
    EXPECT_EQ(c.followed(), 64);
    // Memory grows with the followed bodies (7.9 times as many beyond the first: 500 against
    // 64), above a fixed FFT scratch.
    StreamingCorrelationPlan all{300, 100, 4, 16, 0, {}}, one{300, 100, 4, 16, 1, {}};
    const std::size_t fixed = StreamingCorrelations(500, 0.005, one).bytes();
    EXPECT_GT(StreamingCorrelations(500, 0.005, all).bytes() - fixed, 7 * (before - fixed));
}

TEST(StreamingCorrelations, RefusesUnequalSpacingAndBadPlans) {
    auto samples = synthetic::freeRotors(20, 10, 0.05, 25.0, 4.2, 18.0, 1.154, 2);
    StreamingCorrelationPlan plan{20, 5, 2, 16, 0, {}};
    StreamingCorrelations c(10, sampleIntervalPs(samples), plan);
    c.add(samples[0]);
    EXPECT_THROW(c.add(samples[2]), std::invalid_argument);
    EXPECT_THROW(StreamingCorrelations(10, 0.005, StreamingCorrelationPlan{20, 5, 2, 7, 0, {}}),
                 std::invalid_argument);
    EXPECT_THROW(StreamingCorrelations(10, 0.005, StreamingCorrelationPlan{20, 5, 11, 16, 0, {}}),
                 std::invalid_argument);
    EXPECT_THROW(StreamingCorrelations(10, 0.005, StreamingCorrelationPlan{20, 20, 2, 16, 0, {}}),
                 std::invalid_argument);
}

TEST(RunAnalysis, WritesTheReferenceCurvesAtShortLagsAndItsGAtLargeR) {
    const auto samples = synthetic::freeRotors(64, 200, 0.1, 25.0, 4.2, 18.0, 1.154, 11);
    const ScratchDirectory a("stream");
    StreamingOptions options;
    options.rdfBinAngstrom = 0.1;
    options.rdfMaxAngstrom = 0.0; // L/2, as the reference
    RunAnalysis run(200, 25.0, sampleIntervalPs(samples), 64, options);
    for (const auto& s : samples)
        run.add(s);
    const auto summary = run.write(a.path);
    const int maxLag = lagFor(0.0, sampleIntervalPs(samples), 64, 8);
    const SampledCurve vacf = velocityAutocorrelation(samples, maxLag, 8),
                       msd = meanSquaredDisplacement(samples, maxLag, 8);
    const auto oacf = orientationalAutocorrelation(samples, maxLag, 8);
    const RadialDistribution rdf = radialDistribution(samples, 0.1, 8);
    const std::map<std::string, std::vector<std::vector<double>>> expected{
        {"rdf.csv", {rdf.r, rdf.g, rdf.err}},
        {"vacf.csv", {vacf.tPs, vacf.value, vacf.err}},
        {"oacf.csv", {oacf.c1.tPs, oacf.c1.value, oacf.c1.err, oacf.c2.value, oacf.c2.err}},
        {"msd.csv", {msd.tPs, msd.value, msd.err}}};
    for (const auto& [file, columns] : expected) {
        const CsvTable x = readCsv(a.path / file);
        const int rows = file == "rdf.csv" ? static_cast<int>(rdf.r.size()) : 16;
        ASSERT_GE(x.rows(), rows) << file;
        ASSERT_EQ(x.columns.size(), columns.size()) << file;
        for (std::size_t c = 0; c < columns.size(); ++c)
            for (int r = 0; r < rows; ++r)
                EXPECT_NEAR(x.columns[c][r], columns[c][r],
                            fileRoundOff * std::max(1.0, std::abs(columns[c][r])))
                    << file << " column " << c << " row " << r;
    }
    EXPECT_EQ(summary["samples"], 64);
    // g at large r: the mean over the outer fifth of g(r)'s range, r ≥ 0.8 r_max.
    double sum = 0.0;
    int bins = 0;
    for (std::size_t k = 0; k < rdf.r.size(); ++k)
        if (rdf.r[k] >= 0.8 * 12.5) sum += rdf.g[k], ++bins;
    EXPECT_NEAR(summary["rdf"]["g_large_r"].get<double>(), sum / bins, roundOff);
    EXPECT_EQ(summary["rdf"]["large_r_from_angstrom"].get<double>(), 0.8 * 12.5);
    EXPECT_TRUE(summary["diffusion"]["green_kubo_err"].is_number());
    // The grid's last lag at or before the requested 31 (lags 0 … 15, then 16, 18, … 30).
    EXPECT_EQ(maxLag, 31);
    EXPECT_NEAR(summary["max_lag_ps"].get<double>(), 0.30, 1e-12);
}

TEST(RunAnalysis, ARunStoppedEarlyIsAnalysedOverTheSamplesItHas) {
    const auto samples = synthetic::freeRotors(30, 50, 0.1, 25.0, 4.2, 18.0, 1.154, 4);
    const ScratchDirectory a("early");
    RunAnalysis run(50, 25.0, sampleIntervalPs(samples), 1000, StreamingOptions{});
    for (int k = 0; k < 3; ++k)
        run.add(samples[k]);
    EXPECT_THROW(run.write(a.path), std::invalid_argument); // three samples: nothing to say
    for (int k = 3; k < 30; ++k)
        run.add(samples[k]);
    const auto summary = run.write(a.path);
    EXPECT_EQ(summary["samples"], 30);
    EXPECT_EQ(summary["samples_planned"], 1000);
    const CsvTable vacf = readCsv(a.path / "vacf.csv");
    EXPECT_LE(vacf.columns[0].back(), 29 * 0.01 + 1e-12); // only lags that have origins
    for (double c : vacf.columns[1])
        EXPECT_TRUE(std::isfinite(c));
}

// What the run driver hands over when nothing else needs a sample whole: the followed bodies
// alone, and every position on g(r) frames only. The same numbers as the whole samples.
TEST(RunAnalysis, ASampleInPartsGivesTheNumbersOfTheWholeSample) {
    const auto samples = synthetic::freeRotors(64, 200, 0.1, 25.0, 4.2, 18.0, 1.154, 5);
    const ScratchDirectory a("whole"), b("parts");
    StreamingOptions options;
    options.rdfEvery = 3;
    options.followBodies = 50;
    RunAnalysis whole(200, 25.0, sampleIntervalPs(samples), 64, options);
    RunAnalysis parts(200, 25.0, sampleIntervalPs(samples), 64, options);
    ASSERT_EQ(parts.followedBodies().size(), 50u);
    int framesWithPositions = 0;
    for (const auto& s : samples) {
        whole.add(s);
        Snapshot followed = s, where = s;
        followed.position.clear(), followed.velocity.clear(), followed.axis.clear();
        followed.omega.clear();
        for (const int i : parts.followedBodies()) {
            followed.position.push_back(s.position[i]);
            followed.velocity.push_back(s.velocity[i]);
            followed.axis.push_back(s.axis[i]);
            followed.omega.push_back(s.omega[i]);
        }
        where.velocity.clear(), where.axis.clear(), where.omega.clear();
        if (parts.wantsPositions()) {
            ++framesWithPositions;
            EXPECT_THROW(parts.add(followed, nullptr), std::invalid_argument);
            parts.add(followed, [&where](int b) { return where.position[b]; });
        } else {
            parts.add(followed, nullptr);
        }
    }
    EXPECT_EQ(framesWithPositions, 22); // samples 0, 3, …, 63
    EXPECT_EQ(whole.write(a.path), parts.write(b.path));
    for (const char* file : {"rdf.csv", "vacf.csv", "oacf.csv", "msd.csv"}) {
        const CsvTable x = readCsv(a.path / file), y = readCsv(b.path / file);
        EXPECT_EQ(x.columns, y.columns) << file;
    }
    Snapshot notFollowed = samples.front();
    EXPECT_THROW(parts.add(notFollowed, [&](int b) { return notFollowed.position[b]; }),
                 std::invalid_argument); // 200 bodies, not 50
}

} // namespace test_streaming_analysis
