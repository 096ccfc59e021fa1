// The Lennard-Jones sphere pair loops, the four-lane AVX2 one and the portable scalar one, each
// called explicitly, against the O(N²) minimum-image reference allPairsForces: forces, energy,
// virial and the count of pairs within r_u, for an LJ liquid whose list holds pairs inside r_l,
// in the switch shell and beyond r_u, and for boxes of few bodies (list tails of one to three
// partners, bodies with none). The AVX2 tests are skipped only where those loops cannot run (a
// processor without AVX2, or a build with -DTERRACE_NO_AVX2).
#include "smd/lj_pairs_avx2.hpp"
#include "smd/neighbour_list.hpp"
#include "smd/pair_forces.hpp"
#include "systems.hpp"
#include <gtest/gtest.h>

namespace test_lj_pairs_avx2 {

using namespace terrace;
using namespace terrace::smd;

namespace {

// Pair sums over ~1e4 terms of forces up to ~1e3 kJ/mol/Å in another order: round-off.
constexpr double sumOrderTolerance = 1e-9;
// The virial in another summation order: a few ulp of its size per pair summed.
constexpr double virialUlpsPerPair = 1e-14;
// Per body, both loops add the same per-pair forces in different orders: a few ulps of the
// largest term.
constexpr double loopsAgree = 1e-10;

enum class Loop { scalar, avx2 };

struct Case {
    System<Sphere, fixtures::LJModel> sys;
    NeighbourList list;
    std::vector<Vec3> x; // per list slot
};

/// Lists c's bodies with a 0.3σ skin and fills the slot positions the loops take.
void listWithSkin(Case& c) {
    c.list.skin = 0.3;
    c.list.reach = c.sys.potential.range() + c.list.skin;
    std::vector<Vec3> r;
    for (const auto& b : c.sys.bodies)
        r.push_back(b.r);
    build(c.list, c.sys.box, r);
    for (std::size_t a = 0; a < r.size(); ++a)
        c.x.push_back(r[c.list.order[a]] - c.list.offset[a]);
}

/// LJ spheres on a lattice of perEdge³ sites at density ρ*, each displaced by up to `jitter` σ
/// and some by whole box lengths (unwrapped, as after diffusion), listed with a 0.3σ skin.
Case liquid(int perEdge, double density, double jitter, std::uint64_t seed) {
    Case c{fixtures::ljSpheres(perEdge, density, 0.9, seed), {}, {}};
    std::mt19937_64 rng(seed + 5);
    std::uniform_real_distribution<double> u(-jitter, jitter);
    for (auto& b : c.sys.bodies)
        b.r += Vec3(u(rng), u(rng), u(rng)) +
               c.sys.box.length * Vec3(int(rng() % 3) - 1, int(rng() % 5) - 2, 0);
    listWithSkin(c);
    return c;
}

Forces listForces(const Case& c, Loop loop) {
    Forces f;
    f.reset(c.x.size());
    if (loop == Loop::scalar) {
        accumulateListedPairsScalar<LJPotential>(f, c.sys.potential, c.list, c.x, c.x);
    } else {
#if TERRACE_SMD_AVX2
        const PairSums sums = accumulateLJPairsAvx2(c.sys.potential, c.list, c.x, f.force);
        f.potential = sums.potential;
        f.virial = sums.virial;
        f.evaluations = sums.evaluations;
#endif
    }
    return f;
}

/// Listed pairs by where they lie: inside r_l, in the switch shell, beyond r_u.
std::array<int, 3> listedPairsByZone(const Case& c) {
    std::array<int, 3> zones{};
    const double rl = c.sys.potential.cut.inner(), ru = c.sys.potential.range();
    for (std::size_t a = 0; a + 1 < c.list.start.size(); ++a)
        for (std::size_t k = c.list.start[a]; k < c.list.start[a + 1]; ++k) {
            const std::uint32_t e = c.list.entry[k];
            const double r = (c.x[a] - c.x[e >> NeighbourList::imageBits] +
                              c.list.imageShift[e & NeighbourList::imageMask])
                                 .norm();
            ++zones[r <= rl ? 0 : r < ru ? 1 : 2];
        }
    return zones;
}

void expectEqualsAllPairs(const Case& c, Loop loop) {
    const Forces fast = listForces(c, loop);
    const Forces slow = allPairsForces(c.sys);
    ASSERT_GT(slow.evaluations, 0);
    EXPECT_EQ(fast.evaluations, slow.evaluations);
    EXPECT_NEAR(fast.potential, slow.potential, sumOrderTolerance);
    // Σ r·F in another order, and as f r² against r·(f r): ulps of terms of up to ~1e3 kJ/mol.
    EXPECT_NEAR(fast.virial, slow.virial,
                virialUlpsPerPair * (1.0 + std::abs(slow.virial)) * slow.evaluations);
    for (std::size_t a = 0; a < slow.force.size(); ++a) {
        const int i = c.list.order[a];
        EXPECT_LT((fast.force[a] - slow.force[i]).norm(), sumOrderTolerance) << "body " << i;
    }
}

/// Both list builds: 10³ bodies at ρ* = 0.8 (L ≈ 10.8σ, six cells of half the reach per edge),
/// 8³ (L ≈ 8.6σ, five cells: the stencil spans the box) and 27 in L ≈ 7σ (all pairs).
std::vector<Case> cases() {
    std::vector<Case> all;
    all.push_back(liquid(10, 0.8, 0.1, 1));
    all.push_back(liquid(8, 0.8, 0.1, 2));
    all.push_back(liquid(3, 0.08, 0.5, 3));
    return all;
}

bool skipWithoutAvx2() {
    return !avx2Available();
}

} // namespace

TEST(LJPairLoops, LiquidListSpansAllZones) {
    const Case c = liquid(10, 0.8, 0.1, 1);
    const auto zones = listedPairsByZone(c);
    EXPECT_GT(zones[0], 1000);
    EXPECT_GT(zones[1], 1000);
    EXPECT_GT(zones[2], 100);
}

TEST(LJPairLoops, ScalarEqualsAllPairs) {
    for (const Case& c : cases())
        expectEqualsAllPairs(c, Loop::scalar);
}

TEST(LJPairLoops, Avx2EqualsAllPairs) {
    if (skipWithoutAvx2())
        GTEST_SKIP() << "no AVX2 loops: the processor lacks AVX2 or the build left them out";
    for (const Case& c : cases())
        expectEqualsAllPairs(c, Loop::avx2);
}

TEST(LJPairLoops, Avx2FewBodies) {
    if (skipWithoutAvx2())
        GTEST_SKIP() << "no AVX2 loops: the processor lacks AVX2 or the build left them out";
    // Two to eight bodies in a box of 7σ: each body's partners are fewer than four (list tails
    // only) or none; every N from 2 to 8 gives other tail lengths.
    for (int n = 2; n <= 8; ++n) {
        Case c{fixtures::ljSpheres(2, 8.0 / 343.0, 0.9, 11), {}, {}};
        c.sys.bodies.resize(n);
        std::mt19937_64 rng(100 + n);
        std::uniform_real_distribution<double> u(0.0, c.sys.box.length);
        const auto closeToEarlier = [&](int i) { // nothing far up the repulsive wall, whose
            for (int k = 0; k < i; ++k)          // round-off would swamp the comparison
                if (c.sys.box.minimumImage(c.sys.bodies[i].r - c.sys.bodies[k].r).norm() < 0.9)
                    return true;
            return false;
        };
        for (int i = 0; i < n; ++i)
            do
                c.sys.bodies[i].r = i == 1 ? c.sys.bodies[0].r + Vec3(1.1, u(rng) / 10, 0.0)
                                           : Vec3(u(rng), u(rng), u(rng)); // 0-1: inside r_l
            while (closeToEarlier(i));
        listWithSkin(c);
        SCOPED_TRACE("n = " + std::to_string(n));
        expectEqualsAllPairs(c, Loop::avx2);
        expectEqualsAllPairs(c, Loop::scalar);
    }
}

TEST(LJPairLoops, Avx2AgreesWithScalarPerBody) {
    if (skipWithoutAvx2())
        GTEST_SKIP() << "no AVX2 loops: the processor lacks AVX2 or the build left them out";
    const Case c = liquid(12, 0.8, 0.15, 4);
    const Forces a = listForces(c, Loop::avx2), s = listForces(c, Loop::scalar);
    EXPECT_EQ(a.evaluations, s.evaluations);
    EXPECT_NEAR(a.potential, s.potential, loopsAgree * std::abs(s.potential));
    EXPECT_NEAR(a.virial, s.virial, loopsAgree * std::abs(s.virial));
    for (std::size_t k = 0; k < s.force.size(); ++k)
        EXPECT_LT((a.force[k] - s.force[k]).norm(), loopsAgree * (1.0 + s.force[k].norm()));
}

TEST(LJPairLoops, DispatchTakesAvx2WhereAvailable) {
    const Case c = liquid(8, 0.8, 0.2, 5);
    Forces f;
    f.reset(c.x.size());
    accumulateListedPairs<LJPotential>(f, c.sys.potential, c.list, c.x, c.x);
    const Forces expected = listForces(c, avx2Available() ? Loop::avx2 : Loop::scalar);
    EXPECT_EQ(f.potential, expected.potential); // bit for bit: the same loop
    EXPECT_EQ(f.virial, expected.virial);
    for (std::size_t k = 0; k < f.force.size(); ++k)
        EXPECT_EQ(f.force[k], expected.force[k]);
}

} // namespace test_lj_pairs_avx2
