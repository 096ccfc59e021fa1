// The statistics behind choosing a setting by its bias, on numbers worked by hand: replica means
// and their combination, the decision rule and its Student multiplier, the projection of the
// replicas a decision needs, the power-law fit on exact data, and the order-statistics interval
// of paired cost ratios. The Monte-Carlo checks of error rates and coverage are in
// test_tradeoff_montecarlo.cpp (validation tier).
#include "analysis/tradeoff_stats.hpp"
#include <cmath>
#include <gtest/gtest.h>
#include <numbers>
#include <random>
#include <vector>

namespace test_tradeoff_stats {

using namespace terrace::analysis;

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

double normalCdf(double z) {
    return 0.5 * std::erfc(-z / std::sqrt(2.0));
}

Estimate exact(double mean, double err) {
    return {mean, err, inf, 0};
}

} // namespace

TEST(TradeoffStats, ReplicaMeanOfKnownNumbers) {
    // mean 3.2, Σ(v − 3.2)² = 14.8, sd² = 3.7, se² = 3.7/5
    const std::vector<double> v{1.0, 2.0, 3.0, 4.0, 6.0};
    const Estimate e = replicaMean(v);
    EXPECT_DOUBLE_EQ(e.mean, 3.2);
    EXPECT_DOUBLE_EQ(e.err, std::sqrt(0.74));
    EXPECT_EQ(e.dof, 4.0);
    EXPECT_EQ(e.samples, 5);

    const Estimate one = replicaMean(std::vector<double>{7.0});
    EXPECT_EQ(one.mean, 7.0);
    EXPECT_TRUE(std::isnan(one.err));
    EXPECT_EQ(one.samples, 1);
    EXPECT_TRUE(std::isnan(replicaMean(std::vector<double>{}).mean));
}

TEST(TradeoffStats, BlockMeansCarryTheirDegreesOfFreedom) {
    const Estimate e = blockMean(std::vector<double>{1, 2, 3, 4, 5, 6, 7, 8}, 4);
    EXPECT_EQ(e.samples, 4);
    EXPECT_EQ(e.dof, 3.0);
}

TEST(TradeoffStats, CombinedReplicasTakeTheScatterWhenBlockErrorsAreTooSmall) {
    // Block errors of 0.01 against a scatter of sd 1.92: the scatter is the honest error.
    std::vector<Estimate> r;
    for (double v : {1.0, 2.0, 3.0, 4.0, 6.0})
        r.push_back({v, 0.01, 7.0, 8});
    const Estimate e = combineReplicaEstimates(r);
    EXPECT_DOUBLE_EQ(e.mean, 3.2);
    EXPECT_DOUBLE_EQ(e.err, std::sqrt(0.74));
    EXPECT_EQ(e.dof, 4.0);
    EXPECT_EQ(e.samples, 5);
}

TEST(TradeoffStats, CombinedReplicasTakeThePropagatedErrorWhenTheScatterIsSmall) {
    // Three replicas that agree by chance to 0.1 with block errors of 1 (7 dof each):
    // √(3·1)/3, with ν = (Σσ²)²/Σ(σ⁴/ν_i) = 9/(3/7) = 21.
    const std::vector<Estimate> r{{1.0, 1.0, 7.0, 8}, {1.1, 1.0, 7.0, 8}, {0.9, 1.0, 7.0, 8}};
    const Estimate e = combineReplicaEstimates(r);
    EXPECT_DOUBLE_EQ(e.mean, 1.0);
    EXPECT_DOUBLE_EQ(e.err, std::sqrt(3.0) / 3.0);
    EXPECT_DOUBLE_EQ(e.dof, 21.0);
    EXPECT_EQ(e.samples, 3);
}

TEST(TradeoffStats, DifferenceAddsErrorsInQuadratureAndKeepsTheSmallerDof) {
    const Estimate d = difference({3.0, 0.3, 4.0, 5}, {1.0, 0.4, 99.0, 100});
    EXPECT_DOUBLE_EQ(d.mean, 2.0);
    EXPECT_DOUBLE_EQ(d.err, 0.5);
    EXPECT_EQ(d.dof, 4.0);
    EXPECT_EQ(d.samples, 5);
    // An exact reference leaves the candidate's dof; two exact errors stay exact.
    EXPECT_EQ(difference({3.0, 0.3, 4.0, 5}, exact(1.0, 0.0)).dof, 4.0);
    EXPECT_EQ(difference(exact(3.0, 0.3), exact(1.0, 0.4)).dof, inf);
    EXPECT_TRUE(std::isnan(difference({3.0, 0.3, NAN, 1}, exact(1.0, 0.4)).dof));
}

