// One step table between the species of a mixture (core/step_mixture.hpp): each pair's carrier
// crosses the levels that all pairs share at its own radii r_k σ_ab, its terraces carry the
// table's energies in its own ε_ab, its force against finite differences, its bounds and reach;
// the scene's keys and refusals; and DMD on a square-well mixture of two sizes, depths and
// masses: energy and momentum to round-off, every pair on the terrace that its distance in its
// own σ_ab gives (brute force), the engine's energy the table's in each pair's ε_ab, and the same
// collisions with and without the hold screen.
#include "core/initial_state.hpp"
#include "core/species_sphere.hpp"
#include "core/step_mixture.hpp"
#include "dmd/scene_engine.hpp"
#include "dmd/testing.hpp"
#include "tests/core/scene_errors.hpp"
#include <cmath>
#include <gtest/gtest.h>
#include <string>

namespace test_step_mixture {

using terrace::dmd::testing::Probe;
using namespace terrace;

namespace {

using MixtureEngine = dmd::SceneEngine<SpeciesSphere, StepMixture>;

/// A square well (λ = 1.5) between A (σ 1, ε 1) and B (σ 0.7, ε 0.5, twice as heavy, 40 %),
/// σ = 3 Å, ε = 1 kJ/mol; the unlike pair's own σ (non-additive) and ε 0.9 when sigmaAB > 0.
nlohmann::json mixtureDocument(int n, double density, double temperature, double sigmaAB = 0.0) {
    nlohmann::json j = {
        {"body", {{"kind", "sphere"}, {"mass", 1.0}}},
        {"potential",
         {{"kind", "steps"},
          {"steps", "square_well"},
          {"lambda", 1.5},
          {"epsilon", 1.0},
          {"sigma", 3.0}}},
        {"species",
         {{{"name", "A"}, {"fraction", 0.6}},
          {{"name", "B"}, {"fraction", 0.4}, {"sigma", 0.7}, {"epsilon", 0.5}, {"mass", 2.0}}}},
        {"state", {{"n", n}, {"density", density}, {"temperature", temperature}}}};
    if (sigmaAB > 0.0)
        j["potential"]["pairs"] = {{{"between", {"A", "B"}}, {"epsilon", 0.9}, {"sigma", sigmaAB}}};
    return j;
}

/// Every pair's terrace against the one its distance gives in its own σ_ab (all pairs, O(N²)):
/// no crossing went unseen. Pairs within 1e-9 σ_ab of a radius are skipped (an event there is
/// due now). Returns the number of pairs off terrace 0.
int checkAllPairs(const MixtureEngine& e) {
    const auto s = e.system();
    const StepMixture& p = s.potential;
    const StepTable& table = p.steps.table;
    int bound = 0;
    for (int i = 0; i < s.size(); ++i)
        for (int j = i + 1; j < s.size(); ++j) {
            const double sab = p.pairSigma(s.bodies[i].species, s.bodies[j].species);
            const double r = s.box.minimumImage(s.bodies[i].r - s.bodies[j].r).norm() / sab;
            EXPECT_GE(r, table.hardCore * (1.0 - 1e-12)) << "pair " << i << ", " << j;
            bool near = std::abs(r - table.hardCore) < 1e-9;
            int expected = 0;
            for (std::size_t k = 0; k < table.radii.size(); ++k) {
                near = near || std::abs(r - table.radii[k]) < 1e-9;
                if (r < table.radii[k]) expected = int(k) + 1;
            }
            if (near) continue;
            EXPECT_EQ(Probe::terrace(e, i, j), expected)
                << "pair " << i << ", " << j << " at r = " << r << " σ_ab";
            bound += expected != 0;
        }
    return bound;
}

/// Σ over pairs of the table's energy at their distances, each in its ε_ab (kJ/mol): what the
/// engine's terraced energy must be.
double tableEnergy(const MixtureEngine& e) {
    const auto s = e.system();
    double u = 0.0;
    for (int i = 0; i < s.size(); ++i)
        for (int j = i + 1; j < s.size(); ++j)
            u += s.potential.tableEnergy(s.box.minimumImage(s.bodies[i].r - s.bodies[j].r).norm(),
                                         s.bodies[i].species, s.bodies[j].species);
    return u;
}

} // namespace

TEST(StepMixture, EachPairCrossesTheSharedLevelsAtItsOwnRadii) {
    const Scene s = sceneFromJson(mixtureDocument(100, 0.5, 1.5), "<mix>");
    const StepMixture m = stepMixture(s);
    ASSERT_EQ(m.species, 2);
    // Lorentz–Berthelot: the arithmetic mean of σ (Å), the geometric of ε (over the table's ε).
    EXPECT_DOUBLE_EQ(m.pairSigma(0, 0), 3.0);
    EXPECT_DOUBLE_EQ(m.pairSigma(1, 1), 2.1);
    EXPECT_DOUBLE_EQ(m.pairSigma(0, 1), 2.55);
    EXPECT_DOUBLE_EQ(m.pairSigma(1, 0), 2.55);
    EXPECT_DOUBLE_EQ(m.pairEnergyScale(0, 0), 1.0);
    EXPECT_DOUBLE_EQ(m.pairEnergyScale(1, 1), 0.5);
    EXPECT_DOUBLE_EQ(m.pairEnergyScale(0, 1), std::sqrt(0.5));
    // A non-additive pair takes its own.
    const StepMixture own =
        stepMixture(sceneFromJson(mixtureDocument(100, 0.5, 1.5, 0.9), "<mix>"));
    EXPECT_DOUBLE_EQ(own.pairSigma(0, 1), 2.7);
    EXPECT_DOUBLE_EQ(own.pairEnergyScale(1, 0), 0.9);
    // The levels are those of the table alone: each pair's carrier equals them at r_k σ_ab.
    const std::vector<double> levels = m.steps.levels();
    const StepTable& t = m.steps.table;
    ASSERT_EQ(levels.size(), 2u); // the well's edge and the core
    for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b) {
            const double sab = m.pairSigma(a, b);
            EXPECT_NEAR(m.energy(Vec3(t.radii[0] * sab, 0, 0), a, b), levels[0], 1e-15);
            EXPECT_NEAR(m.energy(Vec3(0, t.hardCore * sab, 0), a, b), levels[1], 1e-15);
            // The table's own energy per pair: −ε_ab inside the well, 0 beyond it, ∞ in the core.
            EXPECT_EQ(m.tableEnergy(1.2 * sab, a, b), -m.pairEnergyScale(a, b));
            EXPECT_EQ(m.tableEnergy(1.6 * sab, a, b), 0.0);
            EXPECT_TRUE(std::isinf(m.tableEnergy(0.9 * sab, a, b)));
        }
    // Force −∇φ against central differences, and dφ/dt = −F·v, for each pair.
    const Vec3 rij(1.1, -2.3, 0.7), vij(0.4, 0.2, -0.9);
    constexpr double h = 1e-6;
    for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b) {
            const PairForce f = m.evaluate(rij, a, b);
            for (int k = 0; k < 3; ++k) {
                Vec3 dr = Vec3::Zero();
                dr[k] = h;
                const double dU = (m.energy(rij + dr, a, b) - m.energy(rij - dr, a, b)) / (2 * h);
                EXPECT_NEAR(f.F[k], -dU, 1e-8) << a << b << " component " << k;
            }
            const EnergyRate rate = m.energyRate(rij, vij, a, Vec3::Zero(), b, Vec3::Zero());
            EXPECT_DOUBLE_EQ(rate.U, f.U);
            EXPECT_NEAR(rate.dUdt, -f.F.dot(vij), 1e-14);
            // The bounds over a shell of ±0.5 Å hold every value in it, and are reached.
            const EnergyRange range = m.energyRange(rij, a, b, 0.5, 0.0, 0.0);
            for (double x = -0.5; x <= 0.5; x += 0.05) {
                const double u = m.energy(rij * (1.0 + x / rij.norm()), a, b);
                EXPECT_GE(u, range.lo - 1e-15);
                EXPECT_LE(u, range.hi + 1e-15);
            }
            EXPECT_NEAR(m.energy(rij * (1.0 + 0.5 / rij.norm()), a, b), range.lo, 1e-15);
        }
    // The reach of a level is the largest pair's radius for it; the lowest φ at r the smallest
    // pair's.
    EXPECT_NEAR(m.reachDistance(levels[0]), t.radii[0] * 3.0, 1e-12);
    EXPECT_NEAR(m.lowestEnergyAt(4.0), m.energy(Vec3(4.0, 0, 0), 1, 1), 1e-15);
    EXPECT_EQ(m.reachDistance(0.0), 0.0);
    EXPECT_EQ(m.reachDistance(2.0), 0.0); // above φ(0) = ε: never taken
}

