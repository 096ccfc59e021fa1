// The engine's per-body candidate lists (dmd/neighbour_lists.hpp) against the O(N²) truth: at
// every check, each pair closer than r_m is listed, on both sides, however the bodies have moved
// since their lists were built. A pair missing there would have its events silently skipped.
#include "test_systems.hpp"
#include <algorithm>
#include <gtest/gtest.h>

using namespace terrace;
using namespace terrace::dmdtest;

namespace {

bool listed(const RodEngine& e, int i, int j) {
    const auto& p = e.neighbourLists().partners(i);
    return std::find(p.begin(), p.end(), j) != p.end();
}

void expectEveryClosePairListed(const RodEngine& e) {
    const RodSystem s = e.synchronisedCopy();
    const double rm = e.interactionRange();
    int close = 0;
    for (int i = 0; i < s.size(); ++i)
        for (int j = 0; j < s.size(); ++j) {
            if (i == j) continue;
            EXPECT_EQ(listed(e, i, j), listed(e, j, i)) << i << " " << j;
            if (s.box.minimumImage(s.bodies[i].r - s.bodies[j].r).norm() > rm) continue;
            ++close;
            ASSERT_TRUE(listed(e, i, j)) << "pair " << i << ", " << j << " inside r_m, unlisted";
        }
    EXPECT_GT(close, s.size()); // a dense liquid: several neighbours per body inside r_m
}

} // namespace

TEST(NeighbourLists, EveryPairInsideRangeIsListedAsBodiesMove) {
    // 216 rods at the paper's dense state: 3 cells per side, so the lists come from the cells.
    const Scene s = rodScene(216, 0.5, 1.4, 0.5);
    RodEngine e(rodSystem(s), s);
    ASSERT_GE(e.cellsPerSide(), 3);
    expectEveryClosePairListed(e);
    for (int k = 0; k < 20; ++k) {
        e.runEvents(5000);
        expectEveryClosePairListed(e);
    }
    EXPECT_GT(e.counts().relist, 216u); // the lists were rebuilt along the way
}
