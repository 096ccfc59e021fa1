// Rods among spheres in both engines (validation tier), both under the same CSVR heat bath: with
// small terraces (ΔV = kT/8) DMD's configurational U per body and virial pressure, on its own
// configurations, agree with SMD's within their error bars, which resolve U/N to 1 %; and each
// part of the kinetic energy comes to its share of kT in both engines. At kT/2 the
// same comparison differs by several error bars (rods-in-solvent.json, 9 ps at N 512: U/N
// −7.44 ± 0.01 kJ/mol against SMD's −7.25 ± 0.02), so the test can tell the two apart.
#include "tests/dmd/engine_agreement.hpp"
#include "tests/dmd/rod_mixture_engines.hpp"
#include <array>
#include <cstdio>
#include <gtest/gtest.h>
#include <utility>

namespace test_rod_mixture_agreement {

using namespace terrace;
using namespace terrace::rod_mixture_tests;
using namespace terrace::agreement_tests;

TEST(RodsAmongSpheres, DmdWithSmallTerracesAgreesWithSmdOnUAndPressure) {
    nlohmann::json j = rodsAmongSpheres(256, 0.5, 1.4, 0.125);
    j["run"] = {{"heat_bath", {{"kind", "csvr"}, {"tau_fs", 100.0}}}};
    const Scene s = sceneFromJson(j, "rods-among-spheres");
    const RodSystem start = rodSystem(s);
    const double volume = start.box.volume();
    DmdRods dmdEngine(start, s);
    SmdRods smdEngine(start, s);
    const Means d = sampleMeans(dmdEngine, s.kT(), volume, start.size());
    const Means m = sampleMeans(smdEngine, s.kT(), volume, start.size());
    expectAgreement(d, m);
}

// Under CSVR each part of the kinetic energy comes to its share of kT: ⟨m v²⟩/3 for each species'
// translation and ⟨I ω²⟩/2 for the rods' rotation (two components each). The bath aims at ½ f kT
// with f = 3N + 2N_rod − 3; counting the spheres' missing rotations (f = 5N − 3) would put every
// part a quarter too hot here. Rotation meets translation in rod–rod collisions alone (a sphere
// exerts no torque), so the rods' rotation relaxes slowly: with half the bodies rods, 2 ps to
// forget the start, then 20 ps of samples, each share to ~2 % (the shares measured: 0.97 to 1.004).
TEST(RodsAmongSpheres, EachPartOfTheKineticEnergyComesToItsShareOfKTInBothEngines) {
    nlohmann::json j = rodsAmongSpheres(512, 0.5, 1.4, 0.5, 1.8);
    j["species"][0]["fraction"] = 0.5; // half rods: their rotation relaxes faster among more rods
    j["species"][1]["fraction"] = 0.5;
    j["run"] = {{"heat_bath", {{"kind", "csvr"}, {"tau_fs", 100.0}}}};
    const Scene s = sceneFromJson(j, "rods-among-spheres");
    const auto shares = [&](auto& e) {
        std::array<double, 3> sum{}; // rods' and spheres' translation, rods' rotation, in kT
        int samples = 0;
        for (int k = 1; k <= 550; ++k) {
            e.advanceTo(units::fromFs(40.0 * k));
            if (k <= 50) continue; // 2 ps to forget the lattice
            const RodSystem now = e.system();
            std::array<double, 3> part{};
            std::array<int, 2> count{};
            for (const auto& b : now.bodies) {
                part[b.species] += bodyMass<SpeciesRotor>(b, now.body) * b.v.squaredNorm() / 3.0;
                if (b.species == 0) part[2] += SpeciesRotor::rotationalKinetic(b, now.body);
                ++count[b.species];
            }
            sum[0] += part[0] / count[0] / s.kT();
            sum[1] += part[1] / count[1] / s.kT();
            sum[2] += part[2] / count[0] / s.kT();
            ++samples;
        }
        for (double& x : sum)
            x /= samples;
        return sum;
    };
    const RodSystem start = rodSystem(s);
    DmdRods dmdEngine(start, s);
    SmdRods smdEngine(start, s);
    for (const auto& [engine, share] :
         {std::pair{"dmd", shares(dmdEngine)}, std::pair{"smd", shares(smdEngine)}}) {
        std::printf("%s: rods' translation %.4f kT, spheres' %.4f kT, rods' rotation %.4f kT\n",
                    engine, share[0], share[1], share[2]);
        for (const double x : share)
            EXPECT_NEAR(x, 1.0, 0.1) << engine;
    }
}

} // namespace test_rod_mixture_agreement
