// Rods among spheres in both engines (validation tier), both under the same CSVR heat bath: with
// small terraces (ΔV = kT/8) DMD's configurational U per body and virial pressure, on its own
// configurations, agree with SMD's within their error bars, which resolve U/N to 1 %. At kT/2 the
// same comparison differs by several error bars (rods-in-solvent.json, 9 ps at N 512: U/N
// −7.44 ± 0.01 kJ/mol against SMD's −7.25 ± 0.02), so the test can tell the two apart.
#include "tests/dmd/engine_agreement.hpp"
#include "tests/dmd/rod_mixture_engines.hpp"
#include <cstdio>
#include <gtest/gtest.h>

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
    // Four combined standard errors, as for the mixture of spheres (test_mixture_agreement.cpp).
    const double uErr = std::hypot(d.u.err, m.u.err), pErr = std::hypot(d.p.err, m.p.err);
    EXPECT_LT(std::abs(d.u.mean - m.u.mean), 4.0 * uErr)
        << "U/N: DMD " << d.u.mean << " ± " << d.u.err << ", SMD " << m.u.mean << " ± " << m.u.err;
    EXPECT_LT(std::abs(d.p.mean - m.p.mean), 4.0 * pErr)
        << "P: DMD " << d.p.mean << " ± " << d.p.err << ", SMD " << m.p.mean << " ± " << m.p.err;
    EXPECT_LT(uErr, 0.01 * std::abs(m.u.mean));
    std::printf("U/N: DMD %.5f ± %.5f, SMD %.5f ± %.5f kJ/mol; P: DMD %.6f ± %.6f, SMD %.6f ± "
                "%.6f kJ/mol/Å³\n",
                d.u.mean, d.u.err, m.u.mean, m.u.err, d.p.mean, d.p.err, m.p.mean, m.p.err);
}

} // namespace test_rod_mixture_agreement
