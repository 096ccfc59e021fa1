// Reduced units (core/unit_system.hpp, core/scene_units.hpp): the scale of a model, conversions
// both ways, and scenes read under units lj: unit-free twins, unit-free keys, refusals, and the
// resolved scene written back and read again to the same numbers.
#include "core/scene.hpp"
#include "core/scene_units.hpp"
#include "core/unit_system.hpp"
#include "tests/core/scene_errors.hpp"
#include <gtest/gtest.h>
#include <random>

namespace test_unit_system {

using namespace terrace;
using nlohmann::json;

namespace {

/// Argon's usual LJ parameters: σ 3.405 Å, ε/k_B 119.8 K, m 39.948 g/mol.
constexpr double argonSigma = 3.405, argonEpsilon = 119.8 * units::kB, argonMass = 39.948;

using scene_tests::errorOf;

/// A small LJ liquid in real units, as experiments/scenes/lj-liquid.json (σ = ε = m = 1: τ is
/// the internal time unit, 100 fs).
json ljLiquid() {
    return json::parse(R"({"body": {"kind": "sphere", "mass": 1.0},
        "potential": {"kind": "lj", "epsilon": 1.0, "sigma": 1.0, "cutoff": [2.5, 3.0]},
        "state": {"n": 64, "density": 0.8, "temperature": 0.9},
        "run": {"equilibrate_ps": 0.9, "time_ps": 2.7, "sample_fs": 9.0, "thermostat_fs": 9.0}})");
}

} // namespace

TEST(UnitSystem, RealIsTheIdentity) {
    const UnitSystem u = UnitSystem::real();
    EXPECT_FALSE(u.reduced());
    for (Dimension d : {Dimension::TimeFs, Dimension::TimePs, Dimension::Length, Dimension::Energy,
                        Dimension::Velocity, Dimension::AngularVelocity})
        EXPECT_EQ(u.scale(d), 1.0);
    EXPECT_EQ(u.time(2.7), 2.7);
    EXPECT_EQ(u.energy(-925.3), -925.3);
    EXPECT_EQ(u.temperature(2.0), units::kelvin(2.0));
    EXPECT_EQ(u.pressure(0.25), units::bar(0.25));
    EXPECT_EQ(u.diffusion(0.5), 0.5);
}

TEST(UnitSystem, ArgonsTauIsTwoPicoseconds) {
    const UnitSystem u = UnitSystem::lj(argonSigma, argonEpsilon, argonMass);
    // τ = σ sqrt(m/ε) in SI: m = 39.948e-3/N_A kg, ε = 119.8 k_B J.
    const double kB = 1.380649e-23, NA = 6.02214076e23;
    const double tauSI = argonSigma * 1e-10 * std::sqrt(argonMass * 1e-3 / NA / (119.8 * kB));
    EXPECT_NEAR(u.tauFs(), tauSI * 1e15, 1e-6 * tauSI * 1e15);
    EXPECT_NEAR(u.tauPs(), 2.1565, 1e-3); // the textbook 2.16 ps
    // k_B T in ε: 119.8 K is T* = 1; a pressure of ε/σ³ is P* = 1.
    EXPECT_NEAR(u.temperatureOfKelvin(119.8), 1.0, 1e-12);
    EXPECT_NEAR(u.temperature(argonEpsilon), 1.0, 1e-15);
    EXPECT_NEAR(u.pressure(argonEpsilon / std::pow(argonSigma, 3)), 1.0, 1e-14);
    // σ²/τ in Å²/ps, and one collision per τ.
    EXPECT_NEAR(u.diffusion(argonSigma * argonSigma / u.tauPs()), 1.0, 1e-14);
    EXPECT_NEAR(u.rate(1.0 / u.tauPs()), 1.0, 1e-14);
    EXPECT_NEAR(u.time(u.tauPs()), 1.0, 1e-15);
    EXPECT_STREQ(u.timeSuffix(), "tau");
}

TEST(UnitSystem, AValueReadInReducedUnitsIsWrittenBackExactly) {
    const UnitSystem u = UnitSystem::lj(argonSigma, argonEpsilon, argonMass);
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> given(1e-3, 1e3);
    for (Dimension d : {Dimension::TimeFs, Dimension::TimePs, Dimension::Length, Dimension::Energy,
                        Dimension::Velocity, Dimension::AngularVelocity})
        for (int k = 0; k < 2000; ++k) {
            const double x = given(rng);
            const double real = u.toReal(x, d);
            EXPECT_EQ(u.toReal(u.fromReal(real, d), d), real);
        }
}

