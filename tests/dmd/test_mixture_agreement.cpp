// A binary Lennard-Jones mixture in both engines (validation tier), both under the same CSVR
// heat bath: with small terraces (ΔV = kT/8) DMD's configurational U per body and virial
// pressure, on its own configurations, agree with SMD's within their error bars, and the error
// bars resolve U/N to 1 %.
#include "tests/dmd/engine_agreement.hpp"
#include "tests/dmd/mixture_engines.hpp"
#include <cstdio>
#include <gtest/gtest.h>
#include <vector>

namespace test_mixture_agreement {

using namespace terrace;

namespace {

using namespace terrace::mixture_tests;
using namespace terrace::agreement_tests;

Scene mixtureScene(int n, double density, double temperature, double dVInKT) {
    nlohmann::json j = mixtureDocument(n, density, temperature, dVInKT);
    // Both engines at the one temperature: after rescaled equilibration alone, NVE production
    // settles a few per cent apart in T (the terraced and the continuous energy relax
    // differently from the lattice), which moves U and P by more than their errors.
    j["run"] = {{"heat_bath", {{"kind", "csvr"}, {"tau_fs", 100.0}}}};
    return sceneFromJson(j, "mixture");
}

} // namespace

TEST(Mixture, DmdWithSmallTerracesAgreesWithSmdOnUAndPressure) {
    const Scene s = mixtureScene(256, 0.8, 2.0, 0.125);
    const MixtureSystem start = mixtureSystem(s);
    const double volume = start.box.volume();
    DmdMixture dmdEngine(start, s);
    SmdMixture smdEngine(start, s);
    const Means d = sampleMeans(dmdEngine, s.kT(), volume, start.size());
    const Means m = sampleMeans(smdEngine, s.kT(), volume, start.size());
    // Four combined standard errors: a true difference of that size fails; the terracing's own
    // bias of the configurational estimators at ΔV = kT/8 is far below the error bars here
    // (results/README.md measures it at kT/2 on the LJ liquid: −0.03 ε per body).
    const double uErr = std::hypot(d.u.err, m.u.err), pErr = std::hypot(d.p.err, m.p.err);
    EXPECT_LT(std::abs(d.u.mean - m.u.mean), 4.0 * uErr)
        << "U/N: DMD " << d.u.mean << " ± " << d.u.err << ", SMD " << m.u.mean << " ± " << m.u.err;
    EXPECT_LT(std::abs(d.p.mean - m.p.mean), 4.0 * pErr)
        << "P: DMD " << d.p.mean << " ± " << d.p.err << ", SMD " << m.p.mean << " ± " << m.p.err;
    // The error bars resolve the mixture: U/N to better than 1 %.
    EXPECT_LT(uErr, 0.01 * std::abs(m.u.mean));
    std::printf("U/N: DMD %.5f ± %.5f, SMD %.5f ± %.5f kJ/mol; P: DMD %.6f ± %.6f, SMD %.6f ± "
                "%.6f kJ/mol/Å³\n",
                d.u.mean, d.u.err, m.u.mean, m.u.err, d.p.mean, d.p.err, m.p.mean, m.p.err);
}

} // namespace test_mixture_agreement
