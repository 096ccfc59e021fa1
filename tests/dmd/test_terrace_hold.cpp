// The hold-time screen (dmd/terrace_hold.hpp): the bands of r_e of the paper's rod terraces, the
// bound's analytic limits, and, against brute force on random free-flying rod pairs up to
// T* = 50, that no pair ever leaves its terrace before its hold time.
#include "core/linear_rotor.hpp"
#include "core/lj_potential.hpp"
#include "core/rod_potential.hpp"
#include "dmd/terrace_hold.hpp"
#include <cmath>
#include <gtest/gtest.h>
#include <random>

using namespace terrace;
using namespace terrace::dmd;

namespace {

const RodPotential rod{};  // ε 3 kJ/mol, σ 3.035 Å, ζ 1 Å (paper, "Model System")
constexpr double kT = 4.2; // T* = 1.4
const TerraceLevels halfKT = TerraceLevels::uniform(0.5 * kT); // levels ±1.05, ±3.15, ...

double radial(double x) {
    const double s6 = std::pow(rod.sigma / x, 6);
    return 4.0 * rod.epsilon * (s6 * s6 - s6);
}

} // namespace

TEST(TerraceHold, BandEdgesAreTheLevels) {
    // Terrace 0 at kT/2, U in (−1.05, 1.05): the wall between the two levels and the whole tail.
    const TerraceBands b = terraceBands(rod, -1.05, 1.05);
    EXPECT_NEAR(b.bottom, std::pow(2.0, 1.0 / 6.0) * rod.sigma, 1e-14);
    EXPECT_NEAR(radial(b.wall.lo), 1.05, 1e-12);
    EXPECT_NEAR(radial(b.wall.hi), -1.05, 1e-12);
    EXPECT_LT(b.wall.hi, b.bottom);
    EXPECT_NEAR(radial(b.tail.lo), -1.05, 1e-12);
    EXPECT_EQ(b.tail.hi, INFINITY);
    // Checked independently: U(r_e) = −1.05 at r_e = σ (2 / (1 − √0.65))^(1/6) in the tail.
    EXPECT_NEAR(b.tail.lo, rod.sigma * std::pow(2.0 / (1.0 - std::sqrt(0.65)), 1.0 / 6.0), 1e-12);
}

TEST(TerraceHold, TerraceHoldingTheMinimumIsOneBand) {
    // Terrace −1 at kT/2, U in (−3.15, −1.05): its lower level lies below −ε = −3.
    const TerraceBands b = terraceBands(rod, -3.15, -1.05);
    EXPECT_EQ(b.wall.lo, b.tail.lo);
    EXPECT_EQ(b.wall.hi, b.tail.hi);
    EXPECT_NEAR(radial(b.wall.lo), -1.05, 1e-12);
    EXPECT_NEAR(radial(b.wall.hi), -1.05, 1e-12);
    EXPECT_LT(b.wall.lo, b.bottom);
    EXPECT_GT(b.wall.hi, b.bottom);
    // The lowest explicit terrace (no lower level) is the same band.
    const TerraceBands open = terraceBands(rod, -INFINITY, -1.05);
    EXPECT_EQ(open.wall.lo, b.wall.lo);
    EXPECT_EQ(open.wall.hi, b.wall.hi);
}

TEST(TerraceHold, RepulsiveTerracesLieOnTheWallOnly) {
    const TerraceBands b = terraceBands(rod, 1.05, 3.15);
    EXPECT_NEAR(radial(b.wall.lo), 3.15, 1e-11);
    EXPECT_NEAR(radial(b.wall.hi), 1.05, 1e-12);
    EXPECT_GE(b.tail.lo, b.tail.hi); // empty: the tail never rises above 0
    const TerraceBands top = terraceBands(rod, 50.0, INFINITY); // highest explicit terrace
    EXPECT_EQ(top.wall.lo, 0.0);
    EXPECT_NEAR(radial(top.wall.hi), 50.0, 1e-10);
    // A terrace wholly below the minimum holds no distance at all.
    const TerraceBands none = terraceBands(rod, -5.25, -3.15);
    EXPECT_GE(none.wall.lo, none.wall.hi);
    EXPECT_GE(none.tail.lo, none.tail.hi);
}

TEST(TerraceHold, AnalyticLimits) {
    const DistanceBand band{3.5, 4.5};
    // No turning: r_e moves at most at the relative speed, towards the nearer edge.
    EXPECT_NEAR(holdTime(band, 4.2, 2.0, 0.3, 0.0, 1.0), 0.3 / 2.0, 1e-8);
    EXPECT_NEAR(holdTime(band, 3.6, 2.0, 0.3, 0.0, 1.0), 0.1 / 2.0, 1e-8);
    // Turning only, from c = 0: r_e can only fall (c² grows), as ζ Ω² τ², towards lo.
    EXPECT_NEAR(holdTime(band, 4.0, 0.0, 0.0, 3.0, 1.0), std::sqrt(0.5 / 9.0), 1e-8);
    // A sphere (ζ = 0) ignores turning.
    EXPECT_NEAR(holdTime(band, 4.0, 1.0, 0.9, 5.0, 0.0), 0.5, 1e-8);
    // Nothing moves: held for ever; on an edge or outside: not at all.
    EXPECT_EQ(holdTime(band, 4.0, 0.0, 0.5, 0.0, 1.0), INFINITY);
    EXPECT_EQ(holdTime(band, 3.5, 1.0, 0.5, 1.0, 1.0), 0.0);
    EXPECT_EQ(holdTime(band, 4.5, 1.0, 0.5, 1.0, 1.0), 0.0);
    EXPECT_EQ(holdTime(band, 5.0, 1.0, 0.5, 1.0, 1.0), 0.0);
    EXPECT_EQ(holdTime({3.5, INFINITY}, 4.0, 0.0, 0.5, 0.0, 1.0), INFINITY);
}

