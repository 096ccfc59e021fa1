// Two-body scenarios with analytic answers: the full engine (search, rule, bookkeeping) on cases
// a pencil-and-paper calculation settles.
#include "core/linear_rotor.hpp"
#include "core/lj_potential.hpp"
#include "core/rod_potential.hpp"
#include "core/sphere.hpp"
#include "dmd/scene_engine.hpp"
#include "dmd/testing.hpp"
#include "test_systems.hpp"
#include <cmath>
#include <gtest/gtest.h>
#include <vector>

namespace test_two_body {

using terrace::dmd::testing::Probe;

using namespace terrace;
using namespace terrace::dmd;
using terrace::dmdtest::innerRoot;

namespace {

// Event times come from a bracketed root refined to ~1e-13 of the search step; the analytic
// times accumulate a few such errors.
constexpr double timeTolerance = 1e-10;
// Speeds after an event follow from energy conservation; round-off of a handful of operations.
constexpr double speedTolerance = 1e-12;
// Separations at an event: event-time error times speed, plus the positions' round-off.
constexpr double separationTol = 1e-9; // Å
// A grazing event comes near closest approach: loose, the test asks that it is caught, not when.
constexpr double closestApproachTol = 0.05; // time units

using RodEngine = dmd::SceneEngine<LinearRotor, RodPotential>;

Scene sceneWithDV(double dVInKT) {
    Scene s;
    s.dmd["dV"] = dVInKT;
    return s;
}

/// Runs single events until the next collision (up, down or reflection); false if none comes.
template <class E> bool runToNextCollision(E& engine, int maxEvents = 100000) {
    const auto before = Probe::counts(engine);
    const auto collisions = [](const EventCounts& c) { return c.up + c.down + c.reflect; };
    for (int k = 0; k < maxEvents; ++k) {
        Probe::runEvents(engine, 1);
        if (collisions(Probe::counts(engine)) > collisions(before)) return true;
    }
    return false;
}

} // namespace

// Parallel rods (c = 1, so r_e = r − ζ/2 and no torque) approaching head-on along x: a 1-D
// stepped potential. With μ = m/2 the relative speed after each level is √(ṙ² − 2ΔE/μ), and the
// crossings happen where LJ(r − ζ/2) equals a level.
TEST(TwoBody, ParallelRodsHeadOnFollowTheSteppedPotential) {
    System<LinearRotor, RodPotential> sys;
    sys.box.length = 40.0;
    sys.body.mass = 18.0;
    sys.body.inertia = Vec3(1.154, 1.154, 0.0);
    sys.kT = 4.2;
    const RodPotential rod;
    sys.potential = rod;
    const double u = 0.5; // Å per time unit, each body
    const double r0 = 6.0;
    sys.bodies.resize(2);
    sys.bodies[0].r = Vec3(10.0 + r0, 20.0, 20.0);
    sys.bodies[0].v = Vec3(-u, 0, 0);
    sys.bodies[1].r = Vec3(10.0, 20.0, 20.0);
    sys.bodies[1].v = Vec3(u, 0, 0);
    for (auto& b : sys.bodies)
        b.s = Vec3::UnitZ();
    RodEngine engine(sys, sceneWithDV(0.5)); // ΔV = 2.1 kJ/mol: levels ±1.05, ±3.15, 5.25, …
    const double dV = 2.1, mu = 9.0;
    const double half = 0.5 * rod.zeta;
    // Expected sequence of (distance, ΔE, outcome) for an initial relative KE of 4.5 kJ/mol.
    struct Step {
        double r;
        double dE;
        Outcome outcome;
    };
    const double outer =
        terrace::detail::lennardJonesRoot(-0.5 * dV, rod.epsilon, rod.sigma) + half;
    const double inner = innerRoot(-0.5 * dV, rod.epsilon, rod.sigma) + half;
    const double wall1 = innerRoot(0.5 * dV, rod.epsilon, rod.sigma) + half;
    const double wall2 = innerRoot(1.5 * dV, rod.epsilon, rod.sigma) + half;
    const double wall3 = innerRoot(2.5 * dV, rod.epsilon, rod.sigma) + half;
    const std::vector<Step> steps = {
        {outer, -dV, Outcome::Down}, {inner, +dV, Outcome::Up},      {wall1, +dV, Outcome::Up},
        {wall2, +dV, Outcome::Up},   {wall3, 0.0, Outcome::Reflect}, {wall2, -dV, Outcome::Down},
        {wall1, -dV, Outcome::Down}, {inner, -dV, Outcome::Down},    {outer, +dV, Outcome::Up},
    };
    double t = 0.0, r = r0, rdot = -2.0 * u;
    for (std::size_t k = 0; k < steps.size(); ++k) {
        SCOPED_TRACE("collision " + std::to_string(k));
        const EventCounts before = Probe::counts(engine);
        ASSERT_TRUE(runToNextCollision(engine));
        t += (steps[k].r - r) / rdot;
        r = steps[k].r;
        const EventCounts& after = Probe::counts(engine);
        EXPECT_EQ(after.up - before.up, steps[k].outcome == Outcome::Up ? 1u : 0u);
        EXPECT_EQ(after.down - before.down, steps[k].outcome == Outcome::Down ? 1u : 0u);
        EXPECT_EQ(after.reflect - before.reflect, steps[k].outcome == Outcome::Reflect ? 1u : 0u);
        EXPECT_NEAR(engine.time(), t, timeTolerance);
        if (steps[k].outcome == Outcome::Reflect)
            rdot = -rdot;
        else
            rdot = std::copysign(std::sqrt(rdot * rdot - 2.0 * steps[k].dE / mu), rdot);
        const auto now = engine.system();
        EXPECT_NEAR(now.bodies[0].v.x(), 0.5 * rdot, speedTolerance);
        EXPECT_NEAR(now.bodies[1].v.x(), -0.5 * rdot, speedTolerance);
        EXPECT_EQ(now.bodies[0].w.norm(), 0.0); // parallel rods feel no torque
        EXPECT_NEAR((now.bodies[0].r - now.bodies[1].r).norm(), r, separationTol);
    }
    EXPECT_EQ(engine.potentialEnergy(), 0.0); // back on terrace 0, flying apart
    // Free flight until the periodic images could meet: no event but virtual and cell ones.
    const EventCounts before = Probe::counts(engine);
    engine.advanceTo(t + 0.9 * (sys.box.length - 2.0 * Probe::interactionRange(engine)) / rdot);
    EXPECT_EQ(Probe::counts(engine).up + Probe::counts(engine).down + Probe::counts(engine).reflect,
              before.up + before.down + before.reflect);
}

namespace {

/// Two LJ spheres passing each other at impact parameter b, on explicit levels {L0, +1}: U has
/// its minimum U(b) at closest approach, the only place the lower level can be reached.
dmd::SceneEngine<Sphere, LJPotential> grazingPass(double b, double L0) {
    System<Sphere, LJPotential> sys;
    sys.box.length = 40.0;
    sys.body.mass = 18.0;
    sys.kT = 4.2;
    sys.potential.epsilon = 3.0;
    sys.potential.sigma = 3.035;
    sys.bodies.resize(2);
    sys.bodies[0].r = Vec3(20.0 - 8.0, 20.0 + b, 20.0);
    sys.bodies[0].v = Vec3(0.3, 0.0, 0.0);
    sys.bodies[1].r = Vec3(20.0, 20.0, 20.0);
    Scene scene;
    scene.dmd["levels"] = {L0, 1.0};
    return dmd::SceneEngine<Sphere, LJPotential>(sys, scene);
}

} // namespace

// A grazing pass whose minimum dips 1e-6 of the level below it is caught; one that stays 1e-6
// above is not. The dip lasts ~1e-4 time units while the search takes steps of up to 4 fs.
TEST(TwoBody, GrazingDipBelowALevelIsCaughtAndOneAboveIsNot) {
    const double b = 4.0; // Å, on the attractive side of the LJ minimum (3.41 Å)
    const double Ub = 4.0 * 3.0 * (std::pow(3.035 / b, 12) - std::pow(3.035 / b, 6));
    constexpr double dip = 1e-6;
    {
        auto engine = grazingPass(b, Ub * (1.0 - dip)); // level just above the minimum
        ASSERT_TRUE(runToNextCollision(engine));
        EXPECT_EQ(Probe::counts(engine).down, 1u);
        EXPECT_NEAR(engine.time(), 8.0 / 0.3, closestApproachTol);
    }
    {
        auto engine = grazingPass(b, Ub * (1.0 + dip)); // level just below the minimum
        EXPECT_FALSE(runToNextCollision(engine, 5000));
        EXPECT_GT(engine.time(), 16.0 / 0.3); // the pass is over
    }
}

} // namespace test_two_body
