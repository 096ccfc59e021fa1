// A mixture's labels as a run gives them to its analysis (cli/body_species.hpp): read from the
// engine, they are the species the initial state dealt, body for body in the scene's numbering,
// from DMD (which numbers its bodies in Morton order inside) and SMD alike, and still after the
// engine has run; a scene without species has none. Each species' D in summary.json's
// "reduced" entry, converted as the total's.
#include "cli/body_species.hpp"
#include "cli/dispatch.hpp"
#include "cli/reduced_summary.hpp"
#include "core/initial_state.hpp"
#include "core/smoothed_potential.hpp"
#include "core/species_sphere.hpp"
#include "dmd/scene_engine.hpp"
#include "smd/scene_engine.hpp"
#include "tests/mixture_scene.hpp"
#include <gtest/gtest.h>

namespace test_body_species {

using namespace terrace;

namespace {

/// 2000 spheres of Kob–Andersen's mixture (tests/mixture_scene.hpp): cells enough for DMD to
/// renumber them inside.
Scene mixtureScene(const std::string& engine) {
    nlohmann::json j = mixture_tests::kobAndersen(2000, 0.8, 1.0);
    j["name"] = "binary";
    j["units"] = "lj";
    j["engine"] = engine;
    j["run"] = {{"equilibrate_ps", 0}, {"time_ps", 0.09}, {"sample_fs", 9}};
    return sceneFromJson(j, "test");
}

template <template <class, class> class Engine>
void labelsAreTheDealtSpecies(const std::string& engine, double runFor) {
    const Scene scene = mixtureScene(engine);
    const auto potential = ljMixture(scene);
    const auto start = buildInitialState<SpeciesSphere>(scene, potential);
    using Model = Smoothed<LJMixture>;
    const auto model = cli::sceneModel(scene, potential, engine == "dmd");
    System<SpeciesSphere, Model> sys;
    sys.box = start.box, sys.body = start.body, sys.kT = start.kT, sys.potential = model;
    sys.bodies = start.bodies;
    Engine<SpeciesSphere, Model> e(sys, scene);
    for (const double t : {0.0, runFor}) {
        if (t > 0.0) e.advanceTo(t);
        const analysis::SpeciesLabels l = cli::bodySpecies(e, scene, start.size());
        ASSERT_EQ(l.names, (std::vector<std::string>{"A", "B"}));
        ASSERT_EQ(l.ofBody.size(), start.bodies.size());
        for (int i = 0; i < start.size(); ++i)
            ASSERT_EQ(l.ofBody[i], start.bodies[i].species) << engine << ", body " << i;
        EXPECT_EQ(l.bodiesPerSpecies(), (std::vector<long>{1600, 400}));
    }
}

} // namespace

TEST(BodySpecies, DmdGivesTheDealtSpeciesInTheScenesNumbering) {
    labelsAreTheDealtSpecies<dmd::SceneEngine>("dmd", 0.5);
}

TEST(BodySpecies, SmdGivesTheDealtSpeciesInTheScenesNumbering) {
    labelsAreTheDealtSpecies<smd::SceneEngine>("smd", 0.2);
}

TEST(BodySpecies, ASceneWithoutSpeciesHasNoLabels) {
    Scene scene = defaultScene();
    scene.state.n = 64;
    scene.body.kind = "sphere", scene.potential.kind = "lj", scene.body.inertia = Vec3::Zero();
    const auto sys = buildInitialState<Sphere>(scene, ljPotential(scene));
    const dmd::SceneEngine<Sphere, LJPotential> e(sys, scene);
    EXPECT_TRUE(cli::bodySpecies(e, scene, sys.size()).empty());
}

TEST(BodySpecies, EachSpeciesDiffusionIsReducedAsTheTotals) {
    const UnitSystem u = UnitSystem::lj(3.405, 0.996, 39.948);
    const nlohmann::json d = {{"einstein_angstrom2_per_ps", 0.5},
                              {"einstein_err", 0.01},
                              {"green_kubo_angstrom2_per_ps", 0.6},
                              {"green_kubo_err", nullptr}};
    nlohmann::json summary = {{"analysis", {{"diffusion", d}}}};
    summary["analysis"]["diffusion"]["species"] = {{"A", d}, {"B", d}};
    const nlohmann::json r = cli::reducedSummary(summary, u)["diffusion"];
    for (const char* name : {"A", "B"}) {
        EXPECT_EQ(r["species"][name]["einstein"], r["einstein"]) << name;
        EXPECT_EQ(r["species"][name]["einstein_err"], r["einstein_err"]) << name;
        EXPECT_EQ(r["species"][name]["green_kubo"], r["green_kubo"]) << name;
        EXPECT_TRUE(r["species"][name]["green_kubo_err"].is_null()) << name;
    }
    EXPECT_EQ(r["einstein"].get<double>(), u.diffusion(0.5));
    summary["analysis"]["diffusion"].erase("species");
    EXPECT_FALSE(cli::reducedSummary(summary, u)["diffusion"].contains("species"));
}

} // namespace test_body_species
