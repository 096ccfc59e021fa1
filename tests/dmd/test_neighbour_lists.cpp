// The engine's per-body candidate lists (dmd/neighbour_lists.hpp) against the O(N²) truth: at
// every check, each pair closer than r_m is listed, on both sides, however the bodies have moved
// since their lists were built. A pair missing there would have its events silently skipped.
// And their storage against a plain model: lists in records and spills, and the terraces beside
// the partners, kept through rebuilds.
#include "dmd/testing.hpp"
#include "test_systems.hpp"
#include <algorithm>
#include <gtest/gtest.h>
#include <map>
#include <random>
#include <utility>
#include <vector>

namespace test_neighbour_lists {

using terrace::dmd::testing::Probe;

using namespace terrace;
using namespace terrace::dmdtest;

namespace {

bool listed(const RodEngine& e, int i, int j) {
    const auto p = Probe::listedPartners(e, i); // in the scene's numbering, as system()'s
    return std::find(p.begin(), p.end(), j) != p.end();
}

void expectEveryClosePairListed(const RodEngine& e) {
    const RodSystem s = e.system();
    const double rm = Probe::interactionRange(e);
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
    ASSERT_GE(Probe::cellsPerSide(e), 3);
    expectEveryClosePairListed(e);
    for (int k = 0; k < 20; ++k) {
        Probe::runEvents(e, 5000);
        expectEveryClosePairListed(e);
    }
    EXPECT_GT(Probe::counts(e).relist, 216u); // the lists were rebuilt along the way
}

// The rebuild distance against the worst case of lists rebuilt one body at a time, on a line:
// j has drifted almost the rebuild distance away from i when i rebuilds (the pair just beyond
// r_m + skin, so left unlisted); then, before either must rebuild again, i closes in by almost the
// rebuild distance and j, turned round by collisions, by almost twice it (from one side of its
// anchor to the other). The pair must still be no closer than r_m. The half-skin rule of lists
// rebuilt all at once fails this by half a skin.
TEST(NeighbourLists, RebuildDistanceCoversBodiesRebuiltOneAtATime) {
    const double rm = 4.98, skin = 0.75, slack = 1e-9;
    const dmd::NeighbourLists lists(2, skin, 4);
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

// Random rebuilds of random bodies' lists against a model (each body's partners in listing order,
// a map of the pairs' terraces), with records of 3 slots among 40 bodies so that lists move into
// spills and back all the time: the same partners in the same order on every check, the lists
// symmetric, the terraces of the pairs a body keeps kept, and the spills returned to the pool.
TEST(NeighbourLists, RecordsAndSpillsBehaveAsPlainListsWithTheirTerraces) {
    constexpr int n = 40;
    dmd::NeighbourLists lists(n, 1.0, 3);
    std::vector<std::vector<int>> model(n);
    std::map<std::pair<int, int>, int> terraceOf; // (i < j) → terrace, pairs off terrace 0 only
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> body(0, n - 1), terraceDraw(-6, 6);
    int spilledSeen = 0;
    for (int round = 0; round < 4000; ++round) {
        const int i = body(rng);
        // The new list: every pair i holds off terrace 0 (as the engine guarantees), and some
        // random others.
        std::vector<int> within;
        for (const auto& [pair, t] : terraceOf)
            if (pair.first == i || pair.second == i)
                within.push_back(pair.first == i ? pair.second : pair.first);
        const int extra = std::uniform_int_distribution<int>(0, 9)(rng);
        for (int k = 0; k < extra; ++k) {
            const int j = body(rng);
            if (j != i && std::find(within.begin(), within.end(), j) == within.end())
                within.push_back(j);
        }
        std::shuffle(within.begin(), within.end(), rng);
        lists.rebuild(i, within, Vec3(round, 0, 0));
        for (const int j : model[i])
            model[j].erase(std::find(model[j].begin(), model[j].end(), i));
        model[i].clear();
        for (const int j : within) {
            model[i].push_back(j);
            model[j].push_back(i);
        }
        // Some listed pairs move to another terrace (0 included).
        for (const int j : within)
            if (std::uniform_int_distribution<int>(0, 3)(rng) == 0) {
                const int t = terraceDraw(rng);
                lists.setTerrace(i, j, t);
                const auto key = std::minmax(i, j);
                if (t == 0)
                    terraceOf.erase(key);
                else
                    terraceOf[key] = t;
            }
        spilledSeen = std::max(spilledSeen, static_cast<int>(lists.spilled()));
        if (round % 97 != 0) continue;
        for (int a = 0; a < n; ++a) {
            const auto p = lists.partners(a);
            ASSERT_EQ(std::vector<int>(p.begin(), p.end()), model[a]) << "body " << a;
            for (const int b : model[a]) {
                const auto it = terraceOf.find(std::minmax(a, b));
                EXPECT_EQ(lists.terrace(a, b), it == terraceOf.end() ? 0 : it->second);
                EXPECT_EQ(lists.terrace(a, b), lists.terrace(b, a));
            }
        }
        int offZero = 0;
        lists.forEachPairOffZero([&](int a, int b, int t) {
            ASSERT_LT(a, b);
            EXPECT_EQ(terraceOf.at({a, b}), t);
            ++offZero;
        });
        EXPECT_EQ(offZero, static_cast<int>(terraceOf.size()));
    }
    EXPECT_GT(spilledSeen, 5);              // the spills were exercised
    for (const auto& [pair, t] : terraceOf) // (the lists refuse to drop a pair off terrace 0)
        lists.setTerrace(pair.first, pair.second, 0);
    for (int i = 0; i < n; ++i)
        lists.rebuild(i, {}, Vec3::Zero());
    EXPECT_EQ(lists.spilled(), 0u);
}

// A crowd of spilled lists that mostly fit their records again leaves idle spills: compacting frees
// them, and the lists and terraces still held in spills are unchanged.
TEST(NeighbourLists, CompactingFreesTheSpillsACrowdLeftIdle) {
    constexpr int n = 300;
    dmd::NeighbourLists lists(n, 1.0, 2);
    const auto ring = [&](int i, int width) {
        std::vector<int> within;
        for (int d = 1; d <= width; ++d)
            within.push_back((i + d) % n);
        return within;
    };
    for (int i = 0; i < n; i += 2) // lists of ~10 in records of 2: all spill
        lists.rebuild(i, ring(i, 5), Vec3::Zero());
    const std::size_t crowd = lists.spillsKept();
    EXPECT_GT(crowd, 200u);
    for (int i = 0; i < n; i += 2)
        lists.rebuild(i, {}, Vec3::Zero());
    for (int i = 0; i < n; i += 20) // a few spill again, some taking an idle spill back
        lists.rebuild(i, ring(i, 4), Vec3::Zero());
    lists.setTerrace(0, 3, -2);
    std::vector<std::vector<int>> before(n);
    for (int i = 0; i < n; ++i) {
        const auto p = lists.partners(i);
        before[i].assign(p.begin(), p.end());
    }
    const std::size_t held = lists.spilled();
    EXPECT_EQ(held, static_cast<std::size_t>(n / 20));
    const std::size_t bytes = lists.bytesReserved();
    lists.compactSpills();
    EXPECT_EQ(lists.spillsKept(), held);
    EXPECT_LT(lists.bytesReserved(), bytes);
    for (int i = 0; i < n; ++i) {
        const auto p = lists.partners(i);
        EXPECT_EQ(std::vector<int>(p.begin(), p.end()), before[i]) << "body " << i;
    }
    EXPECT_EQ(lists.terrace(0, 3), -2);
    EXPECT_EQ(lists.terrace(3, 0), -2);
    EXPECT_EQ(lists.terrace(0, 2), 0);
}

// A pair off terrace 0 is inside r_m, so always listed: the storage refuses to hold one that is
// not, and a rebuild that would drop one, instead of losing its energy silently.
TEST(NeighbourLists, APairOffTerraceZeroMustStayListed) {
    dmd::NeighbourLists lists(4, 1.0, 2);
    const std::vector<int> partners{1, 2};
    lists.rebuild(0, partners, Vec3::Zero());
    EXPECT_THROW(lists.setTerrace(0, 3, -2), std::logic_error);
    EXPECT_NO_THROW(lists.setTerrace(0, 3, 0)); // terrace 0 is what an unlisted pair has
    lists.setTerrace(0, 2, -2);
    EXPECT_EQ(lists.terrace(2, 0), -2);
    const std::vector<int> without2{1, 3};
    EXPECT_THROW(lists.rebuild(0, without2, Vec3::Zero()), std::logic_error);
}

} // namespace test_neighbour_lists
