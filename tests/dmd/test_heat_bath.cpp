// The heat baths (run.heat_bath, core/heat_bath.hpp) in both engines (validation tier): the
// paper's rods (linear rotors, f = 5N or 5N − 3) at N 216, ρ* 0.5, T* 1.4 on the smoothed model,
// melted from the lattice by the bath itself, then sampled every 9 fs:
//  - the kinetic energy is canonical: ⟨K⟩ = (f/2) kT and Var(K) = (f/2)(kT)², each within 4 of
//    its block errors (20 blocks), and the variance's error is below 10 % of it, so that a wrong
//    f (the rotations' 2, the momentum's 3) or a non-canonical bath (a plain rescale has
//    Var(K) ≈ 0; Berendsen's is too narrow) fails;
//  - the effective energy H + (energy the bath removed) is conserved: to round-off in DMD (the
//    bath's exchange is booked exactly and the flow conserves H), and in SMD no worse than the
//    NVE run's own energy error at the same dt;
//  - with no bath the engines are the NVE ones: the same bodies after the same time.
#include "analysis/canonical_kinetic.hpp"
#include "core/initial_state.hpp"
#include "core/rod_potential.hpp"
#include "core/smoothed_potential.hpp"
#include "dmd/scene_engine.hpp"
#include "smd/scene_engine.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <string>
#include <vector>

