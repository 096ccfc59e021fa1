// Scene parsing: defaults equal the paper's dense rods, every key validated, overrides by path.
#include "core/measure.hpp"
#include "core/scene.hpp"
#include "core/utf8.hpp"
#include "tests/core/scene_errors.hpp"
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <unistd.h>

namespace test_scene {

using namespace terrace;
using nlohmann::json;

namespace {

using scene_tests::errorOf;

std::filesystem::path sourceDir() {
    return std::filesystem::path(TERRACE_SOURCE_DIR);
}

} // namespace

TEST(Scene, DefaultIsThePapersDenseRods) {
    const Scene s = defaultScene();
    EXPECT_EQ(s.state.n, 512);
    EXPECT_DOUBLE_EQ(s.state.density, 0.5);
    EXPECT_DOUBLE_EQ(s.state.temperature, 1.4);
    EXPECT_DOUBLE_EQ(s.potential.epsilon, 3.0);
    EXPECT_DOUBLE_EQ(s.potential.sigma, 3.035);
    EXPECT_DOUBLE_EQ(s.potential.zeta, 1.0);
    EXPECT_DOUBLE_EQ(s.body.mass, 18.0);
    EXPECT_DOUBLE_EQ(s.body.inertia[0], 1.154);
    EXPECT_NEAR(s.kT(), 4.2, 1e-12);
    // ρ* = Nσ³/L³
    EXPECT_NEAR(512.0 * std::pow(s.potential.sigma / s.boxLength(), 3), 0.5, 1e-12);
}

// The engines' sections are compared where they are read (tests/cli/test_scene_check.cpp).
TEST(Scene, ShippedDenseRodsEqualsTheBuiltInDefault) {
    json file = toJson(loadScene((sourceDir() / "experiments/scenes/dense-rods.json").string()));
    json builtIn = toJson(defaultScene());
    for (json* j : {&file, &builtIn}) {
        j->erase("dmd");
        j->erase("smd");
    }
    EXPECT_EQ(file, builtIn);
}

TEST(Scene, EngineSectionsAreCarriedAsGiven) {
    const Scene s = sceneFromJson({{"dmd", {{"dV", 0.25}, {"anything", 1}}}}, "t", {"smd.x=2"});
    EXPECT_EQ(s.dmd, json({{"dV", 0.25}, {"anything", 1}}));
    EXPECT_EQ(s.smd, json({{"x", 2}}));
    EXPECT_EQ(defaultScene().dmd, json::object());
    EXPECT_EQ(errorOf({{"dmd", 1}}), "test.json: dmd: must be an object");
    EXPECT_EQ(errorOf({{"smd", {1, 2}}}), "test.json: smd: must be an object");
}

TEST(Scene, ShippedGasRodsIsThePapersGas) {
    const Scene s = loadScene((sourceDir() / "experiments/scenes/gas-rods.json").string());
    EXPECT_DOUBLE_EQ(s.state.temperature, 10.0);
    EXPECT_DOUBLE_EQ(s.state.density, 0.01);
}

TEST(Scene, RoundTripsThroughJson) {
    Scene s = sceneFromJson(toJson(defaultScene()), "x", {"dmd.dV=0.25", "engine=smd"});
    EXPECT_EQ(toJson(sceneFromJson(toJson(s), "y")), toJson(s));
}

TEST(Scene, UnknownKeyIsNamed) {
    // With no known key near it, the section's keys are listed.
    EXPECT_EQ(errorOf({{"bogus", 1}}),
              "test.json: bogus: unknown key (a scene has name, seed, units, body, potential, "
              "species, state, engine, dmd, smd, run, output, analysis)");
    EXPECT_EQ(errorOf({{"state",
                        {{"particles",
                          json::array({{{"r", {0, 0, 0}}, {"x", 1}}, {{"r", {1, 0, 0}}}})}}}}),
              "test.json: state.particles[0].x: unknown key (state.particles[0] has r, v, axis, "
              "orientation, omega)");
}

// "Did you mean": the section's known key nearest a misspelt one, from a file or --set.
TEST(Scene, UnknownKeyNamesTheNearestKnownOne) {
    EXPECT_EQ(errorOf({{"state", {{"desnity", 0.3}}}}),
              "test.json: state.desnity: unknown key; did you mean state.density?");
    EXPECT_EQ(errorOf(json::object(), {"state.temp=2"}),
              "test.json: state.temp: unknown key; did you mean state.temperature?");
    EXPECT_EQ(errorOf(json::object(), {"run.time=2"}),
              "test.json: run.time: unknown key; did you mean run.time_ps?");
    EXPECT_EQ(errorOf(json::object(), {"stat.n=64"}),
              "test.json: stat: unknown key; did you mean state?");
    EXPECT_EQ(errorOf(json::object(), {"output.thermo_every_ps=1"}),
              "test.json: output.thermo_every_ps: unknown key; did you mean "
              "output.thermo_every_fs?");
    // A choice's misspelt value too.
    EXPECT_EQ(errorOf({{"engine", "sdm"}}),
              "test.json: engine: must be one of dmd | smd, got \"sdm\"; did you mean smd?");
}

TEST(Scene, BadValuesAreNamed) {
    EXPECT_NE(errorOf({{"state", {{"n", 1}}}}).find("state.n"), std::string::npos);
    EXPECT_NE(errorOf({{"state", {{"temperature", 0}}}}).find("state.temperature"),
              std::string::npos);
    EXPECT_NE(errorOf({{"state", {{"density", "high"}}}}).find("must be a number"),
              std::string::npos);
    EXPECT_NE(errorOf({{"engine", "lammps"}}).find("engine: must be one of dmd | smd"),
              std::string::npos);
    EXPECT_NE(errorOf({{"potential", {{"cutoff", {3.0, 2.5}}}}}).find("potential.cutoff: must be"),
              std::string::npos);
    EXPECT_NE(errorOf({{"potential", {{"cutoff", {0.0, 2.5}}}}}).find("potential.cutoff"),
              std::string::npos);
    EXPECT_NE(errorOf({{"potential", {{"cutoff", 2.5}}}}).find("potential.cutoff: must be [r_l"),
              std::string::npos);
    EXPECT_NE(errorOf({{"potential", {{"kind", "lj"}}}}).find("potential.kind"), std::string::npos);
    EXPECT_NE(
        errorOf({{"body", {{"kind", "symmetric"}, {"inertia", {1, 2, 3}}}}}).find("body.inertia"),
        std::string::npos);
    EXPECT_NE(errorOf(json::array()).find("JSON object"), std::string::npos);
}

TEST(Scene, OverridesByDottedPath) {
    const Scene s = sceneFromJson(json::object(), "t",
                                  {"dmd.dV=0.125", "engine=smd", "dmd.queue=heap", "name=x y",
                                   "state.n=64", "run.time_ps=0.9"});
    EXPECT_EQ(s.dmd, json({{"dV", 0.125}, {"queue", "heap"}}));
    EXPECT_EQ(s.engine, "smd");
    EXPECT_EQ(s.state.n, 64);
    EXPECT_DOUBLE_EQ(s.run.time_ps, 0.9);
    EXPECT_EQ(s.name, "x y");
    EXPECT_NE(errorOf(json::object(), {"dmd.dV"}).find("key.path=value"), std::string::npos);
    EXPECT_NE(errorOf(json::object(), {"state.nope=1"}).find("state.nope: unknown key"),
              std::string::npos);
    EXPECT_EQ(errorOf({{"state", {{"n", 8}}}}, {"state.n.x=1"}),
              "test.json: state.n: is not an object");
}

TEST(Scene, FileThatIsNotJsonIsAShortError) {
    const auto path = std::filesystem::temp_directory_path() / "terrace-not-json.json";
    std::ofstream(path) << "{ this is not json";
    try {
        loadScene(path.string());
        FAIL() << "expected a SceneError";
    } catch (const SceneError& e) {
        EXPECT_EQ(std::string(e.what()), path.string() + ": not valid JSON");
    }
    EXPECT_THROW(loadScene("/nonexistent/scene.json"), SceneError);
}

TEST(Scene, ExplicitParticles) {
    json j = {
        {"state",
         {{"particles", json::array({{{"r", {0, 0, 0}}, {"v", {1, 0, 0}}, {"axis", {0, 0, 2}}},
                                     {{"r", {4, 0, 0}}, {"omega", {0, 1, 0}}}})}}}};
    const Scene s = sceneFromJson(j, "t");
    ASSERT_EQ(s.state.particles.size(), 2u);
    EXPECT_EQ(s.state.n, 2);
    EXPECT_DOUBLE_EQ(s.state.particles[0].axis.z(), 1.0); // normalised
    EXPECT_NE(
        errorOf({{"state", {{"n", 3}, {"particles", j["state"]["particles"]}}}}).find("state.n"),
        std::string::npos);
}

// --- every value honoured or refused ------------------------------------------------------------

namespace {

json twoBodies(const json& first, const json& second = {{"r", {4, 0, 0}}}) {
    return json::array({first, second});
}

std::string withBody(const std::string& kind, const json& inertia, const json& particles) {
    return errorOf(
        {{"body", {{"kind", kind}, {"inertia", inertia}}}, {"state", {{"particles", particles}}}});
}

/// Writes `text` to a temporary file and returns the message of loading it ("" if it loads).
std::string loadError(const std::string& file, const std::string& text,
                      const std::vector<std::string>& overrides = {}) {
    const auto path = std::filesystem::temp_directory_path() / file;
    std::ofstream(path) << text;
    try {
        loadScene(path.string(), overrides);
    } catch (const SceneError& e) {
        return std::string(e.what()).substr(path.string().size());
    }
    return "";
}

} // namespace

TEST(Scene, LinearRotorTakesItsAxisFromTheOrientation) {
    // 90° about x takes the body z axis to -y.
    const double h = std::sqrt(0.5);
    const Scene s = sceneFromJson(
        {{"state", {{"particles", twoBodies({{"r", {0, 0, 0}}, {"orientation", {h, h, 0, 0}}})}}}},
        "t");
    EXPECT_NEAR((s.state.particles[0].axis - Vec3(0, -1, 0)).norm(), 0.0, 1e-15);
    EXPECT_EQ(toJson(sceneFromJson(toJson(s), "again")), toJson(s));
    // Both given and agreeing is fine; disagreeing is refused.
    EXPECT_EQ(errorOf({{"state",
                        {{"particles", twoBodies({{"r", {0, 0, 0}},
                                                  {"axis", {0, -1, 0}},
                                                  {"orientation", {h, h, 0, 0}}})}}}}),
              "");
    EXPECT_EQ(errorOf({{"state",
                        {{"particles", twoBodies({{"r", {0, 0, 0}},
                                                  {"axis", {0, 0, 1}},
                                                  {"orientation", {h, h, 0, 0}}})}}}}),
              "test.json: state.particles[0].axis: disagrees with state.particles[0].orientation, "
              "whose image of the body z axis is [0, -1, 0]; give one of them, or both agreeing "
              "within 1e-09");
}

TEST(Scene, TopsTakeAnAxisOnlyWhenItFixesTheirMotion) {
    const json axisOnly = twoBodies({{"r", {0, 0, 0}}, {"axis", {1, 0, 0}}});
    const Scene sym = sceneFromJson({{"body", {{"kind", "symmetric"}, {"inertia", {1, 1, 0.5}}}},
                                     {"state", {{"particles", axisOnly}}}},
                                    "t");
    ASSERT_TRUE(sym.state.particles[0].orientation.has_value());
    EXPECT_NEAR((*sym.state.particles[0].orientation * Vec3::UnitZ() - Vec3::UnitX()).norm(), 0.0,
                1e-15);
    EXPECT_EQ(errorOf({{"state", {{"orientations", "aligned"}, {"particles", axisOnly}}}}),
              "test.json: state.orientations: applies to lattice starts only: state.particles "
              "gives each orientation");
    EXPECT_EQ(withBody("asymmetric", {1, 2, 3}, axisOnly),
              "test.json: state.particles[0].axis: an asymmetric top needs .orientation: an axis "
              "leaves its rotation about that axis undetermined");
    // An asymmetric top given an orientation gets the matching axis.
    const Scene asym = sceneFromJson(
        {{"body", {{"kind", "asymmetric"}, {"inertia", {1, 2, 3}}}},
         {"state", {{"particles", twoBodies({{"r", {0, 0, 0}}, {"orientation", {0, 1, 0, 0}}})}}}},
        "t");
    EXPECT_NEAR((asym.state.particles[0].axis - Vec3(0, 0, -1)).norm(), 0.0, 1e-15);
}

TEST(Scene, SpheresRefuseAxisOrientationAndOmega) {
    for (const char* key : {"axis", "orientation", "omega"}) {
        const json value = std::string(key) == "orientation" ? json{1, 0, 0, 0} : json{0, 0, 1};
        EXPECT_EQ(
            errorOf({{"body", {{"kind", "sphere"}}},
                     {"potential", {{"kind", "lj"}}},
                     {"state", {{"particles", twoBodies({{"r", {0, 0, 0}}, {key, value}})}}}}),
            "test.json: state.particles[0]." + std::string(key) +
                ": a sphere has no orientation or rotation (body.kind is sphere)");
    }
    const Scene spheres = sceneFromJson({{"body", {{"kind", "sphere"}}},
                                         {"potential", {{"kind", "lj"}}},
                                         {"state", {{"particles", twoBodies({{"r", {0, 0, 0}}})}}}},
                                        "t");
    EXPECT_EQ(toJson(sceneFromJson(toJson(spheres), "again")), toJson(spheres));
}

TEST(Scene, OverflowingVectorsAreRefused) {
    auto particle = [](const json& body) {
        return errorOf({{"state", {{"particles", twoBodies(body)}}}});
    };
    EXPECT_EQ(
        particle({{"r", {0, 0, 0}}, {"axis", {1e308, 1e308, 0}}}),
        "test.json: state.particles[0].axis: is too large: its length inf overflows a double");
    EXPECT_EQ(particle({{"r", {0, 0, 0}}, {"orientation", {1e308, 1e308, 0, 0}}}),
              "test.json: state.particles[0].orientation: is too large: its norm inf overflows a "
              "double");
    EXPECT_EQ(particle({{"r", {0, 0, 0}}, {"v", {1e160, 0, 0}}}),
              "test.json: state.particles[0].v: is too large: its length inf overflows a double");
    EXPECT_EQ(particle({{"r", {1e100, 0, 0}}}),
              "test.json: state.particles[0].r: lies 1e+100 Å from the origin, beyond 1e+06 box "
              "lengths: the wrap into the box would lose its digits");
    EXPECT_EQ(
        errorOf({{"body", {{"mass", 1e10}}},
                 {"state", {{"particles", twoBodies({{"r", {0, 0, 0}}, {"v", {1e153, 0, 0}}})}}}}),
        "test.json: state.particles[0].v: its kinetic energy ½mv² overflows a double");
    EXPECT_EQ(errorOf({{"body", {{"inertia", {1e150, 1e150, 0}}}}}), "");
    EXPECT_EQ(errorOf({{"body", {{"inertia", {1e150, 1e150, 0}}}},
                       {"state",
                        {{"particles", twoBodies({{"r", {0, 0, 0}}, {"omega", {1e100, 0, 0}}})}}}}),
              "test.json: state.particles[0].omega: its rotational energy ½Iω² overflows a double");
    EXPECT_EQ(errorOf({{"body", {{"inertia", {1e200, 1e200, 0}}}}}),
              "test.json: body.inertia: is too large: its length inf overflows a double");
}

TEST(Scene, DuplicateKeysAreRefusedAtAnyDepth) {
    EXPECT_EQ(loadError("terrace-dup-1.json", R"({"dmd": {"dV": 0.5, "dV": 1}})"),
              ": dmd.dV: duplicate key");
    EXPECT_EQ(loadError("terrace-dup-2.json", R"({"seed": 1, "seed": 2})"),
              ": seed: duplicate key");
    EXPECT_EQ(
        loadError(
            "terrace-dup-3.json",
            R"({"state": {"particles": [{"r": [0, 0, 0]}, {"r": [4, 0, 0], "r": [5, 0, 0]}]}})"),
        ": state.particles[1].r: duplicate key");
    EXPECT_EQ(loadError("terrace-dup-4.json", R"({"dmd": {"dV": 0.5}, "dmd": {"queue": "heap"}})"),
              ": dmd: duplicate key");
    // The same key in different objects, and an override of a key in the file, are not duplicates.
    EXPECT_EQ(loadError("terrace-dup-5.json", R"({"dmd": {"dV": 0.5}, "run": {"time_ps": 0.9}})",
                        {"dmd.dV=1"}),
              "");
}

TEST(Scene, ADirectoryOrAnUnreadableFileIsNamed) {
    const auto dir = std::filesystem::temp_directory_path();
    try {
        loadScene(dir.string());
        FAIL() << "expected a SceneError";
    } catch (const SceneError& e) {
        EXPECT_EQ(std::string(e.what()), dir.string() + ": is a directory, not a scene file");
    }
    try {
        loadScene("/nonexistent/scene.json");
        FAIL() << "expected a SceneError";
    } catch (const SceneError& e) {
        EXPECT_EQ(std::string(e.what()),
                  "/nonexistent/scene.json: cannot open the scene file: No such file or directory");
    }
}

TEST(Scene, IntervalsLongerThanTheRunAreRefused) {
    EXPECT_EQ(errorOf({{"run", {{"time_ps", 0.005}}}}),
              "test.json: run.sample_fs: 9 fs is longer than run.time_ps = 0.005 ps: no sample "
              "would be taken");
    // An equilibration shorter than one thermostat interval is that interval cut short: one
    // rescale, at its end.
    EXPECT_EQ(errorOf({{"run", {{"equilibrate_ps", 0.005}}}}), "");
    EXPECT_EQ(errorOf({{"run", {{"equilibrate_ps", 0}}}}), ""); // no equilibration, no thermostat
    EXPECT_EQ(errorOf({{"output", {{"trajectory_every_fs", 20000}}}}),
              "test.json: output.trajectory_every_fs: 20000 fs is longer than run.time_ps = 9 ps: "
              "no frame would be written");
    EXPECT_EQ(errorOf({{"output", {{"restart_every_ps", 11}}}}),
              "test.json: output.restart_every_ps: 11 ps is longer than run.time_ps = 9 ps: no "
              "restart file would be written");
    EXPECT_EQ(errorOf({{"output", {{"thermo_every_fs", 9009}}}}),
              "test.json: output.thermo_every_fs: 9009 fs is longer than run.time_ps = 9 ps: "
              "no thermo row would be written");
    EXPECT_EQ(errorOf({{"output", {{"thermo_every_fs", 9000}}}}), ""); // 1000 samples
}

TEST(Scene, IntervalsLieOnTheGrid) {
    // SMD's own grid, smd.dt_fs, is checked with the smd section (tests/cli/test_scene_check.cpp).
    EXPECT_EQ(errorOf({{"run", {{"sample_fs", 10}, {"thermostat_fs", 1}}}}), "");
    EXPECT_EQ(
        errorOf({{"output", {{"trajectory_every_fs", 0.001}}}}),
        "test.json: output.trajectory_every_fs: must be a whole multiple of run.sample_fs = 9 "
        "fs, got 0.001 fs; nearest valid: 9 fs");
    EXPECT_EQ(errorOf({{"output", {{"trajectory_every_fs", 90}}}}), "");
    EXPECT_EQ(errorOf({{"output", {{"restart_every_ps", 0.01}}}}),
              "test.json: output.restart_every_ps: must be a whole multiple of run.sample_fs = 9 "
              "fs, got 0.01 ps; nearest valid: 0.009 or 0.018 ps");
    EXPECT_EQ(errorOf({{"output", {{"restart_every_ps", 0.9}}}}), "");
    EXPECT_EQ(errorOf({{"output", {{"thermo_every_fs", 20}}}}),
              "test.json: output.thermo_every_fs: must be a whole multiple of run.sample_fs = 9 "
              "fs, got 20 fs; nearest valid: 18 or 27 fs");
    EXPECT_EQ(errorOf({{"output", {{"thermo_every_fs", 1e-9}}}}),
              "test.json: output.thermo_every_fs: must be a whole multiple of run.sample_fs = 9 "
              "fs, got 1e-09 fs; nearest valid: 9 fs");
    EXPECT_EQ(errorOf({{"output", {{"thermo_every_fs", 90}}}}), "");
}

// What the user asks for is what they get: a run length that is not a whole number of its
// intervals is run as typed (equilibration's last interval cut short, production's tail
// unsampled; cli/run_driver.cpp), not refused and not cut to the last whole interval. Under SMD
// a length must still be whole steps (tests/cli/test_scene_check.cpp).
TEST(Scene, RunLengthsAreHonouredAsTyped) {
    const Scene d = defaultScene();
    EXPECT_DOUBLE_EQ(d.run.equilibrate_ps, 1.8);
    EXPECT_DOUBLE_EQ(d.run.time_ps, 9.0);
    EXPECT_EQ(errorOf(json::object()), "");
    EXPECT_EQ(errorOf({{"engine", "smd"}}), ""); // 9 fs = 5 steps of 1.8 fs
    for (const json& run : {json{{"time_ps", 10}}, json{{"equilibrate_ps", 1}},
                            json{{"equilibrate_ps", 0.5}, {"thermostat_fs", 18}},
                            json{{"time_ps", 2}}, json{{"time_ps", 1000}},
                            json{{"equilibrate_ps", 20}},     // a scene from before, 9 fs rescales
                            json{{"equilibrate_ps", 0.005}}}) // one rescale, at its end
        EXPECT_EQ(errorOf({{"run", run}}), "") << run.dump();
    EXPECT_EQ(errorOf(json::object(), {"run.time_ps=0.5"}), "");
    // No equilibration is no interval at all; the thermostat interval then constrains nothing.
    EXPECT_EQ(errorOf({{"run", {{"equilibrate_ps", 0}}}}), "");
    EXPECT_EQ(errorOf({{"run", {{"equilibrate_ps", 0}, {"thermostat_fs", 7}}}}), "");
    // A sample interval longer than the run takes no sample: refused.
    EXPECT_NE(errorOf({{"run", {{"time_ps", 0.005}}}}).find("run.sample_fs: 9 fs is longer"),
              std::string::npos);
}

TEST(Scene, ThermostatAndRestartKeys) {
    const Scene d = defaultScene();
    EXPECT_DOUBLE_EQ(d.run.thermostat_fs, d.run.sample_fs); // default runs stay the same
    EXPECT_DOUBLE_EQ(d.output.restart_every_ps, 0.0);
    const Scene s =
        sceneFromJson(json::object(), "t", {"run.thermostat_fs=18", "output.restart_every_ps=1.8"});
    EXPECT_DOUBLE_EQ(s.run.thermostat_fs, 18.0);
    EXPECT_DOUBLE_EQ(s.output.restart_every_ps, 1.8);
    EXPECT_EQ(toJson(s)["run"]["thermostat_fs"], 18.0);
    EXPECT_EQ(toJson(s)["output"]["restart_every_ps"], 1.8);
    EXPECT_EQ(toJson(sceneFromJson(toJson(s), "again")), toJson(s));
    EXPECT_EQ(errorOf({{"run", {{"thermostat_fs", 0}}}}),
              "test.json: run.thermostat_fs: must be > 0, got 0");
    EXPECT_EQ(errorOf({{"output", {{"restart_every_ps", -1}}}}),
              "test.json: output.restart_every_ps: must be >= 0, got -1");
    EXPECT_DOUBLE_EQ(d.output.thermo_every_fs, 90.0); // about 100 rows unless told otherwise
    const Scene t = sceneFromJson(json::object(), "t", {"output.thermo_every_fs=45"});
    EXPECT_EQ(toJson(t)["output"]["thermo_every_fs"], 45.0);
    EXPECT_EQ(toJson(sceneFromJson(toJson(t), "again")), toJson(t));
    EXPECT_EQ(errorOf({{"output", {{"thermo_every_fs", -9}}}}),
              "test.json: output.thermo_every_fs: must be >= 0, got -9");
}

TEST(Scene, FloorsOfIntervals) {
    EXPECT_EQ(
        errorOf({{"run", {{"sample_fs", 1e-6}}}}),
        "test.json: run.sample_fs: must be >= 0.01 fs, got 1e-06: thermal motion hardly "
        "changes in so short an interval (bodies take >= 0.1 fs to cross σ or turn a radian)");
    EXPECT_EQ(
        errorOf({{"run", {{"thermostat_fs", 1e-6}}}}),
        "test.json: run.thermostat_fs: must be >= 0.01 fs, got 1e-06: thermal motion hardly "
        "changes in so short an interval (bodies take >= 0.1 fs to cross σ or turn a radian)");
}

TEST(Scene, TemperaturesAndMassesARunCanRepresent) {
    // How many terraces a temperature allows is DMD's to say (tests/cli/test_scene_check.cpp).
    EXPECT_EQ(errorOf({{"state", {{"temperature", 1e-10}}}}), "");
    EXPECT_EQ(errorOf({{"body", {{"mass", 1e-300}}}}),
              "test.json: body.mass: 1e-300 at state.temperature 1.4 makes a thermal body cross σ "
              "in 1.48093e-148 fs, faster than the 0.1 fs the time grid resolves");
    EXPECT_EQ(errorOf({{"body", {{"inertia", {1e-12, 1e-12, 0}}}}}),
              "test.json: body.inertia: 1e-12 at state.temperature 1.4 makes a thermal body turn "
              "one radian in 4.8795e-05 fs, faster than the 0.1 fs the time grid resolves");
    EXPECT_EQ(errorOf({{"state", {{"temperature", 1e12}}}}),
              "test.json: state.temperature: 1e+12 with body.mass = 18 makes a thermal body cross "
              "σ in 0.00074342 fs, faster than the 0.1 fs the time grid resolves");
    EXPECT_EQ(errorOf({{"state", {{"temperature", 1e308}}}}),
              "test.json: state.temperature: kT = T*·ε = inf kJ/mol is not a positive finite "
              "number");
    // A σ far below any body's reach is σ's fault at any mass (was blamed on body.mass).
    EXPECT_EQ(errorOf({{"potential", {{"sigma", 1e-300}}}}),
              "test.json: potential.sigma: 1e-300 Å with body.mass 18 makes a thermal body cross σ "
              "in 2.0702e-298 fs, faster than the 0.1 fs the time grid resolves");
}

TEST(Scene, SeedsBeyondTheRangeAreShownAsGiven) {
    // 2^63 parses as an unsigned integer: shown as it was written, not wrapped to -2^63.
    EXPECT_EQ(errorOf(json::parse(R"({"seed": 9223372036854775808})")),
              "test.json: seed: must be in [0, 4611686018427387904], got 9223372036854775808");
    EXPECT_EQ(errorOf(json::parse(R"({"seed": 18446744073709551615})")),
              "test.json: seed: must be in [0, 4611686018427387904], got 18446744073709551615");
}

TEST(Scene, BodiesLargerThanHalfTheBoxAreRefused) {
    // Sites ±50 Å apart in the 24.5 Å box of 256 dumbbells at ρ* 0.63: the body meets its own
    // images.
    const json dumbbell = {
        {"body",
         {{"kind", "linear"},
          {"sites",
           {{{"r", {0, 0, 50}}, {"mass", 14.0}, {"epsilon", 0.31}, {"sigma", 3.31}},
            {{"r", {0, 0, -50}}, {"mass", 14.0}, {"epsilon", 0.31}, {"sigma", 3.31}}}}}},
        {"potential", {{"kind", "sites"}, {"epsilon", 0.3101}, {"sigma", 3.31}}},
        {"state", {{"n", 256}, {"density", 0.63}, {"temperature", 2.06}}}};
    EXPECT_EQ(errorOf(dumbbell),
              "test.json: body.sites: span 100 Å, more than half the box edge 24.5167 Å (set by "
              "state.n and state.density): a body may reach at most L/2; use more bodies, a lower "
              "density or a smaller molecule");
    json small = dumbbell;
    small["body"]["sites"][0]["r"] = {0, 0, 6};
    small["body"]["sites"][1]["r"] = {0, 0, -6};
    EXPECT_EQ(errorOf(small), "");
}

// A measurement switch lives in the environment, not in the scene: a misspelt one is an error.
TEST(Scene, MeasurementSwitchesAreReadStrictly) {
    const MeasureSwitches none = parseMeasureSwitches("");
    EXPECT_TRUE(none.holdScreen && none.sortDmd && none.sortSmd);
    const MeasureSwitches all = parseMeasureSwitches("no-hold-screen,no-sort-dmd,no-sort-smd");
    EXPECT_FALSE(all.holdScreen || all.sortDmd || all.sortSmd);
    const MeasureSwitches one = parseMeasureSwitches("no-sort-smd");
    EXPECT_TRUE(one.holdScreen && one.sortDmd);
    EXPECT_FALSE(one.sortSmd);
    for (const char* bad :
         {"no-sort", "no-sort-dmd,", ",no-sort-dmd", "hold_screen", " no-sort-smd"})
        EXPECT_THROW(parseMeasureSwitches(bad), std::invalid_argument) << bad;
    try {
        parseMeasureSwitches("no-hold-screen,sort");
    } catch (const std::invalid_argument& e) {
        EXPECT_EQ(std::string(e.what()),
                  "TERRACE_MEASURE: unknown switch \"sort\" (known: no-hold-screen, no-sort-dmd, "
                  "no-sort-smd, separated by commas)");
    }
}

// The name goes into scene.json and summary.json: bytes that are not UTF-8 would stop them.
TEST(Scene, ANameThatIsNotUtf8IsRefused) {
    try {
        sceneFromJson({{"name", "ab\xff"
                                "c"}},
                      "test.json");
        FAIL() << "expected a SceneError";
    } catch (const SceneError& e) {
        EXPECT_EQ(std::string(e.what()), "test.json: name: must be valid UTF-8 text");
    }
    EXPECT_NO_THROW(sceneFromJson(nlohmann::json::object(), "test.json", {"name=dense-rods-ρ0.5"}));
}

TEST(Scene, ASetThatIsNotUtf8IsRefusedNamingTheByte) {
    // In a value or in a key: the bytes are shown escaped, not echoed.
    for (const auto& [set, shown] :
         {std::pair<std::string, std::string>{"name=ab\xff"
                                              "c",
                                              "--set name=ab\\xffc: not UTF-8 text (byte 0xff at "
                                              "character 8)"},
          {"dmd.\xc3=1", "--set dmd.\\xc3=1: not UTF-8 text (byte 0xc3 at character 5)"},
          {"dmd.queue=\"\xed\xa0\x80\"", // a surrogate, which UTF-8 never holds
           "--set dmd.queue=\"\\xed\\xa0\\x80\": not UTF-8 text (byte 0xed at character 12)"}}) {
        try {
            sceneFromJson(nlohmann::json::object(), "test.json", {set});
            ADD_FAILURE() << "expected a SceneError for " << shown;
        } catch (const SceneError& e) {
            EXPECT_EQ(std::string(e.what()), "test.json: " + shown + ": keys and values are UTF-8");
        }
    }
}

TEST(Scene, AFileThatIsNotUtf8IsRefusedNamingTheByte) {
    const auto path =
        std::filesystem::temp_directory_path() / ("terrace-latin1-" + std::to_string(::getpid()));
    std::ofstream(path) << "{\"name\": \"rods\",\n \"state\": {\"n\": 64, \"\xe9\": 1}}\n";
    try {
        loadScene(path.string());
        ADD_FAILURE() << "expected a SceneError";
    } catch (const SceneError& e) {
        EXPECT_EQ(std::string(e.what()),
                  path.string() + ": not UTF-8 text (byte 0xe9 at line 2, column 22): a scene file "
                                  "is JSON, which is UTF-8");
    }
    std::filesystem::remove(path);
}

TEST(Scene, Utf8IsCheckedAsUnicodeDefinesIt) {
    EXPECT_EQ(firstInvalidUtf8("plain ascii"), std::string::npos);
    EXPECT_EQ(firstInvalidUtf8("ρ € 𝄞"), std::string::npos); // two, three and four bytes
    EXPECT_EQ(firstInvalidUtf8("ab\xc0\xaf"), 2u);           // an overlong '/'
    EXPECT_EQ(firstInvalidUtf8("ab\xe2\x82"), 2u);           // cut short
    EXPECT_EQ(firstInvalidUtf8("\xf4\x90\x80\x80"), 0u);     // beyond U+10FFFF
    EXPECT_EQ(firstInvalidUtf8("a\x80"), 1u);                // a continuation alone
    EXPECT_EQ(printableBytes("a\xff"
                             "b\n"),
              "a\\xffb\\x0a");
}

TEST(Scene, ShippedModelScenesLoadAndRoundTrip) {
    for (const char* name : {"gay-berne-liquid", "dumbbell-liquid", "triatomic-liquid"}) {
        const Scene s = loadScene(
            (sourceDir() / "experiments/scenes" / (std::string(name) + ".json")).string());
        EXPECT_EQ(toJson(sceneFromJson(toJson(s), "x")), toJson(s)) << name;
    }
    const Scene gb = loadScene((sourceDir() / "experiments/scenes/gay-berne-liquid.json").string());
    EXPECT_DOUBLE_EQ(gb.potential.kappa, 3.0);
    EXPECT_DOUBLE_EQ(gb.potential.kappa_prime, 5.0);
    EXPECT_DOUBLE_EQ(gb.state.lattice_aspect, 3.0);
}

// body.sites: mass and principal moments from the sites (m = 14 at z = ±0.5 Å: I⊥ = 2·14·0.25),
// given values checked against them, the principal frame required.
TEST(Scene, SitesGiveMassAndInertiaAndMustBeInThePrincipalFrame) {
    const json dumbbell = {
        {"body",
         {{"kind", "linear"},
          {"sites",
           {{{"r", {0, 0, 0.5}}, {"mass", 14.0}, {"epsilon", 0.3}, {"sigma", 3.3}},
            {{"r", {0, 0, -0.5}}, {"mass", 14.0}, {"epsilon", 0.3}, {"sigma", 3.3}}}}}},
        {"potential", {{"kind", "sites"}, {"epsilon", 0.3}, {"sigma", 3.3}}},
        {"state", {{"density", 0.3}, {"temperature", 2.0}}}};
    const Scene s = sceneFromJson(dumbbell, "x");
    EXPECT_DOUBLE_EQ(s.body.mass, 28.0);
    EXPECT_DOUBLE_EQ(s.body.inertia[0], 7.0);
    EXPECT_DOUBLE_EQ(s.body.inertia[1], 7.0);
    ASSERT_EQ(s.body.sites.size(), 2u);

    json j = dumbbell;
    j["body"]["mass"] = 30.0;
    EXPECT_NE(errorOf(j).find("body.mass: 30 disagrees with the sites' total mass 28"),
              std::string::npos)
        << errorOf(j);
    j = dumbbell;
    j["body"]["inertia"] = {7.0, 7.0, 0.0};
    EXPECT_EQ(errorOf(j), "");
    j["body"]["inertia"] = {8.0, 8.0, 0.0};
    EXPECT_NE(errorOf(j).find("body.inertia: disagrees with the sites' principal moments"),
              std::string::npos);
    j = dumbbell;
    j["body"]["sites"][0]["r"] = {0, 0, 0.6};
    EXPECT_NE(errorOf(j).find("centre of mass"), std::string::npos) << errorOf(j);
    j = dumbbell;
    j["body"]["sites"][0]["r"] = {0.1, 0, 0.5};
    EXPECT_NE(errorOf(j).find("body.sites[0].r: a linear molecule's sites lie on the body z"),
              std::string::npos);
    j["body"]["sites"][1]["r"] = {-0.1, 0, -0.5}; // centred, but off the principal axes
    j["body"]["kind"] = "asymmetric";
    EXPECT_NE(errorOf(j).find("principal frame"), std::string::npos) << errorOf(j);
    j = dumbbell;
    j["body"]["sites"][1].erase("sigma");
    EXPECT_NE(errorOf(j).find("body.sites[1].sigma: missing"), std::string::npos);
    j = dumbbell;
    j["potential"]["kind"] = "rod-lj";
    EXPECT_NE(errorOf(j).find("body.sites: only meaningful for potential.kind sites"),
              std::string::npos);
    j = dumbbell;
    j["body"]["kind"] = "symmetric";
    EXPECT_NE(errorOf(j).find("body.kind: sites need linear"), std::string::npos);
    // Sites on one point have no moments: the sites are to blame, not body.inertia (not given).
    j = dumbbell;
    j["body"]["sites"][0]["r"] = {0, 0, 0};
    j["body"]["sites"][1]["r"] = {0, 0, 0};
    EXPECT_EQ(errorOf(j), "test.json: body.sites: a linear rotor needs I1 = I2 > 0 (I3 is "
                          "ignored); the sites give principal moments (0, 0, 0) g/mol Å²: place "
                          "them off a single point (a linear molecule: two or more sites apart "
                          "on z)");
}

TEST(Scene, GayBerneKeysBelongToGayBerneOnLinearBodies) {
    const json gb = {{"potential", {{"kind", "gay-berne"}, {"kappa", 4.4}, {"kappa_prime", 20.0}}}};
    const Scene s = sceneFromJson(gb, "x");
    EXPECT_DOUBLE_EQ(s.potential.kappa, 4.4);
    EXPECT_DOUBLE_EQ(s.potential.mu, 2.0);
    EXPECT_NE(errorOf({{"potential", {{"kappa", 3.0}}}}).find("potential.kappa: only meaningful"),
              std::string::npos);
    EXPECT_NE(errorOf({{"body", {{"kind", "asymmetric"}, {"inertia", {1, 2, 3}}}},
                       {"potential", {{"kind", "gay-berne"}}}})
                  .find("body.kind: gay-berne ellipsoids are uniaxial"),
              std::string::npos);
    EXPECT_NE(errorOf({{"potential", {{"kind", "gay-berne"}, {"zeta", 1.0}}}})
                  .find("potential.zeta: only meaningful for rod-lj"),
              std::string::npos);
    EXPECT_NE(errorOf({{"state", {{"lattice_aspect", 0.5}}}}).find("state.lattice_aspect"),
              std::string::npos);
}

TEST(Scene, AnalysisKeysAreReadCheckedAndWrittenOut) {
    const Scene s = sceneFromJson(
        {{"analysis",
          {{"rdf_max", 3.0}, {"rdf_every", 2}, {"follow_bodies", 0}, {"lags_per_level", 32}}}},
        "test.json");
    EXPECT_EQ(s.analysis.rdf_max, 3.0);
    EXPECT_EQ(s.analysis.rdf_every, 2);
    EXPECT_EQ(s.analysis.follow_bodies, 0);
    EXPECT_EQ(s.analysis.lags_per_level, 32);
    EXPECT_EQ(s.analysis.blocks, 8); // defaults where not given
    const Scene back = sceneFromJson(toJson(s), "round trip");
    EXPECT_EQ(toJson(back), toJson(s));
    EXPECT_EQ(errorOf({{"analysis", {{"lags_per_level", 15}}}})
                  .rfind("test.json: analysis.lags_per_level: 15 is odd", 0),
              0u);
    EXPECT_EQ(errorOf({{"analysis", {{"blocks", 1}}}}),
              "test.json: analysis.blocks: must be in [2, 10000], got 1");
    // More blocks than the samples allow are cut, and said so when they were asked for.
    const Scene cut = sceneFromJson(
        {{"analysis", {{"blocks", 10000}}}, {"run", {{"time_ps", 0.09}}}}, "test.json");
    ASSERT_EQ(cut.warnings.size(), 1u);
    EXPECT_EQ(cut.warnings[0], "analysis.blocks: 10000 asked for, but 10 samples (run.time_ps / "
                               "run.sample_fs) make at most 5 blocks of two samples: 5 are used");
    EXPECT_TRUE(sceneFromJson({{"run", {{"time_ps", 0.09}}}}, "test.json").warnings.empty());
    EXPECT_EQ(errorOf({{"analysis", {{"rdf_every", 0}}}}),
              "test.json: analysis.rdf_every: must be in [1, 1073741824], got 0");
    EXPECT_EQ(errorOf({{"analysis", {{"rdf_bin", 0.1}}}}),
              "test.json: analysis.rdf_bin: unknown key; did you mean analysis.rdf_bin_angstrom?");
    // g(r) reaches half the box at most (the default box, N 512 at ρ* 0.5, is 10.08 σ wide);
    // absent, rdf_max is 5 σ, or L/2 in a narrower box.
    EXPECT_EQ(errorOf({{"analysis", {{"rdf_max", 6.0}}}}),
              "test.json: analysis.rdf_max: 6 σ reaches past half the box, L/2 = 5.03968 σ "
              "(15.2954 Å): give at most 5.0396, or 0 for L/2");
    EXPECT_EQ(errorOf({{"analysis", {{"rdf_max", 5.0396}}}}), "");
    EXPECT_EQ(errorOf({{"analysis", {{"rdf_max", 0}}}}), "");
    const Scene small = sceneFromJson({{"state", {{"n", 64}}}}, "t");
    EXPECT_DOUBLE_EQ(small.analysis.rdf_max, 0.5 * small.boxLength() / small.potential.sigma);
    EXPECT_EQ(toJson(sceneFromJson(toJson(small), "again")), toJson(small));
    // The default box (N 512, ρ* 0.5) is 30.6 Å wide: a 20 Å bin leaves g(r) no bin.
    EXPECT_NE(errorOf({{"analysis", {{"rdf_bin_angstrom", 20.0}}}}).find("wider than half the box"),
              std::string::npos);
}

// output.thermo_every_fs: about 100 rows over production when absent (whole samples, at least
// one), off with an explicit 0, written out resolved so that scene.json says what was done.
TEST(Scene, ThermoIsOnByDefaultOnTheSampleGrid) {
    EXPECT_DOUBLE_EQ(sceneFromJson(json::object(), "t").output.thermo_every_fs, 90.0); // 1000/100
    EXPECT_DOUBLE_EQ(
        sceneFromJson({{"output", {{"thermo_every_fs", 0}}}}, "t").output.thermo_every_fs, 0.0);
    // 0.54 ps of 9 fs: 60 samples, fewer than 150: a row at every sample.
    EXPECT_DOUBLE_EQ(
        sceneFromJson(json::object(), "t", {"run.time_ps=0.54"}).output.thermo_every_fs, 9.0);
    // 2 ps (a partial last interval): 222 whole samples, a row every 2.
    EXPECT_DOUBLE_EQ(sceneFromJson(json::object(), "t", {"run.time_ps=2"}).output.thermo_every_fs,
                     18.0);
    // 250 samples of 4 fs: 2.5 rounds to 3 (round half away from zero), 84 rows.
    EXPECT_DOUBLE_EQ(sceneFromJson(json::object(), "t", {"run.time_ps=1", "run.sample_fs=4"})
                         .output.thermo_every_fs,
                     12.0);
    const Scene s = sceneFromJson(json::object(), "t", {"run.time_ps=90"});
    EXPECT_DOUBLE_EQ(s.output.thermo_every_fs, 900.0);
    EXPECT_EQ(toJson(s)["output"]["thermo_every_fs"], 900.0);
    EXPECT_EQ(toJson(sceneFromJson(toJson(s), "t")), toJson(s));
    // Under lj units the twin key turns it off as well.
    EXPECT_DOUBLE_EQ(sceneFromJson({{"units", "lj"}, {"output", {{"thermo_every", 0}}}}, "t")
                         .output.thermo_every_fs,
                     0.0);
}

// state.lattice: sc (default, not written out), fcc, bcc; lattice starts only; aspect 1 only off
// sc.
TEST(Scene, LatticeIsReadCheckedAndWrittenOut) {
    EXPECT_EQ(sceneFromJson(json::object(), "t").state.lattice, "sc");
    EXPECT_FALSE(toJson(sceneFromJson(json::object(), "t"))["state"].contains("lattice"));
    for (const char* kind : {"fcc", "bcc"}) {
        const Scene s = sceneFromJson({{"state", {{"lattice", kind}}}}, "t");
        EXPECT_EQ(s.state.lattice, kind);
        EXPECT_EQ(toJson(s)["state"]["lattice"], kind);
        EXPECT_EQ(toJson(sceneFromJson(toJson(s), "t")), toJson(s));
    }
    EXPECT_EQ(errorOf({{"state", {{"lattice", "fcc"}, {"lattice_aspect", 2}}}}),
              "test.json: state.lattice_aspect: 2 stretches the simple-cubic cell only; with "
              "state.lattice \"fcc\" give 1, or use state.lattice \"sc\"");
    EXPECT_EQ(errorOf({{"state", {{"lattice", "bcc"}, {"lattice_aspect", 1}}}}), "");
    EXPECT_NE(errorOf({{"state", {{"lattice", "hcp"}}}}).find("state.lattice"), std::string::npos);
    const json twoBodies = json::array({{{"r", {0, 0, 0}}}, {{"r", {5, 0, 0}}}});
    EXPECT_EQ(errorOf({{"body", {{"kind", "sphere"}}},
                       {"potential", {{"kind", "lj"}}},
                       {"state", {{"lattice", "fcc"}, {"particles", twoBodies}}}}),
              "test.json: state.lattice: applies to lattice starts only: state.particles gives "
              "each position");
}

} // namespace test_scene
