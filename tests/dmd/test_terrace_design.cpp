// Terrace designs (dmd/terrace_design.hpp) as pure functions, the per-terrace energies they feed
// to the engine (dmd/terrace_levels.hpp), and their scene keys. The physics checks are
// independent of the code under test where they can be: radii inverted from the profile, the
// second virial coefficient by a radial quadrature of its own, Jensen's inequality.
#include "core/initial_state.hpp"
#include "core/lj_potential.hpp"
#include "core/rod_potential.hpp"
#include "core/scene.hpp"
#include "core/smoothed_potential.hpp"
#include "core/sphere.hpp"
#include "dmd/scene_engine.hpp"
#include "dmd/settings.hpp"
#include "dmd/terrace_design.hpp"
#include "dmd/testing.hpp"
#include <cmath>
#include <gtest/gtest.h>
#include <numbers>
#include <tuple>
#include <vector>

namespace test_terrace_design {

using terrace::dmd::testing::Probe;

using namespace terrace;
using namespace terrace::dmd;

namespace {

// LJ spheres (ε = 1 kJ/mol, σ = 3 Å) smoothed over [2.5, 3.0]σ, at kT = ε.
const Smoothed<LJPotential> lj{LJPotential{1.0, 3.0}, SmoothedCutoff{7.5, 9.0}};
// The paper's rods, smoothed as in its scenes, at T* = 1.4.
const Smoothed<RodPotential> rods{RodPotential{3.0, 3.035, 1.0},
                                  SmoothedCutoff{2.5 * 3.035, 3.0 * 3.035}};
constexpr double ljKT = 1.0, rodKT = 4.2;

// Tolerances.
constexpr double kValueSlack = 1e-12;   // kJ/mol: a terrace mean may sit on its bound (round-off)
constexpr double kStrictlyBelow = 1e-6; // kJ/mol: a mean this far below another differs for real
constexpr double kPlacementTol = 1e-6;  // of x(r_out): the bisection inverting the profile
constexpr double kVirialTol = 1e-3;     // relative: this test's quadrature of B₂ (400 000 points)
constexpr double kStationaryTol = 1e-9; // kJ/mol: above the iteration's stop (1e-12 of the step)
constexpr double kEnergyRoundoff = 1e-12;   // of |K| + |U|: round-off over thousands of crossings
constexpr double kMomentumRoundoff = 1e-12; // of sqrt(|K| + |U|): the same, for Σp

DmdSection designScene(const std::string& levels, const std::string& values, int n, double dV) {
    DmdSection d;
    d.dV = dV;
    d.terraces.levels = levels;
    d.terraces.values = values;
    d.terraces.n = n;
    return d;
}

TerraceDesign design(const DmdSection& d, const auto& p, double kT) {
    const auto t = designTerraces(d, p, kT);
    EXPECT_TRUE(t.has_value());
    return *t;
}

void expectWellFormed(const TerraceDesign& t, double uMin) {
    ASSERT_EQ(t.values.size(), t.levels.size() + 1);
    for (std::size_t k = 0; k < t.levels.size(); ++k) {
        EXPECT_NE(t.levels[k], 0.0);
        if (k > 0) {
            EXPECT_GT(t.levels[k], t.levels[k - 1]);
        }
    }
    EXPECT_GT(t.levels.front(), uMin);
    // Every terrace's energy lies within its bounds (the lowest within [U_min, L_0]), but for the
    // one beyond the cap, which carries the cap.
    for (std::size_t s = 0; s + 1 < t.values.size(); ++s) {
        const double lo = s == 0 ? uMin : t.levels[s - 1], hi = t.levels[s];
        EXPECT_GE(t.values[s], lo - kValueSlack) << "terrace slot " << s;
        EXPECT_LE(t.values[s], hi + kValueSlack) << "terrace slot " << s;
    }
    EXPECT_EQ(t.values.back(), t.levels.back());
}

TEST(TerraceDesign, EnergyPlacementIsThePapersLevelsUpToTheCap) {
    const auto t = design(designScene("energy", "midpoint", 4, 0.5), lj, ljKT);
    const double step = 0.25; // |U_min|/n
    const double cap = 50.0 * ljKT;
    ASSERT_EQ(t.levels.back(), cap);
    std::size_t k = 0;
    for (int j = -3; (j - 0.5) * step < cap; ++j, ++k) { // (j − ½) step from −0.875 up
        ASSERT_LT(k, t.levels.size());
        EXPECT_DOUBLE_EQ(t.levels[k], (j - 0.5) * step);
    }
    // Interior midpoints are the paper's multiples of ΔV.
    EXPECT_DOUBLE_EQ(t.values[1], -0.75);
    EXPECT_DOUBLE_EQ(t.values[5], 0.25);
    expectWellFormed(t, -1.0);
}

TEST(TerraceDesign, DistanceAndVolumePlacementsSpaceTheRadiiEvenly) {
    for (const std::string placement : {"distance", "volume"}) {
        const int n = 6;
        const auto t = design(designScene(placement, "midpoint", n, 0.5), lj, ljKT);
        expectWellFormed(t, -1.0);
        // Invert the profile (LJ: spheres) on its attractive branch at each well level.
        const double rMin = std::pow(2.0, 1.0 / 6.0) * 3.0, rOut = 9.0;
        auto radiusOf = [&](double u) {
            double lo = rMin, hi = rOut;
            for (int it = 0; it < 200; ++it)
                (lj.energy(Vec3((lo + hi) / 2, 0, 0), Vec3::UnitZ(), Vec3::UnitZ()) < u ? lo : hi) =
                    (lo + hi) / 2;
            return (lo + hi) / 2;
        };
        auto x = [&](double r) { return placement == "distance" ? r : r * r * r; };
        const double h = (x(rOut) - x(rMin)) / n;
        for (int k = 1; k <= n; ++k)
            EXPECT_NEAR(x(radiusOf(t.levels[k - 1])), x(rMin) + (k - 0.5) * h,
                        kPlacementTol * x(rOut))
                << placement << " level " << k;
    }
}

TEST(TerraceDesign, AveragedValuesObeyJensen) {
    // On every terrace of the same levels: the Boltzmann mean of U lies at or below the volume
    // mean (weights e^{−βU} favour low U), and −kT ln⟨e^{−βU}⟩ at or below it too (Jensen).
    const auto byVolume = design(designScene("distance", "volume", 8, 0.5), rods, rodKT);
    const auto byBoltzmann = design(designScene("distance", "boltzmann", 8, 0.5), rods, rodKT);
    const auto byVirial = design(designScene("distance", "virial", 8, 0.5), rods, rodKT);
    ASSERT_EQ(byVolume.levels, byBoltzmann.levels);
    ASSERT_EQ(byVolume.levels, byVirial.levels);
    for (const auto* t : {&byVolume, &byBoltzmann, &byVirial})
        expectWellFormed(*t, -3.0);
    int strict = 0;
    for (std::size_t s = 0; s + 1 < byVolume.values.size(); ++s) {
        EXPECT_LE(byBoltzmann.values[s], byVolume.values[s] + kValueSlack);
        EXPECT_LE(byVirial.values[s], byVolume.values[s] + kValueSlack);
        strict += byBoltzmann.values[s] < byVolume.values[s] - kStrictlyBelow;
    }
    EXPECT_GE(strict, 3); // not equal by accident: the terraces are wide enough to tell
}

TEST(TerraceDesign, VirialValuesKeepTheSecondVirialCoefficient) {
    // B₂ contributions −2π∫(e^{−βX} − 1) r² dr of the continuous U and of the terraced V, by a
    // radial quadrature of this test's own, over the radii whose U lies off terrace 0 and below
    // the cap: per terrace they are equal by construction, so in sum too.
    const auto t = design(designScene("energy", "virial", 6, 0.5), lj, ljKT);
    const auto levels = TerraceLevels::explicitLevels(t.levels, t.values);
    double b2U = 0.0, b2V = 0.0, b2Midpoint = 0.0;
    const auto mid = design(designScene("energy", "midpoint", 6, 0.5), lj, ljKT);
    const auto midLevels = TerraceLevels::explicitLevels(mid.levels, mid.values);
    const int points = 400000;
    const double r0 = 2.0, r1 = 9.0, dr = (r1 - r0) / points;
    for (int k = 0; k < points; ++k) {
        const double r = r0 + (k + 0.5) * dr;
        const double u = lj.energy(Vec3(r, 0, 0), Vec3::UnitZ(), Vec3::UnitZ());
        const int n = levels.terraceOf(u);
        if (n == 0 || u >= 50.0 * ljKT) continue;
        const double w = -2.0 * std::numbers::pi * r * r * dr;
        b2U += w * (std::exp(-u / ljKT) - 1.0);
        b2V += w * (std::exp(-levels.energy(n) / ljKT) - 1.0);
        b2Midpoint += w * (std::exp(-midLevels.energy(midLevels.terraceOf(u)) / ljKT) - 1.0);
    }
    EXPECT_NEAR(b2V, b2U, kVirialTol * std::abs(b2U)) << "B2 part, continuous " << b2U;
    // The midpoints miss it by far more: the check has teeth.
    EXPECT_GT(std::abs(b2Midpoint - b2U), 20.0 * std::abs(b2V - b2U));
}

TEST(TerraceDesign, OptimalDesignIsALloydMaxQuantiser) {
    for (const bool rodsToo : {false, true}) {
        const double kT = rodsToo ? rodKT : ljKT;
        const double uMin = rodsToo ? -3.0 : -1.0;
        const auto d = designScene("optimal", "boltzmann", 3, 0.5);
        const auto t = rodsToo ? design(d, rods, kT) : design(d, lj, kT);
        expectWellFormed(t, uMin);
        // Stationary: each free level (all but the cap) is the midpoint of its neighbours'
        // energies (terrace 0's held at 0), and each energy the Boltzmann mean of its terrace.
        for (std::size_t k = 0; k + 1 < t.levels.size(); ++k)
            EXPECT_NEAR(t.levels[k], 0.5 * (t.values[k] + t.values[k + 1]), kStationaryTol);
        // Its error is the lowest of the designs with the same levels counted the same way:
        // uniform levels of the same step with Boltzmann means, and with midpoints.
        const double uCap = 50.0 * kT;
        const double step = -uMin / 3;
        const double rOut = rodsToo ? rods.range() : lj.range();
        const double rIn = 0.5 * (rodsToo ? rods.reachDistance(uCap) : lj.reachDistance(uCap));
        const auto density = rodsToo ? PairEnergyDensity::build(rods, kT, rIn, rOut, uCap)
                                     : PairEnergyDensity::build(lj, kT, rIn, rOut, uCap);
        const auto means = terraceValues(t.levels, "boltzmann", density, uMin);
        for (std::size_t s = 0; s < means.size(); ++s)
            EXPECT_NEAR(t.values[s], means[s], kStationaryTol);
        TerraceDesign uniform;
        for (int k = -3; k <= static_cast<int>(std::floor(5.0 * kT / step + 0.5)); ++k)
            if (k != 0) uniform.levels.push_back((k > 0 ? k - 0.5 : k + 0.5) * step);
        uniform.levels.push_back(uCap);
        ASSERT_EQ(uniform.levels.size(), t.levels.size());
        uniform.values = terraceValues(uniform.levels, "boltzmann", density, uMin);
        const double eUniformMean = designError(uniform, density);
        uniform.values = terraceValues(uniform.levels, "midpoint", density, uMin);
        const double eUniformMid = designError(uniform, density);
        const double eOptimal = designError(t, density);
        EXPECT_LT(eOptimal, eUniformMean);
        EXPECT_LT(eUniformMean, eUniformMid);
        std::printf("%s: E² optimal %.4g, uniform+Boltzmann %.4g, uniform+midpoint %.4g\n",
                    rodsToo ? "rods" : "LJ", eOptimal, eUniformMean, eUniformMid);
    }
}

TEST(TerraceDesign, OptimalDesignsOfEveryAllowedSizeConverge) {
    // The largest n the scene admits on the smoothed rods (2401 levels with the wall's): the
    // 10⁴ sweeps leave every level within 1e-4 kJ/mol (1e-2 of the 0.01 kJ/mol step) of
    // stationary (the bare rods converge fully), and beyond the level cap the design is refused
    // naming dmd.terraces.n (n = 100 000 ran for minutes before the cap).
    const auto t =
        design(designScene("optimal", "boltzmann", maxOptimalWellLevels, 0.5), rods, rodKT);
    expectWellFormed(t, -3.0);
    EXPECT_LE(static_cast<long>(t.levels.size()), maxOptimalLevels);
    for (std::size_t k = 0; k + 1 < t.levels.size(); ++k)
        EXPECT_NEAR(t.levels[k], 0.5 * (t.values[k] + t.values[k + 1]), 1e-4) << k;
    try {
        // Twice as hot: twice the levels up the 5 kT wall for the same step.
        (void)designTerraces(designScene("optimal", "boltzmann", maxOptimalWellLevels, 0.5), rods,
                             2.0 * rodKT);
        FAIL() << "an optimal design beyond the level cap was made";
    } catch (const SceneError& e) {
        EXPECT_EQ(std::string(e.what()).rfind("dmd.terraces.n: 300 levels in the well make ", 0),
                  0u)
            << e.what();
    }
}

TEST(TerraceDesign, DesignsArePureFunctions) {
    const auto d = designScene("optimal", "boltzmann", 0, 0.5);
    const auto a = design(d, rods, rodKT), b = design(d, rods, rodKT);
    EXPECT_EQ(a.levels, b.levels);
    EXPECT_EQ(a.values, b.values);
    EXPECT_FALSE(designTerraces(designScene("energy", "midpoint", 0, 0.5), rods, rodKT));
}

TEST(TerraceDesignEngine, UnequalStepsConserveEnergyAndMomentumToRoundOff) {
    // 108 LJ spheres in the liquid on designs whose steps and values are all unequal: every
    // crossing must exchange V_new − V_old (not a midpoint difference), or K + ΣV would wander.
    for (const char* spec :
         {R"({"levels":"volume","values":"virial","n":4})", R"({"levels":"optimal","n":3})"}) {
        const Scene s = sceneFromJson(
            {{"body", {{"kind", "sphere"}, {"mass", 1.0}, {"inertia", {0, 0, 0}}}},
             {"potential",
              {{"kind", "lj"}, {"epsilon", 1.0}, {"sigma", 1.0}, {"cutoff", {2.0, 2.5}}}},
             {"state", {{"n", 108}, {"density", 0.8}, {"temperature", 0.9}}}},
            "<LJ liquid>", {std::string("dmd.terraces=") + spec});
        using Model = Smoothed<LJPotential>;
        const Model model{ljPotential(s), sceneCutoff(s)};
        dmd::SceneEngine<Sphere, Model> e(buildInitialState<Sphere, Model>(s, model), s);
        ASSERT_FALSE(Probe::levels(e).isUniform());
        const double e0 = e.kineticEnergy() + e.potentialEnergy();
        const Vec3 p0 = e.totalMomentum();
        double scale = 0.0;             // the size of the energies that cancel
        for (int k = 1; k <= 10; ++k) { // 200 fs
            e.advanceTo(k * 0.2);
            scale = std::max(scale, e.kineticEnergy() + std::abs(e.potentialEnergy()));
            EXPECT_NEAR(e.kineticEnergy() + e.potentialEnergy(), e0, kEnergyRoundoff * scale)
                << spec;
            EXPECT_LT((e.totalMomentum() - p0).norm(), kMomentumRoundoff * std::sqrt(scale))
                << spec;
        }
        EXPECT_GT(Probe::counts(e).up + Probe::counts(e).down, 2000u)
            << spec; // thousands of crossings
    }
}

TEST(TerraceLevelsValues, GivenValuesAreTheTerraceEnergies) {
    const auto t =
        TerraceLevels::explicitLevels({-2.0, -0.5, 1.0, 4.0}, {-2.7, -1.1, 0.0, 3.3, 9.0});
    EXPECT_EQ(t.energy(-2), -2.7);
    EXPECT_EQ(t.energy(-1), -1.1);
    EXPECT_EQ(t.energy(0), 0.0);
    EXPECT_EQ(t.energy(1), 3.3);
    EXPECT_EQ(t.energy(2), 9.0);
    EXPECT_THROW(TerraceLevels::explicitLevels({-2.0, 1.0}, {-1.0, 0.0}), SceneError);
    EXPECT_THROW(TerraceLevels::explicitLevels({-2.0, 1.0}, {-1.0, 0.1, 2.0}), SceneError);
    EXPECT_THROW(TerraceLevels::explicitLevels({-2.0, 1.0}, {-1.0, 0.0, NAN}), SceneError);
}

TEST(TerraceDesignScene, KeysReadAndRefused) {
    const nlohmann::json base = toJson(defaultScene());
    auto section = [&](const std::vector<std::string>& sets) {
        Scene s = sceneFromJson(base, "t", sets);
        return resolveDmdSection(s, "t");
    };
    const DmdSection d = section({R"(dmd.terraces={"levels":"optimal","n":3})"});
    EXPECT_EQ(d.terraces.levels, "optimal");
    EXPECT_EQ(d.terraces.values, "boltzmann");
    EXPECT_EQ(d.terraces.n, 3);
    EXPECT_EQ(dmd::toJson(readDmdSection(dmd::toJson(d))), dmd::toJson(d));
    EXPECT_THROW(section({R"(dmd.terraces={"levels":"log"})"}), SceneError);
    EXPECT_THROW(section({R"(dmd.terraces={"levels":"optimal","values":"midpoint"})"}), SceneError);
    EXPECT_THROW(section({R"(dmd.terraces={"levels":"distance","m":3})"}), SceneError);
    // An optimal design takes at most maxOptimalWellLevels in the well; the others 10⁵.
    EXPECT_THROW(section({R"(dmd.terraces={"levels":"optimal","n":100000})"}), SceneError);
    EXPECT_EQ(section({R"(dmd.terraces={"levels":"optimal","n":300})"}).terraces.n, 300);
    EXPECT_EQ(section({R"(dmd.terraces={"levels":"distance","n":100000})"}).terraces.n, 100000);
    EXPECT_THROW(section({"dmd.levels=[-1,1]", "dmd.values=[0,0]"}), SceneError);
    EXPECT_THROW(section({"dmd.values=[0,0,1]"}), SceneError);
    const DmdSection v = section({"dmd.levels=[-1,1]", "dmd.values=[-1.5,0,2]"});
    EXPECT_EQ(v.values, (std::vector<double>{-1.5, 0.0, 2.0}));
}

} // namespace

// A design asked for again (a run's well check, memory estimate and engine each ask) is the one
// built the first time, bit for bit, and is not built again; another kT, terrace key or
// potential parameter is another design.
TEST(TerraceDesign, ADesignIsRememberedForItsInputsAlone) {
    const auto d = designScene("optimal", "boltzmann", 3, 0.5);
    std::size_t built = 0;
    const auto first = rememberedDesign(d, rods, rodKT, &built);
    const std::size_t before = built;
    ASSERT_TRUE(first.has_value());
    const auto fresh = designTerraces(d, rods, rodKT);
    EXPECT_EQ(first->levels, fresh->levels);
    EXPECT_EQ(first->values, fresh->values);
    const auto again = rememberedDesign(d, rods, rodKT, &built);
    EXPECT_EQ(built, before); // served from memory
    EXPECT_EQ(again->levels, fresh->levels);
    EXPECT_EQ(again->values, fresh->values);
    // Each input that changes the design is part of what it is remembered by.
    auto otherN = d;
    otherN.terraces.n = 4;
    auto otherLevels = d;
    otherLevels.terraces.levels = "energy";
    const auto byDV = designScene("optimal", "boltzmann", 0, 0.5);
    auto byDV2 = byDV;
    byDV2.dV = 0.25;
    Smoothed<RodPotential> otherRods = rods;
    otherRods.bare.zeta = 1.1;
    Smoothed<RodPotential> otherCut = rods;
    otherCut.cut = SmoothedCutoff{2.4 * 3.035, 3.0 * 3.035};
    std::size_t expected = before;
    for (const auto& [section, potential, kT] :
         std::vector<std::tuple<DmdSection, Smoothed<RodPotential>, double>>{
             {d, rods, 1.2 * rodKT},
             {otherN, rods, rodKT},
             {otherLevels, rods, rodKT},
             {byDV, rods, rodKT},
             {byDV2, rods, rodKT},
             {d, otherRods, rodKT},
             {d, otherCut, rodKT}}) {
        EXPECT_TRUE(rememberedDesign(section, potential, kT, &built).has_value());
        EXPECT_EQ(built, ++expected);
        rememberedDesign(section, potential, kT, &built); // and each is then remembered
        EXPECT_EQ(built, expected);
    }
    EXPECT_NE(rememberedDesign(otherN, rods, rodKT)->levels, first->levels);
    rememberedDesign(d, rods, rodKT, &built); // the first is still there
    EXPECT_EQ(built, expected);
}

} // namespace test_terrace_design
