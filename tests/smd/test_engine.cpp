// The SMD engine: scene validation, the engine contract, conservation of linear momentum (to
// round-off, Newton's third law) and of total angular momentum of an isolated cluster, time
// reversibility of the splitting, and advanceTo's whole-step time grid.
#include "core/asymmetric_top.hpp"
#include "core/engine.hpp"
#include "core/initial_state.hpp"
#include "core/symmetric_top.hpp"
#include "smd/scene_engine.hpp"
#include "systems.hpp"
#include "tests/measure_guard.hpp"
#include "tests/sample_parts.hpp"
#include <gtest/gtest.h>
#include <memory>
#include <span>
#include <vector>

namespace test_engine {

using namespace terrace;
using RodEngine = smd::SceneEngine<LinearRotor, smd::fixtures::RodModel>;
using LJEngine = smd::SceneEngine<Sphere, smd::fixtures::LJModel>;

static_assert(terrace::Engine<RodEngine>);
static_assert(terrace::Engine<LJEngine>);

namespace {

constexpr double sigmaRod = 3.035; // Å, the paper's σ

/// Expects a SceneError whose message starts with `key`.
template <class F> void expectSceneError(F&& make, const std::string& key) {
    try {
        make();
        ADD_FAILURE() << "no error for " << key;
    } catch (const SceneError& e) {
        EXPECT_EQ(std::string(e.what()).rfind(key, 0), 0u) << e.what();
    }
}

} // namespace

TEST(Engine, PartsOfASampleAreTheWholeSnapshotsOwn) {
    const auto sys = smd::fixtures::rods(6, 0.5, 1.4, 1);
    RodEngine e(sys, smd::fixtures::smdScene(sigmaRod, 1.8));
    e.advanceTo(0.5);
    terrace::testing::expectPartsOfTheSnapshot(e);
}

TEST(Engine, RejectsBadParameters) {
    const auto sys = smd::fixtures::rods(6, 0.5, 1.4, 1);
    auto with = [&](auto edit) {
        Scene s = smd::fixtures::smdScene(sigmaRod, 1.8);
        edit(s);
        return [s, &sys] { RodEngine e(sys, s); };
    };
    expectSceneError(with([](Scene& s) { s.smd["dt_fs"] = 0.0; }), "smd.dt_fs");
    expectSceneError(with([](Scene& s) { s.smd["dt_fs"] = -1.0; }), "smd.dt_fs");
    expectSceneError(with([](Scene& s) { s.smd["dt_fs"] = std::nan(""); }), "smd.dt_fs");
    expectSceneError(with([](Scene& s) { s.smd["skin"] = -0.1; }), "smd.skin");
    // 6³ rods at ρ* = 0.5: L ≈ 7.56σ < 2(4 + 0.3)σ.
    auto wide = sys;
    wide.potential.cut = SmoothedCutoff{2.5 * sigmaRod, 4.0 * sigmaRod};
    const Scene ok = smd::fixtures::smdScene(sigmaRod, 1.8);
    expectSceneError([&] { RodEngine e(wide, ok); }, "potential.cutoff: the box edge");
    // SMD needs a cutoff: the bare model (DMD's dmd.model = bare) has none.
    auto bare = sys;
    bare.potential.cut = SmoothedCutoff::none();
    expectSceneError([&] { RodEngine e(bare, ok); }, "potential.cutoff: SMD needs a finite");
    auto broken = sys;
    broken.bodies[3].v.x() = std::nan("");
    expectSceneError([&] { RodEngine e(broken, ok); }, "state");
}

TEST(Engine, AdvancesInWholeStepsOnTheGrid) {
    RodEngine e(smd::fixtures::rods(6, 0.5, 1.4, 2), smd::fixtures::smdScene(sigmaRod, 2.0));
    const double dt = units::fromFs(2.0);
    e.advanceTo(10 * dt);
    EXPECT_EQ(e.steps(), 10);
    e.advanceTo(10.2 * dt); // off the grid: the next grid point at or after it
    EXPECT_EQ(e.steps(), 11);
    EXPECT_DOUBLE_EQ(e.time(), 11 * dt);
    e.advanceTo(5 * dt); // the past: nothing
    EXPECT_EQ(e.steps(), 11);
    e.advanceTo(units::fromFs(30.0)); // 15 steps, although 30/2 in floating point may not be exact
    EXPECT_EQ(e.steps(), 15);
    const auto stats = e.statistics();
    EXPECT_EQ(stats.at("steps").get<long>(), 15);
    EXPECT_GT(stats.at("pair_evaluations").get<long>(), 0);
    EXPECT_DOUBLE_EQ(stats.at("dt_fs").get<double>(), 2.0);
    EXPECT_TRUE(stats.contains("neighbour_rebuilds"));
    EXPECT_EQ(e.snapshot().size(), 216);
    EXPECT_DOUBLE_EQ(e.snapshot().time, e.time());
}

TEST(Engine, RescalesToTemperature) {
    RodEngine e(smd::fixtures::rods(6, 0.5, 1.4, 3), smd::fixtures::smdScene(sigmaRod, 1.8));
    e.advanceTo(units::fromFs(90.0));
    const double kT = 2.5;
    e.rescaleTemperature(kT);
    EXPECT_NEAR(e.kineticEnergy(), 0.5 * degreesOfFreedom<LinearRotor>(216) * kT,
                1e-12 * e.kineticEnergy()); // one multiplication's round-off per body
}

TEST(Engine, PotentialEnergyIsTheSmoothedAllPairsSum) {
    RodEngine e(smd::fixtures::rods(6, 0.5, 1.4, 4), smd::fixtures::smdScene(sigmaRod, 1.8));
    e.advanceTo(units::fromFs(180.0));
    // Same terms summed in a different order.
    const smd::Forces all = smd::allPairsForces(e.system());
    EXPECT_NEAR(e.potentialEnergy(), all.potential, 1e-9);
    EXPECT_NEAR(e.virial(), all.virial, 1e-9 * std::abs(all.virial));
}

TEST(Engine, ConservesLinearMomentumToRoundOff) {
    RodEngine e(smd::fixtures::rods(6, 0.5, 1.4, 5), smd::fixtures::smdScene(sigmaRod, 1.8));
    const Vec3 p0 = e.totalMomentum();
    e.advanceTo(units::fromFs(500 * 1.8));
    // Each step adds Σ(F - F) round-off: ~1e-16 of |F dt| ~ 10 g/mol Å/100fs per body and step.
    constexpr double roundOffMomentum = 1e-9;
    EXPECT_LT((e.totalMomentum() - p0).norm(), roundOffMomentum);
    LJEngine lj(smd::fixtures::ljSpheres(8, 0.8442, 1.44, 6), smd::fixtures::smdScene(1.0, 0.5));
    const Vec3 q0 = lj.totalMomentum();
    lj.advanceTo(units::fromFs(500 * 0.5));
    EXPECT_LT((lj.totalMomentum() - q0).norm(), roundOffMomentum);
}

TEST(Engine, IsolatedClusterConservesAngularMomentum) {
    // Three rods close together in a box so large that no periodic image is ever in reach.
    System<LinearRotor, smd::fixtures::RodModel> sys = smd::fixtures::rods(1, 0.5, 1.4, 7);
    sys.box.length = 1000.0;
    std::mt19937_64 rng(8);
    sys.bodies.clear();
    const Vec3 sites[3] = {{0, 0, 0}, {1.15 * sigmaRod, 0, 0}, {0.5 * sigmaRod, sigmaRod, 0.3}};
    for (const Vec3& r : sites) {
        LinearRotor::State b;
        b.r = r + Vec3(500, 500, 500);
        b.s = smd::fixtures::randomUnit(rng);
        b.v = 0.3 * smd::fixtures::randomUnit(rng);
        const Vec3 w = 2.0 * smd::fixtures::randomUnit(rng);
        b.w = w - w.dot(b.s) * b.s;
        sys.bodies.push_back(b);
    }
    RodEngine e(sys, smd::fixtures::smdScene(sigmaRod, 1.8));
    const Vec3 l0 = totalAngularMomentum(e.system());
    ASSERT_GT(e.pairEvaluations(), 0);
    const double u0 = e.potentialEnergy();
    e.advanceTo(units::fromFs(2000 * 1.8));
    EXPECT_NE(e.potentialEnergy(), u0); // the rods did interact
    // Central forces and τ_ij = -τ_ji: each kick changes L by round-off of r × F ~ 1e-16·500 Å·F.
    constexpr double roundOffAngularMomentum = 1e-8;
    EXPECT_LT((totalAngularMomentum(e.system()) - l0).norm(), roundOffAngularMomentum)
        << "L0 = " << l0.transpose();
}

TEST(Engine, TimeReversible) {
    const auto start = smd::fixtures::rods(6, 0.5, 1.4, 9);
    // Equilibrate away from the lattice first so that the test runs in a liquid.
    RodEngine warm(start, smd::fixtures::smdScene(sigmaRod, 1.8));
    warm.advanceTo(units::fromFs(200 * 1.8));
    RodEngine e(warm.system(), smd::fixtures::smdScene(sigmaRod, 1.8));
    const auto before = e.system().bodies;
    e.advanceTo(200 * e.parameters().dt);
    e.reverseMotion();
    e.advanceTo(400 * e.parameters().dt);
    ASSERT_GT(e.neighbourRebuilds(), 0); // rebuilds on the way there and back do not matter
    // Round-off amplified by the liquid's chaos over 2 × 200 steps stays orders below this.
    constexpr double reversibilityTolerance = 1e-8; // Å
    double worstPosition = 0.0, worstAxis = 0.0;
    for (std::size_t i = 0; i < before.size(); ++i) {
        worstPosition = std::max(worstPosition, (e.system().bodies[i].r - before[i].r).norm());
        worstAxis = std::max(worstAxis, (e.system().bodies[i].s - before[i].s).norm());
    }
    EXPECT_LT(worstPosition, reversibilityTolerance);
    EXPECT_LT(worstAxis, reversibilityTolerance / sigmaRod);
    std::cout << "largest position error after 200 steps there and back: " << worstPosition
              << " Å\n";
}

namespace {

template <BodyKind Top> void checkTops(const Vec3& inertia) {
    const auto rods = smd::fixtures::rods(6, 0.5, 1.4, 22);
    smd::SceneEngine<Top, smd::fixtures::RodModel> e(
        smd::fixtures::topsFromRods<Top>(rods, inertia), smd::fixtures::smdScene(sigmaRod, 1.0));
    const Vec3 p0 = e.totalMomentum();
    const double e0 = e.kineticEnergy() + e.potentialEnergy();
    e.advanceTo(units::fromFs(200.0));
    EXPECT_LT((e.totalMomentum() - p0).norm(), 1e-9); // round-off, as for rods
    // Rods at 1.8 fs hold std(E) near 1e-4 |U|; 1 fs over 200 steps from the lattice start
    // stays well inside ten times that, while a wrong torque coupling is off by far more.
    constexpr double energyTolerance = 1e-3;
    EXPECT_LT(std::abs(e.kineticEnergy() + e.potentialEnergy() - e0),
              energyTolerance * std::abs(e.potentialEnergy()));
}

} // namespace

TEST(Engine, RunsSymmetricTops) {
    checkTops<SymmetricTop>(Vec3(1.154, 1.154, 0.4));
}

TEST(Engine, RunsAsymmetricTops) {
    checkTops<AsymmetricTop>(Vec3(0.9, 1.154, 0.4));
}

TEST(Engine, OverlappingBodiesAreNamedNotBlamedOnTheTimeStep) {
    // Bodies 1 and 2 on top of each other, placed through state.particles as a user would.
    const nlohmann::json particles = nlohmann::json::array(
        {{{"r", {0, 0, 0}}}, {{"r", {20, 20, 20}}}, {{"r", {20, 20, 20}}}, {{"r", {20, 0, 0}}}});
    const Scene scene = sceneFromJson(
        {{"engine", "smd"}, {"state", {{"density", 0.001}, {"particles", particles}}}}, "t");
    const auto sys = buildInitialState<LinearRotor>(
        scene, smd::fixtures::RodModel{rodPotential(scene), sceneCutoff(scene)});
    try {
        RodEngine e(sys, scene);
        ADD_FAILURE() << "no error for an overlap";
    } catch (const SceneError& e) {
        EXPECT_EQ(std::string(e.what()),
                  "state: bodies 1 and 2 overlap (U = 30021808902.357002 kJ/mol)");
    }
    // Spheres too (LJ has no axis).
    const Scene lj = sceneFromJson({{"engine", "smd"},
                                    {"body", {{"kind", "sphere"}}},
                                    {"potential", {{"kind", "lj"}}},
                                    {"state", {{"density", 0.001}, {"particles", particles}}}},
                                   "t");
    expectSceneError(
        [&] {
            LJEngine e(buildInitialState<Sphere>(
                           lj, smd::fixtures::LJModel{ljPotential(lj), sceneCutoff(lj)}),
                       lj);
        },
        "state: bodies 1 and 2 overlap");
}

// Inside the engine the bodies follow the neighbour list's cell order, re-sorted at every list
// build (unless TERRACE_MEASURE=no-sort-smd); outside it they keep the scene's numbering. The slots
// are filled in the scene's order whatever the engine's, so every sum runs in the same order: with
// and without the sort the trajectory is the same bit for bit, by scene number, through list
// rebuilds, thermostat rescales and a rebuild of the engine from its bodies and checkpoint.
// 12³ rods at ρ* = 0.5: nine cells per edge, some 20 list builds.
TEST(Engine, BodyOrderChangesNoObservable) {
    const Scene sorted = smd::fixtures::smdScene(sigmaRod, 1.8);
    const auto start = smd::fixtures::rods(12, 0.5, 1.4, 11);
    auto unsorted = [&](auto&&... args) {
        const terrace::testing::MeasureGuard measure("no-sort-smd");
        return std::make_unique<RodEngine>(args...);
    };
    auto a = std::make_unique<RodEngine>(start, sorted);
    auto b = unsorted(start, sorted);
    auto expectSame = [&] {
        const Snapshot sa = a->snapshot(), sb = b->snapshot();
        ASSERT_EQ(sa.size(), sb.size());
        for (int i = 0; i < sa.size(); ++i) {
            ASSERT_EQ(sa.position[i], sb.position[i]) << "body " << i;
            ASSERT_EQ(sa.velocity[i], sb.velocity[i]) << "body " << i;
            ASSERT_EQ(sa.axis[i], sb.axis[i]) << "body " << i;
            ASSERT_EQ(sa.omega[i], sb.omega[i]) << "body " << i;
        }
        const auto bodiesA = a->system().bodies, bodiesB = b->system().bodies;
        for (std::size_t i = 0; i < bodiesB.size(); ++i)
            ASSERT_EQ(bodiesA[i].r, bodiesB[i].r) << "body " << i;
        EXPECT_EQ(a->potentialEnergy(), b->potentialEnergy());
        EXPECT_EQ(a->virial(), b->virial());
        EXPECT_EQ(a->kineticEnergy(), b->kineticEnergy());
        EXPECT_EQ(a->translationalKineticEnergy(), b->translationalKineticEnergy());
        EXPECT_EQ(a->totalMomentum(), b->totalMomentum());
        EXPECT_EQ(a->pairEvaluations(), b->pairEvaluations());
        EXPECT_EQ(a->neighbourRebuilds(), b->neighbourRebuilds());
    };
    int moved = 0;
    for (int k = 0; k < start.size(); ++k) {
        EXPECT_EQ(b->sceneIndex(k), k);
        moved += a->sceneIndex(k) != k;
    }
    EXPECT_GT(moved, start.size() / 2); // the lattice's order is not the cells'
    expectSame();
    const double dt = a->parameters().dt;
    for (int tick = 1; tick <= 4; ++tick) { // thermostat every 25 steps
        a->advanceTo(25 * tick * dt);
        b->advanceTo(25 * tick * dt);
        a->rescaleTemperature(start.kT);
        b->rescaleTemperature(start.kT);
    }
    expectSame();
    EXPECT_GT(b->neighbourRebuilds(), 3);
    // Engines rebuilt from their bodies and checkpoints (a restart point) go on the same way.
    a = std::make_unique<RodEngine>(a->system(), sorted, a->checkpoint());
    b = unsorted(b->system(), sorted, b->checkpoint());
    expectSame();
    a->advanceTo(300 * dt);
    b->advanceTo(300 * dt);
    EXPECT_GT(b->neighbourRebuilds(), 3);
    expectSame();
    moved = 0;
    for (int k = 0; k < start.size(); ++k)
        moved += a->sceneIndex(k) != k;
    EXPECT_GT(moved, start.size() / 2);
}

} // namespace test_engine