TEST(StepMixture, SceneKeysAreCheckedAndWrittenBack) {
    using scene_tests::errorOf;
    // A pair of its own gives both its ε and σ, as for Lennard-Jones.
    nlohmann::json j = mixtureDocument(100, 0.5, 1.5, 0.9);
    j["potential"]["pairs"][0].erase("epsilon");
    EXPECT_NE(errorOf(j).find("pairs[0].epsilon: missing"), std::string::npos) << errorOf(j);
    j = mixtureDocument(100, 0.5, 1.5);
    j["potential"]["cutoff_per_pair"] = true;
    EXPECT_NE(errorOf(j).find("cutoff_per_pair: a step table ends at its first radius"),
              std::string::npos)
        << errorOf(j);
    j = mixtureDocument(100, 0.5, 1.5);
    j["engine"] = "smd";
    EXPECT_NE(errorOf(j).find("smd cannot integrate potential.kind steps"), std::string::npos)
        << errorOf(j);
    // The resolved scene reads back to the same pairs.
    const Scene s = sceneFromJson(mixtureDocument(100, 0.5, 1.5, 0.9), "<mix>");
    const Scene back = sceneFromJson(toJson(s), "<back>");
    const StepMixture m = stepMixture(s), n = stepMixture(back);
    for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b) {
            EXPECT_EQ(n.pairSigma(a, b), m.pairSigma(a, b)) << a << b;
            EXPECT_EQ(n.pairEnergyScale(a, b), m.pairEnergyScale(a, b)) << a << b;
        }
    EXPECT_EQ(n.steps.table.radii, m.steps.table.radii);
}

