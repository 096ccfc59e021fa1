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

namespace test_terrace_hold {

using namespace terrace;
using namespace terrace::dmd;

namespace {

const RodPotential rod{};  // ε 3 kJ/mol, σ 3.035 Å, ζ 1 Å (paper, "Model System")
constexpr double kT = 4.2; // T* = 1.4
const TerraceLevels halfKT = TerraceLevels::uniform(0.5 * kT); // levels ±1.05, ±3.15, ...

// The bands' edges are roots of U(r_e) = level: U there is exact to its round-off, which grows
// with the steepness of the wall the level lies on.
constexpr double levelTol = 1e-12;      // kJ/mol, on the tail and the foot of the wall
constexpr double steepLevelTol = 1e-11; // kJ/mol, at 3.15 kJ/mol up the wall
constexpr double capLevelTol = 1e-10;   // kJ/mol, at 50 kJ/mol up the wall
constexpr double distanceTol = 1e-12;   // Å: a root against its closed form, to round-off
constexpr double minimumTol = 1e-14;    // Å: r_min = 2^{1/6}σ, a few ulp

double radial(double x) {
    const double s6 = std::pow(rod.sigma / x, 6);
    return 4.0 * rod.epsilon * (s6 * s6 - s6);
}

} // namespace

TEST(TerraceHold, BandEdgesAreTheLevels) {
    // Terrace 0 at kT/2, U in (−1.05, 1.05): the wall between the two levels and the whole tail.
    const TerraceBands b = terraceBands(rod, -1.05, 1.05);
    EXPECT_NEAR(b.bottom, std::pow(2.0, 1.0 / 6.0) * rod.sigma, minimumTol);
    EXPECT_NEAR(radial(b.wall.lo), 1.05, levelTol);
    EXPECT_NEAR(radial(b.wall.hi), -1.05, levelTol);
    EXPECT_LT(b.wall.hi, b.bottom);
    EXPECT_NEAR(radial(b.tail.lo), -1.05, levelTol);
    EXPECT_EQ(b.tail.hi, INFINITY);
    // Checked independently: U(r_e) = −1.05 at r_e = σ (2 / (1 − √0.65))^(1/6) in the tail.
    EXPECT_NEAR(b.tail.lo, rod.sigma * std::pow(2.0 / (1.0 - std::sqrt(0.65)), 1.0 / 6.0),
                distanceTol);
}

TEST(TerraceHold, TerraceHoldingTheMinimumIsOneBand) {
    // Terrace −1 at kT/2, U in (−3.15, −1.05): its lower level lies below −ε = −3.
    const TerraceBands b = terraceBands(rod, -3.15, -1.05);
    EXPECT_EQ(b.wall.lo, b.tail.lo);
    EXPECT_EQ(b.wall.hi, b.tail.hi);
    EXPECT_NEAR(radial(b.wall.lo), -1.05, levelTol);
    EXPECT_NEAR(radial(b.wall.hi), -1.05, levelTol);
    EXPECT_LT(b.wall.lo, b.bottom);
    EXPECT_GT(b.wall.hi, b.bottom);
    // The lowest explicit terrace (no lower level) is the same band.
    const TerraceBands open = terraceBands(rod, -INFINITY, -1.05);
    EXPECT_EQ(open.wall.lo, b.wall.lo);
    EXPECT_EQ(open.wall.hi, b.wall.hi);
}

TEST(TerraceHold, RepulsiveTerracesLieOnTheWallOnly) {
    const TerraceBands b = terraceBands(rod, 1.05, 3.15);
    EXPECT_NEAR(radial(b.wall.lo), 3.15, steepLevelTol);
    EXPECT_NEAR(radial(b.wall.hi), 1.05, levelTol);
    EXPECT_GE(b.tail.lo, b.tail.hi); // empty: the tail never rises above 0
    const TerraceBands top = terraceBands(rod, 50.0, INFINITY); // highest explicit terrace
    EXPECT_EQ(top.wall.lo, 0.0);
    EXPECT_NEAR(radial(top.wall.hi), 50.0, capLevelTol);
    // A terrace wholly below the minimum holds no distance at all.
    const TerraceBands none = terraceBands(rod, -5.25, -3.15);
    EXPECT_GE(none.wall.lo, none.wall.hi);
    EXPECT_GE(none.tail.lo, none.tail.hi);
}

namespace {

PairMotion still(double r, double c) {
    PairMotion m;
    m.r = r;
    m.c = c;
    return m;
}

} // namespace

TEST(TerraceHold, CentresApproachingHeadOn) {
    // r(τ) = r₀ − |v|τ along the line of centres: the lower envelope is exact.
    PairMotion m = still(4.2, 0.0);
    m.rRate = -2.0;
    m.speedSquared = 4.0;
    const BandHold sphere({3.5, 4.5}, m, 0.0); // ζ = 0: r_e = r
    EXPECT_TRUE(sphere.through(0.3499));
    EXPECT_FALSE(sphere.through(0.3501));
    // A rod pair at fixed alignment c = 0.4: r_e = r + ζ(½ − 0.16), the same crossing time.
    m.c = 0.4;
    const TerraceBands b = terraceBands(rod, -1.05, 1.05);
    m.r = 5.2;
    const double x = rod.effectiveDistance(m.r, m.c);
    const double exact = (x - b.tail.lo) / 2.0;
    const BandHold pair(b.tail, m, rod.zeta);
    EXPECT_TRUE(pair.through(exact * (1.0 - 1e-8)));
    EXPECT_FALSE(pair.through(exact * (1.0 + 1e-8)));
}

TEST(TerraceHold, CentresPassingSideways) {
    // v ⟂ r₀: r(τ) = √(r₀² + v²τ²) ≤ r₀ + v²τ²/(2r₀), which reaches 4.5 at τ = 2 (the true
    // distance does at τ ≈ 2.06); the lower envelope stays at r₀.
    PairMotion m = still(4.0, 0.0);
    m.speedSquared = 1.0;
    const BandHold sphere({3.5, 4.5}, m, 0.0);
    EXPECT_TRUE(sphere.through(1.999));
    EXPECT_FALSE(sphere.through(2.001));
}

TEST(TerraceHold, TurningAxes) {
    // Centres at rest, c₀ = 0 and ċ₀ = 0, Ω = 3: |c| ≤ min(Ωτ, ½Ω²τ²), and r_e = 4.5 − c² falls
    // to 3.6 once c² = 0.9, i.e. at 4.5τ² = √0.9 (τ ≈ 0.4591).
    PairMotion m = still(4.0, 0.0);
    m.turn = 3.0;
    m.turnCurvature = 9.0;
    const BandHold rods({3.6, 4.6}, m, 1.0);
    const double t = std::sqrt(std::sqrt(0.9) / 4.5);
    EXPECT_TRUE(rods.through(t * (1.0 - 1e-6)));
    EXPECT_FALSE(rods.through(t * (1.0 + 1e-6)));
    // Without the curvature bound (a top), only |c| ≤ Ωτ: c² = 0.9 at τ = √0.9 / 3.
    m.turnCurvature = INFINITY;
    const BandHold tops({3.6, 4.6}, m, 1.0);
    EXPECT_TRUE(tops.through(std::sqrt(0.9) / 3.0 * (1.0 - 1e-6)));
    EXPECT_FALSE(tops.through(std::sqrt(0.9) / 3.0 * (1.0 + 1e-6)));
    // A sphere (ζ = 0) ignores turning.
    EXPECT_TRUE(BandHold({3.6, 4.6}, m, 0.0).through(1e6));
}

// The sign of ċ₀ counts. A rod pair at r = 4 with c₀ = ±0.5 sits at r_e = 4.25, 0.01 Å above the
// band's lower edge, which it nears only as |c| grows. Turning towards alignment at ċ = 1
// (Ω = 1, |c̈| ≤ 1) it may reach the edge after ~0.01. Turning away, |c| first falls: its bound
// can pass 0.5 again only on the far side of c = 0, no sooner than Ωτ = 1 allows, so the pair is
// held until then (the symmetric bound |c₀| + |ċ₀|τ + ½Kτ² let it go after ~0.01 as well).
TEST(TerraceHold, AnAlignmentTurningAwayFromTheEdgeIsHeldLonger) {
    for (double c0 : {0.5, -0.5}) {
        PairMotion m = still(4.0, c0);
        m.turn = 1.0;
        m.turnCurvature = 1.0;
        m.cRate = -c0 / std::abs(c0); // |c| shrinks
        const BandHold away({4.24, 5.0}, m, 1.0);
        EXPECT_TRUE(away.through(0.9)) << c0;
        EXPECT_FALSE(away.through(1.1)) << c0;
        m.cRate = -m.cRate; // |c| grows
        const BandHold towards({4.24, 5.0}, m, 1.0);
        EXPECT_TRUE(towards.through(0.005)) << c0;
        EXPECT_FALSE(towards.through(0.02)) << c0;
    }
}

// At an edge exactly (r_e equal to the band's edge as kept, after its margin) the packed rungs
// answer as the scalar ones: "not held", strictly. The band's edge is stepped ulp by ulp across
// r_e, so that some step puts them level whatever the margin's rounding.
TEST(TerraceHold, TwoRungsAtOnceAnswerAsEachAloneOnAnEdge) {
    for (int side = 0; side < 2; ++side) {
        const double r = 4.0, nominal = r - 4e-9 * (side == 0 ? 1.0 : -1.0);
        double edge = nominal;
        for (int k = 0; k < 16; ++k)
            edge = std::nextafter(edge, -INFINITY);
        int flips = 0;
        bool previous = false;
        for (int k = 0; k < 32; ++k, edge = std::nextafter(edge, INFINITY)) {
            const DistanceBand band = side == 0 ? DistanceBand{edge, 5.0} : DistanceBand{3.0, edge};
            const BandHold hold(band, still(r, 0.0), 0.0);
            const bool held = hold.through(0.0);
            EXPECT_EQ(hold.throughBoth(0.0, 0.0), 2 * int(held)) << side << " " << k;
            flips += k > 0 && held != previous;
            previous = held;
        }
        EXPECT_EQ(flips, 1) << side; // the edge was crossed, once
    }
}

TEST(TerraceHold, LadderOfHorizons) {
    PairMotion m = still(4.2, 0.3);
    m.rRate = -1.0;
    m.speedSquared = 1.0;
    const BandHold hold({3.5, 4.5}, m, 0.0); // leaves at τ = 0.7
    EXPECT_EQ(holdTime(hold, 0.04, 0.32), 0.32);
    EXPECT_EQ(holdTime(hold, 0.1, 1.0), 0.4);
    EXPECT_EQ(holdTime(hold, 0.8, 1.6), 0.0);
    // Nothing moves: held up to the last rung; on an edge: not at all.
    EXPECT_EQ(holdTime(BandHold({3.5, 4.5}, still(4.0, 0.5), 1.0), 0.04, 0.32), 0.32);
    EXPECT_EQ(holdTime(BandHold({3.5, 4.5}, still(3.5, 0.0), 0.0), 0.04, 0.32), 0.0);
    EXPECT_EQ(holdTime(BandHold({3.5, 4.5}, still(4.5, 0.0), 0.0), 0.04, 0.32), 0.0);
    EXPECT_EQ(holdTime(BandHold({3.5, 4.5}, still(5.0, 0.0), 0.0), 0.04, 0.32), 0.0);
    EXPECT_GT(holdTime(BandHold({3.5, INFINITY}, still(9.0, 0.0), 0.0), 0.04, 0.32), 0.0);
}

// The packed pair of rungs answers as the two scalar rungs do, for pairs inside, outside and on
// the edges of their band, approaching and receding, with and without a curvature bound, at
// times from 0 to far beyond any hold; and the ladder with an odd number of rungs (the last one
// scalar) counts them all.
TEST(TerraceHold, TwoRungsAtOnceAnswerAsEachAlone) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    long held = 0, total = 0;
    for (int k = 0; k < 20000; ++k) {
        PairMotion m = still(3.0 + 2.0 * u(rng), 2.0 * u(rng) - 1.0);
        m.rRate = 4.0 * u(rng) - 2.0;
        m.speedSquared = m.rRate * m.rRate + 4.0 * u(rng);
        m.cRate = 6.0 * u(rng) - 3.0;
        m.turn = std::abs(m.cRate) + 3.0 * u(rng);
        if (k % 2 == 0) m.turnCurvature = m.turn * m.turn;
        const BandHold hold({3.5, k % 5 == 0 ? double(INFINITY) : 4.5}, m, k % 3 == 0 ? 0.0 : 1.0);
        const double T0 = k % 7 == 0 ? 0.0 : 0.2 * u(rng), T1 = 2.0 * T0 + u(rng) * 0.01;
        const int alone = int(hold.through(T0)) + int(hold.through(T1));
        EXPECT_EQ(hold.throughBoth(T0, T1), alone) << k;
        held += alone;
        total += 2;
        // Rungs first, 2·first, …: five of them up to 16·first, three up to 4·first.
        int five = 0, three = 0;
        for (int rung = 0; rung < 5; ++rung) {
            const int through = hold.through(std::ldexp(0.04, rung));
            five += through;
            if (rung < 3) three += through;
        }
        EXPECT_EQ(holdTime(hold, 0.04, 0.64), five == 0 ? 0.0 : std::ldexp(0.04, five - 1)) << k;
        EXPECT_EQ(holdTime(hold, 0.04, 0.16), three == 0 ? 0.0 : std::ldexp(0.04, three - 1)) << k;
    }
    // Both answers occur often enough to be compared.
    EXPECT_GT(held, total / 10);
    EXPECT_LT(held, total * 9 / 10);
}

