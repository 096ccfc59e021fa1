// DMD's pressure from the impulse virial, P = ρkT + Σ_events r_ij·Δp_i / (3V t): a hand-computed
// reflection and transmission of two spheres (the hard-sphere limit is in test_hard_spheres.cpp).
#include "core/lj_potential.hpp"
#include "core/sphere.hpp"
#include "dmd/scene_engine.hpp"
#include "dmd/testing.hpp"
#include "test_systems.hpp"
#include <cmath>
#include <gtest/gtest.h>
#include <vector>

namespace test_pressure {

using terrace::dmd::testing::Probe;

using namespace terrace;
using terrace::dmdtest::innerRoot;
using terrace::dmdtest::outerRoot;

namespace {

// The event's separation comes from a root refined to round-off; the hand-computed virial uses
// the analytic root of the level, so they agree to the root's refinement (relative).
constexpr double virialTol = 1e-9;

using SphereEngine = dmd::SceneEngine<Sphere, LJPotential>;

/// Two spheres of mass m on the x axis, i at +x0 moving with −u, j at −x0 moving with +u, on the
/// explicit levels {L0, L1} (kJ/mol): ε 3 kJ/mol, σ 3.035 Å.
SphereEngine headOn(double x0, double u, std::vector<double> levels) {
    System<Sphere, LJPotential> sys;
    sys.box.length = 40.0;
    sys.body.mass = 18.0;
    sys.kT = 4.2;
    sys.potential = LJPotential{3.0, 3.035};
    sys.bodies.resize(2);
    sys.bodies[0].r = Vec3(20.0 + x0, 20.0, 20.0);
    sys.bodies[0].v = Vec3(-u, 0.0, 0.0);
    sys.bodies[1].r = Vec3(20.0 - x0, 20.0, 20.0);
    sys.bodies[1].v = Vec3(u, 0.0, 0.0);
    Scene scene;
    scene.dmd["levels"] = std::move(levels);
    return SphereEngine(sys, scene);
}

} // namespace

// A reflection off a step too high to climb: each sphere's momentum turns from −mu to +mu along
// x at separation d, so r_ij·Δp_i = d · 2mu exactly.
TEST(Pressure, ReflectionAddsTheHandComputedImpulseVirial) {
    const double m = 18.0, u = 0.5; // Å per time unit; ½μw² = ½·9·1 = 4.5 kJ/mol < 30
    auto e = headOn(3.0, u, {30.0, 60.0});
    EXPECT_EQ(e.virial(), 0.0);
    e.advanceTo(10.0);
    ASSERT_EQ(Probe::counts(e).reflect, 1u);
    const double d = innerRoot(30.0, 3.0, 3.035);
    EXPECT_NEAR(e.virial(), d * 2.0 * m * u, virialTol * d * m * u);
}

// A transmission down a step of ΔE (the well's first level, crossed inwards): the relative speed
// w = 2u grows to w' = √(w² + 2ΔE/μ), μ = m/2, and Δp_i = μ(w' − w) along r̂_ij, pointing
// inwards (i at +x moves further −x), so r_ij·Δp_i = −d μ (w' − w); then, leaving the well, the
// same step back up restores w and adds the opposite amount.
TEST(Pressure, TransmissionsAddTheHandComputedImpulseVirial) {
    const double m = 18.0, mu = 0.5 * m, u = 0.5;
    const double L0 = -1.5; // kJ/mol
    auto e = headOn(6.0, u, {L0, 60.0});
    // Terrace −1 lies below L0; its energy is the levels' business (dmd/terrace_levels.hpp).
    const auto levels = dmd::TerraceLevels::explicitLevels({L0, 60.0});
    const double dE = levels.energy(-1) - levels.energy(0); // < 0: energy released
    ASSERT_LT(dE, 0.0);
    const double d = outerRoot(L0, 3.0, 3.035);
    e.advanceTo(0.99 * (6.0 - 0.5 * d) / u); // just before the pair reaches d
    ASSERT_EQ(Probe::counts(e).down, 0u);
    e.advanceTo(1.01 * (6.0 - 0.5 * d) / u);
    ASSERT_EQ(Probe::counts(e).down, 1u);
    const double w = 2.0 * u, w1 = std::sqrt(w * w - 2.0 * dE / mu);
    EXPECT_NEAR(e.virial(), -d * mu * (w1 - w), virialTol * d * mu * w);
}

} // namespace test_pressure
