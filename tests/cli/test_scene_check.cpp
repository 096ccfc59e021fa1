// A scene made ready to run (cli/scene_check.hpp): the engines' sections read and checked by
// their owners (dmd/section.hpp, smd/parameters.hpp) with the same one-line errors as the scene's
// own keys, written back resolved; the keys removed from the scene name what replaces them.
#include "cli/restart.hpp"
#include "cli/run_command.hpp"
#include "cli/scene_check.hpp"
#include "cli/sweep_plan.hpp"
#include "dmd/section.hpp"
#include "smd/parameters.hpp"
#include <filesystem>
#include <gtest/gtest.h>
#include <unistd.h>

namespace test_scene_check {

using namespace terrace;
using nlohmann::json;

namespace {

Scene ready(const json& j, const std::vector<std::string>& overrides = {}) {
    Scene s = sceneFromJson(j, "test.json", overrides);
    cli::resolveEngineSections(s, "test.json");
    return s;
}

std::string errorOf(const json& j, const std::vector<std::string>& overrides = {}) {
    try {
        ready(j, overrides);
    } catch (const SceneError& e) {
        return e.what();
    }
    return "";
}

std::filesystem::path sourceDir() {
    return std::filesystem::path(TERRACE_SOURCE_DIR);
}

} // namespace

TEST(SceneCheck, DefaultsAreWrittenBackInFull) {
    const Scene s = ready(json::object());
    EXPECT_EQ(s.dmd, json({{"dV", 0.5},
                           {"queue", "tree"},
                           {"invalidation", "lazy"},
                           {"horizon_fs", 4.0},
                           {"model", "smoothed"}}));
    EXPECT_EQ(s.smd, json({{"dt_fs", 1.8}, {"skin", 0.3}, {"scheme", "verlet"}}));
    const Scene again = ready(toJson(s));
    EXPECT_EQ(toJson(again), toJson(s));
}

TEST(SceneCheck, ShippedDenseRodsEqualsTheBuiltInDefault) {
    // But for the model: the paper's figures terrace the bare potential (dmd.model = bare), the
    // built-in default the smoothed one that SMD integrates.
    Scene file = loadScene((sourceDir() / "experiments/scenes/dense-rods.json").string());
    cli::resolveEngineSections(file, "dense-rods.json");
    EXPECT_EQ(file.dmd["model"], "bare");
    file.dmd["model"] = "smoothed";
    EXPECT_EQ(toJson(file), toJson(ready(json::object())));
}

TEST(SceneCheck, EveryShippedSceneIsReady) {
    for (const auto& entry :
         std::filesystem::directory_iterator(sourceDir() / "experiments/scenes"))
        for (const char* engine : {"dmd", "smd"}) {
            // A step table runs under DMD only: SMD refuses the scene as it is read.
            const bool steps = loadScene(entry.path().string()).potential.kind == "steps";
            if (steps && std::string(engine) == "smd") {
                EXPECT_THROW(loadScene(entry.path().string(), {"engine=smd"}), SceneError)
                    << entry.path();
                continue;
            }
            Scene s = loadScene(entry.path().string(), {std::string("engine=") + engine});
            EXPECT_NO_THROW(cli::resolveEngineSections(s, entry.path().string()))
                << entry.path() << " " << engine;
        }
}

// The sweep planner checks every run's scene as `terrace run` will, before any runs.
TEST(SceneCheck, EveryShippedSweepPlans) {
    for (const auto& entry :
         std::filesystem::directory_iterator(sourceDir() / "experiments/sweeps"))
        // Each plans, and sets no key for runs whose engine ignores it (cli/engine_keys.hpp).
        EXPECT_TRUE(cli::loadSweep(entry.path(), {}).ignoredKeys.empty()) << entry.path();
    const auto sweeps = sourceDir() / "experiments/sweeps";
    try {
        cli::loadSweep(sweeps / "example.json", {"dmd.queue=auto"});
        FAIL() << "a sweep whose runs use a removed key must fail before it runs";
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("dmd.queue: \"auto\" has been removed"),
                  std::string::npos)
            << e.what();
    }
}