TEST(TradeoffStats, RelativeToleranceScalesWithTheReferenceMagnitude) {
    EXPECT_DOUBLE_EQ(absoluteTolerance({0.02, true}, -50.0), 1.0);
    EXPECT_DOUBLE_EQ(absoluteTolerance({0.3, false}, -50.0), 0.3);
    // A floor above |reference| stands in for it; an absolute tolerance ignores it.
    EXPECT_DOUBLE_EQ(absoluteTolerance({0.02, true}, -0.5, 10.0), 0.2);
    EXPECT_DOUBLE_EQ(absoluteTolerance({0.02, true}, -50.0, 10.0), 1.0);
    EXPECT_DOUBLE_EQ(absoluteTolerance({0.3, false}, -0.5, 10.0), 0.3);
}

TEST(TradeoffStats, SequentialZIsBonferroniOverLooks) {
    EXPECT_NEAR(sequentialZ(0.0455, 1), 2.0, 1e-4);
    EXPECT_NEAR(sequentialZ(0.05, 1), 1.959964, 1e-6);
    EXPECT_NEAR(sequentialZ(0.05, 5), 2.575829, 1e-6); // Φ⁻¹(1 − 0.005)
    EXPECT_THROW(sequentialZ(0.05, 0), std::invalid_argument);
    EXPECT_THROW(sequentialZ(0.0, 1), std::invalid_argument);
}

TEST(TradeoffStats, DecisionNeedsTheErrorBarClearOfTheTolerance) {
    // Exact errors (ν = ∞): the multiplier is z. Values chosen to be exact in binary.
    EXPECT_EQ(decideBias(exact(0.5, 0.25), 1.0, 2.0).decision, Decision::Within); // 0.5 + 0.5 = 1
    EXPECT_EQ(decideBias(exact(-0.5, 0.25), 1.0, 2.0).decision, Decision::Within);
    EXPECT_EQ(decideBias(exact(0.5, 0.3), 1.0, 2.0).decision, Decision::Unresolved);
    EXPECT_EQ(decideBias(exact(1.5, 0.25), 1.0, 2.0).decision, Decision::Outside); // 1.5 − 0.5
    EXPECT_EQ(decideBias(exact(-1.5, 0.25), 1.0, 2.0).decision, Decision::Outside);
    EXPECT_EQ(decideBias(exact(1.5, 0.3), 1.0, 2.0).decision, Decision::Unresolved);
    EXPECT_EQ(decideBias(exact(0.5, NAN), 1.0, 2.0).decision, Decision::Unresolved);
    const BiasDecision d = decideBias(exact(0.5, 0.25), 1.0, 2.0);
    EXPECT_EQ(d.multiplier, 2.0);
    EXPECT_EQ(d.tolerance, 1.0);
}

TEST(TradeoffStats, FewReplicasWidenTheMultiplierToStudentsT) {
    // One degree of freedom is Cauchy: T⁻¹(q) = tan(π(q − ½)); at Φ(2) about 13.97.
    const double k1 = std::tan(std::numbers::pi * (normalCdf(2.0) - 0.5));
    EXPECT_NEAR(studentMultiplier(2.0, 1.0), k1, 1e-9 * k1);
    // Two degrees of freedom: T⁻¹(q) = (2q − 1)·√(2/(4q(1 − q))).
    const double q = normalCdf(2.0);
    EXPECT_NEAR(studentMultiplier(2.0, 2.0), (2 * q - 1) * std::sqrt(2.0 / (4 * q * (1 - q))),
                1e-9);
    EXPECT_EQ(studentMultiplier(2.0, inf), 2.0);
    EXPECT_TRUE(std::isnan(studentMultiplier(2.0, 0.0)));
    // 0.5 ± 0.04 is Within at 2σ for an exact error, not for an error from two replicas.
    EXPECT_EQ(decideBias(exact(0.5, 0.04), 1.0, 2.0).decision, Decision::Within);
    EXPECT_EQ(decideBias({0.5, 0.04, 1.0, 2}, 1.0, 2.0).decision, Decision::Unresolved);
    EXPECT_EQ(decideBias({0.5, 0.025, 1.0, 2}, 1.0, 2.0).decision, Decision::Within);
}

