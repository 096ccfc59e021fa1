// Rods among spheres (core/rod_mixture.hpp): a pair of rods is the paper's rod potential, any pair
// with a sphere in it is Lennard-Jones on the centre distance with no torque, the forces and
// torques are the derivatives of U, and the bounds the DMD engine reads (the deepest well, the
// reach of a value, the lowest U at a distance, U's range near a configuration) hold over every
// pair and alignment.
#include "core/rod_mixture.hpp"
#include "core/smoothed_potential.hpp"
#include "tests/core/pair_checks.hpp"
#include <gtest/gtest.h>
#include <random>

namespace test_rod_mixture {

using namespace terrace;
using pairchecks::centralDerivative;
using pairchecks::closeRelative;
using pairchecks::randomUnit;

namespace {

/// Species 0: the paper's rods (ε 3 kJ/mol, σ 3.035 Å, ζ 1 Å); species 1: spheres (ε 1.2, σ 3.4);
/// unlike pairs by Lorentz–Berthelot.
RodMixture rodsInSpheres() {
    RodMixture m;
    m.species = 2;
    m.rod = {true, false};
    const double eps[] = {3.0, 1.2}, sig[] = {3.035, 3.4};
    for (int a = 0; a < 2; ++a)
        for (int b = a; b < 2; ++b)
            m.setPair(a, b, std::sqrt(eps[a] * eps[b]), 0.5 * (sig[a] + sig[b]), 1.0);
    return m;
}

SpeciesAxis rodAlong(const Vec3& s) {
    return {s, 0};
}
SpeciesAxis sphereWith(const Vec3& s) {
    return {s, 1};
} // a sphere's axis is never read

} // namespace

// From shared testdata rod_reference.json ("pair_values", the first pair), computed from the
// paper's formulas ("Model System") independently of terrace's code: a pair of the mixture's rods
// is the paper's pair.
TEST(RodMixture, TwoRodsAreThePapersRodPair) {
    const RodMixture m = rodsInSpheres();
    const Vec3 rij(-1.248309756246021, 2.4950141747896346, -1.1030081686278652);
    const Vec3 si(-0.31355142005619185, -0.9255403067568224, -0.2122749338693397);
    const Vec3 sj(0.7044539819309423, 0.2687176454515708, 0.6569135516676479);
    const PairForce f = m.evaluate(rij, rodAlong(si), rodAlong(sj));
    EXPECT_NEAR(f.U, -1.67219523756012, 1e-12);
    EXPECT_TRUE(closeRelative(f.F, Vec3(-5.303743143243084, 10.6006656245558, -4.68639452830504),
                              1e-12, 1.0));
    EXPECT_TRUE(closeRelative(f.tauI, Vec3(-8.5540955815507, 0.8762523966568763, 8.814709635218373),
                              1e-12, 1.0));
    EXPECT_TRUE(closeRelative(f.tauJ, -f.tauI, 1e-15, 1.0));
    // And bit for bit the rod potential's own numbers.
    const RodPotential rod{3.0, 3.035, 1.0};
    const PairForce g = rod.evaluate(rij, si, sj);
    EXPECT_EQ(f.U, g.U);
    EXPECT_EQ(f.F, g.F);
    EXPECT_EQ(f.tauI, g.tauI);
    EXPECT_EQ(m.energy(rij, rodAlong(si), rodAlong(sj)), rod.energy(rij, si, sj));
}

TEST(RodMixture, APairWithASphereIsLennardJonesOnTheCentresWithNoTorque) {
    const RodMixture m = rodsInSpheres();
    std::mt19937_64 rng(7);
    const double eps01 = std::sqrt(3.0 * 1.2), sig01 = 0.5 * (3.035 + 3.4);
    for (int k = 0; k < 200; ++k) {
        const double r = 3.0 + 0.01 * k;
        const Vec3 rij = r * randomUnit(rng);
        const Vec3 si = randomUnit(rng), sj = randomUnit(rng);
        for (const auto& [i, j, eps, sig] :
             {std::tuple{rodAlong(si), sphereWith(sj), eps01, sig01},
              std::tuple{sphereWith(si), rodAlong(sj), eps01, sig01},
              std::tuple{sphereWith(si), sphereWith(sj), 1.2, 3.4}}) {
            const PairForce f = m.evaluate(rij, i, j);
            const auto lj = detail::lennardJones(r, eps, sig);
            EXPECT_NEAR(f.U, lj.U, 1e-12 * std::max(1.0, std::abs(lj.U)));
            EXPECT_TRUE(closeRelative(f.F, (-lj.dUdx / r) * rij, 1e-12, 1e-9));
            EXPECT_EQ(f.tauI, Vec3::Zero()); // 2ζcU'(s_i × s_j) with ζ = 0: exactly nothing
            EXPECT_EQ(f.tauJ, Vec3::Zero());
            // The sphere's axis is not read: another gives the same numbers.
            SpeciesAxis i2 = i, j2 = j;
            (i.species == 1 ? i2 : j2).axis = randomUnit(rng);
            EXPECT_EQ(m.evaluate(rij, i2, j2).U, f.U);
        }
    }
}

TEST(RodMixture, ForcesTorquesAndRateAreTheDerivativesOfU) {
    const RodMixture m = rodsInSpheres();
    std::mt19937_64 rng(11);
    for (int k = 0; k < 50; ++k) {
        const Vec3 rij = (3.1 + 0.03 * k) * randomUnit(rng);
        const Vec3 si = randomUnit(rng), sj = randomUnit(rng);
        for (const auto& ij :
             {std::pair{rodAlong(si), rodAlong(sj)}, std::pair{rodAlong(si), sphereWith(sj)}}) {
            // Named copies rather than a structured binding: clang 14 cannot capture a binding.
            const SpeciesAxis i = ij.first, j = ij.second;
            const PairForce f = m.evaluate(rij, i, j);
            // F = −∂U/∂r_ij, component by component.
            Vec3 fd;
            for (int d = 0; d < 3; ++d)
                fd[d] = -centralDerivative(
                    [&](double h) {
                        Vec3 x = rij;
                        x[d] += h;
                        return m.energy(x, i, j);
                    },
                    1e-4);
            EXPECT_TRUE(closeRelative(f.F, fd, 1e-7, 1e-3));
            // τ_i·n = −dU/dθ for a turn of s_i by θ about n.
            const Vec3 n = randomUnit(rng);
            const double dUdTheta = centralDerivative(
                [&](double h) {
                    SpeciesAxis turned = i;
                    turned.axis = rotationMatrix(n, h) * i.axis;
                    return m.energy(rij, turned, j);
                },
                1e-4);
            EXPECT_TRUE(closeRelative(f.tauI.dot(n), -dUdTheta, 1e-6, 1e-3));
            // dU/dt from energyRate equals eq. (13) from the force and torques.
            const Vec3 vij = randomUnit(rng), wi = randomUnit(rng), wj = randomUnit(rng);
            const EnergyRate e = m.energyRate(rij, vij, i, wi, j, wj);
            EXPECT_EQ(e.U, f.U);
            EXPECT_NEAR(e.dUdt, dUdt(f, vij, wi, wj), 1e-10 * std::max(1.0, std::abs(e.dUdt)));
        }
    }
}

TEST(RodMixture, BoundsHoldOverEveryPairAndAlignment) {
    const RodMixture m = rodsInSpheres();
    // The deepest well is the rods' own (ε 3), deeper than the unlike (√3.6) and spheres' (1.2).
    EXPECT_DOUBLE_EQ(m.minimumEnergy(), -3.0);
    std::mt19937_64 rng(13);
    // Scan every pair over distances and alignments: U at r is never below lowestEnergyAt(r),
    // and the farthest r at which U reaches u (from the well's side or the wall's) is within
    // reachDistance(u).
    const double levels[] = {-2.5, -1.0, -0.3, 0.5};
    double reached[4] = {0.0, 0.0, 0.0, 0.0};
    for (int k = 0; k < 4000; ++k) {
        const double r = 2.5 + 0.001 * k;
        const Vec3 rij = r * Vec3::UnitX();
        double lowest = std::numeric_limits<double>::infinity();
        for (int t = 0; t < 40; ++t) {
            const Vec3 si = randomUnit(rng), sj = randomUnit(rng);
            for (const auto& [i, j] :
                 {std::pair{rodAlong(si), rodAlong(sj)}, std::pair{rodAlong(si), sphereWith(sj)},
                  std::pair{sphereWith(si), sphereWith(sj)}}) {
                const double u = m.energy(rij, i, j);
                lowest = std::min(lowest, u);
                // U crosses u where it is at or beyond it: below a negative level in the well,
                // above a positive one on the wall.
                for (int l = 0; l < 4; ++l)
                    if (levels[l] < 0.0 ? u <= levels[l] : u >= levels[l])
                        reached[l] = std::max(reached[l], r);
            }
        }
        // Parallel and crossed rods at this distance: the alignments at the ends of r_e's
        // range, which the bounds reach and random axes only come near.
        for (const Vec3& sj : {Vec3(Vec3::UnitZ()), Vec3(Vec3::UnitY())}) {
            const double u = m.energy(rij, rodAlong(Vec3::UnitZ()), rodAlong(sj));
            lowest = std::min(lowest, u);
            for (int l = 0; l < 4; ++l)
                if (levels[l] < 0.0 ? u <= levels[l] : u >= levels[l])
                    reached[l] = std::max(reached[l], r);
        }
        ASSERT_GE(lowest, m.lowestEnergyAt(r) - 1e-12) << "r = " << r;
    }
    for (int l = 0; l < 4; ++l) {
        EXPECT_GE(m.reachDistance(levels[l]), reached[l]) << "u = " << levels[l];
        // Not a loose bound: within the scan's step.
        EXPECT_LT(m.reachDistance(levels[l]), reached[l] + 0.002) << "u = " << levels[l];
    }
    // Under the smoothed cutoff the reach is found through the switch from lowestEnergyAt.
    const Smoothed<RodMixture> s{m, SmoothedCutoff{8.0, 9.0}};
    EXPECT_GE(s.reachDistance(-0.3), reached[2]);
}

TEST(RodMixture, EnergyRangeHoldsOverTheNeighbourhood) {
    const RodMixture m = rodsInSpheres();
    std::mt19937_64 rng(17);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int k = 0; k < 300; ++k) {
        const Vec3 rij = (3.0 + 2.0 * unit(rng)) * randomUnit(rng);
        const Vec3 si = randomUnit(rng), sj = randomUnit(rng);
        const double shift = 0.3 * unit(rng), turnI = 0.4 * unit(rng), turnJ = 0.4 * unit(rng);
        for (const auto& [i, j] :
             {std::pair{rodAlong(si), rodAlong(sj)}, std::pair{rodAlong(si), sphereWith(sj)}}) {
            const EnergyRange range = m.energyRange(rij, i, j, shift, turnI, turnJ);
            double lo = std::numeric_limits<double>::infinity(), hi = -lo;
            for (int t = 0; t < 40; ++t) {
                // A neighbour: the centres moved by at most shift, each axis turned by at most
                // its turn about a random axis.
                const Vec3 moved = rij + shift * unit(rng) * randomUnit(rng);
                SpeciesAxis a = i, b = j;
                a.axis = rotationMatrix(randomUnit(rng), turnI * unit(rng)) * i.axis;
                b.axis = rotationMatrix(randomUnit(rng), turnJ * unit(rng)) * j.axis;
                const double u = m.energy(moved, a, b);
                lo = std::min(lo, u);
                hi = std::max(hi, u);
            }
            ASSERT_LE(range.lo, lo + 1e-12) << "k = " << k;
            ASSERT_GE(range.hi, hi - 1e-12) << "k = " << k;
        }
        // With a sphere in the pair nothing turns U: its range is LJ's over [r − shift, r +
        // shift] exactly, the least at the point nearest the minimum, the most at an end.
        const double r = rij.norm(), eps = std::sqrt(3.0 * 1.2), sig = 0.5 * (3.035 + 3.4);
        const auto lj = [&](double x) { return detail::lennardJones(x, eps, sig).U; };
        const EnergyRange exact = m.energyRange(rij, rodAlong(si), sphereWith(sj), shift, 1.0, 1.0);
        EXPECT_DOUBLE_EQ(exact.lo,
                         lj(std::clamp(sig * RodMixture::minimumOverSigma, r - shift, r + shift)));
        EXPECT_DOUBLE_EQ(exact.hi, std::max(lj(r - shift), lj(r + shift)));
    }
    // Two rods, nothing moved or turned: the range is the pair's own U.
    const Vec3 rij(3.4, 0.2, -0.1), si = Vec3(1, 2, 3).normalized(),
                                    sj = Vec3(-1, 0, 2).normalized();
    const EnergyRange still = m.energyRange(rij, rodAlong(si), rodAlong(sj), 0.0, 0.0, 0.0);
    const double u = m.energy(rij, rodAlong(si), rodAlong(sj));
    EXPECT_NEAR(still.lo, u, 1e-12);
    EXPECT_NEAR(still.hi, u, 1e-12);
}

} // namespace test_rod_mixture
