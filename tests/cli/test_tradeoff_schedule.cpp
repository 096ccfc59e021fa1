// Which rungs `terrace tradeoff` raises (cli/tradeoff_schedule.hpp), on ladders built by hand:
// the cheaper of the engines' cheapest open rungs below their cheapest Within, every ladder's
// under --frontier, and the reference's check rung whatever it costs.
#include "cli/tradeoff_schedule.hpp"
#include <cmath>
#include <gtest/gtest.h>

namespace test_tradeoff_schedule {

using namespace terrace::cli;
using terrace::analysis::Decision;
using Raised = std::vector<std::pair<int, int>>;

constexpr int maxReplicas = 128;

ScheduleRung rung(bool dmd, double cost, Decision d, int target) {
    // An unresolved rung below the replica limit would take the next look; others no more.
    const int next = d == Decision::Unresolved && target < maxReplicas ? 2 * target : target;
    return {dmd, cost, d, target, next, false};
}

/// SMD ladders like the map's dilute rods: dt 0.64, 1, 1.5, 2.25 fs, cost falling with dt; the
/// coarsest Outside, the rest open at 8 replicas.
std::vector<ScheduleRung> smdLadder(double costScale) {
    const double cost[] = {0.113, 0.082, 0.077, 0.075};
    std::vector<ScheduleRung> l;
    for (int i = 0; i < 4; ++i)
        l.push_back(
            rung(false, costScale * cost[i], i == 3 ? Decision::Outside : Decision::Unresolved, 8));
    return l;
}

/// A DMD ladder ΔV = 0.125 … 1 kT, cost halving per rung, the two coarsest Outside.
std::vector<ScheduleRung> dmdLadder(double costScale) {
    std::vector<ScheduleRung> l;
    for (int i = 0; i < 4; ++i)
        l.push_back(rung(true, costScale * 8.0 / (1 << i),
                         i >= 2 ? Decision::Outside : Decision::Unresolved, 8));
    return l;
}

TEST(TradeoffSchedule, OnlyTheCheaperOfTheTwoEnginesPicksIsRaised) {
    // verlet, omelyan (1.4x verlet's cost), yoshida4 (1.8x), then DMD uniform and optimal (2x).
    std::vector<std::vector<ScheduleRung>> ladders{smdLadder(1.0), smdLadder(1.4), smdLadder(1.8),
                                                   dmdLadder(1.0), dmdLadder(2.0)};
    // SMD's pick, verlet's at 0.077 CPU s/ps, before DMD's, uniform's at 4.
    EXPECT_EQ(rungsToRaise(ladders, false), (Raised{{0, 2}}));
    // Once SMD has nothing open, DMD's pick.
    auto closed = ladders;
    for (int l = 0; l < 3; ++l)
        for (auto& r : closed[std::size_t(l)])
            r.decision = Decision::Outside;
    EXPECT_EQ(rungsToRaise(closed, false), (Raised{{3, 1}}));
    // The other way round where DMD is the cheaper, as in a gas.
    EXPECT_EQ(rungsToRaise({smdLadder(1.0), dmdLadder(0.001)}, false), (Raised{{1, 1}}));
    // --frontier: the open rung nearest each ladder's cheap end, every ladder.
    EXPECT_EQ(rungsToRaise(ladders, true), (Raised{{0, 2}, {1, 2}, {2, 2}, {3, 1}, {4, 1}}));
}

TEST(TradeoffSchedule, ARungDearerThanItsEnginesCheapestWithinIsNotRaised) {
    auto verlet = smdLadder(1.0), yoshida = smdLadder(1.8);
    verlet[2].decision = Decision::Outside;
    verlet[1].decision = Decision::Within; // 0.082 CPU s/ps: SMD's choice so far
    // yoshida4's open rungs cost 0.139 and more: none could be SMD's choice.
    EXPECT_EQ(rungsToRaise({verlet, yoshida}, false), Raised{});
    // A cheaper open rung in another ladder is still raised.
    yoshida[2].cost = 0.080;
    EXPECT_EQ(rungsToRaise({verlet, yoshida}, false), (Raised{{1, 2}}));
    // A cost equal to the Within one's cannot improve on it either.
    yoshida[2].cost = 0.082;
    EXPECT_EQ(rungsToRaise({verlet, yoshida}, false), Raised{});
    // Within its own ladder nothing more accurate than the Within rung is raised, even here.
    EXPECT_EQ(rungsToRaise({verlet}, true), Raised{});
}

TEST(TradeoffSchedule, ARungAtTheReplicaLimitIsPassedOverForTheNextMoreAccurate) {
    auto dmd = dmdLadder(1.0);
    dmd[1] = rung(true, 4.0, Decision::Unresolved, maxReplicas); // stuck, e.g. on g_peak
    EXPECT_EQ(rungsToRaise({dmd}, false), (Raised{{0, 0}}));
    dmd[0] = rung(true, 8.0, Decision::Unresolved, maxReplicas);
    EXPECT_EQ(rungsToRaise({dmd}, false), Raised{});
}

TEST(TradeoffSchedule, ARungNotRunYetGoesFirstAndOutsideRungsNever) {
    auto dmd = dmdLadder(1.0);
    // A rung placed by the bias law between the Outside x = 0.5 and an unresolved x = 0.25.
    dmd.insert(dmd.begin() + 2, ScheduleRung{true, NAN, Decision::Unresolved, 0, 0, false});
    EXPECT_EQ(rungsToRaise({dmd}, false), (Raised{{0, 2}}));
    for (auto& r : dmd)
        r.decision = Decision::Outside;
    EXPECT_EQ(rungsToRaise({dmd}, false), Raised{});
}

TEST(TradeoffSchedule, TheReferencesCheckRungIsRaisedWhateverItCosts) {
    auto verlet = smdLadder(1.0), yoshida = smdLadder(1.8);
    verlet[2].decision = Decision::Outside;
    verlet[1].decision = Decision::Within;
    yoshida[0].pinned = true; // twice the reference's dt, its check not yet passed
    EXPECT_EQ(rungsToRaise({verlet, yoshida}, false), (Raised{{1, 0}}));
    // Once it has as many replicas as it can get, it is left.
    yoshida[0].next = yoshida[0].target = maxReplicas;
    EXPECT_EQ(rungsToRaise({verlet, yoshida}, false), Raised{});
    // A pinned rung that is also its engine's pick is raised once.
    yoshida = smdLadder(1.8);
    yoshida[2].pinned = true;
    EXPECT_EQ(rungsToRaise({yoshida}, false), (Raised{{0, 2}}));
}

} // namespace test_tradeoff_schedule