TEST(SceneCheck, UnknownAndBadKeysAreNamed) {
    EXPECT_EQ(errorOf({{"dmd", {{"dv", 1}}}}),
              "test.json: dmd.dv: unknown key; did you mean dmd.dV?");
    EXPECT_NE(errorOf(json::object(), {"dmd.nope=1"}).find("test.json: dmd.nope: unknown key"),
              std::string::npos);
    // The engines' sections name their nearest key too (issue: smd.dt for smd.dt_fs).
    EXPECT_EQ(errorOf(json::object(), {"smd.dt=0.5"}),
              "test.json: smd.dt: unknown key; did you mean smd.dt_fs?");
    EXPECT_EQ(errorOf(json::object(), {"smd.skni=0.5"}),
              "test.json: smd.skni: unknown key; did you mean smd.skin?");
    EXPECT_EQ(errorOf(json::object(), {"smd.bogus=1"}),
              "test.json: smd.bogus: unknown key (smd has dt_fs, skin, scheme)");
    EXPECT_EQ(errorOf(json::object(), {"dmd.horizon=4"}),
              "test.json: dmd.horizon: unknown key; did you mean dmd.horizon_fs?");
    EXPECT_EQ(errorOf(json::object(), {"smd.scheme=verlett"}),
              "test.json: smd.scheme: must be one of omelyan | verlet | yoshida4, got "
              "\"verlett\"; did you mean verlet?");
    EXPECT_NE(errorOf({{"dmd", {{"dV", 0}}}}).find("dmd.dV: must be > 0"), std::string::npos);
    EXPECT_NE(errorOf({{"dmd", {{"dV", -1}}}}).find("dmd.dV"), std::string::npos);
    EXPECT_NE(errorOf({{"smd", {{"dt_fs", 0}}}}).find("smd.dt_fs"), std::string::npos);
    EXPECT_EQ(errorOf({{"dmd", {{"queue", "forest"}}}}),
              "test.json: dmd.queue: must be one of bpq | heap | tree, got \"forest\"");
    EXPECT_NE(errorOf({{"dmd", {{"resort_cells", -1}}}}).find("dmd.resort_cells: must be >= 0"),
              std::string::npos);
    EXPECT_NE(errorOf({{"dmd", {{"model", "exact"}}}}).find("dmd.model"), std::string::npos);
    EXPECT_NE(errorOf({{"dmd", {{"levels", {1.0, 0.5}}}}}).find("strictly increasing"),
              std::string::npos);
    EXPECT_EQ(errorOf({{"dmd", {{"terraces", 3}}}}), "test.json: dmd.terraces: must be an object");
    // The old SMD keys name their new home.
    EXPECT_NE(errorOf({{"smd", {{"r_l", 2.5}}}}).find("smd.r_l: has moved to potential.cutoff"),
              std::string::npos);
    EXPECT_NE(errorOf({{"smd", {{"r_u", 3.0}}}}).find("smd.r_u: has moved to potential.cutoff"),
              std::string::npos);
    // An SMD run's dmd section is checked too: a misspelt key is never silently ignored.
    EXPECT_EQ(errorOf({{"engine", "smd"}, {"dmd", {{"dv", 1}}}}),
              "test.json: dmd.dv: unknown key; did you mean dmd.dV?");
}

// docs/CHANGES.md "Removed scene keys": each old key is one line naming its replacement.
TEST(SceneCheck, RemovedKeysNameTheirReplacement) {
    EXPECT_EQ(errorOf({{"dmd", {{"queue", "auto"}}}}),
              "test.json: dmd.queue: \"auto\" has been removed: use \"tree\", the same queue (the "
              "default)");
    EXPECT_EQ(errorOf({{"dmd", {{"hold_screen", false}}}}),
              "test.json: dmd.hold_screen: has been removed from the scene (the hold-time screen "
              "is always on): to measure without it, set TERRACE_MEASURE=no-hold-screen in the "
              "environment");
    EXPECT_EQ(errorOf({{"dmd", {{"sort_bodies", true}}}}),
              "test.json: dmd.sort_bodies: has been removed from the scene (DMD always keeps its "
              "bodies in the Morton order of their cells): to measure without it, set "
              "TERRACE_MEASURE=no-sort-dmd in the environment");
    EXPECT_EQ(errorOf({{"smd", {{"sort_bodies", false}}}}),
              "test.json: smd.sort_bodies: has been removed from the scene (SMD always keeps its "
              "bodies in cell order): to measure without it, set TERRACE_MEASURE=no-sort-smd in "
              "the environment");
}

TEST(SceneCheck, ResortCellsIsWrittenOnlyWhenSet) {
    EXPECT_FALSE(ready(json::object()).dmd.contains("resort_cells")); // auto: set from N
    EXPECT_FALSE(ready(json::object(), {"dmd.resort_cells=auto"}).dmd.contains("resort_cells"));
    const Scene never = ready(json::object(), {"dmd.resort_cells=0"});
    EXPECT_EQ(never.dmd["resort_cells"], 0.0);
    EXPECT_EQ(ready(toJson(never)).dmd["resort_cells"], 0.0);
}

