// Rods among spheres (core/species_rotor.hpp, core/rod_mixture.hpp) in both engines. DMD: energy
// and momentum to round-off, no missed event (the terraced energy equals the one recomputed from
// each pair's U at every sample), bodies that keep their species, spheres that never turn while
// the rods do. SMD: the energy error ∝ dt², momentum to round-off, spheres without spin. With
// small terraces, DMD's configurational U and pressure agree with SMD's within their error bars,
// and under CSVR each part of the kinetic energy comes to its share of kT
// (test_rod_mixture_agreement.cpp).
#include "dmd/testing.hpp"
#include "tests/dmd/rod_mixture_engines.hpp"
#include <array>
#include <cstdio>
#include <gtest/gtest.h>
#include <utility>

namespace test_rod_mixture_engines {

using terrace::dmd::testing::Probe;
using namespace terrace;
using namespace terrace::rod_mixture_tests;

namespace {

Scene scene(double dVInKT, double dtFs = 0.9) {
    return sceneFromJson(rodsAmongSpheres(256, 0.5, 1.4, dVInKT, dtFs), "rods-among-spheres");
}

/// Every sphere's ω is zero and its axis where it started, to the bit (the analysis tells the
/// species that turn by their axes changing at all); at least one rod has turned.
void expectSpheresStillAndRodsTurning(const RodSystem& start, const RodSystem& end) {
    int turned = 0;
    for (int i = 0; i < end.size(); ++i) {
        const auto &a = start.bodies[i], &b = end.bodies[i];
        ASSERT_EQ(b.species, a.species) << i;
        if (b.species == 1) {
            ASSERT_EQ(b.w, Vec3::Zero()) << i;
            ASSERT_EQ(b.s, a.s) << i;
        } else if ((b.s - a.s).norm() > 0.1) {
            ++turned;
        }
    }
    EXPECT_GT(turned, 0);
}

} // namespace

TEST(RodsAmongSpheres, DmdKeepsEnergyMomentaAndSpeciesAndMissesNoEvent) {
    const Scene s = scene(0.5);
    const RodSystem start = rodSystem(s);
    int rods = 0;
    for (const auto& b : start.bodies) {
        rods += b.species == 0;
        if (b.species == 1) {
            ASSERT_EQ(b.w, Vec3::Zero()); // the bath gave spheres no spin
        }
    }
    EXPECT_EQ(rods, 64);
    DmdRods e(start, s);
    const double e0 = e.kineticEnergy() + e.potentialEnergy();
    const Vec3 p0 = e.totalMomentum();
    for (int k = 1; k <= 20; ++k) {
        e.advanceTo(units::fromFs(25.0 * k));
        ASSERT_NEAR(e.potentialEnergy(), Probe::terracedEnergyFromScratch(e), 1e-9 * std::abs(e0))
            << "sample " << k;
    }
    EXPECT_GT(Probe::counts(e).up + Probe::counts(e).down, 2000u);
    EXPECT_NEAR(e.kineticEnergy() + e.potentialEnergy(), e0, 1e-10 * std::abs(e0) + 1e-9);
    EXPECT_LT((e.totalMomentum() - p0).norm(), 1e-9);
    expectSpheresStillAndRodsTurning(start, e.system());
}

// Velocity Verlet's energy error falls as dt² only if each kick divides by the body's own mass
// and a sphere's (zero) torque turns nothing.
TEST(RodsAmongSpheres, SmdEnergyErrorFallsAsDtSquared) {
    const auto energyError = [](double dtFs) {
        const Scene s = scene(0.5, dtFs);
        const RodSystem start = rodSystem(s);
        SmdRods e(start, s);
        const double e0 = e.kineticEnergy() + e.potentialEnergy();
        const Vec3 p0 = e.totalMomentum();
        double worst = 0.0;
        for (int k = 1; k <= 40; ++k) {
            e.advanceTo(units::fromFs(7.2 * k));
            worst = std::max(worst, std::abs(e.kineticEnergy() + e.potentialEnergy() - e0));
        }
        EXPECT_LT((e.totalMomentum() - p0).norm(), 1e-9) << dtFs << " fs";
        expectSpheresStillAndRodsTurning(start, e.system());
        return worst;
    };
    const double coarse = energyError(1.8), fine = energyError(0.9);
    std::printf("max |E - E0| over 288 fs: %.3g kJ/mol at 1.8 fs, %.3g at 0.9 fs\n", coarse, fine);
    EXPECT_GT(coarse / fine, 3.0);
    EXPECT_LT(coarse / fine, 5.5);
}

} // namespace test_rod_mixture_engines
