// The steps of `terrace tradeoff`'s search (cli/tradeoff_search.hpp) on search states built by
// hand, without a run: each rung's decision and the failure it is known by, the estimator DMD is
// judged by, the CPU budget, the reference's growth and its dt check, and the setting the bias
// law places between two rungs.
#include "cli/tradeoff_search.hpp"
#include <gtest/gtest.h>

namespace test_tradeoff_search {

using namespace terrace;
using namespace terrace::cli;
using analysis::Decision;

namespace {

/// Gives the first n replicas `key` = mean ± spread, ± 2 spread, … in pairs (n even: the mean is
/// exact, the scatter `spread` times a known factor).
void setValues(std::vector<ReplicaResult>& replicas, int n, const std::string& key, double mean,
               double spread) {
    if (int(replicas.size()) < n) replicas.resize(n);
    for (int i = 0; i < n; ++i) {
        replicas[i].ok = true;
        replicas[i].value[key] = mean + (i % 2 ? -1.0 : 1.0) * spread * (1 + i / 2);
    }
}

/// A search over u and d with absolute tolerances 0.01 and 0.05 at z = 2, whose reference (SMD
/// yoshida4 at 0.5 fs) has 8 replicas at u = −2, d = 1, scattered by 1e-4.
Tradeoff searchState() {
    Tradeoff t;
    t.observables = {Observable::U, Observable::D};
    t.tolerance[Observable::U] = {0.01, false};
    t.tolerance[Observable::D] = {0.05, false};
    t.z = 2.0;
    t.options.maxReplicas = 128;
    t.options.budgetCpuHours = 1.0;
    t.schedule = analysis::lookSchedule(2, 128);
    t.reference.setting = smdSetting("yoshida4", 0.5);
    t.reference.setting.ladder = "reference";
    t.reference.target = 8;
    setValues(t.reference.replicas, 8, "u", -2.0, 1e-4);
    setValues(t.reference.replicas, 8, "d", 1.0, 1e-4);
    return t;
}

/// A rung of 4 replicas at u, d, each scattered by `spread`.
Rung rungAt(const Setting& s, double u, double d, double spread) {
    Rung r;
    r.setting = s;
    r.target = 4;
    setValues(r.replicas, 4, "u", u, spread);
    setValues(r.replicas, 4, "d", d, spread);
    return r;
}

ObservableBias biasOn(Observable o, double bias, double err, double tolerance, Decision d) {
    ObservableBias b;
    b.observable = o;
    b.bias = {bias, err};
    b.candidate = {bias, err};
    b.reference = {0.0, 0.0};
    b.tolerance = tolerance;
    b.decision = d;
    return b;
}

} // namespace

// A rung is Within when every observable is, Outside when one is, Unresolved otherwise.
TEST(TradeoffSearch, ARungIsDecidedByItsWorstObservable) {
    Tradeoff t = searchState();
    Rung within = rungAt(smdSetting("verlet", 1.0), -2.0, 1.0, 1e-4);
    Rung outside = rungAt(smdSetting("verlet", 2.0), -2.0, 1.2, 1e-4); // d 4 tolerances off
    Rung unresolved = rungAt(smdSetting("verlet", 1.5), -2.0, 1.05, 1e-4);
    setValues(unresolved.replicas, 4, "d", 1.05, 0.02); // d at the edge, its error 0.018
    chooseEstimators(t);
    for (Rung* r : {&within, &outside, &unresolved})
        judge(t, *r);
    EXPECT_EQ(within.decision, Decision::Within);
    ASSERT_EQ(within.biases.size(), 2u);
    EXPECT_EQ(outside.decision, Decision::Outside);
    ASSERT_EQ(outside.biases.size(), 2u);
    EXPECT_EQ(outside.biases[0].decision, Decision::Within);  // u
    EXPECT_EQ(outside.biases[1].decision, Decision::Outside); // d
    EXPECT_NEAR(outside.biases[1].bias.mean, 0.2, 1e-12);
    EXPECT_EQ(unresolved.decision, Decision::Unresolved);
    ASSERT_EQ(unresolved.biases.size(), 2u);
    EXPECT_EQ(unresolved.biases[0].decision, Decision::Within);
    EXPECT_EQ(unresolved.biases[1].decision, Decision::Unresolved);
    EXPECT_TRUE(outside.failure.empty());
}

// A replica that failed puts its rung outside; where one met SMD's stability limit, that is the
// failure the rung is known by, whichever replica failed first.
TEST(TradeoffSearch, AFailedReplicaIsOutsideAndTheStabilityLimitNamesIt) {
    Tradeoff t = searchState();
    chooseEstimators(t);
    for (const bool crashFirst : {true, false}) {
        Rung r = rungAt(smdSetting("verlet", 4.0), -2.0, 1.0, 1e-4);
        ReplicaResult crash, limit;
        crash.failure = "exit status 1";
        limit.failure = "energy drift beyond the stability limit";
        limit.beyondStability = true;
        r.replicas.push_back(crashFirst ? crash : limit);
        r.replicas.push_back(crashFirst ? limit : crash);
        judge(t, r);
        EXPECT_EQ(r.decision, Decision::Outside);
        EXPECT_TRUE(r.beyondStability);
        EXPECT_EQ(r.failure, limit.failure);
        EXPECT_TRUE(r.biases.empty());
    }
    Rung crashed = rungAt(smdSetting("verlet", 4.0), -2.0, 1.0, 1e-4);
    crashed.replicas[1].ok = false;
    crashed.replicas[1].failure = "exit status 1";
    judge(t, crashed);
    EXPECT_EQ(crashed.decision, Decision::Outside);
    EXPECT_FALSE(crashed.beyondStability);
    EXPECT_EQ(crashed.failure, "exit status 1");
}

// DMD is judged by the estimator whose biases over its rungs are the smaller, per observable;
// D has only its own. The other estimator's bias is kept beside the chosen one.
TEST(TradeoffSearch, DmdIsJudgedByTheEstimatorWithTheSmallerBias) {
    for (const bool terracedFar : {true, false}) {
        Tradeoff t = searchState();
        std::vector<Rung> ladder{rungAt(dmdSetting("dmd-uniform", 0.5), -2.0, 1.0, 1e-4)};
        Rung& r = ladder.front();
        // Terraced U 0.5 off and the configurational 0.002 off, or the other way round.
        setValues(r.replicas, 4, "u", terracedFar ? -1.5 : -2.002, 1e-4);
        setValues(r.replicas, 4, "u_conf", terracedFar ? -2.002 : -1.5, 1e-4);
        t.ladders.push_back(ladder);
        chooseEstimators(t);
        EXPECT_EQ(t.dmdEstimator.at(Observable::U),
                  terracedFar ? Estimator::Configurational : Estimator::Own);
        EXPECT_EQ(t.dmdEstimator.at(Observable::D), Estimator::Own);
        Rung& judged = t.ladders.front().front();
        judge(t, judged);
        ASSERT_EQ(judged.biases.size(), 2u);
        EXPECT_NEAR(judged.biases[0].bias.mean, -0.002, 1e-9);
        EXPECT_EQ(judged.decision, Decision::Within);
        ASSERT_EQ(judged.alternatives.size(), 1u); // u by the other estimator; none for d
        EXPECT_EQ(judged.alternatives[0].observable, Observable::U);
        EXPECT_NEAR(judged.alternatives[0].bias.mean, 0.5, 1e-9);
        EXPECT_EQ(judged.alternatives[0].decision, Decision::Outside);
    }
}

// The runs asked for that would take the CPU spent past the budget are taken back, the costliest
// first; a rung with no runs yet is priced at its ladder's mean per replica.
TEST(TradeoffSearch, TheBudgetTakesBackTheCostliestRunsFirst) {
    const auto state = [](double spent) {
        Tradeoff t = searchState();
        for (auto& r : t.reference.replicas)
            r.cpuSeconds = 10.0;
        Rung a = rungAt(smdSetting("verlet", 1.0), -2.0, 1.0, 1e-4); // 100 CPU s a replica
        Rung b = rungAt(dmdSetting("dmd-uniform", 0.5), -2.0, 1.0, 1e-4);
        for (auto& x : a.replicas)
            x.cpuSeconds = 100.0;
        for (auto& x : b.replicas)
            x.cpuSeconds = 300.0;
        a.target = 6, b.target = 6; // 2 more each: 200 and 600 CPU s
        Rung c;                     // b's ladder, no runs yet: priced at 300 a replica
        c.setting = dmdSetting("dmd-uniform", 1.0);
        c.target = 1;
        t.ladders = {{a}, {b, c}};
        t.cpuSpent = spent;
        return t;
    };
    // 3300 + 600 + 300 + 200 is past 3600: b's runs go, then c's; a's fit.
    Tradeoff t = state(3300.0);
    EXPECT_TRUE(fitBudget(t));
    EXPECT_EQ(t.ladders[0][0].target, 6);
    EXPECT_EQ(t.ladders[1][0].target, 4);
    EXPECT_EQ(t.ladders[1][1].target, 0);
    // Everything fits.
    t = state(2000.0);
    EXPECT_TRUE(fitBudget(t));
    EXPECT_EQ(t.ladders[0][0].target, 6);
    EXPECT_EQ(t.ladders[1][0].target, 6);
    EXPECT_EQ(t.ladders[1][1].target, 1);
    // Nothing fits: no run is left to make.
    t = state(3500.0);
    EXPECT_FALSE(fitBudget(t));
    EXPECT_EQ(t.ladders[0][0].target, 4);
    EXPECT_EQ(t.ladders[1][0].target, 4);
    EXPECT_EQ(t.ladders[1][1].target, 0);
}

// The reference doubles while its standard error is above a third of a tolerance, or is the
// larger share of an open decision's; never past the replica limit.
TEST(TradeoffSearch, TheReferenceDoublesUntilItsErrorIsSmall) {
    // u's tolerance 0.01: a third of it is 0.0033. Replicas ±s, ±2s, ±3s, ±4s have the
    // standard error s·√(60/7)/√8 = 1.035 s.
    Tradeoff t = searchState();
    EXPECT_FALSE(raiseReference(t));
    setValues(t.reference.replicas, 8, "u", -2.0, 0.0030); // 0.0031
    EXPECT_FALSE(raiseReference(t));
    EXPECT_EQ(t.reference.target, 8);
    setValues(t.reference.replicas, 8, "u", -2.0, 0.0034); // 0.0035
    EXPECT_TRUE(raiseReference(t));
    EXPECT_EQ(t.reference.target, 16);
    t.options.maxReplicas = 16;
    EXPECT_FALSE(raiseReference(t));
    EXPECT_EQ(t.reference.target, 16);

    Tradeoff open = searchState();
    Rung r = rungAt(smdSetting("verlet", 1.0), -2.0, 1.0, 1e-4);
    ObservableBias b = biasOn(Observable::D, 0.05, 0.01, 0.05, Decision::Unresolved);
    b.candidate.err = 0.004, b.reference.err = 0.009; // the reference's is the larger share
    r.biases = {b};
    open.ladders = {{r}};
    EXPECT_TRUE(raiseReference(open));
    open.ladders[0][0].biases[0].reference.err = 0.001;
    open.reference.target = 8;
    EXPECT_FALSE(raiseReference(open));
}

// yoshida4 at twice the reference's step bounds the reference's own dt error at 1/15 of the
// difference (dt⁴), taken at |bias| + 2σ; shown converged below a quarter of every tolerance.
TEST(TradeoffSearch, TheReferencesStepIsCheckedAtTwiceIt) {
    Tradeoff t = searchState();
    Rung twice, coarser;
    twice.setting = smdSetting("yoshida4", 1.0);
    coarser.setting = smdSetting("yoshida4", 2.0);
    t.ladders = {{twice, coarser}};
    const Rung* check = referenceCheckRung(t);
    ASSERT_EQ(check, &t.ladders[0][0]);
    EXPECT_FALSE(referenceShownConverged(*check)); // nothing measured yet
    Rung& r = t.ladders[0][0];
    r.biases = {biasOn(Observable::U, 0.1, 0.01, 0.5, Decision::Within)};
    EXPECT_NEAR(referenceBiasBound(r.biases[0], 2.0), 0.12 / 15.0, 1e-15);
    EXPECT_TRUE(referenceShownConverged(r));
    // (1.86 + 2·0.01)/15 = 0.1253 is past a quarter of 0.5.
    r.biases.push_back(biasOn(Observable::D, 1.86, 0.01, 0.5, Decision::Outside));
    EXPECT_FALSE(referenceShownConverged(r));
    t.reference.setting.x = 0.75;
    EXPECT_EQ(referenceCheckRung(t), nullptr);
}

// Between the cheapest Within rung and the Outside one after it, the dt² law of verlet's bias
// places the setting where it reaches the tolerance, on the sampling grid and rounded to the
// finer side; once per ladder.
TEST(TradeoffSearch, TheBiasLawPlacesASettingBetweenWithinAndOutside) {
    Tradeoff t = searchState();
    std::vector<Rung> ladder;
    for (const double dt : {0.5, 1.0, 2.0}) {
        Rung r;
        r.setting = smdSetting("verlet", dt);
        r.target = 4;
        // d's bias 0.025 dt² against 0.05: it reaches the tolerance at dt = √2 fs.
        r.biases = {biasOn(Observable::U, 1e-4, 1e-4, 0.01, Decision::Within),
                    biasOn(Observable::D, 0.025 * dt * dt, 1e-4, 0.05,
                           dt < 1.5 ? Decision::Within : Decision::Outside)};
        r.decision = dt < 1.5 ? Decision::Within : Decision::Outside;
        ladder.push_back(r);
    }
    const std::vector<Rung> asGiven = ladder;
    ASSERT_TRUE(interpolate(t, ladder));
    ASSERT_EQ(ladder.size(), 4u);
    const Setting& placed = ladder[2].setting;
    // sample_fs 9 over whole steps: 9/7 = 1.286 fs is the grid's step at or below √2 = 1.414.
    EXPECT_NEAR(placed.x, 9.0 / 7.0, 1e-12);
    EXPECT_TRUE(placed.interpolated);
    EXPECT_EQ(placed.ladder, "smd-verlet");
    EXPECT_EQ(ladder[2].target, 0); // its replicas are asked for by raiseTargets
    ASSERT_EQ(t.notes.size(), 1u);
    EXPECT_NE(t.notes[0].find("placed by the bias law"), std::string::npos);
    std::vector<Rung> again = asGiven; // once per ladder: offered again, it is left as it is
    EXPECT_FALSE(interpolate(t, again));
    EXPECT_EQ(again.size(), 3u);
}

} // namespace test_tradeoff_search
