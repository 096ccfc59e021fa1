// The adaptive terrace-exit search (paper sec. 3) and the r_m screening on analytic indicators.
#include "dmd/root_search.hpp"
#include "dmd/shell_screening.hpp"
#include <array>
#include <cmath>
#include <gtest/gtest.h>

namespace test_root_search {

using namespace terrace;
using namespace terrace::dmd;

namespace {

// Roots are refined until the bracket is ~1e-13 of the largest step; allow that and round-off.
constexpr double rootTolerance = 1e-12;
// A grazing event is reported within the tiny window the search probes around the extremum.
constexpr double grazeTimeTol = 1e-4;
// Which crossing is found, not how finely: far looser than rootTolerance on purpose.
constexpr double crossingTimeTol = 1e-9;
// Shell windows are roots of a quadratic with small integer coefficients: exact to round-off.
constexpr double shellRoundoff = 1e-15;

SearchSettings settings() {
    SearchSettings s;
    s.maxStep = 0.04;
    s.nudge = 0.04 / 32;
    s.grazeWindow = 0.25;
    s.levelTolerance = 1e-12;
    return s;
}

/// U(t) = A cos(ω t) + c: oscillating, with extrema at multiples of π/ω.
struct Cosine {
    double A, omega, c;
    PairSample operator()(double t) const {
        return {t, A * std::cos(omega * t) + c, -A * omega * std::sin(omega * t)};
    }
};

} // namespace

TEST(RootSearch, FindsTheFirstCrossingOfALinearRamp) {
    auto ramp = [](double t) { return PairSample{t, 0.5 - 2.0 * t, -2.0}; };
    const SearchResult r = findTerraceExit(ramp, ramp(0.0), -1.0, 1.0, 10.0, settings());
    EXPECT_EQ(r.side, ExitSide::Lower);
    EXPECT_NEAR(r.t, 0.75, rootTolerance);
    EXPECT_LE(ramp(r.t).U, -1.0); // reported on the far side of the level
}

TEST(RootSearch, StopsAtTheEndOfTheWindowWithTheEndPoint) {
    const Cosine f{0.5, 3.0, 0.0}; // stays inside (−1, 1)
    const SearchResult r = findTerraceExit(f, f(0.0), -1.0, 1.0, 0.1, settings());
    EXPECT_EQ(r.side, ExitSide::None);
    EXPECT_DOUBLE_EQ(r.end.t, 0.1);
    EXPECT_DOUBLE_EQ(r.end.U, f(0.1).U);
}

// A maximum that rises 1e-9 above the upper level between two grid points is a grazing event.
TEST(RootSearch, CatchesAGrazingMaximumJustAboveTheLevel) {
    const double omega = 2.0 * M_PI / 0.3, c = 0.3;
    for (double excess : {1e-9, -1e-9}) {
        const Cosine f{1.0 - c + excess, omega, c}; // maxima at t = 0.3 k reach 1 + excess
        const PairSample start = f(0.05);
        const SearchResult r = findTerraceExit(f, start, -5.0, 1.0, 0.5, settings());
        if (excess > 0) {
            EXPECT_EQ(r.side, ExitSide::Upper);
            EXPECT_NEAR(r.t, 0.3, grazeTimeTol);
            EXPECT_GE(f(r.t).U, 1.0);
        } else {
            EXPECT_EQ(r.side, ExitSide::None);
        }
    }
}

// Right after an event the pair sits on the level, moving inwards: the start is not an event,
// but the next crossing of the same level is found.
TEST(RootSearch, NeverReturnsTheStartOfAPairOnItsLevelMovingInwards) {
    const Cosine f{1.0, 10.0, 0.0}; // U = cos 10t: U = 1 at t = 0, back at 2π/10 ≈ 0.628
    PairSample start = f(0.0);
    start.dUdt = -1e-3; // moving inwards, as the collision rule leaves it
    const SearchResult r = findTerraceExit(f, start, -2.0, 1.0, 1.0, settings());
    EXPECT_EQ(r.side, ExitSide::None);     // the maximum at 0.628 only touches 1: not above it
    const Cosine g{1.0 + 1e-6, 10.0, 0.0}; // resolved just past U = 1, above it again near 0.628
    PairSample s2 = g(0.0);
    s2.dUdt = -1e-3;
    const SearchResult r2 = findTerraceExit(g, s2, -2.0, 1.0, 1.0, settings(), true);
    EXPECT_EQ(r2.side, ExitSide::Upper);
    EXPECT_GT(r2.t, 0.5);
}

// Bannerman's rule: on or past a level and moving outwards, the event is now (zero delay).
TEST(RootSearch, PastALevelMovingOutwardsIsAnEventNow) {
    auto ramp = [](double t) { return PairSample{t, -1.0 - 1e-14 - t, -1.0}; };
    const SearchResult r = findTerraceExit(ramp, ramp(0.0), -1.0, 1.0, 1.0, settings());
    EXPECT_EQ(r.side, ExitSide::Lower);
    EXPECT_EQ(r.t, 0.0);
    // The same position just resolved (afterEvent) is not taken again.
    auto back = [](double t) { return PairSample{t, -1.0 - 1e-14 + t, 1.0}; };
    const SearchResult r2 = findTerraceExit(back, back(0.0), -1.0, 1.0, 3.0, settings(), true);
    EXPECT_EQ(r2.side, ExitSide::Upper);
    EXPECT_NEAR(r2.t, 2.0, crossingTimeTol);
}

// A pair just moved down through a level sits a round-off beyond it (U = level + 2.8e-13) and moves
// inwards, while the window ends a few 1e-15 later (it leaves r_m, which lies on that level when
// the lowest terrace holds the whole tail: LJ spheres at ΔV > ε). Samples that close still read
// U beyond the level; they must count as on it, or the pair is sent back across at once, again
// and again (a stall found in hot LJ gases). A real return across the level is still found.
TEST(RootSearch, SamplesWithinRoundOffOfTheStartLevelAreOnIt) {
    auto leaving = [](double t) { return PairSample{t, 7.5 + 2.8e-13 - 100.0 * t, -100.0}; };
    SearchSettings s = settings();
    s.levelTolerance = 1.5e-9;
    for (double tEnd : {2.7e-15, 1e-14, 1e-13}) {
        const SearchResult r = findTerraceExit(leaving, leaving(0.0), -7.5, 7.5, tEnd, s, true);
        EXPECT_EQ(r.side, ExitSide::None) << tEnd;
    }
    // Over a longer window the pair leaves the level and, turned round, crosses it again.
    auto turning = [](double t) {
        return PairSample{t, 7.5 + 2.8e-13 - 100.0 * t + 5000.0 * t * t, -100.0 + 10000.0 * t};
    };
    const SearchResult back = findTerraceExit(turning, turning(0.0), -7.5, 7.5, 0.04, s, true);
    EXPECT_EQ(back.side, ExitSide::Upper);
    EXPECT_NEAR(back.t, 0.02, crossingTimeTol);
}

// U of a rod pair at ρ* 0.7, T* 10 (terrace −1 of the optimal ΔV = kT/8 ladder), sampled from
// a missed event of the engine and fitted by a sextic (residual below 1.3e-8 kJ/mol; τ in time
// units, U − U(0) in kJ/mol): rising at 0.026 kJ/mol per time unit from 6.5e-5 above the lower
// level, it turns, dips 4.0e-5 below the level between τ ≈ 0.006 and 0.013, and rises steeply.
// The Hermite cubic through the ends of the full 0.0318 step is monotone, 6.5e-5 above the level
// at its lowest, so the dip is seen only by a shorter step. The first crossing is the event.
TEST(RootSearch, FindsADipThroughTheLevelThatTheStepsCubicDoesNotShow) {
    constexpr std::array<double, 7> c{4.39846809e-05, 2.56789834e+02,  -9.21488177e+04,
                                      6.06880066e+06, -4.28216917e+07, -3.92455106e+08,
                                      3.05795990e+09}; // ×1e-4 kJ/mol, ascending powers of τ
    auto rod = [&](double t) {
        double u = 0.0, du = 0.0;
        for (int k = 6; k >= 0; --k) {
            du = du * t + u;
            u = u * t + c[k];
        }
        return PairSample{t, 1e-4 * u, 1e-4 * du};
    };
    const double lower = -6.5e-5, upper = 1.2, height = upper - lower;
    SearchSettings s;
    s.maxStep = 0.0318;
    s.nudge = s.maxStep / 32;
    s.grazeWindow = 0.25 * height;
    s.levelTolerance = 1e-10 * height;
    // The dip: first below the level near τ = 0.006, back above it near 0.013.
    double first = 0.0;
    for (double t = 0.0; t < 0.02 && first == 0.0; t += 1e-6)
        if (rod(t).U < lower) first = t;
    ASSERT_GT(first, 0.004);
    ASSERT_LT(first, 0.008);
    const SearchResult r = findTerraceExit(rod, rod(0.0), lower, upper, 0.039, s);
    EXPECT_EQ(r.side, ExitSide::Lower);
    EXPECT_NEAR(r.t, first, 2e-6);
    EXPECT_LE(rod(r.t).U, lower);
}

TEST(ShellScreening, WindowsOfTheInteractionShell) {
    // Inside, moving out along x from r = 1 at speed 2: leaves r_m = 3 at τ = 1.
    ShellWindow w = shellWindow(Vec3(1, 0, 0), Vec3(2, 0, 0), 3.0);
    EXPECT_EQ(w.enter, 0.0);
    EXPECT_NEAR(w.exit, 1.0, shellRoundoff);
    // Outside, approaching head-on from 5: enters at τ = 1, leaves at τ = 4.
    w = shellWindow(Vec3(5, 0, 0), Vec3(-2, 0, 0), 3.0);
    EXPECT_NEAR(w.enter, 1.0, shellRoundoff);
    EXPECT_NEAR(w.exit, 4.0, shellRoundoff);
    // Passing by at impact parameter 4 > r_m: never inside.
    EXPECT_TRUE(shellWindow(Vec3(5, 4, 0), Vec3(-1, 0, 0), 3.0).empty());
    // Receding: never inside.
    EXPECT_TRUE(shellWindow(Vec3(5, 0, 0), Vec3(1, 0, 0), 3.0).empty());
    // At rest inside: inside forever.
    w = shellWindow(Vec3(1, 1, 0), Vec3::Zero(), 3.0);
    EXPECT_EQ(w.enter, 0.0);
    EXPECT_TRUE(std::isinf(w.exit));
}

// Cost, not only correctness: a bracketed root of a smooth indicator is pinned down to the time
// tolerance in at most three samples (each a pair evaluation), on the outside of the level.
TEST(RootSearch, RefinesABracketedRootInAFewSamples) {
    constexpr double tolerance = 4e-15;
    for (double omega : {3.0, 10.0, 30.0, 60.0}) {
        const Cosine f{1.0, omega, 0.0};
        const double root = M_PI / 2.0 / omega; // cos crosses 0 downwards
        int evaluations = 0;
        const double t = dmd::detail::refineRoot(f, f(root - 0.013), f(root + 0.027),
                                                 ExitSide::Lower, 0.0, tolerance, evaluations);
        EXPECT_LE(evaluations, 3) << "omega " << omega;
        EXPECT_GE(t, root) << "omega " << omega;                   // reported past the level...
        EXPECT_LE(t - root, 3.0 * tolerance) << "omega " << omega; // ...by the tolerance only
        EXPECT_LT(f(t).U, 0.0);
    }
}

// The grazing check costs a sample or three when the extremum clears the level, and it still
// finds a dip of 1e-9 through it.
TEST(RootSearch, RulesOutAClearExtremumInAFewSamples) {
    for (double omega : {3.0, 10.0, 30.0, 60.0}) {
        const double tm = M_PI / omega; // the minimum of cos
        for (double clearance : {0.2, 1e-2, 1e-4, -1e-9}) {
            const Cosine f{1.0, omega, 1.0 + clearance}; // minimum clearance at tm
            int evaluations = 0;
            const PairSample m = dmd::detail::probeExtremum(f, f(tm - 0.017), f(tm + 0.023),
                                                            dmd::detail::Signed{1.0, 0.0}, 1e-12,
                                                            4e-15, evaluations);
            if (clearance > 0.0) {
                EXPECT_LE(evaluations, 3) << omega << " " << clearance;
                EXPECT_GT(m.U, 0.0);
            } else {
                EXPECT_LT(m.U, 0.0) << omega; // the dip is caught
                EXPECT_LE(evaluations, 12) << omega;
            }
        }
    }
}

} // namespace test_root_search