namespace test_heat_bath {

using namespace terrace;

namespace {

using Model = Smoothed<RodPotential>;
using DmdRods = dmd::SceneEngine<LinearRotor, Model>;
using SmdRods = smd::SceneEngine<LinearRotor, Model>;

constexpr double sampleFs = 9.0, meltPs = 3.0;
constexpr int blocks = 20;

Scene rodScene(const std::string& engine, const std::string& bath) {
    std::vector<std::string> sets{"state.n=216", "engine=" + engine};
    if (!bath.empty()) sets.push_back("run.heat_bath=" + bath);
    return loadScene(std::string(TERRACE_SOURCE_DIR) + "/experiments/scenes/dense-rods.json", sets);
}

Model model(const Scene& s) {
    return {rodPotential(s), sceneCutoff(s)};
}

struct Series {
    std::vector<double> kinetic, effective;
};

/// Melted by the bath for meltPs, then `ps` of samples every 9 fs.
template <class E> Series sample(E& engine, double ps) {
    const double dt = units::fromFs(sampleFs);
    const long melt = std::lround(meltPs * 1000.0 / sampleFs);
    const long samples = std::lround(ps * 1000.0 / sampleFs);
    Series s;
    for (long k = 1; k <= melt + samples; ++k) {
        engine.advanceTo(double(k) * dt);
        if (k <= melt) continue;
        const double kin = engine.kineticEnergy();
        s.kinetic.push_back(kin);
        s.effective.push_back(kin + engine.potentialEnergy() + engine.thermostatEnergy());
    }
    return s;
}

/// As a run's statistics take them (cli/sample_statistics.hpp): blocks of K and of
/// (K − (f/2) kT)² laid over the series.
analysis::CanonicalKinetic canonical(const std::vector<double>& kinetic, int f, double kT) {
    const long n = long(kinetic.size());
    analysis::FixedBlocks k(n, blocks), shiftedSquares(n, blocks);
    for (const double x : kinetic) {
        const double d = x - analysis::canonicalKineticMean(f, kT);
        k.add(x), shiftedSquares.add(d * d);
    }
    return analysis::canonicalKinetic(k, shiftedSquares, f, kT);
}

void expectCanonical(const Series& s, int f, double kT, const char* what) {
    const auto c = canonical(s.kinetic, f, kT);
    std::printf("%s: f %d, <K> %.4f ± %.4f (canonical %.4f, %+.2f errors), Var(K) %.3f ± %.3f "
                "(canonical %.3f, %+.2f errors), %zu samples\n",
                what, f, c.mean.mean, c.mean.err, c.canonicalMean, c.meanDeviation(),
                c.variance.mean, c.variance.err, c.canonicalVariance, c.varianceDeviation(),
                s.kinetic.size());
    EXPECT_LT(std::abs(c.meanDeviation()), 4.0) << what;
    EXPECT_LT(std::abs(c.varianceDeviation()), 4.0) << what;
    EXPECT_LT(c.variance.err, 0.1 * c.canonicalVariance) << what << ": too few samples to tell";
}

double maxDeviation(const std::vector<double>& e) {
    double worst = 0.0;
    for (const double x : e)
        worst = std::max(worst, std::abs(x - e.front()));
    return worst;
}

template <class E>
Series runBath(const std::string& engineName, const std::string& bath, double ps,
               const char* what) {
    const Scene scene = rodScene(engineName, bath);
    E engine(buildInitialState<LinearRotor>(scene, model(scene)), scene);
    const Series s = sample(engine, ps);
    const HeatBath b = heatBathOf(scene);
    expectCanonical(s, heatBathDof(b.kind, LinearRotor::rotationalDof * 216, 216), scene.kT(),
                    what);
    return s;
}

} // namespace

TEST(HeatBath, AndersenInDmdIsCanonical) {
    const Series s = runBath<DmdRods>("dmd", R"({"kind":"andersen","rate_per_ps":20})", 25.0,
                                      "DMD Andersen 20/ps");
    // Booked exactly: what the bath takes is what H loses.
    EXPECT_LT(maxDeviation(s.effective), 1e-9 * std::abs(s.effective.front()) + 1e-9);
}

TEST(HeatBath, CsvrInDmdIsCanonical) {
    const Series s = runBath<DmdRods>("dmd", R"({"kind":"csvr","tau_fs":50})", 25.0,
                                      "DMD CSVR 50 fs (rescaled every 9 fs)");
    EXPECT_LT(maxDeviation(s.effective), 1e-9 * std::abs(s.effective.front()) + 1e-9);
}

TEST(HeatBath, AndersenInSmdIsCanonical) {
    runBath<SmdRods>("smd", R"({"kind":"andersen","rate_per_ps":20})", 25.0, "SMD Andersen 20/ps");
}

TEST(HeatBath, CsvrInSmdIsCanonicalAndConservesItsEffectiveEnergy) {
    const Series bath =
        runBath<SmdRods>("smd", R"({"kind":"csvr","tau_fs":50})", 25.0, "SMD CSVR 50 fs");
    // The NVE run from the same start, over as long: its energy error bounds the bath's.
    const Scene scene = rodScene("smd", "");
    SmdRods engine(buildInitialState<LinearRotor>(scene, model(scene)), scene);
    const Series nve = sample(engine, 25.0);
    const double bathError = maxDeviation(bath.effective), nveError = maxDeviation(nve.effective);
    std::printf("SMD at 1.8 fs: max |ΔE_eff| %.4g kJ/mol under CSVR, max |ΔH| %.4g under NVE\n",
                bathError, nveError);
    EXPECT_LT(bathError, 2.0 * nveError);
}

TEST(HeatBath, NoneIsNve) {
    for (const std::string engineName : {"dmd", "smd"}) {
        const Scene plain = rodScene(engineName, ""), none = rodScene(engineName, "none");
        EXPECT_FALSE(heatBathOf(none).on());
        EXPECT_EQ(toJson(plain).dump(), toJson(none).dump()) << "the resolved scene changed";
        auto run = [&](const Scene& s) {
            if (engineName == "dmd") {
                DmdRods e(buildInitialState<LinearRotor>(s, model(s)), s);
                e.advanceTo(units::fromPs(0.9));
                return std::make_pair(e.snapshot().position, e.thermostatEnergy());
            }
            SmdRods e(buildInitialState<LinearRotor>(s, model(s)), s);
            e.advanceTo(units::fromPs(0.9));
            return std::make_pair(e.snapshot().position, e.thermostatEnergy());
        };
        const auto a = run(plain), b = run(none);
        EXPECT_EQ(a.first, b.first) << engineName;
        EXPECT_EQ(b.second, 0.0) << engineName;
    }
}

// An engine rebuilt from another's bodies and checkpoint goes on with the bath's stream where it
// stood: over the next 90 fs (about 100 Andersen collisions at 5/ps, or 50 CSVR steps) it follows
// the engine that went on, to round-off; a stream started afresh would part at once.
TEST(HeatBath, TheCheckpointCarriesTheBath) {
    for (const std::string engineName : {"dmd", "smd"})
        for (const std::string bath :
             {R"({"kind":"andersen","rate_per_ps":5})", R"({"kind":"csvr","tau_fs":90})"}) {
            const Scene scene = rodScene(engineName, bath);
            auto check = [&]<class E>(E& a) {
                a.advanceTo(units::fromFs(180.0));
                auto released = E(a.system(), scene, a.checkpoint());
                E& b = released;
                for (E* e : {&a, &b})
                    e->advanceTo(units::fromFs(270.0));
                EXPECT_NEAR(b.kineticEnergy(), a.kineticEnergy(), 1e-8 * a.kineticEnergy())
                    << engineName << " " << bath;
                EXPECT_NEAR(b.thermostatEnergy(), a.thermostatEnergy(),
                            1e-8 * a.kineticEnergy() + 1e-9)
                    << engineName << " " << bath;
                EXPECT_NE(a.thermostatEnergy(), 0.0);
            };
            if (engineName == "dmd") {
                DmdRods a(buildInitialState<LinearRotor>(scene, model(scene)), scene);
                check(a);
            } else {
                SmdRods a(buildInitialState<LinearRotor>(scene, model(scene)), scene);
                check(a);
            }
        }
}

} // namespace test_heat_bath