TEST(TerraceHold, HeadOnApproachWithoutTurningIsExact) {
    // Along the line of centres, without rotation, r_e(τ) = r_e(0) − |v| τ: the bound is the
    // crossing time itself (less the relative 1e-9 kept from the edge).
    const TerraceBands b = terraceBands(rod, -1.05, 1.05);
    const double x0 = 5.2, speed = 1.3;
    const double exact = (x0 - b.tail.lo) / speed;
    EXPECT_NEAR(holdTime(b.tail, x0, speed, 0.4, 0.0, rod.zeta), exact, 1e-8 * exact);
    EXPECT_LE(holdTime(b.tail, x0, speed, 0.4, 0.0, rod.zeta), exact);
}

// Random rod pairs in free flight, hot and cold, near and far: U sampled every 0.02 fs along the
// exact free motion never leaves the terrace before the hold time. The bound is useful, too: for
// most thermal pairs it spans more than the first 0.4 fs, and on average a fair part of the time
// the pair really stays.
TEST(TerraceHold, NoPairLeavesItsTerraceBeforeItsHoldTime) {
    std::mt19937_64 rng(20261122);
    std::normal_distribution<double> gauss(0.0, 1.0);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    const double mass = 18.0, inertia = 1.154;
    auto randomUnit = [&] {
        const Vec3 u(gauss(rng), gauss(rng), gauss(rng));
        return Vec3(u / u.norm());
    };
    int held = 0, trials = 0;
    double ratioSum = 0.0;
    int ratios = 0;
    for (const double temperature : {1.4, 10.0, 50.0})
        for (int trial = 0; trial < 400; ++trial) {
            const double kTrial = temperature * rod.epsilon;
            LinearRotor::State a, b;
            a.s = randomUnit();
            b.s = randomUnit();
            b.r = randomUnit() * (2.9 + 2.6 * uniform(rng));
            a.v = Vec3(gauss(rng), gauss(rng), gauss(rng)) * std::sqrt(kTrial / mass);
            b.v = Vec3(gauss(rng), gauss(rng), gauss(rng)) * std::sqrt(kTrial / mass);
            a.w = randomUnit().cross(a.s) * gauss(rng) * std::sqrt(2.0 * kTrial / inertia);
            b.w = randomUnit().cross(b.s) * gauss(rng) * std::sqrt(2.0 * kTrial / inertia);
            auto energyAt = [&](double t) {
                LinearRotor::State p = a, q = b;
                const BodyParams body{mass, Vec3(inertia, inertia, 0.0)};
                freeMove<LinearRotor>(p, body, t);
                freeMove<LinearRotor>(q, body, t);
                return rod.energy(p.r - q.r, p.s, q.s);
            };
            const double U0 = energyAt(0.0);
            if (U0 > 200.0) continue; // deep overlap: not a state a simulation reaches
            const int n = halfKT.terraceOf(U0);
            const double lower = halfKT.lower(n), upper = halfKT.upper(n);
            const TerraceBands bands = terraceBands(rod, lower, upper);
            const double c = a.s.dot(b.s);
            const double x = rod.effectiveDistance((a.r - b.r).norm(), c);
            const double hold =
                holdTime(x <= bands.bottom ? bands.wall : bands.tail, x, (a.v - b.v).norm(),
                         std::abs(c), a.w.norm() + b.w.norm(), rod.zeta);
            ++trials;
            // Brute force over [0, min(hold, 1 ps)) and on to the first exit (for the ratio).
            constexpr double dt = 2e-4; // 0.02 fs
            const double limit = 10.0;  // 1 ps
            double exit = INFINITY;
            for (double t = dt; t < limit; t += dt) {
                const double U = energyAt(t);
                if (U <= lower || U >= upper) {
                    exit = t;
                    break;
                }
            }
            ASSERT_GE(exit, hold) << "T* " << temperature << " trial " << trial << " U0 " << U0
                                  << " terrace " << n;
            if (temperature == 1.4 && hold > 0.004) ++held;
            if (std::isfinite(exit)) ratioSum += hold / exit, ++ratios;
        }
    EXPECT_GT(held, 300) << "of " << trials; // thermal pairs: most held for > 0.4 fs
    EXPECT_GT(ratioSum / ratios, 0.2);
}
