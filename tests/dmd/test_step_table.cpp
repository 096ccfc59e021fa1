// Step tables with a hard core (core/step_table.hpp) and their DMD (core/step_potential.hpp):
// the tables, their validation and generators; the scene keys; and the engine on them — energy
// conserved to round-off, every event at the radius it belongs to (a brute-force check of each
// pair's distance against its terrace), the core never entered, a lattice with pairs on a step
// started without a stall.
#include "core/initial_state.hpp"
#include "core/sphere.hpp"
#include "core/step_potential.hpp"
#include "core/step_table.hpp"
#include "dmd/collision_rule.hpp"
#include "dmd/scene_engine.hpp"
#include "dmd/testing.hpp"
#include <cmath>
#include <gtest/gtest.h>
#include <limits>
#include <numbers>
#include <string>

namespace test_step_table {

using terrace::dmd::testing::Probe;
using namespace terrace;

namespace {

using StepEngine = dmd::SceneEngine<Sphere, StepPotential>;

/// The message of the SceneError `f` throws ("" when none).
template <class F> std::string errorOf(F&& f) {
    try {
        f();
    } catch (const SceneError& e) {
        return e.what();
    }
    return "";
}

nlohmann::json stepScene(nlohmann::json potential, int n, double density, double temperature) {
    potential["kind"] = "steps";
    potential["epsilon"] = 1.0;
    potential["sigma"] = 1.0;
    return {{"body", {{"kind", "sphere"}, {"mass", 1.0}}},
            {"potential", potential},
            {"state", {{"n", n}, {"density", density}, {"temperature", temperature}}}};
}

/// Every listed pair's terrace against the one its distance puts it on (all pairs, O(N²)): the
/// brute-force check that no crossing went unseen. Pairs within `onStep` (σ) of a radius are
/// skipped: an event there is due now. Returns the number of pairs checked off terrace 0.
int checkAllPairs(const StepEngine& e, const StepPotential& p, double onStep = 1e-9) {
    const System<Sphere, StepPotential> s = e.system();
    const auto& table = p.table;
    int bound = 0;
    for (int i = 0; i < s.size(); ++i)
        for (int j = i + 1; j < s.size(); ++j) {
            const double r = s.box.minimumImage(s.bodies[i].r - s.bodies[j].r).norm() / p.sigma;
            EXPECT_GE(r, table.hardCore * (1.0 - 1e-12)) << "pair " << i << ", " << j;
            bool near = std::abs(r - table.hardCore) < onStep;
            int expected = 0;
            for (std::size_t k = 0; k < table.radii.size(); ++k) {
                near = near || std::abs(r - table.radii[k]) < onStep;
                if (r < table.radii[k]) expected = int(k) + 1;
            }
            if (near) continue;
            EXPECT_EQ(Probe::terrace(e, i, j), expected)
                << "pair " << i << ", " << j << " at r = " << r;
            bound += expected != 0;
        }
    return bound;
}

} // namespace

TEST(StepEngine, SquareWellConservesEnergyAndMissesNoEvent) {
    const Scene s = sceneFromJson(
        stepScene({{"steps", "square_well"}, {"lambda", 1.5}}, 216, 0.5, 1.5), "<sw>");
    const StepPotential p = stepPotential(s);
    StepEngine e(buildInitialState<Sphere, StepPotential>(s, p), s);
    const double e0 = e.kineticEnergy() + e.potentialEnergy();
    for (int block = 0; block < 10; ++block) {
        e.advanceTo(e.time() + 0.5);
        EXPECT_NEAR(e.kineticEnergy() + e.potentialEnergy(), e0, 1e-11 * std::abs(e0));
    }
    EXPECT_GT(checkAllPairs(e, p), 0);
}

namespace {

/// The engine on `s` run for `blocks` × `blockTime` time units: energy to round-off after each
/// block, and every pair on the terrace its distance gives at the end.
void runAndCheck(const Scene& s, int blocks, double blockTime) {
    const StepPotential p = stepPotential(s);
    StepEngine e(buildInitialState<Sphere, StepPotential>(s, p), s);
    const double e0 = e.kineticEnergy() + e.potentialEnergy();
    for (int block = 0; block < blocks; ++block) {
        e.advanceTo(e.time() + blockTime);
        EXPECT_NEAR(e.kineticEnergy() + e.potentialEnergy(), e0, 1e-11 * e.kineticEnergy());
    }
    EXPECT_GT(checkAllPairs(e, p), 0);
    EXPECT_GT(Probe::counts(e).reflect, 0u);
    EXPECT_GT(Probe::counts(e).up + Probe::counts(e).down, 0u);
}

/// B2 = −2π ∫ (e^{−βu(r)} − 1) r² dr of a table (σ³), by the midpoint rule on `cells` cells out
/// to its cutoff: the table read only through energyAt.
double numericalB2(const StepTable& t, double beta, int cells) {
    const double h = t.cutoff() / cells;
    double sum = 0.0;
    for (int k = 0; k < cells; ++k) {
        const double r = (k + 0.5) * h;
        sum += std::expm1(-beta * t.energyAt(r)) * r * r * h;
    }
    return -2.0 * std::numbers::pi * sum;
}

} // namespace

TEST(StepTable, EnergiesFollowTheStepsAndTheCore) {
    const StepTable t = steps::chapelaLJ();
    validateStepTable(t, "potential.steps");
    EXPECT_EQ(t.radii.size(), 10u);
    EXPECT_EQ(t.hardCore, 0.75);
    EXPECT_EQ(t.energyAt(2.31), 0.0);
    EXPECT_EQ(t.energyAt(2.30), 0.0); // r_0 itself lies beyond the table: step 0 is r < r_0
    EXPECT_EQ(t.energyAt(1.25), -0.55);
    EXPECT_EQ(t.energyAt(2.2999), -0.06);
    EXPECT_EQ(t.energyAt(1.2), -0.98);
    EXPECT_EQ(t.energyAt(0.76), 66.74);
    EXPECT_TRUE(std::isinf(t.energyAt(0.7499)));
    EXPECT_EQ(t.minimumEnergy(), -0.98);
    const StepTable sw = steps::squareWell(1.5, 2.0), ss = steps::squareShoulder(1.2, 3.0);
    EXPECT_EQ(sw.energyAt(1.2), -2.0);
    EXPECT_EQ(sw.energyAt(1.6), 0.0);
    EXPECT_TRUE(std::isinf(sw.energyAt(0.99)));
    EXPECT_EQ(ss.energyAt(1.1), 3.0);
    EXPECT_EQ(ss.cutoff(), 1.2);
}

TEST(StepTable, ValidationNamesTheKeyAndTheProblem) {
    const std::string key = "potential.steps";
    auto check = [&](StepTable t, const std::string& expected) {
        const std::string message = errorOf([&] { validateStepTable(t, key); });
        EXPECT_NE(message.find(key + ": "), std::string::npos) << message;
        EXPECT_NE(message.find(expected), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    };
    check({{}, {}, 0.0}, "is empty");
    check({{1.5, 2.0}, {-1.0, -0.5}, 0.9}, "sorted by decreasing radius");
    check({{1.5, 1.5}, {-1.0, -0.5}, 0.9}, "repeats the radius");
    check({{1.5, 1.2}, {-1.0, -0.5}, 1.2}, "inside the innermost step");
    check({{1.5, 1.2}, {-1.0, -0.5}, 1.3}, "inside the innermost step");
    check({{1.5}, {std::numeric_limits<double>::infinity()}, 1.0}, "energies must be finite");
    check({{std::numeric_limits<double>::quiet_NaN()}, {-1.0}, 0.0}, "radii must be finite");
    check({{1.5}, {-1.0}, std::numeric_limits<double>::infinity()}, "hard_core must be");
    check({{1.5, -1.0}, {-1.0, 1.0}, 0.0}, "radii must be finite and > 0");
    EXPECT_EQ(errorOf([&] { validateStepTable({{}, {}, 1.0}, key); }), "");        // hard spheres
    EXPECT_EQ(errorOf([&] { validateStepTable({{1.5}, {-1.0}, 0.0}, key); }), ""); // no core
}

TEST(StepTable, SceneKeysAreReadCheckedAndWrittenBack) {
    const auto scene = [](nlohmann::json potential) {
        return sceneFromJson(stepScene(std::move(potential), 64, 0.3, 1.5), "s.json");
    };
    const Scene s = scene({{"steps", {{1.5, -1.0}, {1.2, -2.0}}}, {"hard_core", 1.0}});
    EXPECT_EQ(s.potential.step_radii, (std::vector<double>{1.5, 1.2}));
    EXPECT_EQ(s.potential.step_energies, (std::vector<double>{-1.0, -2.0}));
    EXPECT_EQ(s.potential.hard_core, 1.0);
    const Scene again = sceneFromJson(toJson(s), "scene.json");
    EXPECT_EQ(again.potential.step_radii, s.potential.step_radii);
    EXPECT_EQ(again.potential.step_energies, s.potential.step_energies);
    EXPECT_EQ(again.potential.hard_core, 1.0);
    EXPECT_EQ(scene({{"steps", "chapela_lj"}}).potential.hard_core, 0.75);
    EXPECT_EQ(scene({{"steps", "square_well"}, {"lambda", 1.7}}).potential.step_radii,
              (std::vector<double>{1.7}));
    // Each refusal is one line naming its key.
    const auto refused = [&](nlohmann::json potential, const std::string& expected) {
        const std::string message = errorOf([&] { scene(std::move(potential)); });
        EXPECT_NE(message.find("s.json: " + expected), std::string::npos) << message;
    };
    refused({{"steps", {{1.2, -1.0}, {1.5, -2.0}}}, {"hard_core", 1.0}}, "potential.steps: step 1");
    refused({{"steps", {{1.5, -1.0}, {1.5, -2.0}}}}, "potential.steps: step 1 repeats");
    refused({{"steps", {{1.5, -1.0}}}, {"hard_core", 1.5}}, "potential.steps: hard_core");
    refused({{"steps", nlohmann::json::array()}}, "potential.steps: is empty");
    refused({{"steps", {{1.5}}}}, "potential.steps: step 0 must be [r, E]");
    refused({{"steps", "square"}}, "potential.steps");
    refused({{"steps", "chapela_lj"}, {"lambda", 1.5}}, "potential.lambda");
    refused({{"steps", {{1.5, -1.0}}}, {"cutoff", {2.5, 3.0}}}, "potential.cutoff");
    refused({{"steps", "square_well"}, {"lambda", 0.9}}, "potential.lambda");
    nlohmann::json smd = stepScene({{"steps", "square_well"}}, 64, 0.3, 1.5);
    smd["engine"] = "smd";
    const std::string message = errorOf([&] { sceneFromJson(smd, "s.json"); });
    EXPECT_NE(message.find("s.json: engine: smd cannot integrate potential.kind steps"),
              std::string::npos)
        << message;
    nlohmann::json rods = stepScene({{"steps", "square_well"}}, 64, 0.3, 1.5);
    rods["body"]["kind"] = "linear";
    rods["body"]["inertia"] = {1.0, 1.0, 0.0};
    EXPECT_NE(errorOf([&] { sceneFromJson(rods, "s.json"); }).find("potential.kind"),
              std::string::npos);
    EXPECT_NE(errorOf([&] {
                  scene({{"kind", "lj"}, {"hard_core", 1.0}});
              }).find("hard_core"),
              std::string::npos);
    // Under units lj the table is read in σ and ε as under real units.
    nlohmann::json lj = stepScene({{"steps", "square_well"}}, 64, 0.3, 1.5);
    lj["units"] = "lj";
    lj["potential"]["sigma"] = 3.4;
    EXPECT_EQ(sceneFromJson(lj, "s.json").potential.step_radii, (std::vector<double>{1.5}));
}

TEST(StepTable, DynamoGeneratorPlacesStepsAtEqualEnergyAndAveragesOverVolume) {
    const auto U = [](double r) { return 4.0 * (std::pow(r, -12) - std::pow(r, -6)); };
    const double cutoff = 3.0, n = 5.8, shift = U(cutoff);
    const double rMin = std::pow(2.0, 1.0 / 6.0), dU = -(U(rMin) - shift) / n;
    for (auto rule : {steps::StepEnergyRule::Volume, steps::StepEnergyRule::Midpoint}) {
        const StepTable t = steps::lennardJones(n, cutoff, rule, 100.0);
        validateStepTable(t, "potential.steps");
        ASSERT_GT(t.radii.size(), 8u);
        EXPECT_EQ(t.radii[0], cutoff);
        // Five levels down the attractive side, then back up the wall through the same ones.
        for (int i = 1; i < int(t.radii.size()); ++i) {
            const double level = i <= 5 ? -i * dU : (i - 11) * dU;
            EXPECT_NEAR(U(t.radii[i]) - shift, level, 1e-9) << "step " << i;
            EXPECT_EQ(t.radii[i] > rMin, i <= 5) << "step " << i;
        }
        // Each step's energy: the shifted U's volume average over its shell (Simpson on 2000
        // intervals), or its value at the shell's middle.
        for (std::size_t k = 0; k < t.radii.size(); ++k) {
            const double a = k + 1 < t.radii.size() ? t.radii[k + 1] : t.hardCore, b = t.radii[k];
            double expected = U(0.5 * (a + b)) - shift;
            if (rule == steps::StepEnergyRule::Volume) {
                const int m = 2000;
                double sum = 0.0;
                for (int j = 0; j <= m; ++j) {
                    const double r = a + (b - a) * j / m;
                    sum += (j == 0 || j == m ? 1 : j % 2 ? 4 : 2) * r * r * U(r);
                }
                expected = sum * (b - a) / (3.0 * m) * 3.0 / (b * b * b - a * a * a) - shift;
            }
            EXPECT_NEAR(t.energies[k], expected, 1e-9 * std::max(1.0, std::abs(expected)))
                << "step " << k;
        }
        // The core where the next step's energy, which lies between U at its two levels, would
        // exceed 100 ε: the last step kept does not.
        EXPECT_LE(t.energies.back(), 100.0);
        EXPECT_GT(U(t.hardCore) - shift, 100.0 - dU - 1e-9);
    }
}

TEST(StepTable, SquareWellSecondVirialCoefficientFromTheTable) {
    for (double lambda : {1.25, 1.5, 2.0})
        for (double kT : {0.8, 1.5, 3.0}) {
            const double l3 = lambda * lambda * lambda;
            const double exact =
                2.0 * std::numbers::pi / 3.0 * (1.0 - (l3 - 1.0) * std::expm1(1.0 / kT));
            // 240000 cells put the core (1 σ) and λ on cell edges for these λ: the midpoint rule
            // then errs only by Σ h³/12 on r², below 1e-10.
            const double b2 = numericalB2(steps::squareWell(lambda, 1.0), 1.0 / kT, 240000);
            EXPECT_NEAR(b2, exact, 1e-9) << "λ " << lambda << ", kT " << kT;
        }
}

TEST(StepCollision, TheLevelsSideDecidesNotTheSignOfTheEnergyChange) {
    using namespace dmd;
    // Leaving a square well outwards descends the carrier (b > 0) and costs its depth (dE > 0).
    const ImpulseCoefficients leaving{2.0, 3.0};               // b² = 9
    const Impulse escape = solveCrossing(leaving, 1.0, false); // D = 9 − 8 = 1
    EXPECT_EQ(escape.outcome, Outcome::Down);
    EXPECT_NEAR(2.0 * escape.S * escape.S + 3.0 * escape.S + 1.0, 0.0, 1e-15);
    EXPECT_GT(3.0 + 2.0 * 2.0 * escape.S, 0.0); // still moving out: dU/dt = −(b + 2aS) < 0
    const Impulse held = solveCrossing(leaving, 2.0, false); // D = 9 − 16 < 0
    EXPECT_EQ(held.outcome, Outcome::Reflect);
    EXPECT_EQ(held.S, -1.5);
    // Entering the well climbs the carrier (b < 0) and gains the depth (dE < 0): through.
    const Impulse enter = solveCrossing({2.0, -3.0}, -1.0, true);
    EXPECT_EQ(enter.outcome, Outcome::Up);
    EXPECT_NEAR(2.0 * enter.S * enter.S - 3.0 * enter.S - 1.0, 0.0, 1e-15);
    EXPECT_LT(-3.0 + 2.0 * 2.0 * enter.S, 0.0); // moving on inwards
    // The hard core: a climb of +∞, always reflected.
    const Impulse core = solveCrossing({2.0, -3.0}, std::numeric_limits<double>::infinity(), true);
    EXPECT_EQ(core.outcome, Outcome::Reflect);
    EXPECT_EQ(core.S, 1.5);
    // Terraces that rise with U answer as before.
    for (double dE : {-2.0, -0.5, 0.0, 0.5, 2.0})
        for (double b : {-3.0, -1e-3, 0.0, 1e-3, 3.0}) {
            const Impulse a = solveImpulse({2.0, b}, dE),
                          c = solveCrossing({2.0, b}, dE, dE >= 0.0);
            EXPECT_EQ(a.outcome, c.outcome);
            EXPECT_EQ(a.S, c.S);
        }
}

TEST(StepEngine, ChapelaTableConservesEnergyAndMissesNoEvent) {
    runAndCheck(sceneFromJson(stepScene({{"steps", "chapela_lj"}}, 256, 0.6, 1.5), "<chapela>"), 8,
                0.5);
}

TEST(StepEngine, ShoulderAndGeneratedTablesConserveEnergyAndMissNoEvent) {
    runAndCheck(
        sceneFromJson(stepScene({{"steps", "square_shoulder"}, {"lambda", 1.3}, {"depth", 0.5}},
                                216, 0.6, 1.5),
                      "<shoulder>"),
        8, 0.5);
    runAndCheck(sceneFromJson(stepScene({{"steps", "lj"}}, 216, 0.6, 1.5), "<lj>"), 4, 0.25);
}

TEST(StepEngine, PairsStartedExactlyOnAStepRunWithoutAStall) {
    // N 512 at ρ* 0.5: a simple-cubic lattice of 8 per edge, spacing L/8, which is made the
    // well's edge and, in a second table, a step inside it: every neighbour pair starts on it.
    const double spacing = std::cbrt(512 / 0.5) / 8.0;
    for (nlohmann::json potential :
         {nlohmann::json{{"steps", "square_well"}, {"lambda", spacing}},
          nlohmann::json{{"steps", {{1.6, -0.5}, {spacing, -1.0}}}, {"hard_core", 1.0}}}) {
        const Scene s = sceneFromJson(stepScene(potential, 512, 0.5, 1.5), "<on a step>");
        const StepPotential p = stepPotential(s);
        StepEngine e(buildInitialState<Sphere, StepPotential>(s, p), s);
        Probe::setStallLimit(e, 1000); // a handful of events at one instant at most
        const double e0 = e.kineticEnergy() + e.potentialEnergy();
        e.advanceTo(2.0);
        EXPECT_NEAR(e.kineticEnergy() + e.potentialEnergy(), e0, 1e-11 * e.kineticEnergy());
        EXPECT_GT(checkAllPairs(e, p), 0);
    }
}

TEST(StepEngine, PairsInsideTheCoreAreRefused) {
    nlohmann::json j = stepScene({{"steps", "square_well"}}, 2, 0.01, 1.5);
    j["state"] = {{"temperature", 1.5},
                  {"particles", {{{"r", {0.0, 0.0, 0.0}}}, {{"r", {0.9, 0.0, 0.0}}}}},
                  {"density", 0.01}};
    const Scene s = sceneFromJson(j, "<overlap>");
    const std::string message = errorOf(
        [&] { StepEngine e(buildInitialState<Sphere, StepPotential>(s, stepPotential(s)), s); });
    EXPECT_NE(message.find("overlap"), std::string::npos) << message;
    nlohmann::json lattice = stepScene({{"steps", "square_well"}}, 64, 1.5, 1.5);
    const Scene dense = sceneFromJson(lattice, "<dense>");
    EXPECT_NE(errorOf([&] {
                  buildInitialState<Sphere, StepPotential>(dense, stepPotential(dense));
              }).find("state.density"),
              std::string::npos);
}

TEST(StepEngine, ExplicitLevelsAreRefusedForATable) {
    nlohmann::json j = stepScene({{"steps", "square_well"}}, 64, 0.3, 1.5);
    j["dmd"] = {{"levels", {-0.5, 0.5}}};
    const Scene s = sceneFromJson(j, "<levels>");
    const std::string message = errorOf(
        [&] { StepEngine e(buildInitialState<Sphere, StepPotential>(s, stepPotential(s)), s); });
    EXPECT_NE(message.find("dmd.levels: potential.kind steps sets its own levels"),
              std::string::npos)
        << message;
}

} // namespace test_step_table
