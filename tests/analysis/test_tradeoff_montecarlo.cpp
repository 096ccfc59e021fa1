// Monte-Carlo checks of tradeoff_stats (validation tier): synthetic replicas with a known bias and
// Gaussian noise go through the sequential loop the tradeoff command runs, and the rates of wrong
// decisions are held to the level the rule claims; noisy power laws check that the fit's errors
// cover the truth as often as they say. A fixed seed makes every run the same.
#include "analysis/tradeoff_stats.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <random>
#include <vector>

namespace test_tradeoff_montecarlo {

using namespace terrace::analysis;

namespace {

constexpr std::uint64_t kSeed = 20240611;

/// The sequential loop of the tradeoff command (tradeoff_stats.hpp, nextLook): look at the
/// counts of lookSchedule(2, maxReplicas) that replicasToResolve leads to, at
/// z = sequentialZ(α, schedule size); Unresolved when the budget is spent.
struct Sequential {
    double alpha = 0.0455;
    int maxReplicas = 64;
    int referenceReplicas = 100;
    double sigma = 1.0;     // per-replica scatter of the observable
    double tolerance = 1.0; // in the same units

    Decision run(double trueBias, std::mt19937_64& rng, int& replicasUsed) const {
        std::normal_distribution<double> noise(0.0, sigma);
        std::vector<double> ref(referenceReplicas);
        for (double& v : ref)
            v = noise(rng);
        const Estimate reference = replicaMean(ref);
        const std::vector<int> schedule = lookSchedule(2, maxReplicas);
        const double z = sequentialZ(alpha, static_cast<int>(schedule.size()));
        std::vector<double> cand;
        for (int n = schedule.front();;) {
            while (static_cast<int>(cand.size()) < n)
                cand.push_back(trueBias + noise(rng));
            const Estimate candidate = replicaMean(cand);
            const Decision d = decideBias(difference(candidate, reference), tolerance, z).decision;
            replicasUsed = n;
            if (d != Decision::Unresolved || n >= schedule.back()) return d;
            n = nextLook(schedule, n,
                         replicasToResolve(candidate, reference, tolerance, z, maxReplicas));
        }
    }
};

struct Rates {
    double within = 0, outside = 0, unresolved = 0, meanReplicas = 0;
};

Rates simulate(const Sequential& s, double trueBias, int trials, std::mt19937_64& rng) {
    Rates r;
    for (int t = 0; t < trials; ++t) {
        int used = 0;
        switch (s.run(trueBias, rng, used)) {
        case Decision::Within:
            r.within += 1;
            break;
        case Decision::Outside:
            r.outside += 1;
            break;
        case Decision::Unresolved:
            r.unresolved += 1;
            break;
        }
        r.meanReplicas += used;
    }
    r.within /= trials, r.outside /= trials, r.unresolved /= trials, r.meanReplicas /= trials;
    return r;
}

/// Monte-Carlo standard error of a rate p estimated from n trials.
double mcError(double p, int n) {
    return std::sqrt(p * (1.0 - p) / n);
}

} // namespace

TEST(TradeoffMonteCarlo, SequentialDecisionsKeepTheirLevel) {
    std::mt19937_64 rng(kSeed);
    const Sequential s;
    constexpr int trials = 10000; // about 0.5 s per true bias
    // Each wrong decision has probability ≤ α/2 (decideBias), over all looks by Bonferroni.
    const double oneSided = s.alpha / 2.0;
    const double slack = 3.0 * mcError(oneSided, trials);

    const Rates far = simulate(s, 1.5 * s.tolerance, trials, rng);
    const Rates near = simulate(s, 0.5 * s.tolerance, trials, rng);
    const Rates at = simulate(s, s.tolerance, trials, rng);
    const auto show = [](const char* what, const Rates& r) {
        std::printf("%-12s within %.4f  outside %.4f  unresolved %.4f  mean replicas %.1f\n", what,
                    r.within, r.outside, r.unresolved, r.meanReplicas);
    };
    show("bias 1.5 tol", far);
    show("bias 0.5 tol", near);
    show("bias 1.0 tol", at);

    EXPECT_LE(far.within, oneSided + slack) << "false accept at 1.5 tol";
    EXPECT_LE(near.outside, oneSided + slack) << "false reject at 0.5 tol";
    EXPECT_LE(at.within, oneSided + slack) << "accept at the tolerance";
    EXPECT_LE(at.outside, oneSided + slack) << "reject at the tolerance";
    EXPECT_LE(at.within + at.outside, s.alpha + 3.0 * mcError(s.alpha, trials));
    // A rule that never decides would pass the above: the loop must also resolve most clear
    // cases. (At the budget, 64 replicas of sd 1 against a 100-replica reference, se = 0.16 and
    // the multiplier is 2.75 at 63 dof: an observed gap beyond 0.44 resolves, for a true gap of
    // 0.5 about two times in three.)
    EXPECT_GT(far.outside, 0.5);
    EXPECT_GT(near.within, 0.5);
}

namespace {

struct LadderCoverage {
    double p1 = 0, p3 = 0, x1 = 0, x3 = 0, notOk = 0;
};

/// Fits of bias = c·x^p to a ladder of settings with Gaussian noise of known error bars.
LadderCoverage ladderCoverage(const std::vector<double>& x, const std::vector<double>& err,
                              double c, double p, double xStar, int trials, std::mt19937_64& rng) {
    std::normal_distribution<double> unit(0.0, 1.0);
    const double tolerance = std::abs(c) * std::pow(xStar, p);
    LadderCoverage r;
    std::vector<Estimate> b(x.size());
    for (int t = 0; t < trials; ++t) {
        for (std::size_t i = 0; i < x.size(); ++i)
            b[i] = {c * std::pow(x[i], p) + err[i] * unit(rng), err[i]};
        const PowerLaw law = fitPowerLaw(x, b, std::nullopt);
        if (!law.ok) {
            r.notOk += 1;
            continue;
        }
        const double dp = std::abs(law.p - p);
        r.p1 += dp <= law.pErr, r.p3 += dp <= 3.0 * law.pErr;
        const Interval s = settingAtTolerance(law, tolerance);
        const double sigma = std::log(s.hi / s.value), dx = std::abs(std::log(xStar / s.value));
        r.x1 += dx <= sigma, r.x3 += dx <= 3.0 * sigma;
    }
    r.p1 /= trials, r.p3 /= trials, r.x1 /= trials, r.x3 /= trials, r.notOk /= trials;
    return r;
}

} // namespace

TEST(TradeoffMonteCarlo, PowerLawErrorsCoverTheTruth) {
    std::mt19937_64 rng(kSeed + 1);
    constexpr int trials = 4000;
    constexpr double oneSigma = 0.6827, threeSigma = 0.9973;
    // The 68 % check allows, besides 3 Monte-Carlo errors, 0.02 for the fit's asymptotic errors
    // (five points, a model nonlinear in p); a factor 2 in pErr moves coverage by 0.3.
    const double slack = 3.0 * mcError(oneSigma, trials) + 0.02;
    // A time-step ladder in ps with a second-order bias (in units of the observable) and error bars
    // from replicas: 8 % of the bias, and the same absolute error on every rung (the small steps'
    // biases are then barely resolved, as in a real ladder).
    const std::vector<double> dt{0.001, 0.002, 0.004, 0.008, 0.016};
    const double c = 2.0e4, p = 2.0, xStar = 0.006;
    std::vector<double> relative, absolute(dt.size(), 0.08 * c * std::pow(0.004, p));
    for (double x : dt)
        relative.push_back(0.08 * c * std::pow(x, p));
    for (const auto* err : {&relative, &absolute}) {
        const LadderCoverage r = ladderCoverage(dt, *err, c, p, xStar, trials, rng);
        std::printf("%s errors: p within 1 pErr %.4f, 3 pErr %.4f; x* within 1 sigma %.4f, "
                    "3 sigma %.4f; not ok %.4f\n",
                    err == &relative ? "relative" : "absolute", r.p1, r.p3, r.x1, r.x3, r.notOk);
        EXPECT_NEAR(r.p1, oneSigma, slack);
        EXPECT_GE(r.p3, threeSigma - 3.0 * mcError(threeSigma, trials) - 0.005);
        EXPECT_NEAR(r.x1, oneSigma, slack);
        EXPECT_GE(r.x3, threeSigma - 3.0 * mcError(threeSigma, trials) - 0.005);
    }
}

} // namespace test_tradeoff_montecarlo
