// Restart points: what a restart file holds comes back bit for bit, and an engine rebuilt from it
// goes on exactly as one rebuilt from the live state (cli/restart.hpp, the engines' checkpoint()).
#include "cli/restart.hpp"
#include "cli/run_driver.hpp"
#include "core/asymmetric_top.hpp"
#include "core/initial_state.hpp"
#include "core/linear_rotor.hpp"
#include "core/output_file.hpp"
#include "core/smoothed_potential.hpp"
#include "core/sphere.hpp"
#include "core/symmetric_top.hpp"
#include "dmd/engine.hpp"
#include "smd/engine.hpp"
#include <filesystem>
#include <gtest/gtest.h>
#include <unistd.h>

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

TEST(Restart, SamplesComeBackBitForBit) {
    const Scene scene = smallScene("asymmetric");
    const auto sys = buildInitialState<AsymmetricTop>(scene, rodPotential(scene));
    const Snapshot a = makeSnapshot(sys, 0.25);
    const cli::SampleRecord e{0.125, -3.5, -10.25, 6.75, 4.5, -31.25, 1234.0, a.time};
    const std::string bytes = cli::encodeSample(a, e) + cli::encodeSample(a, e);
    std::vector<Snapshot> samples;
    std::vector<cli::SampleRecord> energies;
    cli::decodeSamples(bytes, a.size(), true, a.boxLength, samples, energies);
    ASSERT_EQ(samples.size(), 2u);
    EXPECT_EQ(samples[1].time, a.time);
    EXPECT_EQ(energies[1].potential, e.potential);
    EXPECT_EQ(energies[1].kineticTranslational, e.kineticTranslational); // the pressure's terms
    EXPECT_EQ(energies[1].virial, e.virial);
    EXPECT_EQ(energies[1].collisions, e.collisions);
    EXPECT_EQ(energies[1].time, a.time);
    for (int i = 0; i < a.size(); ++i) {
        EXPECT_EQ(samples[1].position[i], a.position[i]);
        EXPECT_EQ(samples[1].omega[i], a.omega[i]);
        EXPECT_EQ(samples[1].orientation[i].coeffs(), a.orientation[i].coeffs());
    }
    // A record cut short (a kill during the append) is not a whole sample.
    EXPECT_THROW(cli::decodeSamples(bytes.substr(0, bytes.size() - 8), a.size(), true, a.boxLength,
                                    samples, energies),
                 std::runtime_error);
}

namespace {

/// Two engines rebuilt at time t1 from the same bodies and checkpoint — one from the values in
/// memory, one from them after a trip through CBOR — undergo the same events up to t2.
template <template <class, class> class Engine, class K, class P>
void rebuiltEnginesAgree(const Scene& scene, const P& potential, double t1, double t2) {
    std::optional<Engine<K, P>> engine;
    engine.emplace(buildInitialState<K>(scene, potential), scene);
    engine->advanceTo(t1);
    const auto sys = cli::currentSystem(*engine);
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
    rebuiltEnginesAgree<dmd::Engine, LinearRotor>(
        scene, Smoothed<RodPotential>{rodPotential(scene), sceneCutoff(scene)}, 0.5, 2.0);
}

TEST(Restart, RebuiltSmdEnginesAgreeBitForBit) {
    Scene scene = smallScene("linear");
    scene.state.n = 216;
    scene.engine = "smd";
    rebuiltEnginesAgree<smd::Engine, LinearRotor>(
        scene, Smoothed<RodPotential>{rodPotential(scene), sceneCutoff(scene)}, 0.09, 0.9);
}

namespace {

using RodDmd = dmd::Engine<LinearRotor, RodPotential>;

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
    return {scene, engine.synchronisedCopy(), engine.checkpoint(), engine.interactionRange()};
}

} // namespace

// The checkpoint keeps each pair's terrace: a pair held off terrace 0 beyond the interaction
// range cannot belong to these bodies and is refused, not silently re-derived.
TEST(Restart, ADmdCheckpointThatDoesNotFitTheBodiesIsRefused) {
    auto [scene, sys, checkpoint, rm] = dmdPointAt(0.2);
    ASSERT_FALSE(checkpoint["terraces"].empty());
    int far = 1;
    while ((sys.box.minimumImage(sys.bodies[0].r - sys.bodies[far].r)).norm() < rm)
        ++far;
    checkpoint["terraces"].push_back({0, far, -1});
    EXPECT_THROW(RodDmd(sys, scene, checkpoint), SceneError);
    checkpoint["terraces"].back() = {0, sys.size(), -1};
    EXPECT_THROW(RodDmd(sys, scene, checkpoint), SceneError);
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

// A restart file of another format (version 1's samples lack the pressure's terms) is named as
// such, not read as damaged or misread.
TEST(Restart, ARestartFileOfAnotherFormatIsNamed) {
    const auto dir =
        std::filesystem::temp_directory_path() / ("terrace-format-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    cli::writeRestart(dir, {{"format", "terrace restart 1"}, {"phase", "production"}});
    try {
        cli::readRestart(dir);
        FAIL() << "expected an IoError";
    } catch (const IoError& e) {
        EXPECT_EQ(std::string(e.what()),
                  (dir / "restart.bin").string() +
                      ": written by another version of terrace ('terrace restart 1'; this one "
                      "reads '" +
                      cli::restartFormat + "'): start the run again");
    }
    cli::writeRestart(dir, {{"format", cli::restartFormat}});
    EXPECT_EQ(cli::readRestart(dir).at("format"), cli::restartFormat);
    std::filesystem::remove_all(dir);
}

// A restart file without one of its keys is named as damaged, with the key, before anything is
// cut back.
TEST(Restart, ADamagedRestartFileIsNamed) {
    const auto dir =
        std::filesystem::temp_directory_path() / ("terrace-damaged-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    nlohmann::json restart = {
        {"phase", "production"},
        {"tick", 0},
        {"sample", 3},
        {"t_start", 0.0},
        {"cpu_seconds", 1.0},
        {"cpu_seconds_equilibration", 0.0},
        {"production_statistics", nlohmann::json::object()},
        {"momentum_initial", {0.0, 0.0, 0.0}},
        {"restarts_written", 1},
        {"continuations", 0},
        {"files", {{"trajectory_bytes", 0}, {"thermo_bytes", 0}, {"samples_bytes", 100}}}};
    restart.erase("tick");
    cli::RunRecord run;
    const cli::RunPlan plan = cli::planRun(defaultScene());
    try {
        cli::resumeRun(restart, plan, dir, 8, false, 10.0, run);
        FAIL() << "expected an IoError";
    } catch (const IoError& e) {
        EXPECT_EQ(std::string(e.what()), (dir / "restart.bin").string() +
                                             ": damaged, or written by another version of "
                                             "terrace (key 'tick' not found)");
    }
    // Whole, but samples.bin shorter than its restart point: refused, nothing created or cut.
    restart["tick"] = 0;
    EXPECT_THROW(cli::resumeRun(restart, plan, dir, 8, false, 10.0, run), IoError);
    EXPECT_FALSE(std::filesystem::exists(dir / "samples.bin"));
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
