// DMD on the smoothed model g(r)·U (core/smoothed_potential.hpp) keeps every guarantee it has on
// the bare potential. With the paper's cutoff (r_l = 2.5σ) and ΔV ≥ kT/8, r_m < r_l and the two
// models give the same events bit for bit; with a cutoff that starts inside r_m (r_l = 1.3σ,
// r_u = 1.8σ at ΔV = kT/2: r_l = 3.9 Å, bare r_m = 5.0 Å), levels are crossed in the switch, and
// there energy and momenta stay constant to round-off, no event is missed (the terraced energy
// equals the one recomputed from U at every sample), a grazing dip below a level in the switch is
// caught, and the hold screen, which must then keep r under r_l, changes no collision.
#include "core/lj_potential.hpp"
#include "core/smoothed_potential.hpp"
#include "core/sphere.hpp"
#include "dmd/testing.hpp"
#include "test_systems.hpp"
#include <gtest/gtest.h>

namespace test_smoothed_model {

using terrace::dmd::testing::Probe;

using namespace terrace;
using namespace terrace::dmdtest;

namespace {
/// Dense rods with the cutoff [r_l, r_u] (σ).
Scene switchScene(int n, double rl, double ru) {
    Scene s = rodScene(n, 0.5, 1.4, 0.5);
    s.potential.r_l = rl;
    s.potential.r_u = ru;
    return s;
}

double totalEnergy(const SmoothedRodEngine& e) {
    return e.kineticEnergy() + e.potentialEnergy();
}

} // namespace

TEST(SmoothedModel, SameEventsAsTheBarePotentialWhileTheSwitchLiesBeyondRm) {
    const Scene s = rodScene(256, 0.5, 1.4, 0.5);
    SmoothedRodEngine smoothed(buildInitialState<LinearRotor>(s, smoothedRods(s)), s);
    RodEngine bare(rodSystem(s), s);
    ASSERT_LT(Probe::interactionRange(smoothed), s.potential.r_l * s.potential.sigma);
    EXPECT_EQ(Probe::interactionRange(smoothed), Probe::interactionRange(bare));
    smoothed.advanceTo(units::fromPs(0.5));
    bare.advanceTo(units::fromPs(0.5));
    EXPECT_EQ(Probe::counts(smoothed).total(), Probe::counts(bare).total());
    EXPECT_EQ(Probe::counts(smoothed).up, Probe::counts(bare).up);
    EXPECT_EQ(smoothed.statistics()["search_evaluations"], bare.statistics()["search_evaluations"]);
    const auto a = smoothed.system();
    const auto b = bare.system();
    for (int i = 0; i < a.size(); ++i) {
        ASSERT_EQ(a.bodies[i].r, b.bodies[i].r) << i;
        ASSERT_EQ(a.bodies[i].v, b.bodies[i].v) << i;
    }
}

TEST(SmoothedModel, LevelsInTheSwitchKeepEnergyMomentaAndMissNoEvent) {
    const Scene s = switchScene(256, 1.3, 1.8);
    SmoothedRodEngine e(buildInitialState<LinearRotor>(s, smoothedRods(s)), s);
    const double rl = s.potential.r_l * s.potential.sigma;
    ASSERT_GT(Probe::interactionRange(e), rl); // levels lie in the switch
    ASSERT_LT(Probe::interactionRange(e),
              rodPotential(s).reachDistance(-0.5 * s.dmd["dV"].get<double>() * s.kT()));
    const double e0 = totalEnergy(e);
    for (int k = 1; k <= 500; ++k) { // 1 ps, some 2·10⁴ transmissions
        e.advanceTo(units::fromFs(2.0 * k));
        ASSERT_NEAR(e.potentialEnergy(), Probe::terracedEnergyFromScratch(e),
                    1e-6 * Probe::levels(e).step())
            << 2 * k << " fs";
    }
    EXPECT_GT(Probe::counts(e).up + Probe::counts(e).down, 10000u);
    EXPECT_NEAR(totalEnergy(e), e0, 1e-10 * std::abs(e0));
    EXPECT_LT(e.totalMomentum().norm(), 1e-10);
}

// As Engine.HoldScreenChangesNoCollision for the bare rods: the screen may hold a pair only while
// its centre distance stays below r_l, and must then change no collision.
TEST(SmoothedModel, HoldScreenWithTheCeilingChangesNoCollision) {
    const Scene s = switchScene(512, 1.3, 1.8);
    SmoothedRodEngine screened(buildInitialState<LinearRotor>(s, smoothedRods(s)), s),
        searched(buildInitialState<LinearRotor>(s, smoothedRods(s)), s);
    Probe::setHoldScreen(screened, true);
    Probe::setHoldScreen(searched, false);
    expectSameCollisions(screened, searched, 50);
    if (HasFatalFailure()) return;
    EXPECT_GT(Probe::counts(screened).up + Probe::counts(screened).down, 1000u);
    const auto evaluations = [](const SmoothedRodEngine& e) {
        return e.statistics()["search_evaluations"].get<double>();
    };
    EXPECT_LT(evaluations(screened), 0.9 * evaluations(searched)); // the screen still works
}

namespace {

/// Two LJ spheres passing at impact parameter b inside the switch (r_l = 1.2σ, r_u = 1.8σ), on
/// explicit levels {L0, +1}: U_s = g(r)·U(r) rises with r there, so its minimum along the pass
/// is U_s(b), at closest approach.
dmd::SceneEngine<Sphere, Smoothed<LJPotential>> grazingPass(double b, double L0) {
    System<Sphere, Smoothed<LJPotential>> sys;
    sys.box.length = 40.0;
    sys.body.mass = 18.0;
    sys.kT = 4.2;
    sys.potential.bare = LJPotential{3.0, 3.035};
    sys.potential.cut = SmoothedCutoff{1.2 * 3.035, 1.8 * 3.035};
    sys.bodies.resize(2);
    sys.bodies[0].r = Vec3(20.0 - 8.0, 20.0 + b, 20.0);
    sys.bodies[0].v = Vec3(0.3, 0.0, 0.0);
    sys.bodies[1].r = Vec3(20.0, 20.0, 20.0);
    Scene scene;
    scene.dmd["levels"] = {L0, 1.0};
    return {sys, scene};
}

template <class E> bool runToNextCollision(E& engine, int maxEvents) {
    const auto collisions = [](const dmd::EventCounts& c) { return c.up + c.down + c.reflect; };
    const auto before = collisions(Probe::counts(engine));
    for (int k = 0; k < maxEvents; ++k) {
        Probe::runEvents(engine, 1);
        if (collisions(Probe::counts(engine)) > before) return true;
    }
    return false;
}

} // namespace

TEST(SmoothedModel, GrazingDipBelowALevelInTheSwitchIsCaughtAndOneAboveIsNot) {
    const double b = 4.6; // Å: between r_l = 3.64 Å and r_u = 5.46 Å
    const Smoothed<LJPotential> model{LJPotential{3.0, 3.035},
                                      SmoothedCutoff{1.2 * 3.035, 1.8 * 3.035}};
    const double Ub = model.energy(Vec3(b, 0, 0), Vec3::UnitZ(), Vec3::UnitZ());
    ASSERT_LT(Ub, 0.0);
    constexpr double dip = 1e-6;
    {
        auto engine = grazingPass(b, Ub * (1.0 - dip)); // level just above the minimum
        ASSERT_TRUE(runToNextCollision(engine, 100000));
        EXPECT_EQ(Probe::counts(engine).down, 1u);
        EXPECT_NEAR(engine.time(), 8.0 / 0.3, 0.05); // near closest approach
    }
    {
        auto engine = grazingPass(b, Ub * (1.0 + dip)); // level just below the minimum
        EXPECT_FALSE(runToNextCollision(engine, 5000));
        EXPECT_GT(engine.time(), 16.0 / 0.3); // the pass is over
    }
}

} // namespace test_smoothed_model