TEST(SceneCheck, SmdIntervalsLieOnItsGrid) {
    // 9 / 1.8 is not exact in binary: the default SMD scene must pass.
    EXPECT_EQ(errorOf({{"engine", "smd"}}), "");
    EXPECT_EQ(errorOf({{"engine", "smd"}, {"smd", {{"dt_fs", 0.2}}}}), "");
    EXPECT_EQ(
        errorOf({{"engine", "smd"}, {"run", {{"sample_fs", 10}}}}),
        "test.json: run.sample_fs: must be a whole multiple of smd.dt_fs = 1.8 fs, got 10 fs; "
        "nearest valid: 9 or 10.8 fs");
    EXPECT_EQ(errorOf({{"engine", "smd"}, {"smd", {{"dt_fs", 4}}}}),
              "test.json: run.sample_fs: must be a whole multiple of smd.dt_fs = 4 fs, got 9 fs; "
              "nearest valid: 8 or 12 fs");
    EXPECT_EQ(errorOf({{"engine", "smd"}, {"run", {{"thermostat_fs", 1}}}}),
              "test.json: run.thermostat_fs: must be a whole multiple of smd.dt_fs = 1.8 fs, got 1 "
              "fs; nearest valid: 1.8 fs");
    EXPECT_NE(errorOf({{"engine", "smd"}, {"run", {{"sample_fs", 10}, {"time_ps", 1}}}})
                  .find("run.sample_fs: must be a whole multiple of smd.dt_fs"),
              std::string::npos);
    EXPECT_EQ(errorOf({{"engine", "smd"}, {"smd", {{"dt_fs", 20}}}, {"run", {{"time_ps", 0.009}}}}),
              "test.json: smd.dt_fs: 20 fs is longer than run.time_ps = 0.009 ps: no step would "
              "be taken");
    EXPECT_EQ(errorOf({{"smd", {{"dt_fs", 4}}}}), ""); // DMD runs take no SMD steps
    // Run lengths need not be whole intervals, but SMD cannot stop between two steps.
    EXPECT_EQ(errorOf({{"engine", "smd"}, {"run", {{"time_ps", 2}}}}),
              "test.json: run.time_ps: must be a whole multiple of smd.dt_fs = 1.8 fs, got 2 ps; "
              "nearest valid: 1.9998 or 2.0016 ps");
    EXPECT_EQ(errorOf({{"engine", "smd"}, {"run", {{"equilibrate_ps", 0.5}}}}),
              "test.json: run.equilibrate_ps: must be a whole multiple of smd.dt_fs = 1.8 fs, got "
              "0.5 ps; nearest valid: 0.4986 or 0.5004 ps");
    EXPECT_EQ(errorOf({{"engine", "smd"}, {"smd", {{"dt_fs", 1}}}, {"run", {{"time_ps", 2}}}}),
              ""); // 2000 steps; its last 5 after the last sample at 1.998 ps
}

