// Lattice starts whose neighbours sit on a level (within round-off): a user's levels at round
// radii meet a lattice of the same spacing. Every pair on a level takes the terrace it is heading
// into, so that nothing happens at t = 0, and the run goes on conserving energy. Before, U a
// round-off on the far side of the level put such pairs on the terrace they were leaving: a
// cascade of zero-time events at t = 0 bound whole rows of the lattice, and a row closed round
// the periodic box is rigid when all its pairs are bound at their largest separation, so its
// reflections went on at one instant forever.
#include "core/lj_potential.hpp"
#include "core/sphere.hpp"
#include "dmd/testing.hpp"
#include "test_systems.hpp"
#include <cmath>
#include <gtest/gtest.h>
#include <vector>

namespace test_lattice_on_levels {

using terrace::dmd::testing::Probe;

using namespace terrace;
using namespace terrace::dmdtest;

namespace {

using LJEngine = dmd::SceneEngine<Sphere, LJPotential>;

// Each collision conserves energy to a few ulps; 10^5 events random-walk to well below this.
constexpr double energyTolerance = 1e-12;

/// The scene of the report (LJ spheres, σ 5 Å, its levels U at 1.25, 1.45, 1.75, 2.30 σ and
/// their mirror images), N bodies on the lattice at ρ* 0.5: spacing 1.25 σ for 500 and 512.
Scene ljOnLevels(int n, std::uint64_t seed) {
    Scene s;
    s.seed = seed;
    s.body.kind = "sphere";
    s.body.mass = 4.0;
    s.potential.kind = "lj";
    s.potential.epsilon = 1.0;
    s.potential.sigma = 5.0;
    s.state.n = n;
    s.state.density = 0.5;
    s.state.temperature = 1.5;
    s.dmd["levels"] = {-0.773698093056,     -0.384073183559108, -0.134413246758263,
                       -0.0268379482306181, 0.0268379482306181, 1.96097465688762,
                       6.63611895325291,    17.5152640663382,   42.9488718509674,
                       103.802544402859};
    return s;
}

/// Every pair of the start within `within` of `level` (kJ/mol) is on the terrace it heads into
/// (below the level when U falls, above it otherwise); returns how many such pairs there are.
template <BodyKind K, PairPotential P>
int checkPairsOnTheLevel(const dmd::SceneEngine<K, P>& e, const System<K, P>& sys, double level,
                         double within) {
    int count = 0;
    const dmd::TerraceLevels& levels = Probe::levels(e);
    for (int i = 0; i < sys.size(); ++i)
        for (int j = i + 1; j < sys.size(); ++j) {
            const auto &bi = sys.bodies[i], &bj = sys.bodies[j];
            const Vec3 rij = sys.box.minimumImage(bi.r - bj.r);
            const PairForce f = sys.potential.evaluate(rij, K::axis(bi), K::axis(bj));
            if (!(std::abs(f.U - level) <= within)) continue;
            ++count;
            const double rate = dUdt(f, bi.v - bj.v, K::angularVelocity(bi, sys.body),
                                     K::angularVelocity(bj, sys.body));
            const int expected = levels.terraceOf(level, rate);
            EXPECT_EQ(Probe::terrace(e, i, j), expected)
                << "bodies " << i << ", " << j << ": U − level " << f.U - level << ", dU/dt "
                << rate;
        }
    return count;
}

template <class E> void runConserving(E& e, double fs) {
    const double e0 = e.kineticEnergy() + e.potentialEnergy();
    e.advanceTo(units::fromFs(fs));
    EXPECT_EQ(e.time(), units::fromFs(fs));
    EXPECT_NEAR(e.kineticEnergy() + e.potentialEnergy(), e0, energyTolerance * std::abs(e0));
}

} // namespace

// The scene as reported: seeds 1, 5 and 7 stopped at t = 0 (10^6 events without time
// advancing), with every queue and either invalidation.
TEST(LatticeOnLevels, ReportedSceneRunsInEverySeed) {
    for (std::uint64_t seed = 1; seed <= 7; ++seed) {
        const Scene s = ljOnLevels(500, seed);
        const auto sys = buildInitialState<Sphere, LJPotential>(s, ljPotential(s));
        LJEngine e(sys, s);
        // Neighbours 1.25 σ apart sit on the lowest level; none may have an event at t = 0.
        const double within = 1e-12;
        EXPECT_EQ(checkPairsOnTheLevel(e, sys, s.dmd["levels"][0].get<double>(), within), 1479)
            << seed;
        Probe::setStallLimit(e, 10000);
        runConserving(e, 1000.0);
        EXPECT_GT(Probe::counts(e).down, 1000u) << seed;
    }
    for (const char* queue : {"heap", "bpq"}) {
        Scene s = ljOnLevels(500, 5);
        s.dmd["queue"] = queue;
        s.dmd["invalidation"] = "eager";
        LJEngine e(buildInitialState<Sphere, LJPotential>(s, ljPotential(s)), s);
        Probe::setStallLimit(e, 10000);
        runConserving(e, 300.0);
    }
}

// A full lattice of 512 spheres spaced at each attractive level's radius in turn (1.25, 1.45,
// 1.75 and 2.30 σ; at 2.30 σ the neighbours also sit on r_m), the level set to U of a neighbour
// pair as the engine evaluates it, so that the others land a round-off on either side of it.
TEST(LatticeOnLevels, LennardJonesLatticeAtEachLevelsRadius) {
    for (const double spacing : {1.25, 1.45, 1.75, 2.30})
        for (std::uint64_t seed : {1, 2}) {
            const int level = spacing == 1.25 ? 0 : spacing == 1.45 ? 1 : spacing == 1.75 ? 2 : 3;
            Scene s = ljOnLevels(512, seed);
            s.state.density = 1.0 / (spacing * spacing * spacing);
            const auto sys = buildInitialState<Sphere, LJPotential>(s, ljPotential(s));
            const Vec3 r01 = sys.box.minimumImage(sys.bodies[0].r - sys.bodies[1].r);
            s.dmd["levels"][level] = sys.potential.evaluate(r01, Vec3::UnitZ(), Vec3::UnitZ()).U;
            LJEngine e(sys, s);
            EXPECT_EQ(checkPairsOnTheLevel(e, sys, s.dmd["levels"][level].get<double>(), 1e-12),
                      3 * 512)
                << spacing;
            Probe::setStallLimit(e, 10000);
            runConserving(e, 200.0);
        }
}

// The paper's rods, aligned along z on a lattice at ρ* 0.5 (spacing 3.82 Å): every neighbour pair
// has c = 1 and the same r_e, hence the same U, which is made a level, with the paper's step
// ΔV = kT/2 above it. Parallel, the rods turn off the level at once, most by their rotation.
TEST(LatticeOnLevels, AlignedRodLatticeOnALevel) {
    const double spacing = 3.035 / std::cbrt(0.5);
    for (std::uint64_t seed : {1, 2, 3}) {
        const RodSystem sys = alignedLattice(8, spacing, 4.2, seed);
        const Vec3 r01 = sys.box.minimumImage(sys.bodies[0].r - sys.bodies[1].r);
        const double level =
            sys.potential.evaluate(r01, sys.bodies[0].s, sys.bodies[1].s).U; // −2.92 kJ/mol
        Scene s = rodScene(512, 0.5, 1.4, 0.5);
        s.seed = seed;
        s.dmd["levels"].clear();
        for (int k = 0; k < 8; ++k)
            s.dmd["levels"].push_back(level + 2.1 * k);
        RodEngine e(sys, s);
        EXPECT_EQ(checkPairsOnTheLevel(e, sys, level, 1e-12), 3 * 512);
        Probe::setStallLimit(e, 10000);
        runConserving(e, 200.0);
    }
}

} // namespace test_lattice_on_levels
