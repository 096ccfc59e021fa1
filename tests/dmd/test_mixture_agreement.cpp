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
    // The terracing's own bias of the configurational estimators at ΔV = kT/8 is far below the
    // error bars here (results/README.md measures it at kT/2 on the LJ liquid: −0.03 ε per body).
    expectAgreement(d, m);
}

} // namespace test_mixture_agreement
