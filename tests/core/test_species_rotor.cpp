// Rods among spheres as one body kind (core/species_rotor.hpp): a body of a rod species moves
// exactly as the paper's linear rotor with its species' inertia; a body of a sphere species never
// turns, takes no angular momentum and no spin from the bath, and has no rotational degrees of
// freedom, so the temperature counts 3 per sphere and 5 per rod; the free orbit the DMD search
// samples carries the species that RodMixture reads.
#include "core/body_orientation.hpp"
#include "core/free_orbit.hpp"
#include "core/initial_state.hpp"
#include "core/rod_mixture.hpp"
#include "core/species_rotor.hpp"
#include "core/system.hpp"
#include "tests/core/pair_checks.hpp"
#include <gtest/gtest.h>
#include <random>

namespace test_species_rotor {

using namespace terrace;
using pairchecks::randomUnit;

namespace {

constexpr double rodInertia = 1.154;                // g/mol Å², the paper's rods
constexpr double rodMass = 18.0, sphereMass = 40.0; // g/mol

/// Species 0 rods, species 1 spheres.
BodyParams rodsAndSpheres() {
    BodyParams p;
    p.mass = rodMass;
    p.speciesMass = {rodMass, sphereMass};
    p.speciesInertia = {rodInertia, 0.0};
    return p;
}

/// The same body as the paper's rotor sees it, with the rod species' inertia.
BodyParams rotorParams() {
    return BodyParams{rodMass, Vec3(rodInertia, rodInertia, 0.0)};
}

SpeciesRotor::State body(std::mt19937_64& rng, int species, double spin) {
    SpeciesRotor::State b;
    b.species = species;
    b.r = 10.0 * randomUnit(rng);
    b.v = randomUnit(rng);
    b.s = randomUnit(rng);
    const Vec3 u = randomUnit(rng);
    b.w = spin * (u - u.dot(b.s) * b.s).normalized();
    return b;
}

LinearRotor::State asRotor(const SpeciesRotor::State& b) {
    return static_cast<const LinearRotor::State&>(b);
}

bool sameBits(const Vec3& a, const Vec3& b) {
    return a.x() == b.x() && a.y() == b.y() && a.z() == b.z();
}

} // namespace

TEST(SpeciesRotor, ARodMovesAsThePapersRotorBitForBit) {
    std::mt19937_64 rng(3);
    const BodyParams p = rodsAndSpheres(), q = rotorParams();
    for (int k = 0; k < 20; ++k) {
        SpeciesRotor::State b = body(rng, 0, 5.0 + k);
        LinearRotor::State r = asRotor(b);
        EXPECT_EQ(SpeciesRotor::mass(b, p), rodMass);
        EXPECT_EQ(bodyRotationalDof<SpeciesRotor>(b, p), 2);
        EXPECT_EQ(SpeciesRotor::rotationalKinetic(b, p), LinearRotor::rotationalKinetic(r, q));
        EXPECT_TRUE(
            sameBits(SpeciesRotor::angularMomentum(b, p), LinearRotor::angularMomentum(r, q)));
        const Vec3 a = randomUnit(rng), c = randomUnit(rng);
        EXPECT_EQ(SpeciesRotor::inverseInertia(b, p, a, c),
                  LinearRotor::inverseInertia(r, q, a, c));
        SpeciesRotor::addAngularMomentum(b, p, 0.3 * a);
        LinearRotor::addAngularMomentum(r, q, 0.3 * a);
        freeMove<SpeciesRotor>(b, p, 0.37);
        freeMove<LinearRotor>(r, q, 0.37);
        EXPECT_TRUE(sameBits(b.s, r.s) && sameBits(b.w, r.w) && sameBits(b.r, r.r));
        EXPECT_EQ(b.species, 0);
    }
}

TEST(SpeciesRotor, ASphereNeverTurnsAndTakesNoAngularMomentum) {
    std::mt19937_64 rng(5);
    const BodyParams p = rodsAndSpheres();
    SpeciesRotor::State b = body(rng, 1, 0.0);
    const Vec3 s0 = b.s;
    EXPECT_EQ(SpeciesRotor::mass(b, p), sphereMass);
    EXPECT_EQ(bodyRotationalDof<SpeciesRotor>(b, p), 0);
    const Vec3 tau = randomUnit(rng);
    EXPECT_EQ(SpeciesRotor::inverseInertia(b, p, tau, tau), 0.0); // infinite inertia
    SpeciesRotor::addAngularMomentum(b, p, 4.0 * tau);
    EXPECT_EQ(b.w, Vec3::Zero());
    freeMove<SpeciesRotor>(b, p, 12.5);
    EXPECT_TRUE(sameBits(b.s, s0));
    // As the DMD engine brings it to now, flight after flight: to the bit, not renormalised.
    FreeOrbit<SpeciesRotor> orbit(b, b.w.norm());
    for (int k = 0; k < 100; ++k)
        orbit = orbit.advancedBy(0.37);
    EXPECT_TRUE(sameBits(orbit.axis(), s0));
    EXPECT_EQ(SpeciesRotor::rotationalKinetic(b, p), 0.0);
    EXPECT_EQ(SpeciesRotor::angularMomentum(b, p), Vec3::Zero());
}

TEST(SpeciesRotor, TheOrbitCarriesTheSpeciesAndIsTheRotorsOrbit) {
    std::mt19937_64 rng(7);
    const BodyParams p = rodsAndSpheres(), q = rotorParams();
    for (int k = 0; k < 20; ++k) {
        const int species = k % 2;
        const SpeciesRotor::State b = body(rng, species, species == 0 ? 3.0 + k : 0.0);
        const FreeOrbit<SpeciesRotor> orbit(b, p);
        const FreeOrbit<LinearRotor> rotor(asRotor(b), q);
        for (double tau : {0.0, 0.013, 0.7, 35.0}) {
            const auto a = orbit.at(tau);
            EXPECT_TRUE(sameBits(a.axis, rotor.at(tau).axis));
            EXPECT_TRUE(sameBits(a.w, rotor.at(tau).w));
            EXPECT_EQ(a.species, species);
            const SpeciesAxis o = orientationOf<RodMixture>(a);
            EXPECT_EQ(o.species, species);
            EXPECT_TRUE(sameBits(o.axis, a.axis));
            SpeciesRotor::State moved = b;
            freeMove<SpeciesRotor>(moved, p, tau);
            EXPECT_LE((a.axis - moved.s).norm(), 1e-14);
        }
        // The pair's packed sampling gives each body's own attitude.
        const FreeOrbit<SpeciesRotor> other(body(rng, 1 - species, 2.0), p);
        const auto both = attitudesAt(orbit.from(0.02), other, 0.01);
        EXPECT_EQ(both[0].species, species);
        EXPECT_EQ(both[1].species, 1 - species);
        EXPECT_LE((both[0].axis - orbit.at(0.03).axis).norm(), 1e-14);
        // The orbit a DMD body keeps from its book's |ω| is the same orbit.
        EXPECT_TRUE(
            sameBits(FreeOrbit<SpeciesRotor>(b, b.w.norm()).at(0.2).axis, orbit.at(0.2).axis));
    }
}

TEST(SpeciesRotor, TheTemperatureCountsFivePerRodAndThreePerSphere) {
    std::mt19937_64 rng(13);
    System<SpeciesRotor, RodMixture> sys;
    sys.body = rodsAndSpheres();
    sys.box = PeriodicBox{40.0};
    sys.kT = 2.5;
    const int rods = 300, spheres = 500;
    for (int i = 0; i < rods + spheres; ++i) {
        SpeciesRotor::State b = body(rng, i < rods ? 0 : 1, 0.0);
        b.v.setZero();
        sys.bodies.push_back(b);
    }
    EXPECT_EQ(totalRotationalDof(sys), 2 * rods);
    EXPECT_EQ(degreesOfFreedom(sys), 3 * (rods + spheres) + 2 * rods - 3);
    // The bath's draw: spheres get no spin, rods ω ⟂ s with ⟨½Iω²⟩ = kT (two quadratic terms).
    double rotational = 0.0;
    for (auto& b : sys.bodies) {
        detail::thermalise<SpeciesRotor>(b, sys.body, sys.kT, rng);
        if (b.species == 1) {
            EXPECT_EQ(b.w, Vec3::Zero());
        } else {
            EXPECT_NEAR(b.w.dot(b.s), 0.0, 1e-12 * b.w.norm());
            rotational += SpeciesRotor::rotationalKinetic(b, sys.body);
        }
    }
    // ½Iω² over two components is Gamma(1, kT): standard error kT/√rods per rod.
    EXPECT_NEAR(rotational / rods / sys.kT, 1.0, 4.0 / std::sqrt(double(rods)));
    // The rescale aims at ½ f kT with f counted here by hand: 3 per body, 2 more per rod, less 3.
    rescaleToTemperature(sys, sys.kT);
    const double f = 3.0 * (rods + spheres) + 2.0 * rods - 3.0;
    EXPECT_NEAR(totalKinetic(sys) / (0.5 * f * sys.kT), 1.0, 1e-14);
}

} // namespace test_species_rotor
