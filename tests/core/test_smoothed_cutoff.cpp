// The smoothed cutoff (paper eqs. 22-23): g and g' analytic values, the smoothed force and torque
// against finite differences of U_smooth, and continuity of the force at r_l and r_u.
#include "core/body_kind.hpp"
#include "core/lj_potential.hpp"
#include "core/rod_potential.hpp"
#include "core/smoothed_cutoff.hpp"
#include <gtest/gtest.h>

namespace test_smoothed_cutoff {

using namespace terrace;

namespace {

const RodPotential rod{};
const SmoothedCutoff paperCut{2.5 * rod.sigma, 3.0 * rod.sigma};

// Central differences with h = 1e-5 Å on energies of order 1e-2 kJ/mol: truncation ~h²·U''' and
// round-off ~1e-16/h together stay below this (kJ/mol/Å, or kJ/mol/rad for torques).
constexpr double finiteDifferenceTolerance = 1e-7;
constexpr double h = 1e-5;
// Round-off of the closed-form g at r_l, r_u and the midpoint (a handful of operations).
constexpr double exactTolerance = 1e-14;

double smoothEnergy(const Vec3& rij, const Vec3& si, const Vec3& sj) {
    return smoothed(rod.evaluate(rij, si, sj), rij, rij.norm(), paperCut).U;
}

} // namespace

TEST(SmoothedCutoff, SwitchingValues) {
    const SmoothedCutoff c{2.0, 3.0};
    EXPECT_EQ(c.switching(1.0), 1.0);
    EXPECT_NEAR(c.switching(2.0), 1.0, exactTolerance);
    EXPECT_NEAR(c.switching(2.5), 0.5, exactTolerance); // the cubic is odd about the midpoint
    EXPECT_NEAR(c.switching(3.0), 0.0, exactTolerance);
    EXPECT_EQ(c.switching(3.5), 0.0);
    EXPECT_NEAR(c.switchingSlope(2.5), -1.5, exactTolerance); // -6·0.5·0.5/1
    EXPECT_EQ(c.switchingSlope(2.0), 0.0);
    EXPECT_EQ(c.switchingSlope(3.0), 0.0);
}

TEST(SmoothedCutoff, SlopeIsDerivativeOfSwitching) {
    for (double r = 2.5 * rod.sigma + 0.01; r < 3.0 * rod.sigma; r += 0.1) {
        const double fd = (paperCut.switching(r + h) - paperCut.switching(r - h)) / (2 * h);
        EXPECT_NEAR(paperCut.switchingSlope(r), fd, finiteDifferenceTolerance) << "r = " << r;
    }
}

TEST(SmoothedCutoff, ForceAndTorqueAreMinusGradientsInTheSwitchRegion) {
    const Vec3 si = Vec3(1, 0.3, -0.2).normalized(), sj = Vec3(0.1, 1, 0.4).normalized();
    for (double r : {2.4, 2.55, 2.75, 2.95}) {
        const Vec3 rij = r * rod.sigma * Vec3(0.6, -0.64, 0.48);
        const PairForce f = smoothed(rod.evaluate(rij, si, sj), rij, rij.norm(), paperCut);
        for (int a = 0; a < 3; ++a) {
            const Vec3 e = Vec3::Unit(a);
            const double fd =
                -(smoothEnergy(rij + h * e, si, sj) - smoothEnergy(rij - h * e, si, sj)) / (2 * h);
            EXPECT_NEAR(f.F[a], fd, finiteDifferenceTolerance) << "r/σ = " << r << " axis " << a;
            // Torque on i about axis e: -dU/dθ for s_i rotated by θ about e.
            const double tfd = -(smoothEnergy(rij, rotationMatrix(e, h) * si, sj) -
                                 smoothEnergy(rij, rotationMatrix(e, -h) * si, sj)) /
                               (2 * h);
            EXPECT_NEAR(f.tauI[a], tfd, finiteDifferenceTolerance) << "r/σ = " << r;
        }
    }
}

TEST(SmoothedCutoff, ForceContinuousAtBothEnds) {
    const Vec3 si = Vec3(0, 0, 1), sj = Vec3(0, 0.6, 0.8);
    const Vec3 dir = Vec3(1, 2, 2) / 3.0;
    // One part in 1e-12 of r: the force changes by at most |dF/dr|·δr ~ 1e-12 kJ/mol/Å there.
    const double delta = 1e-12 * paperCut.outer();
    constexpr double continuityTolerance = 1e-10;
    for (double edge : {paperCut.inner(), paperCut.outer()}) {
        const Vec3 below = (edge - delta) * dir, above = (edge + delta) * dir;
        const PairForce fb = smoothed(rod.evaluate(below, si, sj), below, below.norm(), paperCut);
        const PairForce fa =
            edge < paperCut.outer()
                ? smoothed(rod.evaluate(above, si, sj), above, above.norm(), paperCut)
                : PairForce{}; // beyond r_u the pair does not interact at all
        EXPECT_LT((fb.F - fa.F).norm(), continuityTolerance) << "edge " << edge;
        EXPECT_LT((fb.tauI - fa.tauI).norm(), continuityTolerance) << "edge " << edge;
        EXPECT_LT(std::abs(fb.U - fa.U), continuityTolerance) << "edge " << edge;
    }
    // And the raw force is clearly not zero at r_u, so the smoothing is what makes it continuous.
    const Vec3 atOuter = paperCut.outer() * dir;
    EXPECT_GT(rod.evaluate(atOuter, si, sj).F.norm(), 1e3 * continuityTolerance);
}

TEST(SmoothedCutoff, UntouchedInsideInnerRadius) {
    const LJPotential lj{};
    const SmoothedCutoff c{2.5, 3.0};
    const Vec3 rij(1.1, 0.2, 0.0);
    const PairForce raw = lj.evaluate(rij, Vec3::UnitZ(), Vec3::UnitZ());
    const PairForce f = smoothed(raw, rij, rij.norm(), c);
    EXPECT_EQ(f.U, raw.U);
    EXPECT_EQ(f.F, raw.F);
}

} // namespace test_smoothed_cutoff
