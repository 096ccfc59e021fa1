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
    const auto p = e.listedPartners(i); // in the scene's numbering, as synchronisedCopy's
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

// The rebuild distance against the worst case of lists rebuilt one body at a time, on a line:
// j has drifted almost the rebuild distance away from i when i rebuilds (the pair just beyond
// r_m + skin, so left unlisted); then, before either must rebuild again, i closes in by almost the
// rebuild distance and j, turned round by collisions, by almost twice it (from one side of its
// anchor to the other). The pair must still be no closer than r_m. The half-skin rule of lists
// rebuilt all at once fails this by half a skin.
TEST(NeighbourLists, RebuildDistanceCoversBodiesRebuiltOneAtATime) {
    const double rm = 4.98, skin = 0.75, slack = 1e-9;
    const dmd::NeighbourLists lists(2, skin);
    const double d = lists.relistDistance();
    double xi = 0.0;                     // i's anchor
    double xj = rm + skin + 2.0 * slack; // j's anchor
    xj += d - slack;                     // j drifts away, short of rebuilding
    xi += d;                             // i rebuilds here...
    ASSERT_GT(xj - xi, rm + skin);       // ...and leaves j (just) unlisted
    xi += d - slack;                     // i closes in, short of rebuilding again
    xj -= 2.0 * (d - slack);             // j sweeps back through its anchor
    EXPECT_GE(xj - xi, rm) << "an unlisted pair inside r_m with no rebuild due";
}