TEST(SceneCheck, HorizonAndTerraceCountARunCanRepresent) {
    EXPECT_EQ(errorOf({{"dmd", {{"horizon_fs", 1e-6}}}}),
              "test.json: dmd.horizon_fs: must be >= 0.1 fs, got 1e-06: a thermal pair moves ~1e-3 "
              "Å in 0.1 fs, so a shorter horizon only multiplies virtual events (the paper uses 4 "
              "fs)");
    EXPECT_EQ(errorOf({{"dmd", {{"horizon_fs", 0.1}}}}), "");
    EXPECT_EQ(errorOf({{"state", {{"temperature", 1e-10}}}}),
              "test.json: state.temperature: kT = 3e-10 kJ/mol with dmd.dV = 0.5 makes 2e+10 "
              "terraces of 1.5e-10 kJ/mol in the well (U_min = -3 kJ/mol), more than the 100000 a "
              "run can represent (levels would crowd the minimum at round-off); raise "
              "state.temperature at least 200000-fold");
    EXPECT_EQ(errorOf({{"dmd", {{"dV", 1e-6}}}}),
              "test.json: dmd.dV: kT = 4.2 kJ/mol with dmd.dV = 1e-06 makes 714286 terraces of "
              "4.2e-06 kJ/mol in the well (U_min = -3 kJ/mol), more than the 100000 a run can "
              "represent (levels would crowd the minimum at round-off); raise dmd.dV to at least "
              "7.14286e-06");
    // No level in the well and none a thermal pair meets above 0: U = 0 throughout, refused.
    EXPECT_EQ(errorOf({{"dmd", {{"dV", 1e6}}}}),
              "test.json: dmd.dV: 1e+06 kT puts the first level at -2.1e+06 kJ/mol, below the "
              "potential minimum U_min = -3 kJ/mol: no terrace lies in the well, and the first "
              "above 0, 500000 kT, lies beyond every start's energy (50 kT): the bodies would "
              "pass through each other with U = 0 throughout; give dmd.dV < 1.42857 for a well");
    EXPECT_EQ(errorOf({{"dmd", {{"dV", 1.4}}}}), "");
    // A Gay–Berne well deepened by κ → 0 (U_min −10⁶ kJ/mol): κ's fault, not the temperature's.
    EXPECT_EQ(
        errorOf({{"body", {{"kind", "linear"}, {"mass", 40.0}, {"inertia", {180, 180, 0}}}},
                 {"potential",
                  {{"kind", "gay-berne"},
                   {"epsilon", 2.0},
                   {"sigma", 3.0},
                   {"kappa", 1e-6},
                   {"kappa_prime", 5.0},
                   {"cutoff", {3.5, 4.0}}}},
                 {"state", {{"density", 0.28}, {"temperature", 2.0}}}})
            .rfind("test.json: potential.kappa: gives a well U_min = -1e+06 kJ/mol deep, ", 0),
        0u);
    // SMD has no terraces: a cold SMD run is legal.
    EXPECT_EQ(errorOf({{"engine", "smd"}, {"state", {{"temperature", 1e-10}}}}), "");
}

TEST(SceneCheck, WarningsForLegalButSurprisingValues) {
    EXPECT_TRUE(sceneWarnings(ready(json::object())).empty());
    const auto w = sceneWarnings(ready({{"dmd", {{"levels", {0.5, 1.0, 2.0}}}}}));
    ASSERT_EQ(w.size(), 1u);
    EXPECT_EQ(w[0], "dmd.levels: no level lies between the potential minimum U_min = -3 kJ/mol "
                    "and 0, so the terraced potential has no attractive well");
    EXPECT_TRUE(sceneWarnings(ready({{"dmd", {{"levels", {-1.5, 1.0}}}}})).empty());
    // The paper's ΔV = 2 kT on the rods: no level in the well, a purely repulsive model, run.
    const auto repulsive = sceneWarnings(ready({{"dmd", {{"dV", 2.0}}}}));
    ASSERT_EQ(repulsive.size(), 1u);
    EXPECT_EQ(repulsive[0], "dmd.dV: 2 kT puts the first level at -4.2 kJ/mol, below the potential "
                            "minimum U_min = -3 kJ/mol: no terrace lies in the well, so the "
                            "terraced potential is purely repulsive (dmd.dV < 1.42857 gives it a "
                            "well)");
    EXPECT_TRUE(sceneWarnings(ready({{"engine", "smd"}, {"dmd", {{"dV", 2.0}}}})).empty());
}

// A restart file records the resolved scene: one that names the queue "auto" goes on, on the tree
// that "auto" chose. (This file holds nothing else, so the run stops at its missing bodies, after
// the scene has been read.)
TEST(SceneCheck, ARestartFileNamingTheQueueAutoGoesOnWithTheTree) {
    const auto dir =
        std::filesystem::temp_directory_path() / ("terrace-auto-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    json scene = toJson(ready(json::object()));
    scene["dmd"]["queue"] = "auto";
    const std::string sceneText = scene.dump(2) + "\n"; // the run's own scene.json
    writeFileAtomically(dir / "scene.json", sceneText);
    const int n = scene["state"]["n"].get<int>();
    cli::writeRestart(dir, {{"format", cli::restartFormat},
                            {"scene", scene},
                            {"n_bodies", n},
                            {"identity", cli::runIdentity(cli::crc64(sceneText), n,
                                                          scene["engine"].get<std::string>())}});
    Scene continued;
    try {
        cli::continueRun(dir, true, continued);
        ADD_FAILURE() << "expected the missing bodies to be named";
    } catch (const std::exception& e) {
        EXPECT_EQ(std::string(e.what()).find("dmd.queue"), std::string::npos) << e.what();
    }
    EXPECT_EQ(continued.dmd["queue"], "tree");
    std::filesystem::remove_all(dir);
}

} // namespace test_scene_check
