// A mixture of Lennard-Jones spheres (Scene::species; core/lj_mixture.hpp) in both engines. DMD:
// energy and momentum to round-off, no missed event (the terraced energy equals the one recomputed
// from each pair's U at every sample), the same events with and without the hold screen (which
// bounds each pair's U by its own species' ε and σ), and bodies that keep their species. SMD: the
// pair loop's mixture kernel against the all-pairs sum. With a species three times as heavy as
// the other: DMD's energy and momentum Σ m v to round-off, and heat shared out to equipartition
// from a start where the heavy species is twice as hot; SMD's energy error ∝ dt² and its momentum
// to round-off. With small terraces, DMD's
// configurational U and pressure agree with SMD's within their error bars
// (test_mixture_agreement.cpp).
#include "dmd/testing.hpp"
#include "smd/pair_forces.hpp"
#include "tests/dmd/mixture_engines.hpp"
#include <array>
#include <cstdio>
#include <gtest/gtest.h>
#include <vector>

namespace test_mixture {

using terrace::dmd::testing::Probe;
using namespace terrace;

namespace {

using namespace terrace::mixture_tests;

/// The mixture with species B of mass massB (in A's) and SMD's step dtFs; each pair cut at its own
/// σ_ab where perPair.
Scene mixtureScene(int n, double density, double temperature, double dVInKT, double massB = 1.0,
                   double dtFs = 0.2, bool perPair = false) {
    nlohmann::json j = mixtureDocument(n, density, temperature, dVInKT);
    j["species"][1]["mass"] = massB;
    j["smd"]["dt_fs"] = dtFs;
    if (perPair) j["potential"]["cutoff_per_pair"] = true;
    return sceneFromJson(j, "mixture");
}

/// Σ m v² over the bodies of each species (kJ/mol): 3 n_a kT_a.
std::array<double, 2> twiceKinetic(const MixtureSystem& sys) {
    std::array<double, 2> k{0.0, 0.0};
    for (const auto& b : sys.bodies)
        k[b.species] += bodyMass<SpeciesSphere>(b, sys.body) * b.v.squaredNorm();
    return k;
}

double totalEnergy(const DmdMixture& e) {
    return e.kineticEnergy() + e.potentialEnergy();
}

/// Advances e by 500 fs in 20 samples. At each, the terraced energy that the engine carries
/// against every pair's terrace found afresh from its U: a missed crossing leaves them apart. Then
/// enough crossings to mean something, and the energy to round-off.
void expectEnergyKeptAndNoEventMissed(DmdMixture& e) {
    const double e0 = totalEnergy(e);
    const double t0 = e.time();
    for (int k = 1; k <= 20; ++k) {
        e.advanceTo(t0 + units::fromFs(25.0 * k));
        ASSERT_NEAR(e.potentialEnergy(), Probe::terracedEnergyFromScratch(e), 1e-9 * std::abs(e0))
            << "sample " << k;
    }
    EXPECT_GT(Probe::counts(e).up + Probe::counts(e).down, 10000u);
    EXPECT_NEAR(totalEnergy(e), e0, 1e-10 * std::abs(e0) + 1e-9);
}

} // namespace

TEST(Mixture, DmdKeepsEnergyMomentaAndSpeciesAndMissesNoEvent) {
    const Scene s = mixtureScene(256, 0.8, 2.0, 0.375);
    const MixtureSystem start = mixtureSystem(s);
    DmdMixture e(start, s);
    const Vec3 p0 = e.totalMomentum();
    expectEnergyKeptAndNoEventMissed(e);
    EXPECT_LT((e.totalMomentum() - p0).norm(), 1e-9);
    const MixtureSystem end = e.system();
    for (int i = 0; i < end.size(); ++i)
        ASSERT_EQ(end.bodies[i].species, start.bodies[i].species) << i;
}

// The screen only spares searches that could find nothing; the chaos of the liquid amplifies the
// round-off of the root refinement it moves (as for the rods, test_engine.cpp), so the two runs
// are compared over the first 60 fs, collision count by collision count, every 2 fs.
TEST(Mixture, TheHoldScreenChangesNoCollision) {
    const Scene s = mixtureScene(108, 0.8, 2.0, 0.375);
    DmdMixture screened(mixtureSystem(s), s), searched(mixtureSystem(s), s);
    Probe::setHoldScreen(searched, false);
    for (int k = 1; k <= 30; ++k) {
        screened.advanceTo(units::fromFs(2.0 * k));
        searched.advanceTo(units::fromFs(2.0 * k));
        ASSERT_EQ(Probe::counts(screened).up, Probe::counts(searched).up) << 2 * k << " fs";
        ASSERT_EQ(Probe::counts(screened).down, Probe::counts(searched).down) << 2 * k << " fs";
        ASSERT_EQ(Probe::counts(screened).reflect, Probe::counts(searched).reflect)
            << 2 * k << " fs";
    }
    EXPECT_GT(Probe::counts(screened).up + Probe::counts(screened).down, 500u);
    EXPECT_GT(screened.statistics()["searches_screened"].get<double>(), 0.0);
    const auto evaluations = [](const DmdMixture& e) {
        return e.statistics()["search_evaluations"].get<double>();
    };
    std::printf("search evaluations: screened %.0f, searched %.0f; virtual events %lu, %lu\n",
                evaluations(screened), evaluations(searched),
                (unsigned long)Probe::counts(screened).virtualEvents,
                (unsigned long)Probe::counts(searched).virtualEvents);
    EXPECT_LT(evaluations(screened), evaluations(searched)) << "the screen should spare samples";
}

TEST(Mixture, SmdForcesAreTheAllPairsSum) {
    const Scene s = mixtureScene(256, 0.8, 2.0, 0.375);
    SmdMixture e(mixtureSystem(s), s);
    e.advanceTo(units::fromFs(40.0));
    const smd::Forces all = smd::allPairsForces(e.system());
    EXPECT_NEAR(e.potentialEnergy(), all.potential, 1e-9 * std::abs(all.potential));
    EXPECT_NEAR(e.virial(), all.virial, 1e-9 * std::abs(all.virial));
    // The unlike pairs count: the same bodies all of species A have another energy.
    MixtureSystem allA = e.system();
    for (auto& b : allA.bodies)
        b.species = 0;
    EXPECT_GT(std::abs(smd::allPairsForces(allA).potential - all.potential),
              0.01 * std::abs(all.potential));
}

// Each pair on its own cutoff (potential.cutoff_per_pair): the unlike and BB pairs end before the
// envelope's r_u, so a pair between its own r_u and the envelope's must carry no terrace in DMD
// (the terraced energy recomputed from scratch says so at every sample) and no force in SMD's
// pair loop (against the all-pairs sum of the model's own evaluation); the hold screen, whose
// bands hold below the envelope's least r_l, still changes no collision.
TEST(Mixture, EachPairOnItsOwnCutoffInBothEngines) {
    const Scene s = mixtureScene(256, 0.8, 2.0, 0.375, 1.0, 0.2, true);
    const MixtureSystem start = mixtureSystem(s);
    ASSERT_TRUE(start.potential.bare.cutPerPair);
    ASSERT_LT(start.potential.cutOfPair(0, 1).outer(), start.potential.range());
    DmdMixture e(start, s), searched(start, s);
    Probe::setHoldScreen(searched, false);
    expectEnergyKeptAndNoEventMissed(e);
    // The screen against the full search over the first 40 fs (see
    // TheHoldScreenChangesNoCollision).
    DmdMixture screened(start, s);
    for (int k = 1; k <= 20; ++k) {
        screened.advanceTo(units::fromFs(2.0 * k));
        searched.advanceTo(units::fromFs(2.0 * k));
        ASSERT_EQ(Probe::counts(screened).up, Probe::counts(searched).up) << 2 * k << " fs";
        ASSERT_EQ(Probe::counts(screened).down, Probe::counts(searched).down) << 2 * k << " fs";
    }
    SmdMixture smd(start, s);
    smd.advanceTo(units::fromFs(40.0));
    const smd::Forces all = smd::allPairsForces(smd.system());
    EXPECT_NEAR(smd.potentialEnergy(), all.potential, 1e-9 * std::abs(all.potential));
    EXPECT_NEAR(smd.virial(), all.virial, 1e-9 * std::abs(all.virial));
    // The per-pair cutoffs count: the same configuration on the one cutoff has another energy.
    const Scene one = mixtureScene(256, 0.8, 2.0, 0.375);
    MixtureSystem sameCut = smd.system();
    sameCut.potential = Smoothed<LJMixture>{ljMixture(one), sceneCutoff(one)};
    EXPECT_GT(std::abs(smd::allPairsForces(sameCut).potential - all.potential),
              1e-4 * std::abs(all.potential));
}

// Species B three times as heavy, and started twice as hot as A: every collision's impulse divides
// by each body's own mass, so the energy and Σ m v stay to round-off, and collisions share the
// heat out until both species have the one temperature (equipartition).
TEST(Mixture, UnequalMassesDmdKeepsEnergyAndMomentumAndSharesTheHeat) {
    const Scene s = mixtureScene(256, 0.8, 2.0, 0.375, 3.0);
    MixtureSystem start = mixtureSystem(s);
    double massTotal = 0.0;
    Vec3 p = Vec3::Zero();
    for (auto& b : start.bodies) {
        if (b.species == 1) b.v *= std::sqrt(2.0);
        massTotal += bodyMass<SpeciesSphere>(b, start.body);
        p += bodyMass<SpeciesSphere>(b, start.body) * b.v;
    }
    for (auto& b : start.bodies)
        b.v -= p / massTotal;
    int countB = 0;
    for (const auto& b : start.bodies)
        countB += b.species;
    const int countA = start.size() - countB;
    const auto ratio = [&](const MixtureSystem& sys) { // T_B / T_A
        const auto k = twiceKinetic(sys);
        return (k[1] / countB) / (k[0] / countA);
    };
    ASSERT_GT(ratio(start), 1.6);
    DmdMixture e(start, s);
    const double e0 = totalEnergy(e);
    const Vec3 p0 = e.totalMomentum();
    EXPECT_LT(p0.norm(), 1e-9);
    // 0.5 ps to share the heat, then 1.5 ps of samples every 25 fs in 6 blocks.
    e.advanceTo(units::fromFs(500.0));
    const int blocks = 6, perBlock = 10;
    std::vector<double> blockMean;
    for (int k = 0; k < blocks; ++k) {
        double sum = 0.0;
        for (int m = 1; m <= perBlock; ++m) {
            e.advanceTo(units::fromFs(500.0 + 25.0 * (k * perBlock + m)));
            sum += ratio(e.system());
        }
        blockMean.push_back(sum / perBlock);
    }
    double mean = 0.0, var = 0.0;
    for (const double x : blockMean)
        mean += x / blocks;
    for (const double x : blockMean)
        var += (x - mean) * (x - mean) / (blocks - 1);
    const double err = std::sqrt(var / blocks);
    std::printf("T_B/T_A: start %.3f, after 0.5 ps %.4f +- %.4f\n", ratio(start), mean, err);
    EXPECT_LT(err, 0.05);
    EXPECT_LT(std::abs(mean - 1.0), 4.0 * err + 0.01) << mean << " +- " << err;
    EXPECT_NEAR(totalEnergy(e), e0, 1e-10 * std::abs(e0) + 1e-9);
    EXPECT_LT((e.totalMomentum() - p0).norm(), 1e-9);
    EXPECT_NEAR(e.potentialEnergy(), Probe::terracedEnergyFromScratch(e), 1e-9 * std::abs(e0));
}

// SMD with the heavy species: velocity Verlet's energy error falls as dt² only if every kick
// divides each body's force by its own mass; Σ m v is kept to round-off.
TEST(Mixture, UnequalMassesSmdEnergyErrorFallsAsDtSquared) {
    const auto energyError = [](double dtFs) {
        const Scene s = mixtureScene(256, 0.8, 2.0, 0.375, 3.0, dtFs);
        SmdMixture e(mixtureSystem(s), s);
        const double e0 = e.kineticEnergy() + e.potentialEnergy();
        const Vec3 p0 = e.totalMomentum();
        double worst = 0.0;
        for (int k = 1; k <= 40; ++k) {
            e.advanceTo(units::fromFs(2.0 * k));
            worst = std::max(worst, std::abs(e.kineticEnergy() + e.potentialEnergy() - e0));
        }
        EXPECT_LT((e.totalMomentum() - p0).norm(), 1e-9) << dtFs << " fs";
        return worst;
    };
    const double coarse = energyError(0.4), fine = energyError(0.2);
    std::printf("max |E - E0| over 80 fs: %.3g kJ/mol at 0.4 fs, %.3g at 0.2 fs\n", coarse, fine);
    EXPECT_GT(coarse / fine, 3.0);
    EXPECT_LT(coarse / fine, 5.5);
}

} // namespace test_mixture
