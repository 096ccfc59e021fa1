// `terrace tradeoff`'s parts that need no run (cli/tradeoff_plan.hpp, cli/tradeoff_measure.hpp):
// tolerances as typed, the ladders on the sampling grid, the numbers read from a run directory,
// and the bias of a curve with the noise of both sides taken out.
#include "analysis/csv.hpp"
#include "cli/tradeoff_dominance.hpp"
#include "cli/tradeoff_measure.hpp"
#include "cli/tradeoff_plan.hpp"
#include "cli/tradeoff_verdict.hpp"
#include "core/output_file.hpp"
#include <cmath>
#include <filesystem>
#include <gtest/gtest.h>
#include <random>
#include <unistd.h>

namespace test_tradeoff {

using namespace terrace;
using namespace terrace::cli;

namespace {

std::string toleranceError(const std::string& text) {
    try {
        parseTolerance(text);
    } catch (const SceneError& e) {
        return e.what();
    }
    return "";
}

} // namespace

// A relative tolerance is a fraction of max(|reference|, floor): the floors, and the tolerances
// they give at the map's dense liquid and its gas (rods at the loose set's u 2 %, p 5 %; the
// references are those the map measured, results/tradeoff-map/rods-loose).
TEST(Tradeoff, RelativeTolerancesOfUAndPHaveAThermalFloor) {
    EXPECT_DOUBLE_EQ(relativeScaleFloor(Observable::U, 0.01, 10.0), 10.0);
    EXPECT_DOUBLE_EQ(relativeScaleFloor(Observable::P, 0.01, 10.0), 0.1);
    for (Observable o :
         {Observable::D, Observable::G, Observable::GPeak, Observable::TauV, Observable::TauO})
        EXPECT_EQ(relativeScaleFloor(o, 0.5, 1.4), 0.0);
    const analysis::Tolerance u{0.02, true}, p{0.05, true};
    const auto tolerance = [](analysis::Tolerance t, Observable o, double reference, double rho,
                              double temperature) {
        return analysis::absoluteTolerance(t, reference, relativeScaleFloor(o, rho, temperature));
    };
    // Dense rods (ρ* 0.5, T* 1.4): |u| = 3.01 and P* = 0.199 are above their floors.
    EXPECT_NEAR(tolerance(u, Observable::U, -3.0128, 0.5, 1.4), 0.02 * 3.0128, 1e-12);
    EXPECT_NEAR(tolerance(p, Observable::P, 0.1992, 0.5, 1.4), 0.05 * 0.7, 1e-12);
    // The gas (ρ* 0.01, T* 10): u = −0.0315 is below T*, so U is asked to 2 % of kT per body.
    EXPECT_NEAR(tolerance(u, Observable::U, -0.0315, 0.01, 10.0), 0.2, 1e-12);
    EXPECT_NEAR(tolerance(p, Observable::P, 0.1009, 0.01, 10.0), 0.05 * 0.1009, 1e-12);
}

TEST(Tradeoff, TolerancesAreRelativeWithAPercentSignElseAbsolute) {
    const auto [u, tu] = parseTolerance("u=0.5%");
    EXPECT_EQ(u, Observable::U);
    EXPECT_TRUE(tu.relative);
    EXPECT_DOUBLE_EQ(tu.value, 0.005);
    const auto [g, tg] = parseTolerance("g=0.03");
    EXPECT_EQ(g, Observable::G);
    EXPECT_FALSE(tg.relative);
    EXPECT_DOUBLE_EQ(tg.value, 0.03);
    EXPECT_NE(toleranceError("x=1").find("unknown observable 'x'"), std::string::npos);
    EXPECT_NE(toleranceError("u").find("OBS=VALUE"), std::string::npos);
    EXPECT_NE(toleranceError("u=-1%").find("positive"), std::string::npos);
    EXPECT_NE(toleranceError("u=1e").find("positive"), std::string::npos);
    EXPECT_NE(toleranceError("g=2%").find("absolute"), std::string::npos);
    EXPECT_EQ(parseObservables("u,g_peak,tau_o"),
              (std::vector<Observable>{Observable::U, Observable::GPeak, Observable::TauO}));
    EXPECT_THROW(parseObservables("u,,p"), SceneError);
}

TEST(Tradeoff, SmdLaddersStepOnTheSamplingGridFromTheScenesDt) {
    Scene scene; // sample and thermostat 9 fs, smd.dt_fs 1.8 (the default)
    TradeoffOptions options;
    const TradeoffLadders l = tradeoffLadders(scene, options);
    EXPECT_EQ(l.reference.engine, "smd");
    EXPECT_DOUBLE_EQ(l.reference.x, 0.9); // half the scene's step
    ASSERT_EQ(l.ladders.size(), 5u);      // three splittings, two terrace designs
    for (const auto& ladder : l.ladders) {
        ASSERT_GE(ladder.size(), 2u);
        for (std::size_t i = 0; i < ladder.size(); ++i) {
            const double x = ladder[i].x;
            if (ladder[i].engine == "smd") {
                const double steps = 9.0 / x;
                EXPECT_NEAR(steps, std::round(steps), 1e-9) << ladder[i].label();
                EXPECT_LE(x, 18.0 + 1e-9);
                EXPECT_GE(x, 1.8 - 1e-9);
            }
            if (i > 0) {
                EXPECT_GT(x, ladder[i - 1].x) << "most accurate first";
            }
        }
    }
    EXPECT_DOUBLE_EQ(l.ladders[0].front().x, 1.8);
    EXPECT_EQ(l.ladders[0].front().label(), "smd-verlet-dt1.8");
    EXPECT_EQ(l.ladders[3].front().label(), "dmd-uniform-dV0.125");
    EXPECT_EQ(knownOrder(l.ladders[0].front()), 2.0);
    EXPECT_EQ(knownOrder(l.ladders[2].front()), 4.0);
    EXPECT_FALSE(knownOrder(l.ladders[3].front()));
}

TEST(Tradeoff, PeakWindowIsTheMeanCurvesHighestPeakAtHalfItsHeightAboveOne) {
    // g = 3 − ((k − 60.3)/10)² on 120 bins: g − 1 ≥ half its top's (2 − 0.0009) for
    // |k − 60.3| ≤ 10.002, bins 51 to 70.
    std::vector<double> g;
    for (int k = 0; k < 120; ++k)
        g.push_back(3.0 - (k - 60.3) * (k - 60.3) / 100.0);
    // Two copies with opposite noise in bin 20 that would each out-top the peak alone.
    std::vector<double> up = g, down = g;
    up[20] += 5.0, down[20] -= 5.0;
    const auto w = peakWindow({&up, &down});
    ASSERT_TRUE(w);
    EXPECT_EQ(w->first, 51u);
    EXPECT_EQ(w->last, 70u);
    double expected = 0.0;
    for (int k = 51; k <= 70; ++k)
        expected += g[std::size_t(k)] / 20.0;
    EXPECT_NEAR(windowMean(g, *w), expected, 1e-12);
    EXPECT_TRUE(std::isnan(windowMean(std::vector<double>(60, 1.0), *w)));
    // A peak one bin wide is that bin; with no peak above 1, the top bin and its neighbours.
    const std::vector<double> spike{0.0, 2.0, 1.0}, flat{0.5, 0.9, 0.8, 0.7};
    const auto w1 = peakWindow({&spike});
    ASSERT_TRUE(w1);
    EXPECT_EQ(w1->first, 1u);
    EXPECT_EQ(w1->last, 1u);
    const auto w0 = peakWindow({&flat});
    ASSERT_TRUE(w0);
    EXPECT_EQ(w0->first, 0u);
    EXPECT_EQ(w0->last, 2u);
    EXPECT_FALSE(peakWindow({}));
}

TEST(Tradeoff, APeakHeightIsUnbiasedWhereEachRunsHighestBinIsItsNoise) {
    // A dilute g(r): a bump 0.3 high and 20 bins wide under Gaussian bin noise of 0.12, as in one
    // 9-ps run of 512 rods at rho* 0.01. Each run's own highest bin overshoots the bump by about
    // three noise widths; the window's mean is the bump's mean height over it, to its error.
    std::mt19937_64 rng(11);
    std::normal_distribution<double> noise(0.0, 0.12);
    std::vector<double> truth(200, 1.0);
    for (int k = 50; k < 110; ++k)
        truth[std::size_t(k)] += 0.3 * std::exp(-0.5 * (k - 70) * (k - 70) / 100.0);
    std::vector<ReplicaResult> runs(400);
    double ownPeaks = 0.0;
    for (auto& r : runs) {
        r.ok = true;
        for (double x : truth)
            r.g.push_back(x + noise(rng));
        ownPeaks += *std::max_element(r.g.begin(), r.g.end()) / double(runs.size());
    }
    EXPECT_GT(ownPeaks, 1.3 + 0.12); // a run's own peak reads its noise, not the bump
    setPeakHeights({&runs});
    std::vector<double> heights;
    for (const auto& r : runs)
        heights.push_back(r.value.at("g_peak"));
    const auto m = analysis::replicaMean(heights);
    std::vector<const std::vector<double>*> curves;
    for (const auto& r : runs)
        curves.push_back(&r.g);
    const auto w = peakWindow(curves); // the window setPeakHeights used: on the bump's top
    ASSERT_TRUE(w);
    EXPECT_GE(w->first, 55u); // the bump's half height: bins 59 to 81
    EXPECT_LE(w->last, 85u);
    EXPECT_NEAR(m.mean, windowMean(truth, *w), 3.0 * m.err);
    EXPECT_LT(m.err, 0.003);
    EXPECT_FALSE(runs.front().value.count("g_peak_conf")); // no g_continuous, no such value
}

TEST(Tradeoff, TheTrapezoidIntegralStopsAtTheFirstZero) {
    const std::vector<double> t{0.0, 0.5, 1.0}, c{1.0, 0.5, 0.0};
    EXPECT_DOUBLE_EQ(integral(t, c), 0.5);
    // Up to the first zero only: the noisy tail beyond it is left out.
    const std::vector<double> t2{0.0, 1.0, 2.0, 3.0}, c2{1.0, -1.0, 0.5, 0.5};
    EXPECT_DOUBLE_EQ(integral(t2, c2), 0.25);
}

TEST(Tradeoff, CurveDeviationTakesTheNoiseOfBothSidesOut) {
    // Noise-free replicas: the mean square difference exactly, no error.
    const std::vector<std::vector<double>> a{{1.0, 2.0, 3.0}, {1.0, 2.0, 3.0}};
    const std::vector<std::vector<double>> b{{1.0, 2.5, 2.0}, {1.0, 2.5, 2.0}};
    const analysis::Estimate exact = squaredCurveDeviation(a, b);
    EXPECT_DOUBLE_EQ(exact.mean, (0.25 + 1.0) / 3.0);
    EXPECT_DOUBLE_EQ(exact.err, 0.0);
    // Noisy replicas of curves 0.05 apart everywhere: the estimate of 0.0025 is unbiased (the
    // plain mean square would sit at 0.0025 + 2σ²/n = 0.0125) and its error is honest.
    std::mt19937_64 rng(7);
    std::normal_distribution<double> noise(0.0, 0.1);
    const int bins = 200, trials = 400, n = 4;
    double sum = 0.0, sumSq = 0.0, errSum = 0.0;
    for (int trial = 0; trial < trials; ++trial) {
        std::vector<std::vector<double>> x(n, std::vector<double>(bins)), y = x;
        for (int r = 0; r < n; ++r)
            for (int k = 0; k < bins; ++k)
                x[r][k] = 1.05 + noise(rng), y[r][k] = 1.0 + noise(rng);
        const analysis::Estimate e = squaredCurveDeviation(x, y);
        sum += e.mean, sumSq += e.mean * e.mean, errSum += e.err;
    }
    const double mean = sum / trials, sd = std::sqrt(sumSq / trials - mean * mean);
    EXPECT_NEAR(mean, 0.0025, 4.0 * sd / std::sqrt(double(trials)));
    // The error from the Gaussian bins is within a fifth of the scatter it stands for (the bins'
    // variances are themselves estimated from four replicas).
    EXPECT_NEAR(errSum / trials / sd, 1.0, 0.2);
}

TEST(Tradeoff, CurveDeviationOfAgreeingCurvesHasTheNoiseAsItsError) {
    // Curves equal in expectation: the estimate scatters about 0 and its error is never zero
    // (a clipped variance once gave 0 wherever the bins agreed better than their noise).
    std::mt19937_64 rng(11);
    std::normal_distribution<double> noise(0.0, 0.1);
    const int bins = 50, trials = 400, n = 4;
    double sum = 0.0, sumSq = 0.0, errSum = 0.0, smallestErr = 1.0;
    for (int trial = 0; trial < trials; ++trial) {
        std::vector<std::vector<double>> x(n, std::vector<double>(bins)), y = x;
        for (int r = 0; r < n; ++r)
            for (int k = 0; k < bins; ++k)
                x[r][k] = 1.0 + noise(rng), y[r][k] = 1.0 + noise(rng);
        const analysis::Estimate e = squaredCurveDeviation(x, y);
        sum += e.mean, sumSq += e.mean * e.mean, errSum += e.err;
        smallestErr = std::min(smallestErr, e.err);
    }
    const double mean = sum / trials, sd = std::sqrt(sumSq / trials - mean * mean);
    EXPECT_NEAR(mean, 0.0, 4.0 * sd / std::sqrt(double(trials)));
    EXPECT_GT(smallestErr, 0.25 * sd);
    EXPECT_NEAR(errSum / trials / sd, 1.0, 0.25);
}

namespace {

/// A run directory as `terrace run` leaves it, with the numbers given.
std::filesystem::path fakeRun(const std::string& name, double u, double uConf, double p,
                              const std::string& warning = "") {
    const auto dir = std::filesystem::temp_directory_path() /
                     ("terrace-tradeoff-" + std::to_string(getpid())) / name;
    std::filesystem::create_directories(dir);
    nlohmann::json s{
        {"engine", "dmd"},
        {"interrupted", false},
        {"cpu_seconds", 2.0},
        {"cpu_seconds_equilibration", 1.0},
        {"cpu_seconds_per_ps", 0.5},
        {"potential_energy_mean", u},
        {"warnings", nlohmann::json::array()},
        {"pressure", {{"mean_reduced", p}}},
        {"configurational", {{"potential_energy_mean", uConf}, {"pressure_reduced", p}}},
        {"analysis",
         {{"samples", 10}, {"blocks", 8}, {"diffusion", {{"einstein_angstrom2_per_ps", 3.0}}}}}};
    if (!warning.empty()) s["warnings"].push_back(warning);
    writeFileAtomically(dir / "summary.json", s.dump());
    analysis::writeCsv(
        dir / "rdf.csv",
        {{"r_angstrom", "g", "err", "g_continuous", "err_continuous"},
         {{0.5, 1.5, 2.5}, {0.0, 2.0, 1.0}, {0, 0.1, 0.2}, {0.0, 1.8, 1.0}, {0, 0, 0}}});
    analysis::writeCsv(dir / "vacf.csv",
                       {{"t_ps", "c", "err"}, {{0.0, 0.1}, {1.0, 0.0}, {0, 0.02}}});
    return dir;
}

} // namespace

TEST(Tradeoff, ReplicaNumbersComeFromTheRunsFilesPerBodyInEpsilon) {
    std::vector<ReplicaResult> one{readReplica(fakeRun("ok", -200.0, -250.0, 0.4), 100, 2.0)};
    const ReplicaResult& r = one.front();
    ASSERT_TRUE(r.ok) << r.failure;
    EXPECT_FALSE(r.value.count("g_peak")); // it needs the window of every run
    setPeakHeights({&one});
    EXPECT_DOUBLE_EQ(r.value.at("u"), -1.0);
    EXPECT_DOUBLE_EQ(r.value.at("u_conf"), -1.25);
    EXPECT_DOUBLE_EQ(r.value.at("p"), 0.4);
    EXPECT_DOUBLE_EQ(r.value.at("d"), 3.0);
    EXPECT_DOUBLE_EQ(r.value.at("tau_v"), 0.05);
    EXPECT_DOUBLE_EQ(r.value.at("g_peak"), 2.0); // g = 0, 2, 1: its peak is bin 1 alone
    EXPECT_DOUBLE_EQ(r.value.at("g_peak_conf"), 1.8);
    EXPECT_EQ(r.gConf.size(), 3u);
    EXPECT_FALSE(r.withError.count("g_peak")); // their replicas' scatter is their error
    EXPECT_FALSE(r.withError.count("tau_v"));
    EXPECT_FALSE(r.withError.count("u")); // the fake summary gives U no error
    EXPECT_DOUBLE_EQ(r.cpuSeconds, 3.0);  // a run from before process_cpu_seconds: the engine's
    // The whole process where the run gives it: its samples and frames cost CPU too.
    const auto withProcessCpu = fakeRun("process", -200.0, -250.0, 0.4);
    auto summary = nlohmann::json::parse(readWholeFile(withProcessCpu / "summary.json"));
    summary["process_cpu_seconds"] = 4.5;
    writeFileAtomically(withProcessCpu / "summary.json", summary.dump());
    EXPECT_DOUBLE_EQ(readReplica(withProcessCpu, 100, 2.0).cpuSeconds, 4.5);
    // Energy not conserved: beyond the stability limit, not a sample of the model.
    const ReplicaResult bad =
        readReplica(fakeRun("wander", -1, -1, 0,
                            "total energy wandered by 9 kJ/mol: the integration does "
                            "not conserve energy at this time step"),
                    100, 2.0);
    EXPECT_FALSE(bad.ok);
    EXPECT_NE(bad.failure.find("conserve energy"), std::string::npos);
    EXPECT_TRUE(bad.beyondStability);
    EXPECT_FALSE(r.beyondStability);
    // An error: SMD's own stop at an unstable step is the stability limit; any other is not.
    const auto failedWith = [](const std::string& name, const std::string& error) {
        const auto dir = fakeRun(name, -1, -1, 0);
        writeFileAtomically(dir / "summary.json", nlohmann::json{{"error", error}}.dump());
        return readReplica(dir, 100, 2.0);
    };
    const ReplicaResult unstable = failedWith(
        "unstable", "smd: the integration became unstable at t = 540 fs: a body moved 1.06 Å");
    EXPECT_FALSE(unstable.ok);
    EXPECT_TRUE(unstable.beyondStability);
    const ReplicaResult crashed = failedWith("crashed", "terrace: out of memory");
    EXPECT_FALSE(crashed.ok);
    EXPECT_FALSE(crashed.beyondStability);
    std::filesystem::remove_all(std::filesystem::temp_directory_path() /
                                ("terrace-tradeoff-" + std::to_string(getpid())));
}

TEST(Tradeoff, ScalarBiasAgainstTheReferenceIsDecidedAtItsTolerance) {
    const auto replicas = [](std::vector<double> values, const std::string& key) {
        std::vector<ReplicaResult> out;
        for (const double v : values) {
            ReplicaResult r;
            r.ok = true;
            r.value[key] = v;
            out.push_back(r);
        }
        return out;
    };
    const auto ref = replicas({-2.0, -2.002, -1.998, -2.0}, "u");
    // Configurational u 1 % off with tiny scatter: outside a 0.5 % tolerance.
    const auto far =
        scalarBias(Observable::U, Estimator::Configurational,
                   replicas({-1.98, -1.9801, -1.9799}, "u_conf"), ref, {0.005, true}, 0.0, 2.0);
    ASSERT_TRUE(far);
    EXPECT_NEAR(far->bias.mean, 0.02, 1e-12);
    EXPECT_DOUBLE_EQ(far->tolerance, 0.01);
    EXPECT_EQ(far->decision, analysis::Decision::Outside);
    const auto near =
        scalarBias(Observable::U, Estimator::Own, replicas({-2.001, -1.999, -2.0}, "u"), ref,
                   {0.005, true}, 0.0, 2.0);
    ASSERT_TRUE(near);
    EXPECT_EQ(near->decision, analysis::Decision::Within);
    // One replica is no estimate.
    EXPECT_FALSE(scalarBias(Observable::U, Estimator::Own, replicas({-2.0}, "u"), ref,
                            {0.005, true}, 0.0, 2.0));
}

TEST(Tradeoff, LawCrossingIsTheFirstObservableToReachItsTolerance) {
    // Biases 0.4·x (p fitted) and 0.1·x² (p fitted) at x = 1, 1/2, 1/4 with small errors: the
    // first reaches 0.05 at x = 1/8, the second 0.05 at x = 1/√2, so the ladder's crossing is
    // the smaller, 1/8.
    const std::vector<double> x{1.0, 0.5, 0.25};
    LadderBiases linear{{}, 0.05}, square{{}, 0.05};
    for (const double v : x) {
        linear.bias.push_back(analysis::Estimate{0.4 * v, 1e-4 * v, 30.0});
        square.bias.push_back(analysis::Estimate{0.1 * v * v, 1e-4 * v, 30.0});
    }
    EXPECT_NEAR(lawCrossing(x, {linear}, std::nullopt), 0.125, 1e-3);
    EXPECT_NEAR(lawCrossing(x, {square}, std::nullopt), std::sqrt(0.5), 1e-3);
    EXPECT_NEAR(lawCrossing(x, {linear, square}, std::nullopt), 0.125, 1e-3);
    // A known order is used as given: 0.4·x read as x² crosses elsewhere than at 1/8.
    EXPECT_GT(std::abs(lawCrossing(x, {linear}, 2.0) - 0.125), 0.05);
    // Two points cannot fix a free exponent: no law, no crossing.
    EXPECT_TRUE(std::isinf(lawCrossing(
        {1.0, 0.5}, {LadderBiases{{linear.bias[0], linear.bias[1]}, 0.05}}, std::nullopt)));
}

TEST(Tradeoff, ALadderOutsideEverywhereIsExtendedWithinReachOnly) {
    // The law crosses at 1/8 below a front rung of 1/2: extended to 0.8 of the crossing.
    ASSERT_TRUE(extensionBelow(0.5, 0.125).has_value());
    EXPECT_DOUBLE_EQ(*extensionBelow(0.5, 0.125), 0.125 * extrapolationMargin);
    // Not below the front rung: nothing to extend to.
    EXPECT_FALSE(extensionBelow(0.5, 0.6).has_value());
    EXPECT_FALSE(extensionBelow(0.5, std::numeric_limits<double>::infinity()).has_value());
    // Out of reach (a sixteenth of the front rung): not run.
    EXPECT_FALSE(extensionBelow(0.5, 0.5 * extrapolationReach).has_value());
    EXPECT_TRUE(extensionBelow(0.5, 0.5 * extrapolationReach / extrapolationMargin).has_value());
}

namespace {

using analysis::Decision;

ObservableBias biasOf(Observable o, double mean, double err, Decision d) {
    ObservableBias b;
    b.observable = o;
    b.bias = {mean, err};
    b.tolerance = 1.0;
    b.decision = d;
    return b;
}

/// A DMD-like ladder: x = 0.125 … 1 with cost halving per rung, D's bias −2, −3.7, −5.2
/// tolerances on the three coarser rungs (all Outside), the finest unresolved.
std::vector<RungView> growingLadder() {
    std::vector<RungView> l(4);
    const double x[] = {0.125, 0.25, 0.5, 1.0}, cost[] = {8.0, 4.0, 2.0, 1.0};
    const double d[] = {-0.6, -2.0, -3.7, -5.2};
    for (int i = 0; i < 4; ++i) {
        l[i].x = x[i];
        l[i].cost = cost[i];
        l[i].decision = i == 0 ? Decision::Unresolved : Decision::Outside;
        l[i].biases = {
            biasOf(Observable::U, 0.1, 0.3, Decision::Unresolved),
            biasOf(Observable::D, d[i], 0.25, i == 0 ? Decision::Unresolved : Decision::Outside)};
    }
    return l;
}

} // namespace

TEST(Tradeoff, AVerdictSaysCheaperOnlyWhereTheRatiosIntervalLeavesOne) {
    analysis::RatioInterval r;
    r.level = 0.9375;
    r.median = 1.5, r.lo = 1.2, r.hi = 1.8; // DMD's cost over SMD's
    EXPECT_EQ(costComparison("DMD a", "SMD b", r),
              "SMD b is 1.50x (1.20-1.80, 94 %) cheaper than DMD a");
    r.median = 0.5, r.lo = 0.4, r.hi = 0.8;
    EXPECT_EQ(costComparison("DMD a", "SMD b", r),
              "DMD a is 2.00x (1.25-2.50, 94 %) cheaper than SMD b");
    // The rods at rho* 0.3, T* 3: a median on DMD's side, the interval across 1.
    r.median = 0.99, r.lo = 0.78, r.hi = 1.07;
    EXPECT_EQ(costComparison("DMD a", "SMD b", r),
              "neither engine is resolved cheaper: DMD a costs 0.99x (0.78-1.07, 94 %) what SMD "
              "b costs");
}

TEST(TradeoffOpenRungs, AnOpenRungOfTheDearerEngineTurnsTheRatioIntoABoundOrNoVerdict) {
    // The loose rods at rho* 0.5, T* 10 (results/tradeoff-map): SMD verlet 1 fs is 6.88x
    // (6.65-6.95) cheaper than DMD optimal kT/4 (2.64 CPU s per ps), but DMD uniform kT/8, at
    // 1.16, sits at the edge of p after 128 replicas: DMD's cost at the tolerance may be 0.44 of
    // the chosen one's, so SMD is cheaper by at least 3.02x, not 6.88x.
    const analysis::RatioInterval chosen{6.88, 6.65, 6.95, 8, 0.94};
    const double share = 1.16 / 2.64;
    auto v = openRungVerdict(chosen, share, 1.0);
    EXPECT_EQ(v.cheaper, OpenRungVerdict::Cheaper::Smd);
    EXPECT_NEAR(v.least.median, 3.023, 1e-3);
    EXPECT_NEAR(v.least.lo, 6.65 * share, 1e-12);
    EXPECT_DOUBLE_EQ(v.most.median, 6.88); // no open SMD rung: the chosen ratio is the other end
    // An open DMD rung cheap enough to reach below SMD's cost: neither is resolved cheaper.
    v = openRungVerdict(chosen, 0.1, 1.0);
    EXPECT_EQ(v.cheaper, OpenRungVerdict::Cheaper::Neither);
    EXPECT_NEAR(v.least.lo, 0.665, 1e-12);
    EXPECT_DOUBLE_EQ(v.most.hi, 6.95);
}

TEST(TradeoffOpenRungs, AnOpenRungOfTheCheaperEngineOnlyWidensItsLead) {
    // DMD resolved cheaper (ratio 0.5, 0.4-0.8) with an open DMD rung at half the cost: DMD's
    // lead can only grow, so the chosen ratio bounds it (from above on DMD/SMD).
    const analysis::RatioInterval chosen{0.5, 0.4, 0.8, 8, 0.94};
    auto v = openRungVerdict(chosen, 0.5, 1.0);
    EXPECT_EQ(v.cheaper, OpenRungVerdict::Cheaper::Dmd);
    EXPECT_DOUBLE_EQ(v.most.median, 0.5);
    // An open SMD rung at a third of SMD's chosen cost could put SMD ahead: no verdict.
    v = openRungVerdict(chosen, 1.0, 1.0 / 3.0);
    EXPECT_EQ(v.cheaper, OpenRungVerdict::Cheaper::Neither);
    EXPECT_NEAR(v.most.hi, 2.4, 1e-12);
    // At a 0.9 share it cannot: DMD stays cheaper by at least 1/(0.5/0.9) = 1.8x.
    v = openRungVerdict(chosen, 1.0, 0.9);
    EXPECT_EQ(v.cheaper, OpenRungVerdict::Cheaper::Dmd);
    EXPECT_NEAR(1.0 / v.most.median, 1.8, 1e-12);
    // Nothing open: the chosen ratio at both ends.
    v = openRungVerdict(chosen, 1.0, 1.0);
    EXPECT_DOUBLE_EQ(v.least.lo, 0.4);
    EXPECT_DOUBLE_EQ(v.most.hi, 0.8);
}

TEST(TradeoffDominance, TheMostAccurateOutsideRungWhoseBiasGrowsIsTheFloor) {
    const auto f = ladderCostFloor(growingLadder(), 3, 2.0);
    ASSERT_TRUE(f);
    EXPECT_EQ(f->ladder, 3);
    EXPECT_EQ(f->rung, 1); // x = 0.25: every setting within has a smaller x, so costs more
    EXPECT_DOUBLE_EQ(f->cost, 4.0);
    EXPECT_FALSE(f->within);
    EXPECT_EQ(f->ruling.observable, Observable::D);
}

TEST(TradeoffDominance, ABiasThatShrinksOrTurnsOnACoarserRungDoesNotBound) {
    auto l = growingLadder();
    l[2].biases[1].bias.mean = +3.7; // D turns at x = 0.5: neither 0.25 nor 0.5 bounds
    auto f = ladderCostFloor(l, 0, 2.0);
    ASSERT_TRUE(f);
    EXPECT_EQ(f->rung, 3); // the coarsest rung still bounds the settings more accurate than it
    EXPECT_DOUBLE_EQ(f->cost, 1.0);
    EXPECT_FALSE(f->ladderEnd); // as an Outside rung whose bias grows (on no coarser rung)
    l = growingLadder();
    l[3].decision = Decision::Unresolved; // resolved smaller at x = 1 than at 0.25 and 0.5
    l[3].biases[1] = biasOf(Observable::D, -0.1, 0.1, Decision::Unresolved);
    f = ladderCostFloor(l, 0, 2.0); // neither bounds: only the ladder's end, its coarsest rung
    ASSERT_TRUE(f);
    EXPECT_TRUE(f->ladderEnd);
    EXPECT_EQ(f->rung, 3);
    l = growingLadder();
    l[3].biases[1].bias = {-1.9, 0.1}; // smaller, but not resolved smaller than at 0.25
    f = ladderCostFloor(l, 0, 2.0);
    ASSERT_TRUE(f);
    EXPECT_EQ(f->rung, 1);
}

TEST(TradeoffDominance, EveryRungOutsideWithABiasThatTurnsIsBoundedOnlyByTheCoarsest) {
    // DMD uniform on LJ at rho* 0.2, T* 3, strict (results/tradeoff-map/lj-strict/rho0.2-T3,
    // biases in tolerances): D is outside on the three finest rungs and turns positive at kT, so
    // none of them bounds; only kT, outside on u, does. The floor is then the cheapest rung, and
    // `terrace tradeoff` says a setting between the finer rungs may be within.
    std::vector<RungView> l(4);
    const double x[] = {0.125, 0.25, 0.5, 1.0}, cost[] = {8.0, 4.0, 2.0, 1.0};
    const double u[] = {-0.22, 0.76, -1.67, 8.16}, uErr[] = {0.06, 0.34, 0.41, 0.31};
    const double d[] = {-2.30, -2.88, -5.37, 1.92}, dErr[] = {0.11, 0.53, 0.60, 0.56};
    const Decision uIs[] = {Decision::Within, Decision::Unresolved, Decision::Unresolved,
                            Decision::Outside};
    for (int i = 0; i < 4; ++i) {
        l[i].x = x[i];
        l[i].cost = cost[i];
        l[i].decision = Decision::Outside;
        l[i].biases = {
            biasOf(Observable::U, u[i], uErr[i], uIs[i]),
            biasOf(Observable::D, d[i], dErr[i], i < 3 ? Decision::Outside : Decision::Unresolved)};
    }
    auto f = ladderCostFloor(l, 0, 2.0);
    ASSERT_TRUE(f);
    EXPECT_EQ(f->rung, 3);
    EXPECT_DOUBLE_EQ(f->cost, 1.0);
    EXPECT_FALSE(f->ladderEnd);
    EXPECT_EQ(f->ruling.observable, Observable::U);
    // Had D kept its sign at kT, the finest rung would bound the ladder at eight times the cost.
    l[3].biases[1].bias.mean = -7.0;
    f = ladderCostFloor(l, 0, 2.0);
    ASSERT_TRUE(f);
    EXPECT_EQ(f->rung, 0);
    EXPECT_EQ(f->ruling.observable, Observable::D);
}

TEST(TradeoffDominance, AWithinRungCheaperThanTheFloorIsTheFloor) {
    auto l = growingLadder();
    l[0].decision = Decision::Within; // the finest rung within, and (against the rule) cheap
    l[0].cost = 3.0;
    const auto f = ladderCostFloor(l, 0, 2.0);
    ASSERT_TRUE(f);
    EXPECT_TRUE(f->within);
    EXPECT_EQ(f->rung, 0);
    EXPECT_DOUBLE_EQ(f->cost, 3.0);
}

TEST(TradeoffDominance, WithNothingOutsideTheCoarsestRungIsTheFloor) {
    // Every rung unresolved: the candidates lie at or below the coarsest, so its cost bounds.
    auto l = growingLadder();
    for (auto& r : l) {
        r.decision = Decision::Unresolved;
        for (auto& b : r.biases)
            b.decision = Decision::Unresolved;
    }
    auto f = ladderCostFloor(l, 2, 2.0);
    ASSERT_TRUE(f);
    EXPECT_TRUE(f->ladderEnd);
    EXPECT_FALSE(f->within);
    EXPECT_EQ(f->ladder, 2);
    EXPECT_EQ(f->rung, 3);
    EXPECT_DOUBLE_EQ(f->cost, 1.0);
    // A finer rung timed cheaper (noise, against the rule) does not lift the bound above the
    // coarsest's own cost: the coarsest is the floor.
    l[2].cost = 0.5;
    f = ladderCostFloor(l, 0, 2.0);
    ASSERT_TRUE(f);
    EXPECT_EQ(f->rung, 3);
    EXPECT_DOUBLE_EQ(f->cost, 1.0);
    // A Within rung timed below the coarsest's cost becomes the floor, and the ladder's end
    // still limits what the claim covers.
    l[1].decision = Decision::Within;
    l[1].cost = 0.9;
    f = ladderCostFloor(l, 0, 2.0);
    ASSERT_TRUE(f);
    EXPECT_TRUE(f->within);
    EXPECT_TRUE(f->ladderEnd);
    EXPECT_EQ(f->rung, 1);
    l[1].decision = Decision::Unresolved;
    l[1].cost = 4.0;
    // The coarsest not timed yet may be the cheapest: no floor until it is.
    l[3].cost = NAN;
    EXPECT_FALSE(ladderCostFloor(l, 0, 2.0));
    // Past the stability limit a rung is no candidate: the coarsest short of it ends the ladder.
    l[3].failed = l[3].beyondStability = true;
    f = ladderCostFloor(l, 0, 2.0);
    ASSERT_TRUE(f);
    EXPECT_EQ(f->rung, 2);
    // Failed otherwise (a crash), the coarsest says nothing of what the ladder's end costs.
    l[3].beyondStability = false;
    EXPECT_FALSE(ladderCostFloor(l, 0, 2.0));
    // A bound from inside the ladder is kept where there is one: it is the higher.
    f = ladderCostFloor(growingLadder(), 0, 2.0);
    ASSERT_TRUE(f);
    EXPECT_FALSE(f->ladderEnd);
    EXPECT_DOUBLE_EQ(f->cost, 4.0);
}

TEST(TradeoffDominance, StabilityFailuresBoundNothingAndAnEngineTakesItsLeastFloor) {
    auto l = growingLadder();
    for (auto& r : l)
        if (r.decision == Decision::Outside)
            r.failed = r.beyondStability = true, r.cost = NAN, r.biases.clear();
    // Only the finest rung is short of the limit: it ends the ladder and is its floor.
    auto f = ladderCostFloor(l, 0, 2.0);
    ASSERT_TRUE(f);
    EXPECT_TRUE(f->ladderEnd);
    EXPECT_EQ(f->rung, 0);
    EXPECT_DOUBLE_EQ(f->cost, 8.0);
    for (auto& r : l)
        r.failed = r.beyondStability = true;
    EXPECT_FALSE(ladderCostFloor(l, 0, 2.0)); // every rung past the limit: nothing bounds
    // An engine's floor is the least of its ladders', and none when one ladder has none.
    auto cheap = growingLadder();
    for (auto& r : cheap)
        r.cost /= 4.0;
    const auto least = engineCostFloor({growingLadder(), cheap}, 2.0);
    ASSERT_TRUE(least);
    EXPECT_EQ(least->ladder, 1);
    EXPECT_DOUBLE_EQ(least->cost, 1.0);
    EXPECT_FALSE(engineCostFloor({growingLadder(), l}, 2.0));
}

} // namespace test_tradeoff
