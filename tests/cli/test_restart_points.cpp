// The restart points' owner (cli/restart_points.hpp) on its own, without a run: when points are
// due, what restart.bin holds, the engine rebuilt from what it released, production's statistics
// over several engines, and the ends a stop or a failed rebuild leave. The engine is a toy that
// keeps the contract (core/engine.hpp): free bodies in a line, a step counter, a checkpoint.
#include "cli/restart_points.hpp"
#include "core/engine.hpp"
#include <filesystem>
#include <gtest/gtest.h>
#include <memory>
#include <stdexcept>
#include <unistd.h>
#include <vector>

namespace test_restart_points {

using namespace terrace;

namespace {

struct ToyState {
    Vec3 r = Vec3::Zero(), v = Vec3::Zero();
};

struct ToySystem {
    std::vector<ToyState> bodies;
};

/// Bodies in free flight; statistics count advanceTo calls ("steps") since construction.
class ToyEngine {
public:
    static constexpr VirialKind virialKind = VirialKind::Instantaneous;
    static inline int built = 0;

    explicit ToyEngine(ToySystem s, double t = 0.0) : sys_(std::move(s)), time_(t) { ++built; }
    ToyEngine(ToySystem s, const nlohmann::json& checkpoint)
        : ToyEngine(std::move(s), checkpoint.at("time").get<double>()) {}

