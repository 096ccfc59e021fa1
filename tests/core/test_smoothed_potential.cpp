// The model both engines simulate, g(r)·U (core/smoothed_potential.hpp): the bare potential inside
// r_l and without a cutoff, zero beyond r_u, the rate dU_s/dt against a finite difference along
// free motion, and the reach of a level (which sets DMD's r_m) against a brute-force scan over
// orientations.
#include "core/lj_potential.hpp"
#include "core/rod_potential.hpp"
#include "core/smoothed_potential.hpp"
#include <cmath>
#include <gtest/gtest.h>
#include <random>

namespace test_smoothed_potential {

using namespace terrace;

namespace {

const RodPotential rod{};
const Smoothed<RodPotential> model{rod, SmoothedCutoff{2.5 * rod.sigma, 3.0 * rod.sigma}};
const Smoothed<RodPotential> bareModel{rod, SmoothedCutoff::none()};

// A central difference with h = 1e-6 time units: truncation ~h² and round-off ~eps·U/h.
constexpr double centralDifferenceTol = 1e-6;
// The rate by its own formula against the one through force and torques: round-off only.
constexpr double rateRoundoff = 1e-12;
// U at a reach found by bisection equals the level to the bisection's resolution (relative).
constexpr double reachTol = 1e-9;

Vec3 randomUnit(std::mt19937_64& rng) {
    std::normal_distribution<double> g;
    return Vec3(g(rng), g(rng), g(rng)).normalized();
}

/// s turned by ω over t (Rodrigues), for the finite difference along free rotation.
Vec3 turned(const Vec3& s, const Vec3& w, double t) {
    const double a = w.norm() * t;
    if (a == 0.0) return s;
    const Vec3 k = w.normalized();
    return s * std::cos(a) + k.cross(s) * std::sin(a) + k * k.dot(s) * (1.0 - std::cos(a));
}

} // namespace

TEST(SmoothedPotential, BareInsideInnerRadiusAndWithoutCutoff) {
    std::mt19937_64 rng(1);
    for (double r : {3.0, 5.0, 7.0, 7.5}) { // r_l = 7.5875 Å
        const Vec3 rij = r * randomUnit(rng), si = randomUnit(rng), sj = randomUnit(rng);
        const PairForce a = model.evaluate(rij, si, sj), b = rod.evaluate(rij, si, sj);
        EXPECT_EQ(a.U, b.U);
        EXPECT_EQ(a.F, b.F);
        EXPECT_EQ(a.tauI, b.tauI);
        EXPECT_EQ(model.energy(rij, si, sj), rod.energy(rij, si, sj));
    }
    for (double r : {3.0, 8.0, 9.5, 40.0}) { // no cutoff: the bare potential at every distance
        const Vec3 rij = r * randomUnit(rng), si = randomUnit(rng), sj = randomUnit(rng);
        EXPECT_EQ(bareModel.evaluate(rij, si, sj).U, rod.evaluate(rij, si, sj).U);
        EXPECT_EQ(bareModel.energy(rij, si, sj), rod.energy(rij, si, sj));
        EXPECT_EQ(bareModel.reachDistance(-0.01), rod.reachDistance(-0.01));
    }
}

TEST(SmoothedPotential, ZeroBeyondOuterRadiusScaledInTheSwitch) {
    std::mt19937_64 rng(2);
    const double ru = model.range();
    for (double r : {ru, ru * 1.01, 30.0}) {
        // r·û has a norm within an ulp of r either way; at r = r_u it must not fall below it
        // (the switch is then a few ulp from zero, not zero: −5e-32 in clang's build).
        Vec3 rij = r * randomUnit(rng);
        while (rij.norm() < r)
            rij *= std::nextafter(1.0, 2.0);
        const Vec3 si = randomUnit(rng), sj = randomUnit(rng);
        const PairForce f = model.evaluate(rij, si, sj);
        EXPECT_EQ(f.U, 0.0);
        EXPECT_EQ(f.F, Vec3::Zero());
        EXPECT_EQ(model.energy(rij, si, sj), 0.0);
    }
    const double r = 8.3; // in the switch
    const Vec3 rij = r * randomUnit(rng), si = randomUnit(rng), sj = randomUnit(rng);
    EXPECT_DOUBLE_EQ(model.energy(rij, si, sj), model.cut.switching(r) * rod.energy(rij, si, sj));
    EXPECT_DOUBLE_EQ(model.evaluate(rij, si, sj).U, model.energy(rij, si, sj));
}

TEST(SmoothedPotential, RateIsTheDerivativeAlongFreeMotion) {
    // Pairs inside r_l, in the switch and just beyond: dU_s/dt against a central difference of
    // U_s along straight-line translation and uniform rotation of both axes.
    std::mt19937_64 rng(3);
    constexpr double h = 1e-6; // time units; U_s ~ 1e-1 kJ/mol, rates ~ 1 kJ/mol per time unit
    for (double r : {4.0, 7.9, 8.4, 9.0}) {
        const Vec3 rij = r * randomUnit(rng), v = 2.0 * randomUnit(rng);
        const Vec3 si = randomUnit(rng), sj = randomUnit(rng);
        const Vec3 wi = 3.0 * randomUnit(rng), wj = 3.0 * randomUnit(rng);
        auto at = [&](double t) {
            return model.energy(rij + v * t, turned(si, wi, t), turned(sj, wj, t));
        };
        const double numeric = (at(h) - at(-h)) / (2.0 * h);
        const EnergyRate e = model.energyRate(rij, v, si, wi, sj, wj);
        EXPECT_DOUBLE_EQ(e.U, model.energy(rij, si, sj));
        EXPECT_NEAR(e.dUdt, numeric, centralDifferenceTol * (1.0 + std::abs(numeric)))
            << "r = " << r;
        // And the rate through the force and torques (paper eq. 13) agrees.
        EXPECT_NEAR(e.dUdt, dUdt(model.evaluate(rij, si, sj), v, wi, wj),
                    rateRoundoff * (1.0 + std::abs(numeric)));
    }
}

TEST(SmoothedPotential, ReachOfALevelIsTheLastDistanceAnyOrientationReachesIt) {
    // Deep levels are reached inside r_l, where the reach is the bare one; shallow ones only in
    // the switch, closer than the bare reach and than r_u.
    EXPECT_EQ(model.reachDistance(-1.0), rod.reachDistance(-1.0));
    EXPECT_EQ(model.reachDistance(1.0), rod.reachDistance(1.0)); // the wall: inside r_l
    std::mt19937_64 rng(4);
    for (double u : {-0.02, -0.005, -0.001}) {
        const double reach = model.reachDistance(u);
        EXPECT_GT(reach, model.cut.inner()) << u;
        EXPECT_LT(reach, std::min(rod.reachDistance(u), model.range())) << u;
        // Parallel axes perpendicular to r_ij give the lowest U (r_e = r − ζ/2): at the reach
        // U_s = u to the bisection's resolution, and no orientation goes below u beyond it.
        const Vec3 s = Vec3::UnitX(), dir = Vec3::UnitZ();
        EXPECT_NEAR(model.energy(reach * dir, s, s), u, reachTol * std::abs(u)) << u;
        for (int k = 0; k < 2000; ++k) {
            const double r = reach * (1.0 + 1e-6) + 0.5 * k / 2000.0;
            EXPECT_GT(model.energy(r * randomUnit(rng), randomUnit(rng), randomUnit(rng)), u);
        }
        EXPECT_LT(model.energy((reach * (1.0 - 1e-6)) * dir, s, s), u);
    }
    // Lennard-Jones spheres: the reach solves g(r)·U(r) = u.
    const LJPotential lj{};
    const Smoothed<LJPotential> ljModel{lj, SmoothedCutoff{2.5, 3.0}};
    const double reach = ljModel.reachDistance(-0.01);
    EXPECT_GT(reach, 2.5);
    EXPECT_NEAR(ljModel.energy(Vec3(reach, 0, 0), Vec3::UnitZ(), Vec3::UnitZ()), -0.01,
                reachTol * 0.01);
}

} // namespace test_smoothed_potential
