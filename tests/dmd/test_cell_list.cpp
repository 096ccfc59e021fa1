// Cell list: neighbour sets cover every pair within the cell edge, crossings move bodies.
#include "dmd/cell_list.hpp"
#include <algorithm>
#include <gtest/gtest.h>
#include <random>
#include <set>

namespace test_cell_list {

using namespace terrace;
using namespace terrace::dmd;

TEST(CellList, NeighboursIncludeEveryPairWithinTheEdge) {
    const double L = 20.0, rm = 4.5;
    const int n = 200;
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(-3 * L, 3 * L); // unwrapped positions
    std::vector<Vec3> r(n);
    for (auto& x : r)
        x = Vec3(u(rng), u(rng), u(rng));
    CellList cells(L, rm, n);
    EXPECT_EQ(cells.cellsPerSide(), 4);
    for (int i = 0; i < n; ++i)
        cells.insert(i, r[i]);
    for (int i = 0; i < n; ++i) {
        std::set<int> listed;
        cells.forEachNeighbour(i, [&](int j) { listed.insert(j); });
        for (int j = 0; j < n; ++j) {
            Vec3 d = r[i] - r[j];
            for (int a = 0; a < 3; ++a)
                d[a] -= L * std::nearbyint(d[a] / L);
            if (j != i && d.norm() < rm) {
                EXPECT_TRUE(listed.count(j)) << i << " " << j;
            }
        }
    }
}

// The pruned scan skips only cells beyond the reach: every body within it is still visited, in
// the order of the full scan, for boxes of 3 (where a neighbouring cell is also two cells away
// the other way round) to 5 cells a side, with bodies anywhere, on cell faces and at reach exactly.
TEST(CellList, PrunedScanVisitsEveryBodyWithinReachInOrder) {
    std::mt19937_64 rng(11);
    for (const int side : {3, 4, 5}) {
        const double reach = 4.5, L = side * reach * 1.1;
        const int n = 300;
        std::uniform_real_distribution<double> u(-2 * L, 2 * L);
        CellList cells(L, reach, n);
        ASSERT_EQ(cells.cellsPerSide(), side);
        std::vector<Vec3> r(n);
        for (int i = 0; i < n; ++i) {
            r[i] = Vec3(u(rng), u(rng), u(rng));
            if (i % 10 == 0)
                r[i].x() = std::floor(r[i].x() / cells.edge()) * cells.edge(); // on a face
            cells.insert(i, r[i]);
        }
        // A body at exactly the reach from body 1 along z.
        r[2] = r[1] + Vec3(0.0, 0.0, reach);
        CellList moved(L, reach, n);
        for (int i = 0; i < n; ++i)
            moved.insert(i, r[i]);
        long skipped = 0;
        for (int i = 0; i < n; ++i) {
            std::vector<int> all, pruned;
            moved.forEachNeighbour(i, [&](int j) { all.push_back(j); });
            moved.forEachNeighbourWithin(i, &r[i], reach, [&](int j) { pruned.push_back(j); });
            std::vector<int> near;
            for (const int j : all) {
                Vec3 d = r[i] - r[j];
                for (int a = 0; a < 3; ++a)
                    d[a] -= L * std::nearbyint(d[a] / L);
                if (d.norm() <= reach) near.push_back(j);
            }
            std::vector<int> prunedNear;
            for (const int j : pruned)
                if (std::find(near.begin(), near.end(), j) != near.end()) prunedNear.push_back(j);
            EXPECT_EQ(prunedNear, near) << "side " << side << " body " << i;
            skipped += static_cast<long>(all.size() - pruned.size());
        }
        EXPECT_GT(skipped, 0) << side; // it does prune
    }
}

TEST(CellList, CrossingTimesMoveTheBodyOneCellAtATime) {
    CellList cells(30.0, 9.0, 1); // 3 cells of 10 Å
    Vec3 r(5.0, 5.0, 5.0);
    const Vec3 v(2.0, -0.5, 0.0);
    cells.insert(0, r);
    int axis = -1, dir = 0;
    double t = cells.crossingTime(0, r, v, axis, dir);
    EXPECT_DOUBLE_EQ(t, 2.5);
    EXPECT_EQ(axis, 0);
    EXPECT_EQ(dir, 1);
    r += v * t;
    cells.cross(0, axis, dir);
    t = cells.crossingTime(0, r, v, axis, dir); // next: x face at 20 (5 later), y face at 0 (7.5)
    EXPECT_DOUBLE_EQ(t, 5.0);
    EXPECT_EQ(axis, 0);
}

TEST(CellList, SmallBoxesUseOneCell) {
    CellList cells(10.0, 4.0, 3); // 2 cells per side would repeat neighbours
    EXPECT_TRUE(cells.single());
    for (int i = 0; i < 3; ++i)
        cells.insert(i, Vec3(i, i, i));
    int count = 0;
    cells.forEachNeighbour(0, [&](int) { ++count; });
    EXPECT_EQ(count, 2);
    int axis, dir;
    EXPECT_TRUE(std::isinf(cells.crossingTime(0, Vec3(1, 1, 1), Vec3(1, 0, 0), axis, dir)));
}

} // namespace test_cell_list