TEST(TradeoffStats, ProjectedReplicasAreTheFewestThatResolve) {
    const double tol = 1.0, z = 2.0;
    const Estimate reference{0.0, 0.05, 40.0, 41};
    // Per-replica sd 0.4: se = 0.2 at 4 replicas, 0.5 ± 0.2 is unresolved.
    const Estimate candidate{0.5, 0.2, 3.0, 4};
    const int n = replicasToResolve(candidate, reference, tol, z, 100);
    ASSERT_GT(n, 4);
    ASSERT_LT(n, 100);
    const auto at = [&](int m) {
        const Estimate c{0.5, 0.4 / std::sqrt(m), m - 1.0, m};
        return decideBias(difference(c, reference), tol, z).decision;
    };
    EXPECT_EQ(at(n), Decision::Within);
    EXPECT_EQ(at(n - 1), Decision::Unresolved);

    // Already resolved: the current count; capped; no error yet: 2.
    EXPECT_EQ(replicasToResolve({0.2, 0.05, 9.0, 10}, reference, tol, z, 100), 10);
    EXPECT_EQ(replicasToResolve(candidate, reference, tol, z, 6), 6);
    EXPECT_EQ(replicasToResolve({0.5, NAN, 0.0, 1}, reference, tol, z, 100), 2);
    // On the tolerance, or with a reference too uncertain for the gap: the cap.
    EXPECT_EQ(replicasToResolve({1.0, 0.2, 3.0, 4}, reference, tol, z, 50), 50);
    EXPECT_EQ(replicasToResolve(candidate, {0.0, 0.3, 40.0, 41}, tol, z, 50), 50);
}

TEST(TradeoffStats, LooksFollowAFixedDoublingSchedule) {
    EXPECT_EQ(lookSchedule(2, 50), (std::vector<int>{2, 4, 8, 16, 32, 50}));
    EXPECT_EQ(lookSchedule(2, 64), (std::vector<int>{2, 4, 8, 16, 32, 64}));
    EXPECT_EQ(lookSchedule(3, 3), (std::vector<int>{3}));
    EXPECT_THROW(lookSchedule(0, 8), std::invalid_argument);
    const std::vector<int> s{2, 4, 8, 16, 32, 50};
    EXPECT_EQ(nextLook(s, 2, 3), 4); // the projection rounded up to the schedule
    EXPECT_EQ(nextLook(s, 2, 11), 16);
    EXPECT_EQ(nextLook(s, 8, 8), 16);   // always beyond the current count
    EXPECT_EQ(nextLook(s, 16, 60), 50); // capped at the budget
}

TEST(TradeoffStats, PowerLawFitRecoversAnExactLaw) {
    // Time steps in ps with a bias 2.5e4·dt^2.7 and 5 % error bars, no noise.
    const double c = 2.5e4, p = 2.7;
    const std::vector<double> dt{0.001, 0.002, 0.004, 0.008, 0.016};
    std::vector<Estimate> b;
    for (double x : dt)
        b.push_back(exact(c * std::pow(x, p), 0.05 * c * std::pow(x, p)));
    const PowerLaw law = fitPowerLaw(dt, b, std::nullopt);
    ASSERT_TRUE(law.ok) << law.why;
    EXPECT_NEAR(law.p, p, 1e-7);
    EXPECT_NEAR(law.c, c, 1e-6 * c);
    EXPECT_LT(law.chi2, 1e-12);
    EXPECT_EQ(law.points, 5);
    // In the small-error limit the Δχ² = 1 half-width is the linear error of a straight-line fit
    // in log-log coordinates: 1/√(Σ w_i (ln x_i − mean)²), w_i = 1/0.05², ln x_i = ln 2·(−2…2).
    const double linear = 0.05 / (std::log(2.0) * std::sqrt(10.0));
    EXPECT_NEAR(law.pErr, linear, 0.02 * linear);
    EXPECT_NEAR(law.pFisherErr, linear, 1e-9 * linear);

    // A negative bias, with the exponent fixed: c alone, in closed form.
    std::vector<Estimate> neg;
    for (double x : dt)
        neg.push_back(exact(-3.0 * x * x, 0.01));
    const PowerLaw fixed = fitPowerLaw(dt, neg, 2.0);
    ASSERT_TRUE(fixed.ok) << fixed.why;
    EXPECT_NEAR(fixed.c, -3.0, 1e-12);
    EXPECT_EQ(fixed.p, 2.0);
    EXPECT_EQ(fixed.pErr, 0.0);
}

