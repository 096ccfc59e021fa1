// Regression compare: an independent re-run agrees, a shifted curve does not.
#include "analysis/compare.hpp"
#include "analysis/csv.hpp"
#include "analysis/reference/all_pairs_rdf.hpp"
#include "analysis/reference/direct_correlations.hpp"
#include "synthetic_samples.hpp"
#include <cmath>
#include <fstream>
#include <gtest/gtest.h>
#include <limits>
#include <random>
#include <unistd.h>

namespace test_compare {

using namespace terrace;
using namespace terrace::analysis;
namespace fs = std::filesystem;

namespace {

// Ornstein–Uhlenbeck "runs": 100 bodies, 2000 samples 10 fs apart, VACF e^{−γt} with
// 1/γ = 2 time units (0.2 ps = 20 samples); a run differs from its re-run by the seed only.
constexpr int samples = 2000, bodies = 100;
constexpr double interval = 0.1, decayRate = 0.5, length = 30.0, kT = 4.2, mass = 18.0;
/// The project's default regression threshold.
constexpr double tolSigma = 3.0;

/// The curves of a run on every lag (the reference's all-origins sums, so that the comparison
/// has many points), in the files and columns a run writes.
void writeRun(const std::vector<Snapshot>& run, const fs::path& dir) {
    constexpr int blocks = 8;
    const double dtPs = reference::sampleIntervalPs(run);
    const int maxLag = lagFor(0.0, dtPs, static_cast<long>(run.size()), blocks);
    const SampledCurve vacf = reference::velocityAutocorrelation(run, maxLag, blocks),
                       msd = reference::meanSquaredDisplacement(run, maxLag, blocks);
    const RadialDistribution rdf = reference::radialDistribution(run, 0.05, blocks);
    fs::create_directories(dir);
    writeCsv(dir / "rdf.csv", {{"r_angstrom", "g", "err"}, {rdf.r, rdf.g, rdf.err}});
    writeCsv(dir / "vacf.csv", {{"t_ps", "c", "err"}, {vacf.tPs, vacf.value, vacf.err}});
    writeCsv(dir / "msd.csv", {{"t_ps", "msd_angstrom2", "err"}, {msd.tPs, msd.value, msd.err}});
}

struct Runs : ::testing::Test {
    static fs::path root;
    static void SetUpTestSuite() {
        // One directory per process: ctest -j runs the tests of this suite side by side.
        root =
            fs::temp_directory_path() / ("terrace_analysis_compare_" + std::to_string(::getpid()));
        fs::remove_all(root);
        for (auto [name, seed] : {std::pair{"a", 101u}, std::pair{"b", 202u}})
            writeRun(synthetic::ornsteinUhlenbeck(samples, bodies, interval, length, kT, mass,
                                                  decayRate, seed),
                     root / name);
    }
    static void TearDownTestSuite() { fs::remove_all(root); }
    /// B's vacf.csv with its columns changed by f, written as a new file.
    static fs::path modified(const std::string& name, void (*f)(CsvTable&)) {
        CsvTable t = readCsv(root / "b" / "vacf.csv");
        f(t);
        writeCsv(root / name, t);
        return root / name;
    }
};
fs::path Runs::root;

} // namespace

TEST(CompareLimits, OnePointLimitsAreTheToleranceItself) {
    EXPECT_DOUBLE_EQ(pointLimitSigma(3.0, 1), 3.0);
    EXPECT_NEAR(chi2PerDofLimit(3.0, 1), 9.0, 1e-9); // χ²₁ = z², so its quantile is 3²
    EXPECT_GT(pointLimitSigma(3.0, 1000), 4.5);      // Bonferroni over 1000 points
    EXPECT_LT(pointLimitSigma(3.0, 1000), 5.0);
    EXPECT_LT(chi2PerDofLimit(3.0, 500), 1.5); // many independent points: χ²/dof near 1
}

TEST(CompareLimits, EffectivePointsOfIndependentAndOfSmoothDeviations) {
    std::mt19937_64 rng(9);
    std::normal_distribution<double> g(0.0, 1.0);
    std::vector<double> white(1000), smooth(1000);
    double walk = 0.0;
    for (int i = 0; i < 1000; ++i) {
        white[i] = g(rng);
        walk = 0.95 * walk + std::sqrt(1.0 - 0.95 * 0.95) * g(rng); // correlation length 20
        smooth[i] = walk + 2.0;                                     // plus a constant shift
    }
    EXPECT_GT(effectivePoints(white), 700.0);
    // AR(1) with ρ = 0.95: n (1 − ρ)/(1 + ρ) ≈ 26 independent points, whatever the shift.
    EXPECT_GT(effectivePoints(smooth), 10.0);
    EXPECT_LT(effectivePoints(smooth), 60.0);
    EXPECT_EQ(effectivePoints(std::vector<double>(50, 1.5)), 1.0);
}

TEST(CompareGrids, CurvedCurveOnAnotherGridAgreesWithItself) {
    // c(t) = exp(−(t/τ)²), τ = 0.1 ps: A on SMD's 10.8 fs grid with errors 1e-4, B the same
    // function on a 10 fs grid without errors. Linear interpolation would be off by ~h²c''/8 ≈
    // 2.5e-3 = 25 error bars at short times; the cubic is off by ~3e-5.
    const auto curve = [](double t) { return std::exp(-(t / 0.1) * (t / 0.1)); };
    CsvTable a{{"t_ps", "c", "err"}, {{}, {}, {}}}, b{{"t_ps", "c"}, {{}, {}}};
    for (int k = 0; k < 60; ++k) {
        a.columns[0].push_back(k * 0.0108);
        a.columns[1].push_back(curve(k * 0.0108));
        a.columns[2].push_back(1e-4);
    }
    for (int k = 0; k < 65; ++k) { // to 640 fs: A's 637 fs lies within one step of its end
        b.columns[0].push_back(k * 0.01);
        b.columns[1].push_back(curve(k * 0.01));
    }
    const fs::path dir = fs::temp_directory_path();
    const std::string tag = std::to_string(::getpid());
    writeCsv(dir / ("terrace_grid_a_" + tag + ".csv"), a);
    writeCsv(dir / ("terrace_grid_b_" + tag + ".csv"), b);
    const Comparison c = compareCsv(dir / ("terrace_grid_a_" + tag + ".csv"),
                                    dir / ("terrace_grid_b_" + tag + ".csv"), tolSigma);
    EXPECT_TRUE(c.agree) << c.verdict;
    EXPECT_LT(c.maxDeviationSigma, 1.0);
    EXPECT_EQ(c.points, 60); // 59 · 10.8 fs = 637 fs lies inside B's 640 fs
    fs::remove(dir / ("terrace_grid_a_" + tag + ".csv"));
    fs::remove(dir / ("terrace_grid_b_" + tag + ".csv"));
}

TEST_F(Runs, IndependentReRunAgrees) {
    for (const char* file : {"vacf.csv", "msd.csv", "rdf.csv"}) {
        const Comparison c = compareCsv(root / "a" / file, root / "b" / file, tolSigma);
        EXPECT_TRUE(c.agree) << file << ": " << c.verdict;
        EXPECT_GT(c.points, 100);
        EXPECT_EQ(c.verdict.find('\n'), std::string::npos);
    }
}

TEST_F(Runs, RunAgreesWithTheExactCurveOnAnotherGrid) {
    // e^{−γt} every 5 fs (twice as fine), no error column: B counts as exact and is interpolated.
    CsvTable exact{{"t_ps", "c"}, {{}, {}}};
    for (int k = 0; k <= 2 * samples / 2; ++k) {
        exact.columns[0].push_back(k * 0.005);
        exact.columns[1].push_back(std::exp(-decayRate * units::fromPs(k * 0.005)));
    }
    writeCsv(root / "exact.csv", exact);
    const Comparison c = compareCsv(root / "a" / "vacf.csv", root / "exact.csv", tolSigma);
    EXPECT_TRUE(c.agree) << c.verdict;
    EXPECT_EQ(c.points, 1000); // lags 0 … 999 of A, all inside the exact curve's range
}

TEST_F(Runs, ShiftedCurveDisagrees) {
    // An offset of 0.02 after t = 0 (c(0) = 1 kept, so that the exact point cannot tell): about
    // twice the combined error of a typical point.
    const auto shifted = modified("shifted.csv", [](CsvTable& t) {
        for (std::size_t k = 1; k < t.columns[1].size(); ++k)
            t.columns[1][k] += 0.02;
    });
    const Comparison c = compareCsv(root / "a" / "vacf.csv", shifted, tolSigma);
    EXPECT_FALSE(c.agree) << c.verdict;
    // The χ² test flags it too: above its limit even for as few as 5 independent points (these
    // runs have 10–30), whatever the few precise short-lag points say.
    EXPECT_GT(c.chi2PerDof, chi2PerDofLimit(tolSigma, 5.0));
    EXPECT_EQ(c.verdict.rfind("DISAGREE", 0), 0u);
}

TEST_F(Runs, CurveShiftedInTimeDisagrees) {
    // One sample (10 fs) late, within the ends' one-step tolerance: the steep start of e^{−γt}
    // exposes it point by point.
    const auto late = modified("late.csv", [](CsvTable& t) {
        for (double& x : t.columns[0])
            x += 0.01;
    });
    const Comparison c = compareCsv(root / "a" / "vacf.csv", late, tolSigma);
    EXPECT_FALSE(c.agree) << c.verdict;
    EXPECT_GT(c.maxDeviationSigma, pointLimitSigma(tolSigma, c.points));
    // Two samples late, its ends no longer meet A's: refused as another range.
    const auto later = modified("later.csv", [](CsvTable& t) {
        for (double& x : t.columns[0])
            x += 0.02;
    });
    EXPECT_THROW(compareCsv(root / "a" / "vacf.csv", later, tolSigma), CsvError);
}

TEST_F(Runs, OneOutlierDisagrees) {
    const auto outlier = modified(
        "outlier.csv", [](CsvTable& t) { t.columns[1][40] += 10.0 * t.columns[2][40] + 0.1; });
    const Comparison c = compareCsv(root / "a" / "vacf.csv", outlier, tolSigma);
    EXPECT_FALSE(c.agree) << c.verdict;
    EXPECT_NEAR(c.atX, 0.4, 1e-12);
}

TEST_F(Runs, ExactPointsMustMatch) {
    // c(0) = 1 with zero error in both: changing it alone is a disagreement.
    const auto wrongStart = modified("start.csv", [](CsvTable& t) { t.columns[1][0] = 0.999; });
    const Comparison c = compareCsv(root / "a" / "vacf.csv", wrongStart, tolSigma);
    EXPECT_FALSE(c.agree) << c.verdict;
    EXPECT_TRUE(std::isinf(c.maxDeviationSigma));
}

TEST_F(Runs, RoundOffAtAnExactPointIsNoDisagreement) {
    // OACF(0) = 1 comes out as 1 + 2e-16 with an "error" of 1e-17: round-off, not a deviation.
    const auto roundOff = modified("roundoff.csv", [](CsvTable& t) {
        t.columns[1][0] = 1.0 + 2.2e-16;
        t.columns[2][0] = 1e-17;
    });
    const Comparison c = compareCsv(root / "a" / "vacf.csv", roundOff, tolSigma);
    EXPECT_TRUE(c.agree) << c.verdict;
}

TEST_F(Runs, NoErrorBarsOrNoCommonColumnIsAnError) {
    CsvTable bare{{"t_ps", "c"}, {{0.0, 0.01}, {1.0, 0.9}}};
    writeCsv(root / "bare.csv", bare);
    EXPECT_THROW(compareCsv(root / "bare.csv", root / "bare.csv", tolSigma), CsvError);
    EXPECT_THROW(compareCsv(root / "a" / "vacf.csv", root / "a" / "rdf.csv", tolSigma), CsvError);
    EXPECT_THROW(compareCsv(root / "a" / "vacf.csv", root / "b" / "vacf.csv", tolSigma, "g"),
                 CsvError);
    EXPECT_THROW(compareCsv(root / "a" / "vacf.csv", root / "b" / "vacf.csv", 0.0),
                 std::invalid_argument);
    EXPECT_THROW(compareCsv(root / "a" / "vacf.csv", root / "b" / "vacf.csv",
                            std::numeric_limits<double>::infinity()),
                 std::invalid_argument);
}

TEST_F(Runs, CurvesOverDifferentRangesAreRefusedNamingTheirPoints) {
    // B is A's first half: the common points agree, but half of A would go unchecked.
    const auto half = modified("half.csv", [](CsvTable& t) {
        for (auto& column : t.columns)
            column.resize(column.size() / 2);
    });
    try {
        (void)compareCsv(root / "a" / "vacf.csv", half, tolSigma);
        FAIL() << "a curve cut to half its range was compared";
    } catch (const CsvError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("cover different ranges"), std::string::npos) << what;
        EXPECT_NE(what.find("has 1000 points"), std::string::npos) << what;
        EXPECT_NE(what.find(" 500 points"), std::string::npos) << what;
    }
}

TEST(Csv, CommentLinesAreSkipped) {
    // thermo.csv carries its units and a note as '#' lines under the header.
    const fs::path path =
        fs::temp_directory_path() / ("terrace_comments_" + std::to_string(::getpid()) + ".csv");
    {
        std::ofstream out(path);
        out << "time_ps,u\n# ps,kJ/mol\n# a note, with commas\n0,1\n0.5,2\n";
    }
    const CsvTable t = readCsv(path);
    fs::remove(path);
    ASSERT_EQ(t.rows(), 2);
    EXPECT_EQ(t.columns[1][1], 2.0);
}

} // namespace test_compare