    void advanceTo(double t) {
        for (auto& b : sys_.bodies)
            b.r += b.v * (t - time_);
        time_ = t;
        ++steps_;
    }
    double time() const { return time_; }
    Snapshot snapshot() const { return positions(); }
    Snapshot snapshot(std::span<const int>) const { return positions(); }
    Snapshot positions() const {
        Snapshot s;
        s.time = time_;
        s.boxLength = 10.0;
        for (const auto& b : sys_.bodies)
            s.position.push_back(b.r);
        return s;
    }
    Vec3 position(int b) const { return sys_.bodies[b].r; }
    double kineticEnergy() const { return 0.0; }
    double translationalKineticEnergy() const { return 0.0; }
    double potentialEnergy() const { return 0.0; }
    ContinuousSums continuousSums(TerracingProfile*) const { return {}; }
    double virial() const { return 0.0; }
    Vec3 totalMomentum() const { return Vec3(time_, 0.0, 0.0); }
    void rescaleTemperature(double) {}
    double thermostatEnergy() const { return 0.0; }
    nlohmann::json statistics() const { return {{"steps", steps_}, {"time", time_}}; }
    nlohmann::json checkpoint() const { return {{"time", time_}}; }
    ToySystem system() const { return sys_; }
    Released<ToySystem> release() && { return {std::move(sys_), checkpoint()}; }

private:
    ToySystem sys_;
    double time_ = 0.0;
    long steps_ = 0;
};
static_assert(Engine<ToyEngine>);

using Points = cli::RestartPoints<ToyEngine>;

ToySystem threeBodies() {
    ToySystem s;
    for (int i = 0; i < 3; ++i)
        s.bodies.push_back({Vec3(i, 0.0, 0.0), Vec3(0.0, 1.0 + i, 0.0)});
    return s;
}

Points::Rebuild rebuildToy() {
    return [](Released<ToySystem>&& r) {
        return std::make_unique<ToyEngine>(std::move(r.system), r.checkpoint);
    };
}

struct Fixture {
    std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("terrace-points-" + std::to_string(::getpid()));
    cli::RunPlan plan;
    cli::RunRecord run;
    cli::RunPosition at;
    cli::RunFiles files;
    Fixture() {
        std::filesystem::remove_all(dir);
        std::filesystem::create_directories(dir);
        plan.restartEvery = 3;
        plan.restartEveryTicks = 2;
        run.bodies = 3;
    }
    ~Fixture() { std::filesystem::remove_all(dir); }
    Points points(Points::Rebuild rebuild = rebuildToy()) {
        return Points(plan, dir, {{"name", "toy"}}, std::move(rebuild), run, at, files);
    }
};

} // namespace

TEST(RestartPoints, AreDueEveryIntervalOfTheirPhaseAndNeverWhenOff) {
    Fixture f;
    Points p = f.points();
    EXPECT_TRUE(p.on());
    std::vector<long> ticks, samples;
    for (long k = 1; k <= 7; ++k) {
        if (p.dueAfterTick(k)) ticks.push_back(k);
        if (p.dueAfterSample(k)) samples.push_back(k);
    }
    EXPECT_EQ(ticks, (std::vector<long>{2, 4, 6}));
    EXPECT_EQ(samples, (std::vector<long>{3, 6}));
    f.plan.restartEvery = 0;
    Points off = f.points();
    EXPECT_FALSE(off.on());
    EXPECT_FALSE(off.dueAfterTick(2));
    EXPECT_FALSE(off.dueAfterSample(3));
}

// A point writes the run as it stands and puts in the engine's place one built from the bodies
// and checkpoint it released; the file's bodies are the engine's, bit for bit.
TEST(RestartPoints, WriteTheRunAsItStandsAndRebuildTheEngine) {
    Fixture f;
    Points p = f.points();
    auto engine = std::make_unique<ToyEngine>(threeBodies());
    engine->advanceTo(0.5);
    const ToySystem before = engine->system();
    f.at.inProduction = true;
    f.at.sample = 3;
    f.at.cpuProduction = 2.0;
    p.beginStretch(*engine);
    ToyEngine::built = 0;
    p.take(engine, "interval", true, 0.25);
    ASSERT_TRUE(engine);
    EXPECT_EQ(ToyEngine::built, 1);
    EXPECT_EQ(engine->time(), 0.5);
    const nlohmann::json file = cli::readRestart(f.dir);
    EXPECT_EQ(file.at("reason"), "interval");
    EXPECT_EQ(file.at("phase"), "production");
    EXPECT_EQ(file.at("sample"), 3);
    EXPECT_EQ(file.at("cpu_seconds"), 2.25); // the phase's CPU so far added
    EXPECT_EQ(file.at("engine").at("time"), 0.5);
    EXPECT_EQ(file.at("restarts_written"), 1);
    EXPECT_EQ(file.at("scene").at("name"), "toy");
    const auto bodies = cli::bodiesFromBinary<ToyState>(file.at("bodies"), 3);
    for (int i = 0; i < 3; ++i) {
        EXPECT_EQ(bodies[i].r, before.bodies[i].r);
        EXPECT_EQ(bodies[i].v, before.bodies[i].v);
        EXPECT_EQ(engine->position(i), before.bodies[i].r);
    }
    EXPECT_EQ(f.run.restartsWritten, 1);
}

// Production's counters add up over the engines that a restart point replaces; during
// equilibration nothing is counted.
TEST(RestartPoints, KeepProductionStatisticsOverSeveralEngines) {
    Fixture f;
    Points p = f.points();
    auto engine = std::make_unique<ToyEngine>(threeBodies());
    engine->advanceTo(0.1); // equilibration: not production's
    p.take(engine, "interval", true, 0.0);
    f.at.inProduction = true;
    p.beginStretch(*engine);
    engine->advanceTo(0.2);
    engine->advanceTo(0.3);
    p.take(engine, "interval", true, 0.0);
    engine->advanceTo(0.4);
    const cli::EngineEnd& end = p.end(engine.get());
    EXPECT_EQ(f.run.production.at("steps"), 3);
    EXPECT_EQ(f.run.production.at("time"), 0.4); // not a counter: its value at the end
    EXPECT_EQ(end.time, 0.4);
    EXPECT_EQ(end.momentum, Vec3(0.4, 0.0, 0.0));
}

// A stop writes the file and builds nothing; the run's end is the stopped engine's.
TEST(RestartPoints, AStopWritesTheFileAndLeavesNoEngine) {
    Fixture f;
    Points p = f.points();
    auto engine = std::make_unique<ToyEngine>(threeBodies());
    f.at.inProduction = true;
    p.beginStretch(*engine);
    engine->advanceTo(0.7);
    ToyEngine::built = 0;
    p.take(engine, "SIGTERM", false, 0.0);
    EXPECT_FALSE(engine);
    EXPECT_EQ(ToyEngine::built, 0);
    EXPECT_EQ(cli::readRestart(f.dir).at("reason"), "SIGTERM");
    const cli::EngineEnd& end = p.end(nullptr);
    EXPECT_EQ(end.time, 0.7);
    EXPECT_EQ(f.run.production.at("steps"), 1);
}

// A rebuild that fails leaves no engine, keeps the file written before it, and the run's end
// is the dropped engine's.
TEST(RestartPoints, AFailedRebuildKeepsTheFileAndTheEnd) {
    Fixture f;
    Points p = f.points([](Released<ToySystem>&&) -> std::unique_ptr<ToyEngine> {
        throw std::runtime_error("no room");
    });
    auto engine = std::make_unique<ToyEngine>(threeBodies());
    f.at.inProduction = true;
    p.beginStretch(*engine);
    engine->advanceTo(0.3);
    EXPECT_THROW(p.take(engine, "interval", true, 0.0), std::runtime_error);
    EXPECT_FALSE(engine);
    EXPECT_EQ(cli::readRestart(f.dir).at("engine").at("time"), 0.3);
    EXPECT_EQ(p.end(nullptr).time, 0.3);
    EXPECT_EQ(f.run.production.at("steps"), 1);
}

} // namespace test_restart_points