// At T = 0 (a pair exactly on r_m has its shell exit at −0) a pair inside its band is held,
// whether or not its alignment has a curvature bound: no 0·∞ may turn the answer into NaN.
TEST(TerraceHold, HeldAtTimeZero) {
    PairMotion m = still(4.0, 0.3);
    m.rRate = -0.5;
    m.speedSquared = 2.0;
    m.cRate = 1.0;
    m.turn = 3.0;
    for (double curvature : {9.0, double(INFINITY)}) {
        m.turnCurvature = curvature;
        for (double zeta : {0.0, 1.0}) {
            const BandHold hold({3.5, 4.5}, m, zeta);
            EXPECT_TRUE(hold.through(0.0)) << curvature << " " << zeta;
            EXPECT_TRUE(hold.through(-0.0)) << curvature << " " << zeta;
            EXPECT_TRUE(hold.through(1e-3)) << curvature << " " << zeta;
        }
    }
}

// Random rod pairs in free flight, hot and cold, near and far: wherever the envelopes say the
// pair stays in its band through T, r_e sampled every 0.02 fs along the exact free motion does,
// and U never leaves the terrace before the hold time. The bound is useful, too: most thermal
// pairs are held through 1 fs, and on average for a fair part of the time they really stay.
TEST(TerraceHold, NoPairLeavesItsTerraceBeforeItsHoldTime) {
    std::mt19937_64 rng(20261122);
    std::normal_distribution<double> gauss(0.0, 1.0);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    const double mass = 18.0, inertia = 1.154;
    const BodyParams body{mass, Vec3(inertia, inertia, 0.0)};
    auto randomUnit = [&] {
        const Vec3 u(gauss(rng), gauss(rng), gauss(rng));
        return Vec3(u / u.norm());
    };
    int held = 0, trials = 0, checked = 0;
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
            auto at = [&](double t) {
                LinearRotor::State p = a, q = b;
                freeMove<LinearRotor>(p, body, t);
                freeMove<LinearRotor>(q, body, t);
                return std::pair{p, q};
            };
            const double U0 = rod.energy(a.r - b.r, a.s, b.s);
            if (U0 > 200.0) continue; // deep overlap: not a state a simulation reaches
            const int n = halfKT.terraceOf(U0);
            const double lower = halfKT.lower(n), upper = halfKT.upper(n);
            const TerraceBands bands = terraceBands(rod, lower, upper);
            PairMotion m;
            const Vec3 rij = a.r - b.r, vij = a.v - b.v;
            m.r = rij.norm();
            m.rRate = rij.dot(vij) / m.r;
            m.speedSquared = vij.squaredNorm();
            m.c = a.s.dot(b.s);
            m.cRate = (a.w - b.w).dot(a.s.cross(b.s));
            m.turn = a.w.norm() + b.w.norm();
            m.turnCurvature = m.turn * m.turn;
            const double x = rod.effectiveDistance(m.r, m.c);
            const DistanceBand& band = x <= bands.bottom ? bands.wall : bands.tail;
            const BandHold envelope(band, m, rod.zeta);
            const double hold = holdTime(envelope, 0.01, 0.32); // 1 fs … 32 fs
            const double probe = 0.5 * uniform(rng);            // one more time, anywhere
            const bool probeHeld = envelope.through(probe);
            ++trials;
            // Brute force on to the first exit, at least through the probe (1 ps at most).
            constexpr double dt = 2e-4; // 0.02 fs
            double exit = INFINITY;
            for (double t = dt; t < 10.0; t += dt) {
                const auto [p, q] = at(t);
                const double U = rod.energy(p.r - q.r, p.s, q.s);
                if (t <= probe && probeHeld) {
                    const double xt = rod.effectiveDistance((p.r - q.r).norm(), p.s.dot(q.s));
                    ASSERT_TRUE(xt > band.lo && xt < band.hi)
                        << "T* " << temperature << " trial " << trial << " r_e " << xt;
                    ++checked;
                }
                if (U <= lower || U >= upper) {
                    exit = t;
                    break;
                }
            }
            ASSERT_GE(exit, hold) << "T* " << temperature << " trial " << trial << " U0 " << U0
                                  << " terrace " << n;
            if (temperature == 1.4 && hold > 0.0) ++held;
            if (std::isfinite(exit)) ratioSum += hold / exit, ++ratios;
        }
    EXPECT_GT(held, 250) << "of 400 at T* = 1.4, " << trials << " in all"; // most held through 1 fs
    EXPECT_GT(checked, 100000);
    EXPECT_GT(ratioSum / ratios, 0.2);
}

} // namespace test_terrace_hold
