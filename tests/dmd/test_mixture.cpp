// A mixture of Lennard-Jones spheres (Scene::species; core/lj_mixture.hpp) in both engines. DMD:
// energy and momentum to round-off, no missed event (the terraced energy equals the one recomputed
// from each pair's U at every sample), the same events with and without the hold screen (which
// bounds each pair's U by its own species' ε and σ), and bodies that keep their species. SMD: the
// pair loop's mixture kernel against the all-pairs sum. With small terraces, DMD's
// configurational U and pressure agree with SMD's within their error bars
// (test_mixture_agreement.cpp).
#include "core/initial_state.hpp"
#include "core/lj_mixture.hpp"
#include "core/smoothed_potential.hpp"
#include "core/species_sphere.hpp"
#include "dmd/scene_engine.hpp"
#include "dmd/testing.hpp"
#include "smd/pair_forces.hpp"
#include "smd/scene_engine.hpp"
#include "tests/mixture_scene.hpp"
#include <cstdio>
#include <gtest/gtest.h>
#include <vector>

using terrace::dmd::testing::Probe;
using namespace terrace;

namespace {

using Model = Smoothed<LJMixture>;
using MixtureSystem = System<SpeciesSphere, Model>;
using DmdMixture = dmd::SceneEngine<SpeciesSphere, Model>;
using SmdMixture = smd::SceneEngine<SpeciesSphere, Model>;

/// Kob–Andersen's mixture (tests/mixture_scene.hpp) on an fcc lattice, at a liquid state point
/// well above its glass transition.
Scene mixtureScene(int n, double density, double temperature, double dVInKT) {
    nlohmann::json j = mixture_tests::kobAndersen(n, density, temperature);
    j["state"]["lattice"] = "fcc";
    j["dmd"] = {{"model", "smoothed"}, {"dV", dVInKT}};
    j["smd"] = {{"dt_fs", 0.2}};
    return sceneFromJson(j, "mixture");
}

MixtureSystem mixtureSystem(const Scene& s) {
    return buildInitialState<SpeciesSphere>(s, Model{ljMixture(s), sceneCutoff(s)});
}

double totalEnergy(const DmdMixture& e) {
    return e.kineticEnergy() + e.potentialEnergy();
}

} // namespace

TEST(Mixture, DmdKeepsEnergyMomentaAndSpeciesAndMissesNoEvent) {
    const Scene s = mixtureScene(256, 0.8, 2.0, 0.375);
    const MixtureSystem start = mixtureSystem(s);
    DmdMixture e(start, s);
    const double e0 = totalEnergy(e);
    const Vec3 p0 = e.totalMomentum();
    for (int k = 1; k <= 20; ++k) {
        e.advanceTo(units::fromFs(25.0 * k));
        // The terraced energy that the engine carries, against every pair's terrace found afresh
        // from its U: a missed crossing leaves them apart.
        ASSERT_NEAR(e.potentialEnergy(), Probe::terracedEnergyFromScratch(e), 1e-9 * std::abs(e0))
            << "sample " << k;
    }
    EXPECT_GT(Probe::counts(e).up + Probe::counts(e).down, 10000u);
    EXPECT_NEAR(totalEnergy(e), e0, 1e-10 * std::abs(e0) + 1e-9);
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
