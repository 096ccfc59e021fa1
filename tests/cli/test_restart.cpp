// Restart points: what a restart file holds comes back bit for bit, and an engine rebuilt from it
// goes on exactly as one rebuilt from the live state (cli/restart.hpp, the engines' checkpoint()).
#include "cli/dispatch.hpp"
#include "cli/restart.hpp"
#include "cli/run_driver.hpp"
#include "core/asymmetric_top.hpp"
#include "core/initial_state.hpp"
#include "core/linear_rotor.hpp"
#include "core/output_file.hpp"
#include "core/smoothed_potential.hpp"
#include "core/species_sphere.hpp"
#include "core/sphere.hpp"
#include "core/symmetric_top.hpp"
#include "dmd/scene_engine.hpp"
#include "dmd/testing.hpp"
#include "smd/scene_engine.hpp"
#include <array>
#include <filesystem>
#include <gtest/gtest.h>
#include <set>
#include <unistd.h>

namespace test_restart {

using terrace::dmd::testing::Probe;

using namespace terrace;

namespace {

Scene smallScene(const std::string& kind) {
    Scene s = defaultScene();
    s.state.n = 64;
    s.body.kind = kind;
    if (kind == "sphere") s.potential.kind = "lj", s.body.inertia = Vec3::Zero();
    if (kind == "symmetric") s.body.inertia = Vec3(1.154, 1.154, 0.4);
    if (kind == "asymmetric") s.body.inertia = Vec3(1.0, 1.3, 0.4);
    return s;
}

template <class State> std::vector<double> numbersOf(State b) {
    std::vector<double> xs;
    cli::forEachField(b,
                      [&](const auto& m) { xs.insert(xs.end(), m.data(), m.data() + m.size()); });
    return xs;
}

template <class State> bool sameBits(const State& a, const State& b) {
    const auto x = numbersOf(a), y = numbersOf(b);
    return x.size() == y.size() && std::memcmp(x.data(), y.data(), x.size() * sizeof(double)) == 0;
}

template <class K, class P> void bodiesRoundTrip(const Scene& scene, const P& potential) {
    const auto sys = buildInitialState<K>(scene, potential);
    // Through CBOR, as restart.bin stores them.
    const auto cbor = nlohmann::json::to_cbor({{"bodies", cli::bodiesToBinary(sys.bodies)}});
    const auto back = cli::bodiesFromBinary<typename K::State>(
        nlohmann::json::from_cbor(cbor).at("bodies"), sys.size());
    ASSERT_EQ(back.size(), sys.bodies.size());
    for (int i = 0; i < sys.size(); ++i)
        EXPECT_TRUE(sameBits(back[i], sys.bodies[i])) << K::name << " body " << i;
    EXPECT_THROW(cli::bodiesFromBinary<typename K::State>(
                     nlohmann::json::from_cbor(cbor).at("bodies"), sys.size() + 1),
                 std::runtime_error);
}

} // namespace

TEST(Restart, BodiesOfEveryKindComeBackBitForBit) {
    bodiesRoundTrip<Sphere>(smallScene("sphere"), ljPotential(smallScene("sphere")));
    bodiesRoundTrip<LinearRotor>(smallScene("linear"), rodPotential(smallScene("linear")));
    bodiesRoundTrip<SymmetricTop>(smallScene("symmetric"), rodPotential(smallScene("symmetric")));
    bodiesRoundTrip<AsymmetricTop>(smallScene("asymmetric"),
                                   rodPotential(smallScene("asymmetric")));
}

// Samples' records (thermo.csv's last row) come back bit for bit through CBOR, NaN (no g(r) frame)
// included; bytes that are not whole records are refused.
TEST(Restart, RecordsComeBackBitForBit) {
    std::vector<cli::SampleRecord> records(3);
    records[0] = {0.125, -3.5, -10.25, 6.75, 4.5, -31.25, 1234.0, 0.5};
    records[1] = {0.25, -3.25, -10.0, 6.75, 4.25, -30.0, 2345.0, 1.0, -9.5, -29.75, -17.125};
    records[2] = {0.375, 1e-300, -0.0, 6.5, 4.0, 1e300, 3456.0, 1.5};
    const auto cbor = nlohmann::json::to_cbor({{"records", cli::recordsToBinary(records)}});
    const auto back = cli::recordsFromBinary(nlohmann::json::from_cbor(cbor).at("records"));
    ASSERT_EQ(back.size(), records.size());
    static_assert(sizeof(cli::SampleRecord) == 11 * sizeof(double));
    for (std::size_t k = 0; k < records.size(); ++k)
        EXPECT_EQ(std::memcmp(&back[k], &records[k], sizeof(cli::SampleRecord)), 0) << k;
    auto bytes = cli::recordsToBinary(records).get_binary();
    bytes.pop_back();
    EXPECT_THROW(cli::recordsFromBinary(nlohmann::json::binary(bytes)), std::runtime_error);
}

namespace {

/// Two engines rebuilt at time t1 from the same bodies and checkpoint — one from the values in
/// memory, one from them after a trip through CBOR — undergo the same events up to t2.
template <template <class, class> class Engine, class K, class P>
void rebuiltEnginesAgree(const Scene& scene, const P& potential, double t1, double t2) {
    std::optional<Engine<K, P>> engine;
    engine.emplace(buildInitialState<K>(scene, potential), scene);
    engine->advanceTo(t1);
    const auto sys = engine->system();
    const nlohmann::json checkpoint = engine->checkpoint();
    const auto stored = nlohmann::json::from_cbor(nlohmann::json::to_cbor(
        {{"bodies", cli::bodiesToBinary(sys.bodies)}, {"engine", checkpoint}}));
    auto fromFile = sys;
    fromFile.bodies = cli::bodiesFromBinary<typename K::State>(stored.at("bodies"), sys.size());
    Engine<K, P> a(sys, scene, checkpoint), b(fromFile, scene, stored.at("engine"));
    EXPECT_EQ(a.time(), engine->time());
    EXPECT_EQ(a.potentialEnergy(), engine->potentialEnergy()); // terraces kept, not re-derived
    a.advanceTo(t2);
    b.advanceTo(t2);
    const Snapshot x = a.snapshot(), y = b.snapshot();
    for (int i = 0; i < x.size(); ++i) {
        ASSERT_EQ(x.position[i], y.position[i]) << "body " << i;
        ASSERT_EQ(x.velocity[i], y.velocity[i]) << "body " << i;
        ASSERT_EQ(x.omega[i], y.omega[i]) << "body " << i;
    }
    auto sa = a.statistics(), sb = b.statistics();
    sa.erase("phase_seconds"), sb.erase("phase_seconds"); // SMD's wall-clock timings
    EXPECT_EQ(sa.dump(), sb.dump());
}

} // namespace

TEST(Restart, RebuiltDmdEnginesAgreeBitForBit) {
    Scene scene = smallScene("linear");
    scene.state.n = 216;
    rebuiltEnginesAgree<dmd::SceneEngine, LinearRotor>(
        scene, Smoothed<RodPotential>{rodPotential(scene), sceneCutoff(scene)}, 0.5, 2.0);
}

TEST(Restart, RebuiltSmdEnginesAgreeBitForBit) {
    Scene scene = smallScene("linear");
    scene.state.n = 216;
    scene.engine = "smd";
    rebuiltEnginesAgree<smd::SceneEngine, LinearRotor>(
        scene, Smoothed<RodPotential>{rodPotential(scene), sceneCutoff(scene)}, 0.09, 0.9);
}

namespace {

using RodDmd = dmd::SceneEngine<LinearRotor, RodPotential>;

/// 216 rods run by DMD to time t: the scene, the bodies there, the engine's checkpoint and r_m.
struct DmdPoint {
    Scene scene;
    System<LinearRotor, RodPotential> sys;
    nlohmann::json checkpoint;
    double rm;
};

DmdPoint dmdPointAt(double t) {
    Scene scene = smallScene("linear");
    scene.state.n = 216;
    RodDmd engine(buildInitialState<LinearRotor>(scene, rodPotential(scene)), scene);
    engine.advanceTo(t);
    return {scene, engine.system(), engine.checkpoint(), Probe::interactionRange(engine)};
}

} // namespace

// The checkpoint keeps each pair's terrace: a pair held off terrace 0 beyond the interaction
// range cannot belong to these bodies and is refused, not silently re-derived.
TEST(Restart, ADmdCheckpointThatDoesNotFitTheBodiesIsRefused) {
    const auto [scene, sys, checkpoint, rm] = dmdPointAt(0.2);
    ASSERT_FALSE(dmd::pairTerraces(checkpoint.at("terraces")).empty());
    int far = 1;
    while ((sys.box.minimumImage(sys.bodies[0].r - sys.bodies[far].r)).norm() < rm)
        ++far;
    for (const dmd::PairTerrace& extra : {dmd::PairTerrace{0, far, -1}, {0, sys.size(), -1}}) {
        nlohmann::json wrong = checkpoint;
        dmd::appendPairTerrace(wrong["terraces"].get_binary(), extra);
        EXPECT_THROW(RodDmd(sys, scene, wrong), SceneError) << extra.j;
    }
}

// The checkpoint's pair terraces are raw bytes, 12 per pair: they decode, after a trip through
// CBOR as in restart.bin, to exactly the pairs the engine holds off terrace 0.
TEST(Restart, ADmdCheckpointsCompactTerracesAreTheEnginesPairs) {
    Scene scene = smallScene("linear");
    scene.state.n = 216;
    RodDmd engine(buildInitialState<LinearRotor>(scene, rodPotential(scene)), scene);
    engine.advanceTo(0.5);
    const nlohmann::json checkpoint = engine.checkpoint();
    ASSERT_TRUE(checkpoint.at("terraces").is_binary());
    const auto stored = nlohmann::json::from_cbor(nlohmann::json::to_cbor(checkpoint));
    std::set<std::array<int, 3>> decoded;
    for (const dmd::PairTerrace& p : dmd::pairTerraces(stored.at("terraces"))) {
        EXPECT_LT(p.i, p.j);
        decoded.insert({p.i, p.j, p.terrace});
    }
    std::set<std::array<int, 3>> held;
    for (int i = 0; i < scene.state.n; ++i)
        for (int j = i + 1; j < scene.state.n; ++j)
            if (Probe::terrace(engine, i, j) != 0)
                held.insert({i, j, Probe::terrace(engine, i, j)});
    EXPECT_GT(held.size(), std::size_t(scene.state.n)); // a dense liquid: several pairs per body
    EXPECT_EQ(decoded, held);
    EXPECT_EQ(stored.at("terraces").get_binary().size(), 12 * held.size());
}

// Pair bytes cut short or damaged, or the JSON arrays of an older checkpoint, are refused with a
// message that says so, rather than read as other pairs.
TEST(Restart, ADamagedDmdPairBlobIsNamed) {
    const auto [scene, sys, checkpoint, rm] = dmdPointAt(0.2);
    auto messageOf = [&, &scene = scene, &sys = sys](const nlohmann::json& c) {
        try {
            RodDmd engine(sys, scene, c);
        } catch (const SceneError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    nlohmann::json cut = checkpoint;
    auto& bytes = cut["terraces"].get_binary();
    bytes.resize(bytes.size() - 5);
    EXPECT_EQ(messageOf(cut), "restart: the DMD pair terraces hold " +
                                  std::to_string(bytes.size()) +
                                  " bytes, not whole records of 12 (damaged or cut short)");
    nlohmann::json arrays = checkpoint;
    arrays["terraces"] = nlohmann::json::array({{0, 1, -1}});
    EXPECT_EQ(messageOf(arrays),
              "restart: the DMD pair terraces are not raw bytes (a checkpoint of another format)");
}

TEST(Restart, StatisticsAddUpOverRebuiltStretches) {
    nlohmann::json production = nlohmann::json::object();
    cli::accumulateStatistics(production,
                              {{"events", {{"up", 10}}},
                               {"max_queue_size", 5},
                               {"phase_seconds", {{"force", 1.0}}},
                               {"r_m_angstrom", 9.0}},
                              {{"events", {{"up", 25}}},
                               {"max_queue_size", 7},
                               {"phase_seconds", {{"force", 1.5}}},
                               {"r_m_angstrom", 9.0}});
    cli::accumulateStatistics(production,
                              {{"events", {{"up", 0}}},
                               {"max_queue_size", 1},
                               {"phase_seconds", {{"force", 0.0}}},
                               {"r_m_angstrom", 9.5}},
                              {{"events", {{"up", 4}}},
                               {"max_queue_size", 3},
                               {"phase_seconds", {{"force", 0.25}}},
                               {"r_m_angstrom", 9.5}});
    EXPECT_EQ(production["events"]["up"], 19);             // counters: increases add up
    EXPECT_EQ(production["max_queue_size"], 7);            // maxima: the largest
    EXPECT_EQ(production["phase_seconds"]["force"], 0.75); // durations: add up
    EXPECT_EQ(production["r_m_angstrom"], 9.5);            // settings: the value at the end
}

// The horizon stream goes on where it stood, rather than starting over at every restart point:
// the same bodies and terraces with the stream elsewhere undergo other virtual events.
TEST(Restart, ADmdEngineContinuesItsHorizonStream) {
    const auto [scene, sys, checkpoint, rm] = dmdPointAt(0.5);
    nlohmann::json elsewhere = checkpoint;
    elsewhere["horizon_stream"]["state"] =
        checkpoint["horizon_stream"]["state"].get<std::uint64_t>() + 1;
    RodDmd a(sys, scene, checkpoint), b(sys, scene, elsewhere);
    a.advanceTo(1.0);
    b.advanceTo(1.0);
    EXPECT_NE(a.statistics()["events"]["virtual"], b.statistics()["events"]["virtual"]);
}

// A restart file of another format (version 1's samples lack the pressure's terms, version 2's
// DMD checkpoint holds its pairs as JSON arrays, version 6's the samples' records in place of
// their statistics, version 7's samples no heat bath) is named as such, not read as damaged or
// misread.
TEST(Restart, ARestartFileOfAnotherFormatIsNamed) {
    const auto dir =
        std::filesystem::temp_directory_path() / ("terrace-format-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    // Version 2 held the DMD pair terraces as JSON arrays.
    for (const std::string old :
         {"terrace restart 1", "terrace restart 2", "terrace restart 6", "terrace restart 7"}) {
        cli::writeRestart(dir, {{"format", old}, {"phase", "production"}});
        try {
            cli::readRestart(dir);
            ADD_FAILURE() << "expected an IoError for " << old;
        } catch (const IoError& e) {
            EXPECT_EQ(std::string(e.what()), (dir / "restart.bin").string() +
                                                 ": written by another version of terrace ('" +
                                                 old + "'; this one reads '" + cli::restartFormat +
                                                 "'): start the run again");
        }
    }
    cli::writeRestart(dir, {{"format", cli::restartFormat}});
    EXPECT_EQ(cli::readRestart(dir).at("format"), cli::restartFormat);
    std::filesystem::remove_all(dir);
}

namespace {

const cli::SamplePlan plan11{11, 0, terrace::VirialKind::Impulse, 1000.0, 9};

/// The state of sample statistics after `n` samples (of `plan`).
std::vector<std::uint8_t> statisticsOf(int n, const cli::SamplePlan& plan = plan11) {
    cli::SampleStatistics stats(plan);
    for (int k = 0; k < n; ++k) {
        cli::SampleRecord e;
        e.tPs = 0.01 * k, e.time = 0.1 * (k + 1);
        stats.add(e);
    }
    return stats.state();
}

} // namespace

// A restart file without one of its keys is named as damaged, with the key, before anything is
// cut back.
TEST(Restart, ADamagedRestartFileIsNamed) {
    const auto dir =
        std::filesystem::temp_directory_path() / ("terrace-damaged-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    nlohmann::json restart = {{"phase", "production"},
                              {"tick", 0},
                              {"sample", 3},
                              {"t_start", 0.0},
                              {"cpu_seconds", 1.0},
                              {"cpu_seconds_equilibration", 0.0},
                              {"production_statistics", nlohmann::json::object()},
                              {"momentum_initial", {0.0, 0.0, 0.0}},
                              {"restarts_written", 1},
                              {"continuations", 0},
                              {"melt_warning", ""},
                              {"identity", cli::runIdentity(0, 8, "dmd")},
                              {"files",
                               {{"trajectory_bytes", 0},
                                {"thermo_bytes", 100},
                                {"trajectory_tail_crc64", 0},
                                {"thermo_tail_crc64", 0}}},
                              {"sample_statistics", nlohmann::json::binary(statisticsOf(2))},
                              {"thermo_row", cli::recordsToBinary({cli::SampleRecord()})},
                              {"analysis", nullptr}};
    restart.erase("tick");
    cli::RunRecord run;
    run.samples = cli::SampleStatistics(plan11);
    cli::RunFiles files;
    cli::RunPlan plan = cli::planRun(defaultScene());
    plan.thermoEvery = 1;
    try {
        cli::resumeRun(restart, plan, dir, run, files);
        FAIL() << "expected an IoError";
    } catch (const IoError& e) {
        EXPECT_EQ(std::string(e.what()), (dir / "restart.bin").string() +
                                             ": damaged, or written by another version of "
                                             "terrace (key 'tick' not found)");
    }
    // Whole, but with statistics of fewer samples than its restart point: refused.
    const auto resumeError = [&] {
        try {
            cli::resumeRun(restart, plan, dir, run, files);
        } catch (const IoError& e) {
            return std::string(e.what());
        }
        return std::string("no IoError");
    };
    restart["tick"] = 0;
    EXPECT_EQ(resumeError(), (dir / "restart.bin").string() +
                                 ": damaged: its sample statistics hold 2 samples, its restart "
                                 "point 4");
    // Statistics of another plan (another run's): refused, naming them.
    restart["sample_statistics"] = nlohmann::json::binary(
        statisticsOf(4, cli::SamplePlan{12, 0, terrace::VirialKind::Impulse, 1000.0, 9}));
    EXPECT_EQ(resumeError(), (dir / "restart.bin").string() +
                                 ": analysis state: temperature blocks was planned for another "
                                 "number of samples");
    // Its statistics whole, but thermo.csv shorter than its restart point: refused, nothing
    // created or cut.
    restart["sample_statistics"] = nlohmann::json::binary(statisticsOf(4));
    EXPECT_THROW(cli::resumeRun(restart, plan, dir, run, files), IoError);
    EXPECT_FALSE(std::filesystem::exists(dir / "thermo.csv"));
    std::filesystem::remove_all(dir);
}

// A write that fails during the analysis is an error of the run, and summary.json says so.
TEST(Restart, AWriteThatFailsInTheAnalysisIsRecorded) {
    const auto dir =
        std::filesystem::temp_directory_path() / ("terrace-analysis-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(
        dir / ("." + std::string("rdf.csv") + ".partial-" + std::to_string(::getpid())) /
        "in-the-way");
    Scene scene = smallScene("linear");
    const auto sys = buildInitialState<LinearRotor>(scene, rodPotential(scene));
    cli::RunRecord run;
    run.bodies = sys.size();
    run.dof = degreesOfFreedom<LinearRotor>(sys.size());
    run.samples = cli::SampleStatistics(cli::SamplePlan{8, 0, run.virialKind, 1000.0, run.dof});
    run.kT = scene.kT();
    run.analysis = std::make_unique<analysis::RunAnalysis>(run.bodies, sys.box.length, 0.001, 8,
                                                           cli::streamingOptions(scene));
    for (int k = 0; k < 8; ++k) {
        auto moved = sys;
        for (auto& b : moved.bodies)
            b.r += b.v * (0.01 * k);
        run.add({0.001 * k, 1.0, -1.0, 2.0}, makeSnapshot(moved, 0.01 * k));
    }
    const cli::InterruptGuard interrupt;
    bool analysed = true;
    EXPECT_THROW(cli::writeSummaryAndAnalysis(scene, run, dir, interrupt, 0, analysed), IoError);
    EXPECT_FALSE(analysed);
    const auto summary = nlohmann::json::parse(readWholeFile(dir / "summary.json"));
    EXPECT_NE(summary.value("error", "").find("cannot write " + (dir / "rdf.csv").string()),
              std::string::npos)
        << summary.dump();
    std::filesystem::remove_all(dir);
}

namespace {

/// A DMD engine that counts its rebuilds from a checkpoint, notes a rebuild begun while another
/// engine of its kind still lives, and refuses the rebuild numbered `failAt`.
struct WatchedDmd : RodDmd {
    static inline int live = 0, rebuilds = 0, failAt = 0, besideAnother = 0;
    WatchedDmd(System<LinearRotor, RodPotential> sys, const Scene& scene)
        : RodDmd(std::move(sys), scene) {
        ++live;
    }
    WatchedDmd(System<LinearRotor, RodPotential> sys, const Scene& scene, const nlohmann::json& c)
        : RodDmd(rebuilding(std::move(sys)), scene, c) {
        ++live;
    }
    // What the run driver's rebuilds call, as they call the engine's own (the checkpoint spent).
    WatchedDmd(System<LinearRotor, RodPotential> sys, const Scene& scene, nlohmann::json&& c)
        : RodDmd(rebuilding(std::move(sys)), scene, std::move(c)) {
        ++live;
    }
    ~WatchedDmd() { --live; }

private:
    static System<LinearRotor, RodPotential> rebuilding(System<LinearRotor, RodPotential> sys) {
        besideAnother += live > 0;
        if (++rebuilds == failAt) throw std::runtime_error("the rebuild failed");
        return sys;
    }
};

/// 64 rods, 10 production samples after 2 thermostat ticks, a restart point every 3 samples.
Scene watchedScene() {
    Scene scene = smallScene("linear");
    scene.run.equilibrate_ps = 0.018;
    scene.run.time_ps = 0.09;
    scene.output.restart_every_ps = 0.027;
    scene.output.thermo_every_fs = 9.0;
    return scene;
}

/// Runs the scene with a WatchedDmd into a fresh `dir` (or, with `resume`, continues there, as
/// `terrace run --continue` does: the engine's bodies and checkpoint are taken out of `*resume`).
cli::RunOutcome runWatched(const Scene& scene, const std::filesystem::path& dir,
                           nlohmann::json* resume = nullptr) {
    const cli::RunTarget target{dir, resume ? cli::OutputMode::Continue : cli::OutputMode::Fresh,
                                true, resume};
    if (!resume) {
        std::filesystem::remove_all(dir);
        std::filesystem::create_directories(dir);
    }
    auto make = [&scene](System<LinearRotor, RodPotential>&& s, nlohmann::json* checkpoint) {
        if (!checkpoint) return std::make_unique<WatchedDmd>(std::move(s), scene);
        return std::make_unique<WatchedDmd>(std::move(s), scene, std::move(*checkpoint));
    };
    auto engine =
        cli::startingEngine<WatchedDmd, LinearRotor>(scene, rodPotential(scene), target, make);
    return cli::drive(engine, cli::rebuildWith(make), scene, target, LinearRotor::rotationalDof);
}

std::filesystem::path scratch(const std::string& name) {
    return std::filesystem::temp_directory_path() /
           ("terrace-" + name + "-" + std::to_string(::getpid()));
}

} // namespace

// A restart point moves the bodies out of the DMD engine it drops: the same bits, in the scene's
// order, as the copy an engine left alive gives (512 rods, numbered otherwise inside the engine).
TEST(Restart, BodiesReleasedFromADmdEngineAreItsSynchronisedCopy) {
    Scene scene = smallScene("linear");
    scene.state.n = 512;
    const auto start = buildInitialState<LinearRotor>(scene, rodPotential(scene));
    RodDmd kept(start, scene), dropped(start, scene);
    kept.advanceTo(0.5);
    dropped.advanceTo(0.5);
    int renumbered = 0;
    for (int b = 0; b < scene.state.n; ++b)
        renumbered += Probe::engineIndex(kept, b) != b;
    ASSERT_GT(renumbered, scene.state.n / 2);
    const auto copy = kept.system();
    const auto released = Probe::releaseSystem(std::move(dropped));
    ASSERT_EQ(released.size(), copy.size());
    for (int b = 0; b < copy.size(); ++b)
        ASSERT_TRUE(sameBits(released.bodies[b], copy.bodies[b])) << "body " << b;
}

// A restart point drops the engine before it builds the next one, or both would live at once
// (twice the engine's memory at the run's peak).
TEST(Restart, ARestartPointDropsTheEngineBeforeItsSuccessorIsBuilt) {
    WatchedDmd::rebuilds = WatchedDmd::besideAnother = 0, WatchedDmd::failAt = 0;
    const auto dir = scratch("successor");
    runWatched(watchedScene(), dir);
    EXPECT_EQ(WatchedDmd::rebuilds, 4); // at production's start and at samples 3, 6, 9
    EXPECT_EQ(WatchedDmd::besideAnother, 0);
    EXPECT_EQ(WatchedDmd::live, 0);
    std::filesystem::remove_all(dir);
}

// A rebuild that fails at a restart point ends the run as any failure does: the error raised and
// in summary.json, the samples until then analysed and their files kept, and restart.bin written
// at that point, from which a continued run ends with the same bytes as one that never failed.
TEST(Restart, ARebuildThatFailsEndsTheRunWithItsFilesKept) {
    const Scene scene = watchedScene();
    const auto whole = scratch("whole"), failed = scratch("failed");
    WatchedDmd::failAt = 0;
    runWatched(scene, whole);
    WatchedDmd::rebuilds = 0, WatchedDmd::failAt = 3; // the restart point at sample 6
    try {
        runWatched(scene, failed);
        ADD_FAILURE() << "expected the rebuild's error";
    } catch (const std::runtime_error& e) {
        EXPECT_EQ(std::string(e.what()),
                  "the rebuild failed (output so far in " + failed.string() + ")");
    }
    EXPECT_EQ(WatchedDmd::live, 0);
    const auto summary = nlohmann::json::parse(readWholeFile(failed / "summary.json"));
    EXPECT_EQ(summary.at("error"), "the rebuild failed");
    EXPECT_EQ(summary.at("samples"), 7);
    EXPECT_NEAR(summary.at("simulated_ps").get<double>(), 0.054, 1e-12);
    EXPECT_EQ(summary.at("restarts").at("written"), 3);
    EXPECT_GT(summary.at("events").at("up").get<long>(), 0); // production's statistics kept
    EXPECT_TRUE(std::filesystem::exists(failed / "rdf.csv"));
    nlohmann::json restart = cli::readRestart(failed);
    EXPECT_EQ(restart.at("sample"), 6);
    WatchedDmd::failAt = 0;
    runWatched(scene, failed, &restart);
    // The continued run's engine took the bodies and checkpoint out of the file it was read from:
    // nothing of them stays beside it for the rest of the run.
    EXPECT_FALSE(restart.contains("bodies"));
    EXPECT_FALSE(restart.contains("engine"));
    for (const char* f : {"thermo.csv", "rdf.csv", "vacf.csv", "oacf.csv", "msd.csv"})
        EXPECT_EQ(readWholeFile(failed / f), readWholeFile(whole / f)) << f;
    std::filesystem::remove_all(whole);
    std::filesystem::remove_all(failed);
}

// restart.bin holds the analysis' state and the sample statistics, not the samples: stopped at
// sample 100 it is as large as at sample 10 but for the integers that grew (event counters, file
// lengths, the sample number: 1 to 9 bytes each in CBOR, a hundred bytes or so in all) and the
// engine's checkpoint (a state of the configuration, whatever the samples taken), never by
// the samples' energies (90 × 88 bytes, 7.9 kB) nor their bodies (90 × 64 rods × 96 bytes,
// 553 kB); its analysis' state and its statistics are the same size at both.
TEST(Restart, ARestartFileDoesNotGrowWithTheSamplesTaken) {
    Scene scene = watchedScene();
    scene.run.time_ps = 1.8;              // 200 samples planned, the same analysis for both
    scene.output.restart_every_ps = 0.09; // every 10 samples
    const auto early = scratch("early"), late = scratch("late");
    WatchedDmd::rebuilds = 0, WatchedDmd::failAt = 2; // the restart point at sample 10
    EXPECT_THROW(runWatched(scene, early), std::runtime_error);
    WatchedDmd::rebuilds = 0, WatchedDmd::failAt = 11; // at sample 100
    EXPECT_THROW(runWatched(scene, late), std::runtime_error);
    WatchedDmd::failAt = 0;
    const nlohmann::json a = cli::readRestart(early), b = cli::readRestart(late);
    ASSERT_EQ(a.at("sample"), 10);
    ASSERT_EQ(b.at("sample"), 100);
    EXPECT_FALSE(std::filesystem::exists(early / "samples.bin"));
    EXPECT_EQ(a.at("analysis").get_binary().size(), b.at("analysis").get_binary().size());
    EXPECT_EQ(a.at("sample_statistics").get_binary().size(),
              b.at("sample_statistics").get_binary().size());
    // Less the DMD checkpoint, whose pairs off terrace 0 (12 bytes each) come and go with the
    // configuration, not with the samples taken.
    const auto sizeOf = [](const std::filesystem::path& dir, const nlohmann::json& r) {
        return std::int64_t(std::filesystem::file_size(dir / "restart.bin")) -
               std::int64_t(nlohmann::json::to_cbor(r.at("engine")).size());
    };
    const std::int64_t sizeA = sizeOf(early, a), sizeB = sizeOf(late, b);
    EXPECT_LE(std::abs(sizeB - sizeA), 256) << sizeA << " then " << sizeB << " bytes";
    std::filesystem::remove_all(early);
    std::filesystem::remove_all(late);
}

// The checksum is CRC-64/XZ: its check value, and the same when computed in two parts.
TEST(Restart, TheChecksumIsCrc64Xz) {
    EXPECT_EQ(cli::crc64("123456789"), 0x995DC9BBDF1939FAull);
    EXPECT_EQ(cli::crc64("6789", cli::crc64("12345")), cli::crc64("123456789"));
    EXPECT_EQ(cli::crc64(""), 0u);
}

// Any one byte of a restart file changed is refused by readRestart before its content is used,
// at every position of the file (the document and its trailer alike).
TEST(Restart, EveryByteOfARestartFileChangedIsRefused) {
    // A small analysis, so that the file stays small: each of its bytes is changed twice and the
    // whole file checked each time (its analysis' state at the defaults, all 64 rods followed by
    // 16 lags a level, would be some 0.5 MB of a 0.5 MB file).
    Scene scene = watchedScene();
    scene.analysis.follow_bodies = 4, scene.analysis.lags_per_level = 4;
    scene.analysis.blocks = 2, scene.analysis.rdf_bin_angstrom = 0.25;
    const auto dir = scratch("flipped");
    WatchedDmd::rebuilds = 0, WatchedDmd::failAt = 3; // stopped at the restart point of sample 6
    EXPECT_THROW(runWatched(scene, dir), std::runtime_error);
    WatchedDmd::failAt = 0;
    const auto path = dir / "restart.bin";
    const std::string good = readWholeFile(path);
    ASSERT_EQ(cli::decodeRestart(good, path).at("sample"), 6);
    std::string bytes = good;
    std::size_t refused = 0;
    for (std::size_t k = 0; k < bytes.size(); ++k) {
        for (const unsigned char to :
             {static_cast<unsigned char>(~bytes[k]), (unsigned char)0xff}) {
            if (char(to) == good[k]) continue;
            bytes[k] = char(to);
            try {
                cli::decodeRestart(bytes, path);
                ADD_FAILURE() << "byte " << k << " set to " << int(to) << " was not noticed";
            } catch (const IoError&) {
                ++refused;
            }
            bytes[k] = good[k];
        }
    }
    EXPECT_GE(refused, good.size());
    // Through the file, as --continue reads it.
    bytes[bytes.size() / 2] ^= 0x01;
    writeFileAtomically(path, bytes);
    try {
        cli::readRestart(dir);
        ADD_FAILURE() << "expected an IoError";
    } catch (const IoError& e) {
        EXPECT_EQ(std::string(e.what()).rfind(path.string() + ": damaged: its checksum", 0), 0u)
            << e.what();
    }
    std::filesystem::remove_all(dir);
}

// A restart file of the format before the checksum (the CBOR document alone) is named as of
// another version.
TEST(Restart, ARestartFileWithoutItsTrailerIsOfAnotherVersion) {
    const auto dir = scratch("unframed");
    std::filesystem::create_directories(dir);
    const auto cbor = nlohmann::json::to_cbor({{"format", "terrace restart 4"}, {"tick", 1}});
    writeFileAtomically(dir / "restart.bin",
                        std::string_view(reinterpret_cast<const char*>(cbor.data()), cbor.size()));
    try {
        cli::readRestart(dir);
        ADD_FAILURE() << "expected an IoError";
    } catch (const IoError& e) {
        EXPECT_EQ(std::string(e.what()),
                  (dir / "restart.bin").string() +
                      ": written by another version of terrace ('terrace restart 4'; this one "
                      "reads '" +
                      cli::restartFormat + "'): start the run again");
    }
    std::filesystem::remove_all(dir);
}

// A restart file from another run of the same N (another seed) is refused, naming what differs:
// alone, by the scene it was written for; with that run's scene.json too, by thermo.csv's tail.
// The run's own file still continues.
TEST(Restart, ARestartFileFromAnotherRunIsRefused) {
    Scene scene = watchedScene(), other = watchedScene();
    other.seed = 2;
    const auto mine = scratch("mine"), theirs = scratch("theirs");
    WatchedDmd::rebuilds = 0, WatchedDmd::failAt = 3;
    EXPECT_THROW(runWatched(scene, mine), std::runtime_error);
    WatchedDmd::rebuilds = 0;
    EXPECT_THROW(runWatched(other, theirs), std::runtime_error);
    WatchedDmd::failAt = 0;
    const std::string own = readWholeFile(mine / "restart.bin");
    const std::string ownScene = readWholeFile(mine / "scene.json");
    std::filesystem::copy_file(theirs / "restart.bin", mine / "restart.bin",
                               std::filesystem::copy_options::overwrite_existing);
    try {
        cli::checkRunIdentity(mine, cli::readRestart(mine));
        ADD_FAILURE() << "expected an IoError";
    } catch (const IoError& e) {
        const std::string text = e.what();
        EXPECT_EQ(text.rfind((mine / "restart.bin").string() +
                                 ": from another run: the scene it was written for (CRC-64 ",
                             0),
                  0u)
            << text;
        EXPECT_NE(text.find("; seed differs)"), std::string::npos) << text;
    }
    // Their scene.json as well: the scene agrees, thermo.csv does not, and nothing is cut back.
    std::filesystem::copy_file(theirs / "scene.json", mine / "scene.json",
                               std::filesystem::copy_options::overwrite_existing);
    nlohmann::json restart = cli::readRestart(mine);
    EXPECT_NO_THROW(cli::checkRunIdentity(mine, restart));
    const auto thermoBefore = std::filesystem::file_size(mine / "thermo.csv");
    const auto theirs6 = restart.at("files").at("thermo_bytes").get<std::uintmax_t>();
    try {
        runWatched(other, mine, &restart);
        ADD_FAILURE() << "expected an IoError";
    } catch (const IoError& e) {
        // Their rows may print longer than this run's: then the file is too short for them.
        const std::string path = (mine / "thermo.csv").string();
        EXPECT_EQ(std::string(e.what()),
                  thermoBefore < theirs6
                      ? path + " holds " + std::to_string(thermoBefore) +
                            " bytes, fewer than the " + std::to_string(theirs6) +
                            " of its restart point: it was changed after restart.bin was written"
                      : path + ": its last " +
                            std::to_string(std::min<std::uintmax_t>(theirs6, cli::tailBytes)) +
                            " bytes before the restart point are not those restart.bin was "
                            "written with (checksum): the file is another run's, or was changed "
                            "since");
    }
    EXPECT_EQ(std::filesystem::file_size(mine / "thermo.csv"), thermoBefore);
    // Its own restart file and scene: continued to the end.
    writeFileAtomically(mine / "restart.bin", own);
    writeFileAtomically(mine / "scene.json", ownScene);
    restart = cli::readRestart(mine);
    cli::checkRunIdentity(mine, restart);
    EXPECT_NO_THROW(runWatched(scene, mine, &restart));
    std::filesystem::remove_all(mine);
    std::filesystem::remove_all(theirs);
}

// What a restart or re-sort point does to the physics: an engine rebuilt from its bodies and
// checkpoint mid-run (512 dense rods at 50 fs, numbered afresh inside) undergoes the collisions
// of one that goes on, over the next 100 fs, and ends with the same terraced energy and bodies
// that agree to the round-off the liquid's chaos grows (the rebuild re-predicts every pair from
// now, so searches start elsewhere and find the same events to their tolerance). Its lists are
// re-anchored, so relists and virtual events are not counted alike.
// How the two differ, measured (largest |Δv| in Å/ps and |Δω| in rad/ps over the bodies; thermal
// scales 0.73 Å/ps and 2.9 rad/ps): 10 fs after the rebuild 5e-14 and 1-2e-13 in both GCC's and
// clang's builds; at 100 fs 1.7e-11 and 2.1e-10 (GCC), 2.7e-10 and 3.6e-9 (clang): the difference
// e-folds every ~10-15 fs with jumps at near-grazing collisions, as chaos does, so at 100 fs it
// says which compiler rounded, not whether the rebuild is right. Hence round-off is asked for
// 10 fs after the rebuild, and at 100 fs 1e-7: 28 times the largest measured, and far below what
// one changed collision (ω by O(1 rad/ps)) would leave.
TEST(Restart, ARebuiltDmdEngineUndergoesTheCollisionsOfOneThatGoesOn) {
    Scene scene = defaultScene();
    scene.state.n = 512;
    scene.state.density = 0.5;
    scene.state.temperature = 1.4;
    const auto start = buildInitialState<LinearRotor>(scene, rodPotential(scene));
    RodDmd goesOn(start, scene);
    auto rebuilt = std::make_unique<RodDmd>(start, scene);
    ASSERT_GE(Probe::cellsPerSide(goesOn), 3);
    const double t1 = units::fromFs(50.0);
    goesOn.advanceTo(t1);
    rebuilt->advanceTo(t1);
    auto collisions = [](const dmd::EventCounts& c) {
        return std::array<std::uint64_t, 3>{c.up, c.down, c.reflect};
    };
    const auto before = collisions(Probe::counts(*rebuilt));
    ASSERT_EQ(before, collisions(Probe::counts(goesOn)));
    const nlohmann::json checkpoint = rebuilt->checkpoint();
    auto sys = Probe::releaseSystem(std::move(*rebuilt));
    rebuilt = std::make_unique<RodDmd>(std::move(sys), scene, checkpoint);
    int renumbered = 0; // the lattice's order was the cells' at the start; the liquid's is not
    for (int b = 0; b < scene.state.n; ++b)
        renumbered += Probe::engineIndex(*rebuilt, b) != Probe::engineIndex(goesOn, b);
    EXPECT_GT(renumbered, 0);
    // The largest difference of position (Å), velocity (Å/ps), axis and ω (rad/ps) over the bodies.
    auto largestDifference = [&] {
        const Snapshot a = rebuilt->snapshot(), b = goesOn.snapshot();
        double largest = 0.0;
        for (int i = 0; i < a.size(); ++i)
            largest = std::max({largest, (a.position[i] - b.position[i]).norm(),
                                (a.velocity[i] - b.velocity[i]).norm(),
                                (a.axis[i] - b.axis[i]).norm(), (a.omega[i] - b.omega[i]).norm()});
        return largest;
    };
    for (int k = 1; k <= 50; ++k) {
        const double t = t1 + units::fromFs(2.0 * k);
        goesOn.advanceTo(t);
        rebuilt->advanceTo(t);
        auto sum = collisions(Probe::counts(*rebuilt));
        for (int m = 0; m < 3; ++m)
            sum[m] += before[m];
        ASSERT_EQ(sum, collisions(Probe::counts(goesOn))) << 50 + 2 * k << " fs";
        if (k == 5) {
            EXPECT_LT(largestDifference(), 1e-11) << "10 fs after the rebuild";
        }
    }
    EXPECT_GT(Probe::counts(goesOn).up + Probe::counts(goesOn).down, 1000u);
    EXPECT_EQ(rebuilt->potentialEnergy(), goesOn.potentialEnergy());
    EXPECT_LT(largestDifference(), 1e-7) << "100 fs after the rebuild";
}

// dmd.resort_cells: the engine renumbers its bodies at the start of an advanceTo where their
// order has decayed (here at once: a thousandth of a cell), that is at the sample or thermostat
// tick before; a restart point itself renumbers them and is not counted. summary.json counts the
// renumberings of production, restart.bin those so far, and a continued run ends with the same
// files as the whole run. With resort_cells 0 nothing is renumbered between restart points.
TEST(Restart, ARunRenumbersItsBodiesWhereTheirOrderHasDecayed) {
    Scene scene = watchedScene();
    scene.state.n = 512;
    scene.state.density = 0.5;
    scene.dmd["resort_cells"] = 1e-3;
    {
        const RodDmd probe(buildInitialState<LinearRotor>(scene, rodPotential(scene)), scene);
        ASSERT_GE(Probe::cellsPerSide(probe), 3);
    }
    const auto whole = scratch("resort-whole"), cut = scratch("resort-cut");
    WatchedDmd::rebuilds = WatchedDmd::besideAnother = 0, WatchedDmd::failAt = 0;
    runWatched(scene, whole);
    // Restart points at production's start and at samples 3, 6, 9; renumberings on the way to
    // samples 2, 3, 5, 6, 8, 9 (an engine just built has not moved).
    EXPECT_EQ(WatchedDmd::rebuilds, 4);
    EXPECT_EQ(WatchedDmd::besideAnother, 0);
    const auto summary = nlohmann::json::parse(readWholeFile(whole / "summary.json"));
    EXPECT_EQ(summary.at("resorts"), 6);
    EXPECT_EQ(summary.at("restarts").at("written"), 4);

    // Stopped by a failed rebuild at the restart point of sample 6, then continued.
    WatchedDmd::rebuilds = 0, WatchedDmd::failAt = 3;
    EXPECT_THROW(runWatched(scene, cut), std::runtime_error);
    nlohmann::json restart = cli::readRestart(cut);
    ASSERT_EQ(restart.at("sample"), 6);
    EXPECT_EQ(restart.at("production_statistics").at("resorts"), 4);
    WatchedDmd::failAt = 0;
    runWatched(scene, cut, &restart);
    const auto continued = nlohmann::json::parse(readWholeFile(cut / "summary.json"));
    EXPECT_EQ(continued.at("resorts"), 6);
    for (const char* f : {"thermo.csv", "rdf.csv", "vacf.csv", "oacf.csv", "msd.csv"})
        EXPECT_EQ(readWholeFile(cut / f), readWholeFile(whole / f)) << f;

    scene.dmd["resort_cells"] = 0.0;
    WatchedDmd::rebuilds = 0;
    runWatched(scene, whole);
    EXPECT_EQ(WatchedDmd::rebuilds, 4);
    EXPECT_EQ(nlohmann::json::parse(readWholeFile(whole / "summary.json")).at("resorts"), 0);
    std::filesystem::remove_all(whole);
    std::filesystem::remove_all(cut);
}

// A DMD engine rebuilt from a checkpoint it is handed to spend frees the checkpoint's pairs before
// it predicts them (the rebuild's peak memory), and goes on as one rebuilt from a kept copy.
TEST(Restart, ADmdRebuildSpendsTheCheckpointItIsHanded) {
    Scene scene = smallScene("linear");
    scene.state.n = 216;
    RodDmd engine(buildInitialState<LinearRotor>(scene, rodPotential(scene)), scene);
    engine.advanceTo(0.5);
    const auto sys = engine.system();
    const nlohmann::json kept = engine.checkpoint();
    nlohmann::json handed = kept;
    RodDmd a(sys, scene, kept), b(sys, scene, std::move(handed));
    EXPECT_TRUE(handed.is_null()); // NOLINT(bugprone-use-after-move): spent, as documented
    EXPECT_FALSE(kept.is_null());
    a.advanceTo(1.5);
    b.advanceTo(1.5);
    const Snapshot x = a.snapshot(), y = b.snapshot();
    for (int i = 0; i < x.size(); ++i) {
        ASSERT_EQ(x.position[i], y.position[i]) << "body " << i;
        ASSERT_EQ(x.velocity[i], y.velocity[i]) << "body " << i;
    }
    EXPECT_EQ(a.statistics().dump(), b.statistics().dump());
}

// At a restart or re-sort point the engine sheds its calendar, agendas and orbits before its
// checkpoint is taken: it then gives the same checkpoint and bodies, holds none of their bytes
// (over 300 a body), and refuses to advance.
TEST(Restart, ADmdEngineThatShedItsEventsGivesTheSameCheckpointAndBodies) {
    Scene scene = smallScene("linear");
    scene.state.n = 512;
    RodDmd engine(buildInitialState<LinearRotor>(scene, rodPotential(scene)), scene);
    engine.advanceTo(0.5);
    const nlohmann::json before = engine.checkpoint();
    const auto copy = engine.system();
    const std::size_t bytes = Probe::bytesReserved(engine);
    std::size_t eventLoop = 0; // what shed() frees
    for (const auto& [part, size] : Probe::memoryByPart(engine))
        if (std::string(part) == "agendas" || std::string(part) == "orbits" ||
            std::string(part) == "calendar")
            eventLoop += size;
    ASSERT_GT(eventLoop, 300u * 512u);
    Probe::shed(engine);
    EXPECT_LE(Probe::bytesReserved(engine),
              bytes - eventLoop + 1024); // an empty calendar's few bytes
    EXPECT_EQ(engine.checkpoint(), before);
    EXPECT_THROW(engine.advanceTo(1.0), std::logic_error);
    const auto released = Probe::releaseSystem(std::move(engine));
    for (int b = 0; b < copy.size(); ++b)
        ASSERT_TRUE(sameBits(released.bodies[b], copy.bodies[b])) << "body " << b;
}

// A mixture's bodies carry their species through a restart file, in each body's record (a
// continued Kob–Andersen run once came back all of species A, and its analysis stopped: "species
// B has no bodies"); the record of a body without species is too short for one with, and a
// species the scene lacks is refused.
TEST(Restart, AMixturesSpeciesComeBackAndABadRecordIsRefused) {
    std::vector<SpeciesSphere::State> bodies(5);
    for (int i = 0; i < 5; ++i) {
        bodies[i].species = i % 3;
        bodies[i].r = Vec3(0.1 * i, 1.0 / 3.0, -2.0);
        bodies[i].v = Vec3(1e-300, -0.7, i);
    }
    const auto cbor = nlohmann::json::to_cbor(cli::bodiesToBinary(bodies));
    const auto back =
        cli::bodiesFromBinary<SpeciesSphere::State>(nlohmann::json::from_cbor(cbor), 5);
    for (int i = 0; i < 5; ++i) {
        EXPECT_EQ(back[i].species, i % 3) << i;
        EXPECT_TRUE(sameBits(back[i], bodies[i])) << i;
    }
    EXPECT_NO_THROW(cli::checkSpecies(back, 3));
    const auto messageOf = [](const auto& read) {
        try {
            read();
        } catch (const std::runtime_error& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    EXPECT_EQ(messageOf([&] { cli::checkSpecies(back, 2); }),
              "restart: body 2 has species 2, where the scene has 2");
    // Plain spheres' records (r, v) hold no species: read as a mixture's they run short.
    std::vector<Sphere::State> plain(5);
    const auto plainBytes = cli::bodiesToBinary(plain);
    EXPECT_EQ(messageOf([&] { cli::bodiesFromBinary<SpeciesSphere::State>(plainBytes, 5); }),
              "restart: too few body records for 5 bodies of this kind");
}

} // namespace test_restart
