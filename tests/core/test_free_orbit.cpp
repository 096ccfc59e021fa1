// FreeOrbit (core/free_orbit.hpp) against freeMove from the same State: the orbit is the kind's
// own free rotation prepared once, so the two must agree to round-off at every τ, for every kind.
#include "core/asymmetric_top.hpp"
#include "core/free_orbit.hpp"
#include "core/symmetric_top.hpp"
#include <bit>
#include <cmath>
#include <cstdint>
#include <gtest/gtest.h>
#include <limits>
#include <random>

namespace test_free_orbit {

namespace {

using namespace terrace;

// The linear rotor's orbit evaluates freeRotate's expression without its renormalisation (the
// rotated axis has unit length to a few ulp): differences of a few ulp per component.
constexpr double roundoffTol = 8.0 * std::numeric_limits<double>::epsilon();
// sinCos's series against the library: about an ulp of values ≤ 1.
constexpr double sinCosTol = 2.5e-16;
// A re-based orbit turns by τ from its own start: the angle's round-off grows with |ω|τ.
constexpr double angleRoundoffPerRadian = 1e-15;
// An angle summed over 10⁵ flights, |ω|t ~ 1.4e5 rad, carries ~3e-11 of round-off.
constexpr double summedAngleTol = 1e-9;

Vec3 randomUnit(std::mt19937_64& rng) {
    std::normal_distribution<double> g;
    const Vec3 v(g(rng), g(rng), g(rng));
    return v / v.norm();
}

const double taus[] = {0.0, 1e-9, 0.013, 0.04, -0.02, 0.7, 35.0};

/// A rotor with a random axis spinning at `speed` (rad per time unit) about a random ω ⟂ s.
LinearRotor::State spinningRotor(std::mt19937_64& rng, double speed) {
    LinearRotor::State b;
    b.s = randomUnit(rng);
    const Vec3 u = randomUnit(rng);
    b.w = speed * (u - u.dot(b.s) * b.s).normalized();
    return b;
}

TEST(FreeOrbit, LinearRotorMatchesFreeMove) {
    std::mt19937_64 rng(11);
    const BodyParams p{18.0, Vec3(1.154, 1.154, 0.0)};
    for (int k = 0; k < 50; ++k) {
        LinearRotor::State b;
        b.s = randomUnit(rng);
        const Vec3 u = randomUnit(rng);
        b.w = 25.0 * (u - u.dot(b.s) * b.s); // ω ⟂ s, a few rad per 100 fs
        const FreeOrbit<LinearRotor> orbit(b, p);
        for (double tau : taus) {
            LinearRotor::State moved = b;
            freeMove<LinearRotor>(moved, p, tau);
            const auto a = orbit.at(tau);
            EXPECT_LE((a.axis - LinearRotor::axis(moved)).norm(), roundoffTol) << tau;
            EXPECT_LE((a.w - LinearRotor::angularVelocity(moved, p)).norm(), roundoffTol);
        }
    }
}

TEST(FreeOrbit, LinearRotorAtRest) {
    const BodyParams p{18.0, Vec3(1.154, 1.154, 0.0)};
    LinearRotor::State b;
    b.s = Vec3(0.6, 0.0, 0.8);
    const auto a = FreeOrbit<LinearRotor>(b, p).at(3.0);
    EXPECT_EQ(a.axis, b.s);
    EXPECT_EQ(a.w, Vec3::Zero());
}

TEST(FreeOrbit, SphereDoesNotTurn) {
    const BodyParams p{18.0, Vec3::Zero()};
    const auto a = FreeOrbit<Sphere>(Sphere::State{}, p).at(2.0);
    EXPECT_EQ(a.axis, Vec3::UnitZ());
    EXPECT_EQ(a.w, Vec3::Zero());
}

template <class K> void expectTopMatchesFreeMove(const BodyParams& p) {
    std::mt19937_64 rng(5);
    for (int k = 0; k < 10; ++k) {
        typename K::State b;
        b.A = rotationMatrix(randomUnit(rng), 2.0 * k + 0.3);
        b.L = 4.0 * randomUnit(rng);
        const FreeOrbit<K> orbit(b, p);
        for (double tau : taus) {
            typename K::State moved = b;
            freeMove<K>(moved, p, tau);
            const auto a = orbit.at(tau);
            EXPECT_LE((a.axis - K::axis(moved)).norm(), roundoffTol) << tau;
            EXPECT_LE((a.w - K::angularVelocity(moved, p)).norm(), roundoffTol) << tau;
            // the whole frame, which a frame potential reads (core/body_orientation.hpp)
            EXPECT_LE((a.frame - K::frame(moved)).norm(), roundoffTol) << tau;
        }
    }
}

TEST(FreeOrbit, SymmetricTopMatchesFreeMove) {
    expectTopMatchesFreeMove<SymmetricTop>({18.0, Vec3(1.2, 1.2, 0.4)});
}

TEST(FreeOrbit, AsymmetricTopMatchesFreeMove) {
    expectTopMatchesFreeMove<AsymmetricTop>({18.0, Vec3(0.6, 1.2, 1.7)});
}

// from(τ₀) is the same orbit re-based: from(τ₀).at(τ) = at(τ₀ + τ), for every kind, up to the
// rounding of the angle turned (ε per radian: at(τ₀ + τ) rounds τ₀ + τ, from(τ₀) does not).
template <class K> void expectRebasedOrbitAgrees(const typename K::State& b, const BodyParams& p) {
    const FreeOrbit<K> orbit(b, p);
    for (double tau0 : {0.0, 0.01, 0.3, 4.7, -1.1}) // 0.01: shifted, not turned
        for (double tau : {0.0, 0.004, 0.04, 0.9}) {
            const auto direct = orbit.at(tau0 + tau), rebased = orbit.from(tau0).at(tau);
            const double angle = direct.w.norm() * (std::abs(tau0) + std::abs(tau));
            EXPECT_LE((direct.axis - rebased.axis).norm(), roundoffTol * (4.0 + angle))
                << tau0 << " " << tau;
            EXPECT_LE((direct.w - rebased.w).norm(), 4.0 * roundoffTol * (1.0 + direct.w.norm()));
        }
}

TEST(FreeOrbit, RebasedOrbitIsTheSameOrbit) {
    std::mt19937_64 rng(3);
    LinearRotor::State rod;
    rod.s = randomUnit(rng);
    const Vec3 u = randomUnit(rng);
    rod.w = 25.0 * (u - u.dot(rod.s) * rod.s);
    expectRebasedOrbitAgrees<LinearRotor>(rod, {18.0, Vec3(1.154, 1.154, 0.0)});
    SymmetricTop::State top;
    top.A = rotationMatrix(randomUnit(rng), 0.7);
    top.L = 4.0 * randomUnit(rng);
    expectRebasedOrbitAgrees<SymmetricTop>(top, {18.0, Vec3(1.2, 1.2, 0.4)});
    expectRebasedOrbitAgrees<Sphere>(Sphere::State{}, {18.0, Vec3::Zero()});
}

// The series branch of sinCos agrees with the library to round-off, on both sides of its limit.
TEST(SmallAngle, SinCosAgreesWithTheLibrary) {
    for (int k = -4000; k <= 4000; ++k) {
        const double x = 1.2 * k / 4000.0; // beyond π/4 the library itself answers
        const SinCos sc = sinCos(x);
        EXPECT_NEAR(sc.sin, std::sin(x), sinCosTol) << x;
        EXPECT_NEAR(sc.cos, std::cos(x), sinCosTol) << x;
    }
    EXPECT_EQ(sinCos(0.0).sin, 0.0);
    EXPECT_EQ(sinCos(0.0).cos, 1.0);
}

// The packed pair gives each angle exactly what sinCos gives it, inside and beyond the series.
TEST(SmallAngle, PairIsTwoSingles) {
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> angle(-1.2, 1.2);
    for (int k = 0; k < 2000; ++k) {
        const double a = angle(rng), b = k % 7 == 0 ? 0.0 : angle(rng);
        const auto pair = sinCosPair(a, b);
        EXPECT_EQ(pair[0].sin, sinCos(a).sin) << a;
        EXPECT_EQ(pair[0].cos, sinCos(a).cos) << a;
        EXPECT_EQ(pair[1].sin, sinCos(b).sin) << b;
        EXPECT_EQ(pair[1].cos, sinCos(b).cos) << b;
    }
}

// A pair's two attitudes at τ are those of the two orbits taken one at a time, rotors at rest and
// re-based orbits included.
TEST(FreeOrbit, PairAttitudesAreTheSingleAttitudes) {
    std::mt19937_64 rng(19);
    const BodyParams p{18.0, Vec3(1.154, 1.154, 0.0)};
    auto rotor = [&](double speed) { return FreeOrbit<LinearRotor>(spinningRotor(rng, speed), p); };
    for (int k = 0; k < 50; ++k) {
        const FreeOrbit<LinearRotor> i = rotor(k % 5 == 0 ? 0.0 : 3.0 + k),
                                     j = rotor(2.0 + 0.5 * k).from(0.01 * k);
        for (double tau : taus) {
            const auto both = attitudesAt(i, j, tau);
            EXPECT_EQ(both[0].axis, i.at(tau).axis) << tau;
            EXPECT_EQ(both[0].w, i.at(tau).w);
            EXPECT_EQ(both[1].axis, j.at(tau).axis) << tau;
            EXPECT_EQ(both[1].w, j.at(tau).w);
        }
    }
}

// startOf(τ₀), the attitude the DMD hold screen takes for a partner, is bit for bit what the
// search's orbit from(τ₀) gives at its start, for small shifts (kept as a shift), large ones (a
// turned orbit), orbits shifted before, and rotors at rest: a screened and an unscreened run must
// see the same attitudes.
TEST(FreeOrbit, StartOfIsTheShiftedOrbitsStart) {
    std::mt19937_64 rng(23);
    const BodyParams p{18.0, Vec3(1.154, 1.154, 0.0)};
    for (int k = 0; k < 60; ++k) {
        const LinearRotor::State b = spinningRotor(rng, k % 6 == 0 ? 0.0 : 1.0 + k);
        const FreeOrbit<LinearRotor> orbit =
            FreeOrbit<LinearRotor>(b, p).from(k % 3 == 0 ? 0.0 : 0.003 * k);
        for (double tau0 : {0.0, 1e-9, 0.004, 0.02, 0.3, -0.05, 2.5}) {
            const auto direct = orbit.startOf(tau0);
            const auto shifted = orbit.from(tau0).at(0.0);
            for (int a = 0; a < 3; ++a) {
                EXPECT_EQ(std::bit_cast<std::uint64_t>(direct.axis[a]),
                          std::bit_cast<std::uint64_t>(shifted.axis[a]))
                    << k << " " << tau0;
                EXPECT_EQ(std::bit_cast<std::uint64_t>(direct.w[a]),
                          std::bit_cast<std::uint64_t>(shifted.w[a]))
                    << k << " " << tau0;
            }
        }
    }
}

// advancedBy(τ₀), how the DMD engine brings a rotor in free flight to now: its axis is where
// freeMove takes the state, and the advanced orbit is the orbit seen from τ₀. Over 10⁵ flights of
// random length (a body sampled every few fs for ~100 ps with no collision) the axis stays a unit
// vector and on the exact rotation, to round-off that does not build up.
TEST(FreeOrbit, AdvancedOrbitFollowsFreeMove) {
    std::mt19937_64 rng(31);
    const BodyParams p{18.0, Vec3(1.154, 1.154, 0.0)};
    for (int k = 0; k < 40; ++k) {
        const LinearRotor::State b = spinningRotor(rng, k % 8 == 0 ? 0.0 : 0.5 * k);
        const FreeOrbit<LinearRotor> orbit(b, p);
        for (double tau0 : {0.0, 1e-9, 0.004, 0.09, 0.3, -0.05, 2.5}) {
            LinearRotor::State moved = b;
            freeMove<LinearRotor>(moved, p, tau0);
            const FreeOrbit<LinearRotor> advanced = orbit.advancedBy(tau0);
            EXPECT_LE((advanced.axis() - moved.s).norm(), roundoffTol) << k << " " << tau0;
            for (double tau : taus)
                EXPECT_LE((advanced.at(tau).axis - orbit.at(tau0 + tau).axis).norm(),
                          4.0 * roundoffTol + angleRoundoffPerRadian * std::abs(b.w.norm() * tau))
                    << k << " " << tau0 << " " << tau;
        }
    }
    const LinearRotor::State b = spinningRotor(rng, 30.0);
    FreeOrbit<LinearRotor> orbit(b, p);
    std::uniform_real_distribution<double> flight(0.0, 0.09);
    double t = 0.0;
    for (int k = 0; k < 100000; ++k) {
        const double dt = flight(rng);
        orbit = orbit.advancedBy(dt);
        t += dt;
    }
    LinearRotor::State exact = b;
    freeMove<LinearRotor>(exact, p, t); // one rotation by the whole angle, ~1.4e5 rad
    EXPECT_NEAR(orbit.axis().norm(), 1.0, 4.0 * std::numeric_limits<double>::epsilon());
    // The angle itself is summed over 10⁵ flights, and |ω|t ~ 1.4e5 rad carries ~3e-11 of
    // round-off: the axes agree to that, not to a few ulp.
    EXPECT_LE((orbit.axis() - exact.s).norm(), summedAngleTol);
}

// The DMD engine keeps no orbit for a rotor (dmd/body_clocks.hpp keepsOrbit): at every flight it
// builds one from the state the last flight left (its s renormalised, ω̂ × s rebuilt from it, |ω|
// as its book holds it) instead of carrying the orbit along as above. Over 10⁵ flights the axis
// stays a unit vector perpendicular to ω and on the exact rotation, as the carried orbit does.
TEST(FreeOrbit, ARotorFlownFromItsStateAtEveryFlightStaysOnItsExactRotation) {
    std::mt19937_64 rng(37);
    const BodyParams p{18.0, Vec3(1.154, 1.154, 0.0)};
    LinearRotor::State flown = spinningRotor(rng, 30.0);
    const LinearRotor::State start = flown;
    const double speed = flown.w.norm();
    std::uniform_real_distribution<double> flight(0.0, 0.09);
    double t = 0.0;
    for (int k = 0; k < 100000; ++k) {
        const double dt = flight(rng);
        flown.s = FreeOrbit<LinearRotor>(flown, speed).advancedBy(dt).axis();
        t += dt;
    }
    LinearRotor::State exact = start;
    freeMove<LinearRotor>(exact, p, t); // one rotation by the whole angle, ~1.4e5 rad
    EXPECT_NEAR(flown.s.norm(), 1.0, 4.0 * std::numeric_limits<double>::epsilon());
    EXPECT_LE(std::abs(flown.s.dot(flown.w)) / speed, 8.0 * std::numeric_limits<double>::epsilon());
    EXPECT_LE((flown.s - exact.s).norm(), summedAngleTol);
}

} // namespace

} // namespace test_free_orbit