TEST(SceneUnits, LjReadsUnitFreeTwinsInTauAndNamedKeysInTheirUnits) {
    json j = ljLiquid();
    j["units"] = "lj";
    j["run"] = {{"equilibrate", 9}, {"time", 27}, {"sample", 0.09}, {"thermostat", 0.09}};
    j["smd"] = {{"dt", 0.002}};
    j["analysis"] = {{"rdf_bin", 0.05}};
    j["output"] = {{"thermo_every_fs", 90.0}}; // a named unit is read in it, under lj too
    const Scene s = sceneFromJson(j, "test.json");
    EXPECT_EQ(s.units, "lj");
    EXPECT_EQ(s.run.time_ps, 27 * 0.1);
    EXPECT_EQ(s.run.equilibrate_ps, 0.9);
    EXPECT_EQ(s.run.sample_fs, 9.0);
    EXPECT_EQ(s.smd["dt_fs"], 0.2);
    EXPECT_EQ(s.analysis.rdf_bin_angstrom, 0.05);
    EXPECT_EQ(s.output.thermo_every_fs, 90.0);
    // The same scene in real units reads to the same numbers.
    const Scene r =
        sceneFromJson(ljLiquid(), "test.json", {"smd.dt_fs=0.2", "output.thermo_every_fs=90"});
    EXPECT_EQ(r.run.time_ps, s.run.time_ps);
    EXPECT_EQ(r.run.sample_fs, s.run.sample_fs);
    EXPECT_EQ(r.units, "real");
}

TEST(SceneUnits, TwinsAreUnknownUnderRealAndRefusedInPairs) {
    json j = ljLiquid();
    j["run"]["time"] = 27;
    // Under real the twins do not exist: unknown keys, naming the key with the unit.
    EXPECT_EQ(errorOf(j), "test.json: run.time: unknown key; did you mean run.time_ps?");
    j["units"] = "lj";
    const std::string both = errorOf(j);
    EXPECT_NE(both.find("run.time: and run.time_ps set the same value: give one of them"),
              std::string::npos)
        << both;
    // An override of either twin replaces the one the scene gives.
    const Scene s = sceneFromJson(ljLiquid(), "test.json", {"units=lj", "run.time=54"});
    EXPECT_EQ(s.run.time_ps, 54 * 0.1);
    json given = ljLiquid();
    given["units"] = "lj";
    given["run"].erase("time_ps");
    given["run"]["time"] = 27;
    EXPECT_EQ(sceneFromJson(given, "test.json", {"run.time_ps=1.8"}).run.time_ps, 1.8);
    EXPECT_EQ(errorOf(ljLiquid(), {"units=SI"}),
              "test.json: units: must be one of real | lj, got \"SI\"");
}

TEST(SceneUnits, ARefusalUnderLjGivesTheScale) {
    const std::string e = errorOf(ljLiquid(), {"units=lj", "run.sample=900"});
    EXPECT_NE(e.find("run.sample_fs: 90000 fs is longer than run.time_ps"), std::string::npos) << e;
    EXPECT_NE(e.find("(units lj: τ = 100 fs, σ = 1 Å, ε = 1 kJ/mol;"), std::string::npos) << e;
}

TEST(SceneUnits, UnitFreeKeysAreReducedAndTheSceneRoundTrips) {
    json j = ljLiquid();
    j["units"] = "lj";
    j["body"]["mass"] = argonMass;
    j["potential"]["sigma"] = argonSigma;
    j["potential"]["epsilon"] = argonEpsilon;
    j["state"] = json::parse(R"({"temperature": 1.2, "density": 0.001, "particles": [
        {"r": [0.1, 0.2, 0.3], "v": [1.5, -0.5, 0.25]},
        {"r": [3.7, 4.1, 2.9], "v": [-1.5, 0.5, -0.25]}]})");
    j["dmd"] = {{"levels", {-0.9, -0.3}}, {"values", {-0.6, -0.1, 0.0}}};
    j["run"] = {{"equilibrate", 0}, {"time", 1.3}, {"sample", 0.013}};
    const UnitSystem u = UnitSystem::lj(argonSigma, argonEpsilon, argonMass);
    const Scene s = sceneFromJson(j, "test.json");
    ASSERT_EQ(s.state.particles.size(), 2u);
    EXPECT_EQ(s.state.particles[1].r.x(), 3.7 * argonSigma);
    EXPECT_EQ(s.state.particles[0].v.x(), 1.5 * (argonSigma / u.tauPs()));
    EXPECT_EQ(s.dmd["levels"][0].get<double>(), -0.9 * argonEpsilon);
    EXPECT_EQ(s.run.time_ps, 1.3 * u.tauPs());
    // Written back: units lj, the unit-free keys in reduced units again, exactly; the named
    // keys in their units. Read again, the same scene.
    const json back = toJson(s);
    EXPECT_EQ(back["units"], "lj");
    EXPECT_EQ(back["state"]["particles"][1]["r"][0].get<double>(), 3.7);
    EXPECT_EQ(back["state"]["particles"][0]["v"][2].get<double>(), 0.25);
    EXPECT_EQ(back["dmd"]["levels"][1].get<double>(), -0.3);
    EXPECT_EQ(back["run"]["time_ps"].get<double>(), 1.3 * u.tauPs());
    const Scene again = sceneFromJson(back, "scene.json");
    EXPECT_EQ(toJson(again), back);
    EXPECT_EQ(again.state.particles[0].v, s.state.particles[0].v);
    // Under real, scene.json is as it was before units existed: no "units" key.
    EXPECT_FALSE(toJson(sceneFromJson(ljLiquid(), "test.json")).contains("units"));
}

} // namespace test_unit_system
