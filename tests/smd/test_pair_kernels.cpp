// The pair loop's kernels equal the potential's own evaluate() followed by smoothed(): the
// squared-distance form of Lennard-Jones (pair_kernels.hpp) across the whole range, including
// the switch region, and the general kernel for rods.
#include "core/lj_potential.hpp"
#include "core/rod_potential.hpp"
#include "smd/pair_kernels.hpp"
#include <gtest/gtest.h>

namespace test_pair_kernels {

using namespace terrace;
using namespace terrace::smd;

namespace {

// The two forms differ by a few roundings of quantities up to ~1e3 (deep in the repulsive wall):
// relative agreement to this is round-off, a wrong formula is off by O(1).
constexpr double relativeRoundOff = 1e-12;

void expectSame(const PairForce& a, const PairForce& b) {
    const double scale = 1.0 + std::abs(b.U) + b.F.norm() + b.tauI.norm();
    EXPECT_NEAR(a.U, b.U, relativeRoundOff * scale);
    EXPECT_LT((a.F - b.F).norm(), relativeRoundOff * scale);
    EXPECT_LT((a.tauI - b.tauI).norm(), relativeRoundOff * scale);
    EXPECT_LT((a.tauJ - b.tauJ).norm(), relativeRoundOff * scale);
}

} // namespace

TEST(PairKernels, LennardJonesSquaredDistanceFormEqualsEvaluate) {
    const LJPotential lj{1.3, 0.9};
    const SmoothedCutoff cut{2.5 * 0.9, 3.0 * 0.9};
    const Vec3 dir = Vec3(0.3, -0.5, 0.81).normalized(), z = Vec3::UnitZ();
    for (double r = 0.8; r < cut.outer(); r += 0.013) {
        const Vec3 rij = r * dir;
        const CentralForce f =
            PairKernel<Smoothed<LJPotential>>::evaluate({lj, cut}, rij, rij.squaredNorm(), z, z);
        PairForce asPair;
        asPair.U = f.U;
        asPair.F = f.F;
        expectSame(asPair, smoothed(lj.evaluate(rij, z, z), rij, r, cut));
    }
}

TEST(PairKernels, RodKernelIsEvaluateThenSmoothed) {
    const RodPotential rod{};
    const SmoothedCutoff cut{2.5 * rod.sigma, 3.0 * rod.sigma};
    const Vec3 si = Vec3(1, 0.2, 0.1).normalized(), sj = Vec3(-0.3, 1, 0.5).normalized();
    for (double r = 2.8; r < cut.outer(); r += 0.05) {
        const Vec3 rij = r * Vec3(0, 0.6, 0.8);
        expectSame(PairKernel<Smoothed<RodPotential>>::evaluate({rod, cut}, rij, rij.squaredNorm(),
                                                                si, sj),
                   smoothed(rod.evaluate(rij, si, sj), rij, r, cut));
    }
}

} // namespace test_pair_kernels
