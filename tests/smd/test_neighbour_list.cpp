// Verlet-list forces against the O(N²) minimum-image reference on random configurations, before
// and after the bodies drift by up to skin/2 (no rebuild), through the cell-list path (box of
// five or more cells of half the reach per edge) and the all-pairs path (fewer).
#include "smd/neighbour_list.hpp"
#include "smd/pair_forces.hpp"
#include "systems.hpp"
#include <algorithm>
#include <gtest/gtest.h>
#include <numeric>
#include <random>
#include <set>

namespace test_neighbour_list {

using namespace terrace;
using namespace terrace::smd;

namespace {

// Pair sums over ~1e4 terms of forces up to ~1e2 kJ/mol/Å in a different order: round-off.
constexpr double sumOrderTolerance = 1e-9;
// Bodies placed far up the wall carry forces and torques up to ~1e5 (kJ/mol/Å, kJ/mol), whose
// round-off in another pair order scales with them: measured up to 1.9e-13 of the body's own in
// GCC's build and 2.7e-13 in clang's (where an absolute 1e-9 alone failed at 4e-9).
constexpr double relativeSumOrderTolerance = 1e-12;
// The virial in another summation order: a few ulp of its size per pair summed.
constexpr double virialUlpsPerPair = 1e-14;

/// Rods scattered by random displacements of up to `jitter` Å about a lattice, random axes.
System<LinearRotor, smd::fixtures::RodModel> scatteredRods(int perEdge, double density,
                                                           double jitter, std::uint64_t seed) {
    auto sys = fixtures::rods(perEdge, density, 1.4, seed);
    std::mt19937_64 rng(seed + 17);
    std::uniform_real_distribution<double> u(-jitter, jitter);
    // Some bodies several boxes away (unwrapped), as after long diffusion.
    for (auto& b : sys.bodies)
        b.r += Vec3(u(rng), u(rng), u(rng)) +
               sys.box.length * Vec3(int(rng() % 5) - 2, 0, int(rng() % 3) - 1);
    return sys;
}

template <class Sys> Forces listForces(const Sys& sys, const NeighbourList& list) {
    std::vector<Vec3> x, axis; // per list slot
    for (std::size_t a = 0; a < sys.bodies.size(); ++a) {
        const auto& b = sys.bodies[list.order[a]];
        x.push_back(b.r - list.offset[a]);
        axis.push_back(b.s);
    }
    Forces f;
    f.reset(x.size());
    accumulateListedPairs(f, sys.potential, list, x, axis);
    return f;
}

template <class Sys> void expectSameForces(const Sys& sys, const NeighbourList& list) {
    const Forces fast = listForces(sys, list);
    const Forces slow = allPairsForces(sys);
    ASSERT_GT(slow.evaluations, 0);
    EXPECT_EQ(fast.evaluations, slow.evaluations);
    EXPECT_NEAR(fast.potential, slow.potential, sumOrderTolerance);
    // The virial sums r·F, up to ~1e5 kJ/mol here (some scattered pairs sit far up the wall).
    EXPECT_NEAR(fast.virial, slow.virial,
                virialUlpsPerPair * std::abs(slow.virial) * slow.evaluations);
    for (std::size_t a = 0; a < slow.force.size(); ++a) {
        const int i = list.order[a];
        EXPECT_LT((fast.force[a] - slow.force[i]).norm(),
                  sumOrderTolerance + relativeSumOrderTolerance * slow.force[i].norm())
            << "body " << i;
        EXPECT_LT((fast.torque[a] - slow.torque[i]).norm(),
                  sumOrderTolerance + relativeSumOrderTolerance * slow.torque[i].norm())
            << "body " << i;
    }
}

void checkAgainstAllPairs(int perEdge, double density, std::uint64_t seed) {
    auto sys = scatteredRods(perEdge, density, 0.8, seed);
    const double sigma = sys.potential.bare.sigma;
    NeighbourList list;
    list.skin = 0.3 * sigma;
    list.reach = sys.potential.range() + list.skin;
    std::vector<Vec3> r;
    for (const auto& b : sys.bodies)
        r.push_back(b.r);
    build(list, sys.box, r);
    expectSameForces(sys, list);

    // Drift every body by just under skin/2: the list must still hold every pair within r_u.
    std::mt19937_64 rng(seed + 1);
    for (std::size_t i = 0; i < r.size(); ++i) {
        sys.bodies[i].r += 0.4999 * list.skin * fixtures::randomUnit(rng);
        r[i] = sys.bodies[i].r;
    }
    EXPECT_FALSE(needsRebuild(list, r));
    expectSameForces(sys, list);

    r[0] = list.builtAt[0] + 0.5001 * list.skin * Vec3::UnitX();
    EXPECT_TRUE(needsRebuild(list, r));
}

} // namespace

TEST(NeighbourList, CellListForcesEqualAllPairs) {
    // 8³ bodies at ρ* = 0.5: L ≈ 10.1σ, six cells of 1.65σ per edge (the fewest allowed + 1).
    for (std::uint64_t seed : {1u, 2u, 3u})
        checkAgainstAllPairs(8, 0.5, seed);
}

TEST(NeighbourList, ManyCellsForcesEqualAllPairs) {
    checkAgainstAllPairs(10, 0.3, 4); // L ≈ 15σ: nine cells per edge
}

TEST(NeighbourList, FiveCellsPerEdgeForcesEqualAllPairs) {
    checkAgainstAllPairs(7, 0.5, 7); // L ≈ 8.8σ: five cells, the stencil spans the whole box
}

TEST(NeighbourList, SparseBoxWiderCellsForcesEqualAllPairs) {
    // L ≈ 21.7σ would hold 13 cells of half the reach; capped at ten per edge (~2 per body).
    checkAgainstAllPairs(8, 0.05, 8);
}

TEST(NeighbourList, SmallBoxFallsBackToAllPairs) {
    checkAgainstAllPairs(6, 0.5, 5); // L ≈ 7.6σ: four cells per edge, too few
}

TEST(NeighbourList, EachPairListedOnce) {
    auto sys = scatteredRods(8, 0.5, 0.5, 6);
    NeighbourList list;
    list.skin = 1.0;
    list.reach = 10.0;
    std::vector<Vec3> r;
    for (const auto& b : sys.bodies)
        r.push_back(b.r);
    build(list, sys.box, r);
    std::set<std::pair<int, int>> seen;
    std::size_t expected = 0;
    for (std::size_t i = 0; i < r.size(); ++i) {
        for (std::size_t j = i + 1; j < r.size(); ++j)
            if (sys.box.minimumImage(r[i] - r[j]).norm() < list.reach) ++expected;
        for (std::size_t k = list.start[i]; k < list.start[i + 1]; ++k) {
            const std::size_t b = list.entry[k] >> NeighbourList::imageBits;
            const int bi = list.order[i], bj = list.order[b];
            const auto key = std::make_pair(std::min(bi, bj), std::max(bi, bj));
            EXPECT_TRUE(seen.insert(key).second) << bi << "-" << bj << " listed twice";
            const Vec3 rij = r[bi] - list.offset[i] - (r[bj] - list.offset[b]) +
                             list.imageShift[list.entry[k] & NeighbourList::imageMask];
            EXPECT_NEAR(rij.norm(), sys.box.minimumImage(r[bi] - r[bj]).norm(), sumOrderTolerance);
        }
    }
    EXPECT_EQ(seen.size(), expected);
}

TEST(NeighbourList, Avx2BuildListsTheScalarBuildsEntries) {
    if (!avx2Available())
        GTEST_SKIP() << "no AVX2 loops: the processor lacks AVX2 or the build left them out";
    // Cell counts from five per edge up, cells of one to a dozen bodies, unwrapped positions.
    for (auto [perEdge, density] : {std::pair{7, 0.5}, {8, 0.5}, {10, 0.3}, {12, 0.9}}) {
        auto sys = scatteredRods(perEdge, density, 0.8, 30 + perEdge);
        std::vector<Vec3> r;
        for (const auto& b : sys.bodies)
            r.push_back(b.r);
        NeighbourList scalar, avx2;
        scalar.skin = avx2.skin = 0.3 * sys.potential.bare.sigma;
        scalar.reach = avx2.reach = sys.potential.range() + scalar.skin;
        for (int rebuild = 0; rebuild < 2; ++rebuild) { // the second reuses the entry buffer
            build(scalar, sys.box, r, false);
            build(avx2, sys.box, r, true);
            ASSERT_GT(scalar.pairCount(), 0u);
            EXPECT_EQ(avx2.order, scalar.order);
            EXPECT_EQ(avx2.start, scalar.start);
            EXPECT_EQ(avx2.entry, scalar.entry);
            for (auto& x : r)
                x += Vec3(0.7, -0.3, 0.2); // a new arrangement for the second build
        }
    }
}

// The order in which bodies take their slots (build's `visit`): the same bodies in another order,
// visited in the first order, give the same slots, entries and offsets, through the cell path
// (six and nine cells per edge) and the all-pairs path.
TEST(NeighbourList, VisitingOrderFixesTheSlots) {
    for (auto [perEdge, density] : {std::pair{8, 0.5}, {10, 0.3}, {6, 0.5}}) {
        auto sys = scatteredRods(perEdge, density, 0.8, 40 + perEdge);
        const std::size_t n = sys.bodies.size();
        std::vector<Vec3> r, shuffled(n);
        for (const auto& b : sys.bodies)
            r.push_back(b.r);
        std::vector<int> at(n); // body i of r sits at at[i] in shuffled
        std::iota(at.begin(), at.end(), 0);
        std::shuffle(at.begin(), at.end(), std::mt19937_64(perEdge));
        for (std::size_t i = 0; i < n; ++i)
            shuffled[at[i]] = r[i];
        NeighbourList given, visited;
        given.skin = visited.skin = 0.3 * sys.potential.bare.sigma;
        given.reach = visited.reach = sys.potential.range() + given.skin;
        build(given, sys.box, r);
        build(visited, sys.box, shuffled, avx2Available(), at);
        ASSERT_GT(given.pairCount(), 0u);
        for (std::size_t a = 0; a < n; ++a)
            ASSERT_EQ(visited.order[a], at[given.order[a]]) << "slot " << a;
        EXPECT_EQ(visited.start, given.start);
        EXPECT_EQ(visited.entry, given.entry);
        EXPECT_EQ(visited.offset, given.offset);
    }
}

} // namespace test_neighbour_list