TEST(TradeoffStats, PowerLawFitRefusesTooFewPointsAndAnExponentAtTheEdge) {
    const std::vector<double> two{1.0, 2.0};
    const std::vector<Estimate> b2{exact(1.0, 0.1), exact(4.0, 0.1)};
    const PowerLaw free = fitPowerLaw(two, b2, std::nullopt);
    EXPECT_FALSE(free.ok);
    EXPECT_FALSE(free.why.empty());
    EXPECT_TRUE(fitPowerLaw(two, b2, 2.0).ok);
    // Points without an error or at x ≤ 0 do not count.
    const std::vector<double> x3{0.0, 1.0, 2.0};
    const std::vector<Estimate> b3{exact(0.0, 0.1), exact(1.0, 0.1), exact(4.0, 0.0)};
    const PowerLaw one = fitPowerLaw(x3, b3, 2.0);
    EXPECT_FALSE(one.ok);
    EXPECT_EQ(one.points, 1);
    // x^10 lies beyond pMax = 8.
    const std::vector<double> x{1.0, 2.0, 3.0};
    const std::vector<Estimate> steep{exact(1.0, 0.01), exact(1024.0, 10.24),
                                      exact(59049.0, 590.49)};
    const PowerLaw edge = fitPowerLaw(x, steep, std::nullopt);
    EXPECT_FALSE(edge.ok);
    EXPECT_FALSE(edge.why.empty());
    EXPECT_THROW(fitPowerLaw(x, b2, std::nullopt), std::invalid_argument);
}

TEST(TradeoffStats, SettingAtToleranceInvertsTheLaw) {
    PowerLaw law;
    law.ok = true;
    law.c = -3.0, law.p = 2.0, law.pivot = 0.1;
    law.lnAmplitudeErr = 0.1, law.pFisherErr = 0.0, law.correlation = 0.0;
    // |c|·x² = 0.12 at x = 0.2; ln x* = ln x0 + ln(tol/|a|)/p carries σ_ln|a|/p = 0.05.
    const Interval s = settingAtTolerance(law, 0.12);
    EXPECT_NEAR(s.value, 0.2, 1e-12);
    EXPECT_NEAR(s.lo, 0.2 * std::exp(-0.05), 1e-12);
    EXPECT_NEAR(s.hi, 0.2 * std::exp(0.05), 1e-12);
    // An uncertain exponent widens the band by σ_p·ln(x*/x0)/p.
    law.pFisherErr = 0.2;
    const double sp = 0.2 * std::log(2.0) / 2.0;
    EXPECT_NEAR(settingAtTolerance(law, 0.12).hi, 0.2 * std::exp(std::hypot(0.05, sp)), 1e-12);
    EXPECT_TRUE(std::isnan(settingAtTolerance(law, 0.0).value));
    law.ok = false;
    EXPECT_TRUE(std::isnan(settingAtTolerance(law, 0.12).value));
}

TEST(TradeoffStats, PairedRatioIntervalFromOrderStatistics) {
    // Sorted ratios 1.1 1.2 1.3 1.5 1.6 1.7 1.9 2.0 2.4 3.0; median (1.6 + 1.7)/2. For n = 10,
    // P(Bin ≤ 1) = 11/1024 gives coverage 1 − 22/1024 = 0.9785 ≥ 0.95 at k = 2, while k = 3 has
    // P(Bin ≤ 2) = 56/1024, coverage 0.8906: the interval is [r_(2), r_(9)] = [1.2, 2.4].
    const std::vector<double> r{1.9, 1.2, 2.4, 1.5, 1.1, 2.0, 1.7, 1.3, 3.0, 1.6};
    std::vector<double> a, b;
    for (double x : r)
        a.push_back(2.0 * x), b.push_back(2.0);
    const RatioInterval ci = pairedRatio(a, b, 0.95);
    EXPECT_DOUBLE_EQ(ci.median, 1.65);
    EXPECT_DOUBLE_EQ(ci.lo, 1.2);
    EXPECT_DOUBLE_EQ(ci.hi, 2.4);
    EXPECT_EQ(ci.pairs, 10);
    EXPECT_DOUBLE_EQ(ci.level, 1.0 - 22.0 / 1024.0);
    // At 0.85 the k = 3 interval suffices.
    const RatioInterval ci85 = pairedRatio(a, b, 0.85);
    EXPECT_DOUBLE_EQ(ci85.lo, 1.3);
    EXPECT_DOUBLE_EQ(ci85.hi, 2.0);
    EXPECT_DOUBLE_EQ(ci85.level, 1.0 - 112.0 / 1024.0);
}

