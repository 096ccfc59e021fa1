// cli/provenance.hpp: summary.json's record of what ran, kept small for a large explicit start.
#include "cli/provenance.hpp"
#include "core/scene.hpp"
#include <gtest/gtest.h>

namespace test_provenance {

using namespace terrace;
using json = nlohmann::json;

namespace {

Scene explicitStart(int n) {
    json particles = json::array();
    for (int i = 0; i < n; ++i)
        particles.push_back({{"r", {6.0 * (i % 10), 6.0 * ((i / 10) % 10), 6.0 * (i / 100)}}});
    return sceneFromJson({{"state", {{"particles", particles}}}}, "t");
}

} // namespace

TEST(Provenance, AFewExplicitBodiesAreCopiedWhole) {
    const json p = cli::provenance(explicitStart(int(cli::provenanceParticlesInline)));
    const json& particles = p.at("scene").at("state").at("particles");
    ASSERT_TRUE(particles.is_array());
    EXPECT_EQ(particles.size(), cli::provenanceParticlesInline);
}

TEST(Provenance, ManyAreNamedByCountChecksumAndFile) {
    const Scene a = explicitStart(500);
    const json whole = cli::provenance(a);
    const json& p = whole.at("scene").at("state").at("particles");
    ASSERT_TRUE(p.is_object());
    EXPECT_EQ(p.at("count"), 500);
    EXPECT_EQ(p.at("file"), "scene.json");
    EXPECT_EQ(p.at("crc64_of_json").get<std::string>().size(), 16u);
    // The checksum is of the bodies: one moved changes it, the same ones give the same.
    Scene b = a;
    b.state.particles[7].r.x() += 0.5;
    EXPECT_EQ(cli::provenance(a).at("scene").at("state").at("particles").at("crc64_of_json"),
              p.at("crc64_of_json"));
    EXPECT_NE(cli::provenance(b).at("scene").at("state").at("particles").at("crc64_of_json"),
              p.at("crc64_of_json"));
    EXPECT_LT(cli::provenance(a).dump().size(), 4000u);
}

} // namespace test_provenance