TEST(StepMixture, DmdKeepsEnergyAndMomentumAndEachPairOnItsOwnRadii) {
    const Scene s = sceneFromJson(mixtureDocument(216, 0.6, 1.5), "<mix>");
    MixtureEngine e(buildInitialState<SpeciesSphere, StepMixture>(s, stepMixture(s)), s);
    const double e0 = e.kineticEnergy() + e.potentialEnergy();
    const Vec3 p0 = e.totalMomentum();
    for (int block = 1; block <= 10; ++block) {
        e.advanceTo(0.5 * block);
        EXPECT_NEAR(e.kineticEnergy() + e.potentialEnergy(), e0, 1e-11 * std::abs(e0)) << block;
        EXPECT_NEAR(e.potentialEnergy(), tableEnergy(e), 1e-9) << block;
    }
    EXPECT_LT((e.totalMomentum() - p0).norm(), 1e-9);
    EXPECT_GT(checkAllPairs(e), 0);
    EXPECT_GT(Probe::counts(e).reflect, 100u);
    EXPECT_GT(Probe::counts(e).up + Probe::counts(e).down, 100u);
    // Every kind of pair was bound at some point: A–A, A–B, B–B.
    const auto sys = e.system();
    int boundKinds = 0;
    for (int a = 0; a < 2; ++a)
        for (int b = a; b < 2; ++b) {
            bool any = false;
            for (int i = 0; i < sys.size() && !any; ++i)
                for (int j = i + 1; j < sys.size() && !any; ++j)
                    any = ((sys.bodies[i].species == a && sys.bodies[j].species == b) ||
                           (sys.bodies[i].species == b && sys.bodies[j].species == a)) &&
                          Probe::terrace(e, i, j) == 1;
            boundKinds += any;
        }
    EXPECT_EQ(boundKinds, 3);
}

TEST(StepMixture, TheHoldScreenChangesNoCollision) {
    const Scene s = sceneFromJson(mixtureDocument(125, 0.6, 1.5, 0.9), "<mix>");
    const auto start = buildInitialState<SpeciesSphere, StepMixture>(s, stepMixture(s));
    MixtureEngine screened(start, s), searched(start, s);
    Probe::setHoldScreen(searched, false);
    for (int k = 1; k <= 30; ++k) {
        screened.advanceTo(0.02 * k);
        searched.advanceTo(0.02 * k);
        ASSERT_EQ(Probe::counts(screened).up, Probe::counts(searched).up) << k;
        ASSERT_EQ(Probe::counts(screened).down, Probe::counts(searched).down) << k;
        ASSERT_EQ(Probe::counts(screened).reflect, Probe::counts(searched).reflect) << k;
    }
    EXPECT_GT(Probe::counts(screened).reflect + Probe::counts(screened).up, 50u);
    EXPECT_GT(screened.statistics()["searches_screened"].get<double>(), 0.0);
}

} // namespace test_step_mixture
