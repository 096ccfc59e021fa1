// Scene parsing: defaults equal the paper's dense rods, every key validated, overrides by path.
#include "core/scene.hpp"
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>

using namespace terrace;
using nlohmann::json;

namespace {

std::string errorOf(const json& j, const std::vector<std::string>& overrides = {}) {
    try {
        sceneFromJson(j, "test.json", overrides);
    } catch (const SceneError& e) {
        return e.what();
    }
    return "";
}

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

TEST(Scene, ShippedDenseRodsEqualsTheBuiltInDefault) {
    const Scene file = loadScene((sourceDir() / "experiments/scenes/dense-rods.json").string());
    EXPECT_EQ(toJson(file), toJson(defaultScene()));
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
    EXPECT_EQ(errorOf({{"bogus", 1}}), "test.json: bogus: unknown key");
    EXPECT_EQ(errorOf({{"dmd", {{"dv", 1}}}}), "test.json: dmd.dv: unknown key");
    EXPECT_EQ(errorOf({{"state",
                        {{"particles",
                          json::array({{{"r", {0, 0, 0}}, {"x", 1}}, {{"r", {1, 0, 0}}}})}}}}),
              "test.json: state.particles[0].x: unknown key");
}

TEST(Scene, BadValuesAreNamed) {
    EXPECT_NE(errorOf({{"dmd", {{"dV", 0}}}}).find("dmd.dV: must be > 0"), std::string::npos);
    EXPECT_NE(errorOf({{"dmd", {{"dV", -1}}}}).find("dmd.dV"), std::string::npos);
    EXPECT_NE(errorOf({{"smd", {{"dt_fs", 0}}}}).find("smd.dt_fs"), std::string::npos);
    EXPECT_NE(errorOf({{"state", {{"n", 1}}}}).find("state.n"), std::string::npos);
    EXPECT_NE(errorOf({{"state", {{"temperature", 0}}}}).find("state.temperature"),
              std::string::npos);
    EXPECT_NE(errorOf({{"state", {{"density", "high"}}}}).find("must be a number"),
              std::string::npos);
    EXPECT_NE(errorOf({{"engine", "lammps"}}).find("engine: must be one of dmd | smd"),
              std::string::npos);
    EXPECT_NE(errorOf({{"dmd", {{"queue", "tree"}}}}).find("dmd.queue"), std::string::npos);
    EXPECT_NE(errorOf({{"smd", {{"r_l", 3.0}, {"r_u", 2.5}}}}).find("smd.r_u"), std::string::npos);
    EXPECT_NE(errorOf({{"dmd", {{"levels", {1.0, 0.5}}}}}).find("strictly increasing"),
              std::string::npos);
    EXPECT_NE(errorOf({{"potential", {{"kind", "lj"}}}}).find("potential.kind"), std::string::npos);
    EXPECT_NE(
        errorOf({{"body", {{"kind", "symmetric"}, {"inertia", {1, 2, 3}}}}}).find("body.inertia"),
        std::string::npos);
    EXPECT_NE(errorOf(json::array()).find("JSON object"), std::string::npos);
}

TEST(Scene, OverridesByDottedPath) {
    const Scene s = sceneFromJson(json::object(), "t",
                                  {"dmd.dV=0.125", "engine=smd", "dmd.queue=heap", "name=x y"});
    EXPECT_DOUBLE_EQ(s.dmd.dV, 0.125);
    EXPECT_EQ(s.engine, "smd");
    EXPECT_EQ(s.dmd.queue, "heap");
    EXPECT_EQ(s.name, "x y");
    EXPECT_NE(errorOf(json::object(), {"dmd.dV"}).find("key.path=value"), std::string::npos);
    EXPECT_NE(errorOf(json::object(), {"dmd.nope=1"}).find("dmd.nope: unknown key"),
              std::string::npos);
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
