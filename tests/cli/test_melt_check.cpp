// The melt check of lattice starts (cli/melt_check.hpp): the order parameters on the lattice, on
// a melted state, and the warning's thresholds and words.
#include "cli/melt_check.hpp"
#include "core/initial_state.hpp"
#include <gtest/gtest.h>
#include <random>

namespace test_melt_check {

using namespace terrace;

namespace {

Scene latticeScene(int n, double aspect) {
    Scene s = defaultScene();
    s.state.n = n;
    s.state.lattice_aspect = aspect;
    return s;
}

/// The scene's lattice sites, every axis along z (or isotropic), and the same sites moved by
/// `jiggle` box lengths at random.
Snapshot bodies(const Scene& s, bool aligned, double jiggle, std::uint64_t seed) {
    const int n = s.state.n;
    const double L = s.boxLength();
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-0.5, 0.5);
    Snapshot snap;
    const LatticeShape shape =
        latticeShape(n, L, latticeKind(s.state.lattice), s.state.lattice_aspect);
    for (const Vec3& r : latticeSites(shape, n)) {
        snap.position.push_back(r + jiggle * L * Vec3(u(rng), u(rng), u(rng)));
        snap.axis.push_back(aligned ? Vec3::UnitZ() : detail::randomUnitVector(rng));
    }
    return snap;
}

cli::LatticeOrder orderOf(const Scene& s, const Snapshot& b) {
    cli::LatticeOrderSum sum(s);
    sum.add(b, true);
    return sum.result();
}

} // namespace

TEST(MeltCheck, TheLatticeIsOrderedAndAGasIsNot) {
    for (const double aspect : {1.0, 2.0}) {
        const Scene s = latticeScene(512, aspect);
        const auto lattice = orderOf(s, bodies(s, true, 0.0, 1));
        EXPECT_NEAR(lattice.translational, 1.0, 1e-9) << aspect;
        EXPECT_NEAR(lattice.s2, 1.0, 1e-12);
        const auto gas = orderOf(s, bodies(s, false, 1.0, 2));
        EXPECT_LT(gas.translational, 20.0 / 512);
        EXPECT_LT(gas.s2, 3.0 / std::sqrt(512.0));
        EXPECT_FALSE(cli::meltWarning(s, gas, 512, true));
    }
}

TEST(MeltCheck, AnOrderedStartIsWarnedWithItsNumbersAndTheKey) {
    const Scene s = latticeScene(512, 1.0);
    const auto w = cli::meltWarning(s, orderOf(s, bodies(s, true, 0.0, 1)), 512, true);
    ASSERT_TRUE(w);
    EXPECT_NE(w->find("S(k1)/N = 1 > 0.1"), std::string::npos) << *w;
    EXPECT_NE(w->find("S2 = 1 > 0.133"), std::string::npos) << *w;
    EXPECT_NE(w->find("raise run.equilibrate_ps"), std::string::npos) << *w;
    // Spheres are judged by their positions alone; an explicit start not at all.
    const auto disordered = orderOf(s, bodies(s, false, 1.0, 3));
    EXPECT_FALSE(cli::meltWarning(s, {disordered.translational, 0.9}, 512, false));
    Scene explicitStart = s;
    explicitStart.state.particles.resize(2);
    EXPECT_FALSE(cli::meltWarning(explicitStart, {1.0, 1.0}, 2, true));
}

// fcc and bcc starts are judged at their own first reciprocal vectors ((111), (110)): 1 on the
// perfect lattice, where the simple-cubic vectors see nothing (the conventional cell's (100) is
// extinct on both), and a liquid's ~1/N once the sites are scattered.
TEST(MeltCheck, FccAndBccAreJudgedOnTheirOwnLattice) {
    for (const auto& [lattice, n] : {std::pair<const char*, int>{"fcc", 500}, {"bcc", 432}}) {
        Scene s = latticeScene(n, 1.0);
        s.state.lattice = lattice;
        const auto ordered = orderOf(s, bodies(s, true, 0.0, 1));
        EXPECT_NEAR(ordered.translational, 1.0, 1e-9) << lattice;
        const auto w = cli::meltWarning(s, ordered, n, false);
        ASSERT_TRUE(w) << lattice;
        EXPECT_NE(w->find("S(k1)/N = 1 >"), std::string::npos) << *w;
        const auto gas = orderOf(s, bodies(s, false, 1.0, 2));
        EXPECT_LT(gas.translational, 20.0 / n) << lattice;
        EXPECT_FALSE(cli::meltWarning(s, gas, n, false)) << lattice;
    }
}

// Rods among spheres: the spheres' axes never move (here all along z, as an aligned start leaves
// them), so S2 is over the rods alone: isotropic rods have melted whatever the spheres' axes, and
// aligned rods have not, judged at the rods' own number.
TEST(MeltCheck, AmongSpheresOnlyTheRodsAxesCount) {
    Scene s = latticeScene(512, 1.0);
    s.body.kind = "linear";
    s.species = {SpeciesSpec{"rod", 0.25, 1.0, 1.0, 1.0, "linear", 1.0},
                 SpeciesSpec{"solvent", 0.75, 1.0, 1.0, 1.0, "sphere", 0.0}};
    for (const bool rodsAligned : {false, true}) {
        Snapshot b = bodies(s, rodsAligned, 1.0, 4);
        for (int i = 0; i < b.size(); ++i) {
            b.species.push_back(i % 4 == 0 ? 0 : 1);
            if (i % 4 != 0) b.axis[i] = Vec3::UnitZ();
        }
        const auto order = orderOf(s, b);
        EXPECT_EQ(order.turning, 128);
        if (rodsAligned) {
            EXPECT_NEAR(order.s2, 1.0, 1e-12);
            const auto w = cli::meltWarning(s, order, 512, true);
            ASSERT_TRUE(w);
            EXPECT_NE(w->find("> 0.265"), std::string::npos) << *w; // 3/√128
        } else {
            EXPECT_LT(order.s2, 3.0 / std::sqrt(128.0));
            EXPECT_FALSE(cli::meltWarning(s, order, 512, true));
        }
    }
}

} // namespace test_melt_check
