// Many-body behaviour of the DMD engine on small systems: conservation, bookkeeping, queue and
// invalidation variants, reversibility, bad input, stall detection.
#include "core/asymmetric_top.hpp"
#include "core/sphere.hpp"
#include "core/symmetric_top.hpp"
#include "dmd/testing.hpp"
#include "test_systems.hpp"
#include "tests/measure_guard.hpp"
#include "tests/sample_parts.hpp"
#include <algorithm>
#include <array>
#include <gtest/gtest.h>
#include <span>
#include <string>

namespace test_engine {

using terrace::dmd::testing::Probe;

using namespace terrace;
using namespace terrace::dmdtest;

namespace {

// Each collision conserves energy to a few ulps; 10^5 events random-walk to well below this.
constexpr double energyTolerance = 1e-12;
// Momentum starts at round-off (~1e-15 per body) and each impulse adds ±S F/m exactly.
constexpr double momentumTolerance = 1e-11;

// A small dense liquid: 64 rods at the paper's ρ* = 0.5, T* = 1.4.
Scene denseScene(double dV = 0.5) {
    return rodScene(64, 0.5, 1.4, dV);
}

bool sameBodies(const RodSystem& a, const RodSystem& b) {
    for (int i = 0; i < a.size(); ++i)
        if (a.bodies[i].r != b.bodies[i].r || a.bodies[i].v != b.bodies[i].v ||
            a.bodies[i].s != b.bodies[i].s || a.bodies[i].w != b.bodies[i].w)
            return false;
    return true;
}

/// Two rods in the well, never colliding: parallel along z, 3.95 Å apart along x, body 0 turning
/// about x (c = cos ωt), so r_e = 4.45 − c² runs over [3.45, 4.45] Å, inside terrace −1
/// (r_e in (3.09, 4.48) Å at ΔV = kT/2): U swings between −3.0 and −1.08 kJ/mol.
RodSystem turningPairInTheWell() {
    RodSystem sys;
    sys.box.length = 40.0;
    sys.body.mass = 18.0;
    sys.body.inertia = Vec3(1.154, 1.154, 0.0);
    sys.kT = 4.2;
    sys.bodies.resize(2);
    sys.bodies[0].r = Vec3(10.0, 10.0, 10.0);
    sys.bodies[0].w = Vec3(3.0, 0.0, 0.0);
    sys.bodies[1].r = Vec3(13.95, 10.0, 10.0);
    return sys;
}

} // namespace

TEST(Engine, ShortRunConservesEnergyAndMomentum) {
    const Scene s = denseScene();
    RodEngine e(rodSystem(s), s);
    const double e0 = totalEnergy(e);
    Probe::runEvents(e, 100000);
    EXPECT_GT(Probe::counts(e).up + Probe::counts(e).down, 1000u);
    EXPECT_NEAR(totalEnergy(e), e0, energyTolerance * std::abs(e0));
    EXPECT_LT(e.totalMomentum().norm(), momentumTolerance);
}

TEST(Engine, BookkeptTerracedEnergyEqualsRecomputedAtEverySample) {
    const Scene s = denseScene();
    RodEngine e(rodSystem(s), s);
    const double dV = Probe::levels(e).step();
    for (int k = 1; k <= 100; ++k) {
        e.advanceTo(units::fromFs(10.0 * k));
        // Sample times fall between events, never on a level: any disagreement is a whole ΔV.
        ASSERT_NEAR(e.potentialEnergy(), Probe::terracedEnergyFromScratch(e), 1e-6 * dV)
            << "sample " << k;
    }
    EXPECT_GT(Probe::counts(e).up, 100u);
}

TEST(Engine, HeapAndBoundedQueueGiveTheSameTrajectory) {
    Scene heap = denseScene(), bpq = denseScene();
    heap.dmd["queue"] = "heap";
    bpq.dmd["queue"] = "bpq";
    RodEngine a(rodSystem(heap), heap), b(rodSystem(bpq), bpq);
    for (int k = 1; k <= 20; ++k) {
        a.advanceTo(units::fromFs(25.0 * k));
        b.advanceTo(units::fromFs(25.0 * k));
    }
    EXPECT_GT(Probe::counts(a).total(), 5000u);
    EXPECT_EQ(Probe::counts(a).total(), Probe::counts(b).total());
    EXPECT_TRUE(sameBodies(a.system(), b.system())); // bit for bit
}

// The tournament tree keeps one entry per body, overwriting the one a body's new entry supersedes
// where the heap leaves it stale: the same valid entries leave in the same order, bit for bit, in
// both invalidation modes, and none is ever popped stale but those whose owner dropped its entry
// without a new one.
TEST(Engine, TreeAndHeapGiveTheSameTrajectory) {
    for (const char* invalidation : {"lazy", "eager"}) {
        Scene heap = denseScene(), tree = denseScene();
        heap.dmd["queue"] = "heap";
        tree.dmd["queue"] = "tree";
        heap.dmd["invalidation"] = tree.dmd["invalidation"] = invalidation;
        RodEngine a(rodSystem(heap), heap), b(rodSystem(tree), tree);
        for (int k = 1; k <= 20; ++k) {
            a.advanceTo(units::fromFs(25.0 * k));
            b.advanceTo(units::fromFs(25.0 * k));
        }
        EXPECT_GT(Probe::counts(a).total(), 5000u);
        EXPECT_EQ(Probe::counts(a).total(), Probe::counts(b).total()) << invalidation;
        EXPECT_TRUE(sameBodies(a.system(), b.system())) << invalidation;
        EXPECT_EQ(b.statistics()["queue"], "tree");
        if (std::string(invalidation) == "lazy") {
            EXPECT_LT(b.statistics()["stale_events"].get<double>(),
                      0.05 * a.statistics()["stale_events"].get<double>());
        }
    }
}

// The hold-time screen (dmd/terrace_hold.hpp) only skips searches that could not find an event:
// with and without it, 512 dense rods undergo the same collisions, in the same order, to the
// last digits, until the chaos of the liquid amplifies the round-off of the root refinement
// (whose samples the screen moves): over 100 fs (~1600 collisions) bodies agree to ~1e-11, and
// the difference then grows e-fold every ~12 fs. The screened run needs far fewer samples.
TEST(Engine, HoldScreenChangesNoCollision) {
    const Scene s = rodScene(512, 0.5, 1.4, 0.5);
    RodEngine screened(rodSystem(s), s), searched(rodSystem(s), s);
    Probe::setHoldScreen(screened, true); // the same fresh start for both
    Probe::setHoldScreen(searched, false);
    const auto count = [](const RodEngine& e, const char* key) {
        return e.statistics()[key].get<double>();
    };
    const double screenedAtStart = count(searched, "searches_screened");
    expectSameCollisions(screened, searched, 50);
    if (HasFatalFailure()) return;
    EXPECT_GT(Probe::counts(screened).up + Probe::counts(screened).down +
                  Probe::counts(screened).reflect,
              1000u);
    const RodSystem a = screened.system(), b = searched.system();
    double largest = 0.0;
    for (int i = 0; i < a.size(); ++i)
        largest = std::max({largest, (a.bodies[i].r - b.bodies[i].r).norm(),
                            (a.bodies[i].v - b.bodies[i].v).norm(),
                            (a.bodies[i].w - b.bodies[i].w).norm()});
    EXPECT_LT(largest, 1e-9);
    EXPECT_LT(count(screened, "search_evaluations"), 0.7 * count(searched, "search_evaluations"));
    EXPECT_GT(count(screened, "searches_screened"), screenedAtStart);
    EXPECT_EQ(count(searched, "searches_screened"), screenedAtStart);
}

// The calendar is the tournament tree unless the scene chooses another; the choice stands, and
// the engine reports the queue it took.
TEST(Engine, TheQueueIsTheTreeUnlessChosen) {
    Scene s = denseScene();
    ASSERT_FALSE(s.dmd.contains("queue"));
    const auto potential = rodPotential(s);
    const auto kind = [&] {
        return dmd::readDmdSettings(s.dmd, potential, s.kT(), s.boxLength()).queue;
    };
    EXPECT_EQ(kind(), dmd::QueueKind::Tree);
    const Scene small = denseScene();
    EXPECT_EQ(RodEngine(rodSystem(small), small).statistics()["queue"], "tree");
    s.dmd["queue"] = "bpq";
    EXPECT_EQ(kind(), dmd::QueueKind::BoundedPriority);
    EXPECT_EQ(RodEngine(rodSystem(s), s).statistics()["queue"], "bpq");
    s.dmd["queue"] = "heap";
    EXPECT_EQ(kind(), dmd::QueueKind::Heap);
    EXPECT_EQ(RodEngine(rodSystem(s), s).statistics()["queue"], "heap");
    s.dmd["queue"] = "tree";
    EXPECT_EQ(kind(), dmd::QueueKind::Tree);
}

// In the engine's Morton order, with clocks apart (between events) and after a synchronisation.
TEST(Engine, PartsOfASampleAreTheWholeSnapshotsOwn) {
    const Scene s = rodScene(216, 0.5, 1.4, 0.5);
    RodEngine e(rodSystem(s), s);
    Probe::runEvents(e, 3000);
    terrace::testing::expectPartsOfTheSnapshot(e);
    e.advanceTo(e.time() + 0.05);
    terrace::testing::expectPartsOfTheSnapshot(e);
}

// Inside the engine the bodies are numbered in the Morton order of their cells (unless
// TERRACE_MEASURE=no-sort-dmd, for memory locality); outside, they keep the scene's numbering. The
// order changes only which pair is predicted first, and so which horizon each search draws: with
// and without it 512 dense rods undergo the same collisions over 100 fs, the terraced energy is the
// same integer sum, and every body, taken by its scene number, agrees to round-off grown by the
// chaos of the liquid (as with the hold screen above). Snapshots, copies and checkpoints come in
// the scene's order.
TEST(Engine, BodyOrderChangesNoObservable) {
    const Scene sorted = rodScene(512, 0.5, 1.4, 0.5);
    const RodSystem start = rodSystem(sorted);
    RodEngine a(start, sorted);
    RodEngine b = [&] {
        const terrace::testing::MeasureGuard unsorted("no-sort-dmd");
        return RodEngine(start, sorted);
    }();
    ASSERT_GE(Probe::cellsPerSide(a), 3);
    int moved = 0;
    for (int k = 0; k < start.size(); ++k) {
        ASSERT_EQ(Probe::engineIndex(a, Probe::sceneIndex(a, k)), k);
        ASSERT_EQ(Probe::sceneIndex(b, k), k);
        moved += Probe::sceneIndex(a, k) != k;
    }
    EXPECT_GT(moved, start.size() / 2); // the lattice's order is not the cells' Morton order
    // At the start both engines hand the bodies back in the order given, the same bit for bit.
    EXPECT_TRUE(sameBodies(a.system(), b.system()));
    expectSameCollisions(a, b, 50);
    if (HasFatalFailure()) return;
    EXPECT_GT(Probe::counts(a).up + Probe::counts(a).down + Probe::counts(a).reflect, 1000u);
    EXPECT_EQ(a.potentialEnergy(), b.potentialEnergy());
    EXPECT_NEAR(a.kineticEnergy(), b.kineticEnergy(), 1e-9 * b.kineticEnergy());
    const ContinuousSums ca = a.continuousSums(), cb = b.continuousSums();
    EXPECT_NEAR(ca.potential, cb.potential, 1e-9 * std::abs(cb.potential));
    EXPECT_NEAR(ca.virial, cb.virial, 1e-9 * std::abs(cb.virial));
    const Snapshot sa = a.snapshot(), sb = b.snapshot();
    ASSERT_EQ(sa.size(), sb.size());
    double largest = 0.0;
    for (int i = 0; i < sa.size(); ++i)
        largest = std::max({largest, (sa.position[i] - sb.position[i]).norm(),
                            (sa.velocity[i] - sb.velocity[i]).norm(),
                            (sa.axis[i] - sb.axis[i]).norm(), (sa.omega[i] - sb.omega[i]).norm()});
    EXPECT_LT(largest, 1e-9);
    for (int i = 0; i < start.size(); i += 37)
        for (int j = i + 1; j < start.size(); j += 11)
            ASSERT_EQ(Probe::terrace(a, i, j), Probe::terrace(b, i, j)) << i << " " << j;
    // The checkpoint lists the same pairs on the same terraces, by scene number.
    auto pairs = [](const RodEngine& e) {
        std::vector<std::array<int, 3>> list;
        for (const dmd::PairTerrace& p : dmd::pairTerraces(e.checkpoint().at("terraces")))
            list.push_back({p.i, p.j, p.terrace});
        std::sort(list.begin(), list.end());
        return list;
    };
    EXPECT_EQ(pairs(a), pairs(b));
}

// The order decays as the liquid diffuses: orderHasDecayed is whether the RMS displacement of the
// bodies since they were numbered (every body, below 4 096) has reached dmd.resort_cells cell
// widths. Three engines that differ only in that threshold undergo the same events; the RMS is
// taken here from their snapshots, and a threshold just above it and just below it fall on
// either side. Unsorted bodies have no order to lose. Left to itself (auto) the threshold is one
// cell width where the engine's data outgrow the caches, and never below.
TEST(Engine, OrderDecaysWhenTheBodiesHaveMovedTheirShareOfACell) {
    Scene s = rodScene(512, 0.5, 1.4, 0.5);
    const RodSystem start = rodSystem(s);
    RodEngine probe(start, s);
    ASSERT_GE(Probe::cellsPerSide(probe), 3);
    EXPECT_FALSE(Probe::orderHasDecayed(probe));
    probe.advanceTo(units::fromFs(30.0));
    const Snapshot now = probe.snapshot();
    double sum = 0.0;
    for (int i = 0; i < now.size(); ++i)
        sum += start.box.minimumImage(now.position[i] - start.bodies[i].r).squaredNorm();
    const double cells =
        std::sqrt(sum / now.size()) / (start.box.length / Probe::cellsPerSide(probe));
    ASSERT_GT(cells, 0.01);
    ASSERT_LT(cells, 1.0);
    EXPECT_FALSE(Probe::orderHasDecayed(probe));
    EXPECT_EQ(Probe::resortDistance(probe),
              0.0); // auto: never below dmd::prefetchFromBodies bodies
    for (const double factor : {0.99, 1.01}) {
        Scene t = s;
        t.dmd["resort_cells"] = factor * cells;
        RodEngine e(start, t);
        e.advanceTo(units::fromFs(30.0));
        EXPECT_EQ(Probe::counts(e).total(), Probe::counts(probe).total());
        EXPECT_EQ(Probe::orderHasDecayed(e), factor < 1.0) << factor;
    }
    Scene never = s, unsorted = s;
    never.dmd["resort_cells"] = 0.0;
    unsorted.dmd["resort_cells"] = 1e-6;
    for (const std::string measure : {"", "no-sort-dmd"}) {
        const terrace::testing::MeasureGuard guard(measure);
        RodEngine e(start, measure.empty() ? never : unsorted);
        e.advanceTo(units::fromFs(30.0));
        EXPECT_FALSE(Probe::orderHasDecayed(e));
        EXPECT_EQ(Probe::resortDistance(e), 0.0);
    }
    // From dmd::prefetchFromBodies bodies on, auto is one cell width; above 4 096 bodies the
    // sample is every stride-th body in the engine's numbering (16 384: every fourth), and the
    // threshold brackets the RMS over just those.
    Scene large = rodScene(dmd::prefetchFromBodies, 0.5, 1.4, 0.5);
    const RodSystem bigStart = rodSystem(large);
    RodEngine big(bigStart, large);
    EXPECT_NEAR(Probe::resortDistance(big), large.boxLength() / Probe::cellsPerSide(big), 1e-12);
    ASSERT_EQ(Probe::orderSampleBodies(big), 4096u);
    big.advanceTo(units::fromFs(10.0));
    const Snapshot bigNow = big.snapshot();
    double sampled = 0.0;
    for (int k = 0; k < 4096; ++k) {
        const int b = Probe::sceneIndex(big, 4 * k);
        sampled +=
            bigStart.box.minimumImage(bigNow.position[b] - bigStart.bodies[b].r).squaredNorm();
    }
    const double bigCells =
        std::sqrt(sampled / 4096) / (large.boxLength() / Probe::cellsPerSide(big));
    // (Tight: another 4 096 bodies would give an RMS ~0.6 % away.)
    for (const double factor : {0.9999, 1.0001}) {
        large.dmd["resort_cells"] = factor * bigCells;
        RodEngine e(bigStart, large);
        e.advanceTo(units::fromFs(10.0));
        EXPECT_EQ(Probe::orderHasDecayed(e), factor < 1.0) << factor;
    }
}

// advanceTo renumbers the bodies where their order has decayed, by the rebuild a restart point
// does: an engine that renumbers at every sample but the first undergoes the same events as one
// rebuilt from its released bodies and checkpoint at the same instants, and counts the
// renumberings.
TEST(Engine, RenumberingInsideAdvanceToIsTheRebuildOfARestartPoint) {
    const Scene s = rodScene(512, 0.5, 1.4, 0.5);
    Scene renumbering = s, never = s;
    renumbering.dmd["resort_cells"] = 1e-3;
    never.dmd["resort_cells"] = 0.0;
    RodEngine a(rodSystem(s), renumbering);
    auto b = std::make_unique<RodEngine>(rodSystem(s), never);
    constexpr int samples = 5;
    dmd::EventCounts inB; // over b's engines, each of which counts from its start
    auto addCounts = [&inB](const dmd::EventCounts& c) {
        inB.up += c.up, inB.down += c.down, inB.reflect += c.reflect;
        inB.virtualEvents += c.virtualEvents, inB.cell += c.cell, inB.relist += c.relist;
    };
    for (int k = 1; k <= samples; ++k) {
        const double t = units::fromFs(9.0 * k);
        a.advanceTo(t);
        b->advanceTo(t);
        addCounts(Probe::counts(*b));
        if (k == samples) break; // a renumbers at the start of its next advanceTo
        auto released = std::move(*b).release();
        b.reset();
        b = std::make_unique<RodEngine>(std::move(released.system), never,
                                        std::move(released.checkpoint));
    }
    EXPECT_EQ(a.statistics().at("resorts"), samples - 1);
    EXPECT_TRUE(sameBodies(a.system(), b->system())); // bit for bit
    EXPECT_EQ(a.potentialEnergy(), b->potentialEnergy());
    EXPECT_EQ(a.virial(), b->virial());
    // The counters carried over the renumberings: every event of b's engines, in a's alone.
    const dmd::EventCounts& inA = Probe::counts(a);
    EXPECT_GT(inA.up + inA.down, 0u);
    EXPECT_EQ(inA.up, inB.up);
    EXPECT_EQ(inA.down, inB.down);
    EXPECT_EQ(inA.reflect, inB.reflect);
    EXPECT_EQ(inA.virtualEvents, inB.virtualEvents);
    EXPECT_EQ(inA.cell, inB.cell);
    EXPECT_EQ(inA.relist, inB.relist);
}

// Both modes push the same calendar entries in the same order (one erases what the other leaves
// stale), so even events at one instant — a relist due now, say — come in the same order: 512
// bodies over 1 ps, where entries renewed only when their stale predecessor surfaced had already
// parted the two. (The tree overwrites an entry its owner's next one supersedes: lazy, it pops
// stale only the few an owner dropped without a new one.)
TEST(Engine, LazyAndEagerInvalidationGiveTheSameTrajectory) {
    for (const char* queue : {"heap", "tree"}) {
        Scene lazy = rodScene(512, 0.5, 1.4, 0.5);
        lazy.dmd["queue"] = queue;
        Scene eager = lazy;
        lazy.dmd["invalidation"] = "lazy";
        eager.dmd["invalidation"] = "eager";
        RodEngine a(rodSystem(lazy), lazy), b(rodSystem(eager), eager);
        a.advanceTo(units::fromPs(1.0));
        b.advanceTo(units::fromPs(1.0));
        EXPECT_EQ(Probe::counts(a).total(), Probe::counts(b).total()) << queue;
        EXPECT_EQ(Probe::counts(a).up, Probe::counts(b).up);
        EXPECT_EQ(Probe::counts(a).reflect, Probe::counts(b).reflect);
        EXPECT_TRUE(sameBodies(a.system(), b.system())) << queue;
        EXPECT_EQ(b.statistics()["stale_events"], 0); // eager leaves nothing stale in the queue
        if (std::string(queue) == "heap") {
            EXPECT_GT(a.statistics()["stale_events"].get<long>(), 0);
        }
    }
}

// The calendar holds one entry per body (the earliest event of its agenda): with eager
// invalidation, where superseded and invalidated entries are erased at once, it never holds more
// than N; with lazy invalidation it pops some two stale entries per collision (the entries of
// the two bodies and of those whose earliest event was with one of them), where a calendar of
// every predicted event popped some eighteen.
TEST(Engine, CalendarHoldsOneEntryPerBody) {
    Scene lazy = denseScene(), eager = denseScene();
    lazy.dmd["queue"] = eager.dmd["queue"] =
        "heap"; // the tree holds one entry per body by its shape
    lazy.dmd["invalidation"] = "lazy";
    eager.dmd["invalidation"] = "eager";
    RodEngine a(rodSystem(lazy), lazy), b(rodSystem(eager), eager);
    const std::size_t n = static_cast<std::size_t>(a.system().size());
    for (int k = 0; k < 200; ++k) {
        Probe::runEvents(b, 100);
        ASSERT_LE(Probe::queueSize(b), n) << "after " << 100 * (k + 1) << " events";
    }
    Probe::runEvents(a, 20000);
    const double collisions =
        Probe::counts(a).up + Probe::counts(a).down + Probe::counts(a).reflect;
    EXPECT_LT(a.statistics()["stale_events"].get<double>(), 3.0 * collisions);
}

TEST(Engine, RescalingSetsTheTemperatureAndKeepsTheEnergyAfterwards) {
    const Scene s = denseScene();
    RodEngine e(rodSystem(s), s);
    e.advanceTo(units::fromFs(100.0));
    e.rescaleTemperature(2.0);
    const int dof = degreesOfFreedom<LinearRotor>(64);
    EXPECT_NEAR(e.kineticEnergy(), 0.5 * dof * 2.0, 1e-12 * dof);
    const double e0 = totalEnergy(e);
    e.advanceTo(units::fromFs(200.0));
    EXPECT_NEAR(totalEnergy(e), e0, energyTolerance * std::abs(e0));
}

// Reverse every velocity and angular velocity at time t and run for t again: the bodies return
// to their start. Round-off grows with the (short) run's chaos; 1e-7 Å is far below any physics.
TEST(Engine, TimeReversalReturnsToTheStart) {
    constexpr double returnTolerance = 1e-7; // Å and Å per time unit
    const Scene s = denseScene();
    const RodSystem start = rodSystem(s);
    RodEngine forward(start, s);
    const double t = units::fromFs(200.0);
    forward.advanceTo(t);
    EXPECT_GT(Probe::counts(forward).up + Probe::counts(forward).down +
                  Probe::counts(forward).reflect,
              200u);
    RodSystem reversed = forward.system();
    for (auto& b : reversed.bodies) {
        b.v = -b.v;
        b.w = -b.w;
    }
    RodEngine backward(reversed, s);
    backward.advanceTo(t);
    const RodSystem end = backward.system();
    double worst = 0.0;
    for (int i = 0; i < start.size(); ++i) {
        worst = std::max(worst, (end.bodies[i].r - start.bodies[i].r).norm());
        worst = std::max(worst, (end.bodies[i].s - start.bodies[i].s).norm());
        worst = std::max(worst, (end.bodies[i].v + start.bodies[i].v).norm());
    }
    EXPECT_LT(worst, returnTolerance);
}

// A cluster far from its periodic images: total angular momentum Σ r × p + L is conserved too.
TEST(Engine, IsolatedClusterConservesAngularMomentum) {
    constexpr double angularTolerance = 1e-11;      // relative, after ~10^4 events
    RodSystem sys = alignedLattice(3, 4.2, 1.0, 7); // 27 rods, 12.6 Å across
    sys.box.length = 60.0;                          // images ≥ 47 Å away, r_m ≈ 5 Å
    for (auto& b : sys.bodies) {
        b.r += Vec3(20, 20, 20);
        b.s = Vec3(b.w.x(), 1.0, 0.3).normalized(); // varied axes: torques are nonzero
        b.w -= b.w.dot(b.s) * b.s;
    }
    const Scene s = rodScene(27, 0.5, 1.4, 0.5);
    RodEngine e(sys, s);
    const Vec3 l0 = totalAngularMomentum(e.system());
    Probe::runEvents(e, 20000);
    EXPECT_GT(Probe::counts(e).up + Probe::counts(e).down, 500u);
    const Vec3 l1 = totalAngularMomentum(e.system());
    EXPECT_LT((l1 - l0).norm(), angularTolerance * std::max(1.0, l0.norm()));
}

namespace {
std::string errorOf(const Scene& s, const RodSystem& sys) {
    try {
        RodEngine e(sys, s);
    } catch (const SceneError& err) {
        return err.what();
    }
    return "";
}
} // namespace

TEST(Engine, BadSettingsAreErrorsNamingTheKey) {
    const RodSystem sys = rodSystem(denseScene());
    Scene s = denseScene();
    s.dmd["dV"] = 0.0;
    EXPECT_NE(errorOf(s, sys).find("dmd.dV"), std::string::npos);
    s = denseScene();
    s.dmd["queue"] = "fifo";
    EXPECT_NE(errorOf(s, sys).find("dmd.queue"), std::string::npos);
    s = denseScene();
    s.dmd["invalidation"] = "never";
    EXPECT_NE(errorOf(s, sys).find("dmd.invalidation"), std::string::npos);
    s = denseScene();
    s.dmd["horizon_fs"] = -1.0;
    EXPECT_NE(errorOf(s, sys).find("dmd.horizon_fs"), std::string::npos);
    s = denseScene();
    s.dmd["levels"] = {-3.0, -1.0, 1.0}; // −3 = −ε, the potential's minimum
    EXPECT_NE(errorOf(s, sys).find("dmd.levels"), std::string::npos);
    s = denseScene();
    s.dmd["dV"] = 2.0 / 1.4; // ΔV/2 = ε: the level −ΔV/2 sits on the minimum
    EXPECT_NE(errorOf(s, sys).find("minimum"), std::string::npos);
    RodSystem tiny = sys;
    tiny.box.length = 9.0; // < 2 r_m ≈ 9.96 Å at ΔV = kT/2
    EXPECT_NE(errorOf(denseScene(), tiny).find("r_m"), std::string::npos);
}

TEST(Engine, FewerThanThreeCellsPerSideStillWork) {
    const Scene s = rodScene(27, 0.5, 1.4, 0.5); // L ≈ 11.5 Å < 3 r_m: one cell
    RodEngine e(rodSystem(s), s);
    EXPECT_EQ(e.statistics()["cells_per_side"], 1);
    const double e0 = totalEnergy(e);
    Probe::runEvents(e, 20000);
    EXPECT_NEAR(totalEnergy(e), e0, energyTolerance * std::abs(e0));
    e.advanceTo(e.time() + units::fromFs(0.1)); // off the level the last event left a pair on
    EXPECT_NEAR(e.potentialEnergy(), Probe::terracedEnergyFromScratch(e), 1e-6);
}

// Head-on pairs on a lattice all meet at the same instant. The stall detector, set low, reports
// the stuck clock instead of spinning; at its default the same start simply proceeds.
TEST(Engine, AStoppedClockIsReportedNotSpunOn) {
    RodSystem sys = alignedLattice(4, 6.0, 1.0, 3);
    for (int i = 0; i < sys.size(); ++i) {
        sys.bodies[i].w = Vec3::Zero();
        sys.bodies[i].v = Vec3((i / 16) % 2 == 0 ? 0.5 : -0.5, 0, 0); // x-layers approach
    }
    const Scene s = rodScene(64, 0.5, 1.4, 0.5);
    RodEngine strict(sys, s);
    Probe::setStallLimit(strict, 3);
    try {
        strict.advanceTo(units::fromFs(200.0));
        ADD_FAILURE() << "expected the stall detector to fire";
    } catch (const std::runtime_error& err) {
        EXPECT_NE(std::string(err.what()).find("clock stopped"), std::string::npos) << err.what();
    }
    RodEngine normal(sys, s);
    normal.advanceTo(units::fromFs(200.0));
    EXPECT_DOUBLE_EQ(normal.time(), units::fromFs(200.0));
    EXPECT_GT(Probe::counts(normal).down, 16u);
}

// Bookkeeping that no longer describes the system (a pair on the wrong terrace, as a missed event
// leaves it) is reported with the bodies and the time, not spun on: two rods in the well
// (terrace −1 at ΔV = kT/2), one turning, are put on terrace 0 by hand.
TEST(Engine, APairBeyondItsTerraceIsReported) {
    Scene s = defaultScene();
    s.dmd["dV"] = 0.5;
    RodEngine e(turningPairInTheWell(), s);
    Probe::runEvents(e, 100); // consistent: runs
    ASSERT_EQ(Probe::terrace(e, 0, 1), -1);
    Probe::overrideTerrace(e, 0, 1, 0);
    try {
        Probe::runEvents(e, 100);
        ADD_FAILURE() << "expected the missed event to be reported";
    } catch (const std::logic_error& err) {
        EXPECT_NE(std::string(err.what()).find("an event was missed"), std::string::npos)
            << err.what();
        EXPECT_NE(std::string(err.what()).find("bodies 0 and 1"), std::string::npos) << err.what();
    }
}

static_assert(terrace::Engine<RodEngine>, "the DMD engine fulfils the engines' contract");

namespace {
template <class K, class P> void expectConservation(const Scene& s, const P& potential) {
    dmd::SceneEngine<K, P> e(buildInitialState<K, P>(s, potential), s);
    const double e0 = e.kineticEnergy() + e.potentialEnergy();
    for (int k = 1; k <= 20; ++k) {
        e.advanceTo(units::fromFs(10.0 * k));
        // A missed crossing (a search or a hold screen trusting a wrong bound) shows here.
        ASSERT_NEAR(e.potentialEnergy(), Probe::terracedEnergyFromScratch(e),
                    1e-6 * Probe::levels(e).step())
            << K::name << " at " << 10 * k << " fs";
    }
    EXPECT_GT(Probe::counts(e).up + Probe::counts(e).down, 100u) << K::name;
    EXPECT_NEAR(e.kineticEnergy() + e.potentialEnergy(), e0, energyTolerance * std::abs(e0))
        << K::name;
}
} // namespace

// Free flight uses each kind's exact motion from core: tops and spheres run as rods do.
TEST(Engine, EveryBodyKindConservesEnergy) {
    Scene s = rodScene(64, 0.5, 1.4, 0.5);
    s.body.kind = "symmetric";
    s.body.inertia = Vec3(1.154, 1.154, 0.5);
    expectConservation<SymmetricTop, RodPotential>(s, rodPotential(s));
    s.body.kind = "asymmetric";
    s.body.inertia = Vec3(1.0, 1.5, 0.7);
    expectConservation<AsymmetricTop, RodPotential>(s, rodPotential(s));
    s.body.kind = "sphere";
    s.potential.kind = "lj";
    expectConservation<Sphere, LJPotential>(s, ljPotential(s));
}

// Lennard-Jones spheres at ΔV = kT/2 = 5ε (T* = 10) have no attractive terrace: the lowest terrace
// holds the whole tail, and r_m lies on the wall's first level. A pair transmitted down through
// that level leaves r_m at the same instant, and round-off in U once sent it straight back across,
// in a zero-time loop that the stall watch stopped (here at 184 fs): the gas must run.
TEST(Engine, HotLennardJonesGasWithoutAnAttractiveTerraceAdvances) {
    Scene s = rodScene(16, 0.05, 10.0, 0.5);
    s.seed = 1;
    s.body.kind = "sphere";
    s.potential.kind = "lj";
    dmd::SceneEngine<Sphere, LJPotential> e(
        buildInitialState<Sphere, LJPotential>(s, ljPotential(s)), s);
    const double e0 = e.kineticEnergy() + e.potentialEnergy();
    e.advanceTo(units::fromFs(2000.0));
    EXPECT_EQ(e.time(), units::fromFs(2000.0));
    EXPECT_GT(Probe::counts(e).up + Probe::counts(e).down, 40u);
    EXPECT_NEAR(e.kineticEnergy() + e.potentialEnergy(), e0, energyTolerance * std::abs(e0));
}

// Memory stays bounded when bodies never collide: two rods side by side, one turning in place
// (turningPairInTheWell), keep a chain of virtual events going forever, and each renews the
// calendar entry of the pair's owner, which is listed with its partner (so that invalidating the
// partner would renew it at once). Without pruning those lists grow by one entry per virtual
// event; both modes keep them, eager invalidation also a handle per body.
TEST(Engine, BookkeepingStaysBoundedWithoutCollisions) {
    for (const char* queue : {"bpq", "heap", "tree"})
        for (const char* invalidation : {"lazy", "eager"}) {
            Scene s = defaultScene();
            s.dmd["dV"] = 0.5;
            s.dmd["queue"] = queue;
            s.dmd["invalidation"] = invalidation;
            RodEngine e(turningPairInTheWell(), s);
            ASSERT_EQ(Probe::terrace(e, 0, 1), -1);
            Probe::runEvents(e, 70000); // past the bounded queue's first retuning of its bins
            const std::size_t early = Probe::bytesReserved(e);
            Probe::runEvents(e, 200000);
            EXPECT_EQ(Probe::counts(e).virtualEvents, 270000u) << queue << ", " << invalidation;
            EXPECT_LT(Probe::bytesReserved(e), early + early / 10)
                << queue << ", " << invalidation << ": grew from " << early;
        }
}

} // namespace test_engine
