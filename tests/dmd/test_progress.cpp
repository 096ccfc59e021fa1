// Guaranteed progress on degenerate starts at N = 32768 (validation tier): an engine that
// re-schedules the same zero-time event forever is a known failure of event-driven codes.
#include "dmd/testing.hpp"
#include "test_systems.hpp"
#include <gtest/gtest.h>

namespace test_progress {

using terrace::dmd::testing::Probe;

using namespace terrace;
using namespace terrace::dmdtest;

namespace {

constexpr double energyTolerance = 1e-10; // relative, as for the long conservation run
constexpr int side = 32;                  // 32³ = 32768 rods
constexpr double onLevelTol = 1e-12;      // kJ/mol: the closed-form spacing puts U on the level

void expectProgress(RodEngine& e, double runFs) {
    const double e0 = totalEnergy(e);
    e.advanceTo(units::fromFs(runFs));
    EXPECT_DOUBLE_EQ(e.time(), units::fromFs(runFs));
    EXPECT_GT(Probe::counts(e).up + Probe::counts(e).down + Probe::counts(e).reflect, 1000u);
    EXPECT_NEAR(totalEnergy(e), e0, energyTolerance * std::abs(e0));
}

} // namespace

// All rods exactly parallel and not rotating: torques vanish identically (s_i × s_j = 0) and stay
// zero, every nearest-neighbour pair starts at the same U, and the lattice is perfectly regular.
TEST(Progress, ExactlyParallelRodsOnALatticeAdvance) {
    const double kT = 4.2, a = 3.035 / std::cbrt(0.5); // ρ* = 0.5
    RodSystem sys = alignedLattice(side, a, kT, 11);
    for (auto& b : sys.bodies)
        b.w = Vec3::Zero();
    RodEngine e(sys, rodScene(side * side * side, 0.5, 1.4, 0.5));
    expectProgress(e, 60.0); // the bound lattice pairs need a while to reach their levels
}

// Lattice spacing chosen so that parallel nearest neighbours sit exactly on the level +ΔV/2 of
// ΔV = kT/2: U(a) = 1.05 kJ/mol with r_e = a − ζ/2 on the repulsive wall.
TEST(Progress, PairsExactlyOnALevelAdvance) {
    const double kT = 4.2, dV = 0.5 * kT, epsilon = 3.0, sigma = 3.035;
    const double y = 0.5 * (1.0 + std::sqrt(1.0 + 0.5 * dV / epsilon)); // (σ/r_e)^6 on the wall
    const double a = sigma / std::pow(y, 1.0 / 6.0) + 0.5;
    RodSystem sys = alignedLattice(side, a, kT, 13);
    const RodPotential rod;
    const double U = rod.energy(Vec3(a, 0, 0), Vec3::UnitZ(), Vec3::UnitZ());
    ASSERT_NEAR(U, 0.5 * dV, onLevelTol); // the start really is on the level
    RodEngine e(sys, rodScene(side * side * side, 0.5, 1.4, 0.5));
    expectProgress(e, 10.0); // ~10⁵ collisions
}

} // namespace test_progress