TEST(TradeoffStats, PairedRatioReportsTheLevelFewPairsReach) {
    // Five pairs cannot reach 0.95: [min, max] covers with 1 − 2/2⁵ = 0.9375.
    const std::vector<double> a{3.0, 1.0, 5.0, 2.0, 4.0}, b(5, 1.0);
    const RatioInterval ci = pairedRatio(a, b, 0.95);
    EXPECT_DOUBLE_EQ(ci.median, 3.0);
    EXPECT_DOUBLE_EQ(ci.lo, 1.0);
    EXPECT_DOUBLE_EQ(ci.hi, 5.0);
    EXPECT_DOUBLE_EQ(ci.level, 0.9375);
    EXPECT_EQ(pairedRatio(std::vector<double>{2.0}, std::vector<double>{1.0}).level, 0.0);
    EXPECT_THROW(pairedRatio(a, std::vector<double>{1.0}), std::invalid_argument);
    EXPECT_THROW(pairedRatio(std::vector<double>{1.0}, std::vector<double>{0.0}),
                 std::invalid_argument);
}

TEST(TradeoffStats, PooledEstimateTakesTheBlocksUnlessTheScatterContradictsThem) {
    // Two replicas of 8 blocks each (7 dof), scatter well inside what the blocks say: the blocks'
    // error, √(0.1² + 0.1²)/2, with 14 dof.
    const std::vector<Estimate> agree{{1.0, 0.1, 7.0, 1}, {1.05, 0.1, 7.0, 1}};
    const Estimate a = pooledReplicaEstimate(agree);
    EXPECT_DOUBLE_EQ(a.mean, 1.025);
    EXPECT_DOUBLE_EQ(a.err, std::sqrt(0.02) / 2.0);
    EXPECT_NEAR(a.dof, 14.0, 1e-12);
    // Runs a whole unit apart with errors of 0.01: the blocks miss something, the scatter rules.
    const std::vector<Estimate> disagree{{1.0, 0.01, 7.0, 1}, {2.0, 0.01, 7.0, 1}};
    const Estimate d = pooledReplicaEstimate(disagree);
    EXPECT_DOUBLE_EQ(d.err, 0.5);
    EXPECT_DOUBLE_EQ(d.dof, 1.0);
    // A replica without an error: the scatter alone.
    const std::vector<Estimate> unknown{{1.0, 0.1, 7.0, 1}, {1.2, NAN, 7.0, 1}};
    EXPECT_DOUBLE_EQ(pooledReplicaEstimate(unknown).dof, 1.0);
}

TEST(TradeoffStats, PooledEstimateCoversTheTruthAtItsLevel) {
    // Replicas whose 8 blocks are independent Gaussian (the blocks' assumption holds): the
    // Student interval of the pooled estimate covers the true mean 95 % of the time, within
    // Monte-Carlo error, though the F test sometimes hands the decision to the scatter.
    std::mt19937_64 rng(11);
    std::normal_distribution<double> noise(0.0, 1.0);
    const int trials = 20000, replicas = 2, blocks = 8;
    int covered = 0;
    for (int t = 0; t < trials; ++t) {
        std::vector<Estimate> runs;
        for (int r = 0; r < replicas; ++r) {
            std::vector<double> b;
            for (int k = 0; k < blocks; ++k)
                b.push_back(noise(rng));
            const Estimate m = replicaMean(b);
            runs.push_back({m.mean, m.err, double(blocks - 1), 1});
        }
        const Estimate p = pooledReplicaEstimate(runs);
        const double k = studentMultiplier(1.959964, p.dof);
        covered += std::abs(p.mean) <= k * p.err;
    }
    const double rate = double(covered) / trials;
    EXPECT_NEAR(rate, 0.95, 3.0 * std::sqrt(0.05 * 0.95 / trials) + 0.01);
}

} // namespace test_tradeoff_stats
