#pragma once
// Restart points (cli/restart.hpp): every output.restart_every_ps, at production's start and at a
// signal's stop, the run writes restart.bin and the engine is rebuilt from its bodies and
// checkpoint, exactly as a run continued from that file builds it, so that both undergo the same
// events. This owner also keeps the engine's statistics over production, which a rebuild would
// otherwise restart: production is a sequence of stretches, one per engine.
//
// Nothing the size of an engine lives beside one: the bodies are moved out of the old engine,
// which is dropped before the new one is built (the two side by side doubled the run's peak);
// the file is written in between, and so is kept should the rebuild fail. The growing files
// reach the disk before the restart file that counts their bytes.
#include "cli/run_record.hpp"
#include "core/engine.hpp"
#include "core/huge_pages.hpp"
#include "core/units.hpp"
#if defined(__GLIBC__)
#include <malloc.h> // malloc_trim
#endif
#include <algorithm>
#include <filesystem>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>

namespace terrace::cli {

/// Hands back to the system the pages a dropped engine left free inside the heap. glibc keeps
/// them resident (the old engine's lists and agendas were many blocks, freed in no useful order),
/// and the next engine's arrays would then be counted beside them.
inline void returnFreedMemory() {
#if defined(__GLIBC__)
    malloc_trim(0);
#endif
}

/// What the summary reads of an engine at its end, kept at every restart point: the engine is
/// dropped there, and a rebuild that fails leaves none.
struct EngineEnd {
    nlohmann::json statistics;
    double time = 0.0;
    Vec3 momentum = Vec3::Zero();
};

template <Engine E> class RestartPoints {
public:
    using System = decltype(std::declval<const E&>().system());
    /// Builds the engine that goes on from a released one's bodies and checkpoint.
    using Rebuild = std::function<std::unique_ptr<E>(Released<System>&&)>;

    RestartPoints(const RunPlan& plan, std::filesystem::path dir, nlohmann::json scene,
                  Rebuild rebuild, RunRecord& run, RunPosition& at, RunFiles& files)
        : plan_(plan), dir_(std::move(dir)), scene_(std::move(scene)), rebuild_(std::move(rebuild)),
          run_(run), at_(at), files_(files) {}

    bool on() const { return plan_.restartEvery > 0; }
    /// After thermostat tick `tick` (not the last), or production sample `sample` (not the last).
    bool dueAfterTick(long tick) const { return on() && tick % plan_.restartEveryTicks == 0; }
    bool dueAfterSample(long sample) const { return on() && sample % plan_.restartEvery == 0; }

    /// The engine's current stretch of production begins now.
    void beginStretch(const E& engine) { stretchStart_ = engine.statistics(); }
    /// Collisions since production began: the finished stretches' and the current one's.
    double productionCollisions(const E& engine) const {
        return collisionCount(run_.production) + collisionCount(engine.statistics()) -
               collisionCount(stretchStart_);
    }

    /// Writes restart.bin with the run as it stands (`reason`: interval, production, or the
    /// signal's name; `phaseCpu`: CPU seconds of the current phase not yet in `at`) and puts in
    /// the engine's place one rebuilt from its bodies and checkpoint, or none (`rebuild` false:
    /// the run ends here). A failure leaves `engine` null, with end() still answering.
    void take(std::unique_ptr<E>& engine, const std::string& reason, bool rebuild,
              double phaseCpu) {
        Released<System> released = release(engine);
        files_.sync();
        writeRestart(dir_, restartFile(reason, released, phaseCpu));
        ++run_.restartsWritten;
        if (!rebuild) return;
        returnFreedMemory(); // the restart file's buffers
        engine = rebuild_(std::move(released));
        stretchStart_ = engine->statistics();
    }

    /// The run has ended: production's statistics include the last stretch, and this is where
    /// the engine ended (the last restart point's end when no engine is left).
    const EngineEnd& end(const E* engine) {
        if (engine) closeStretch(*engine); // else the last restart point closed it
        return last_;
    }

private:
    /// The engine's end recorded and its stretch of production added up; the next stretch
    /// starts here.
    void closeStretch(const E& e) {
        // The engine's arrays are all there now: what of the process lies in huge pages.
        run_.hugePageBytes = std::max(run_.hugePageBytes, processHugePageBytes());
        last_ = EngineEnd{e.statistics(), e.time(), e.totalMomentum()};
        if (at_.inProduction)
            accumulateStatistics(run_.production, stretchStart_, last_.statistics);
        stretchStart_ = last_.statistics;
    }

    /// The engine's end is recorded and its stretch closed; then its bodies and checkpoint are
    /// moved out and it is dropped.
    Released<System> release(std::unique_ptr<E>& engine) {
        closeStretch(*engine);
        try {
            Released<System> r = std::move(*engine).release();
            engine.reset();
            returnFreedMemory();
            return r;
        } catch (...) { // a spent engine is fit for nothing else: last_ is its end
            engine.reset();
            throw;
        }
    }

    nlohmann::json restartFile(const std::string& reason, const Released<System>& r,
                               double phaseCpu) const {
        const bool production = at_.inProduction;
        // The analysis' accumulators and the sample statistics, not the samples they were made
        // from: a size fixed by the settings, whatever the run's length (cli/restart.hpp).
        nlohmann::json analysis;
        if (production && run_.analysis) analysis = nlohmann::json::binary(run_.analysis->state());
        return {{"format", restartFormat},
                {"reason", reason},
                {"scene", scene_},
                {"identity", runIdentity(run_.sceneChecksum, run_.bodies,
                                         scene_.value("engine", std::string()))},
                {"phase", production ? "production" : "equilibration"},
                {"tick", at_.tick},
                {"sample", at_.sample},
                {"t_start", at_.tStart},
                {"time_fs", units::toFs(last_.time)},
                {"n_bodies", run_.bodies},
                {"bodies", bodiesToBinary(r.system.bodies)},
                {"engine", r.checkpoint},
                {"production_statistics", run_.production},
                {"momentum_initial", vec3Json(run_.momentumInitial)},
                {"cpu_seconds", at_.cpuProduction + (production ? phaseCpu : 0.0)},
                {"cpu_seconds_equilibration", at_.cpuEquilibration + (production ? 0.0 : phaseCpu)},
                {"process_cpu_seconds", run_.processCpu()},
                {"restarts_written", run_.restartsWritten + 1},
                {"continuations", run_.continuations},
                {"melt_warning", run_.meltWarning},
                {"files", files_.sizes()},
                {"sample_statistics", nlohmann::json::binary(run_.samples.state())},
                {"thermo_row", recordsToBinary({run_.thermoRow})},
                {"analysis", std::move(analysis)}};
    }

    const RunPlan& plan_;
    std::filesystem::path dir_;
    nlohmann::json scene_; // resolved, as the file records it
    Rebuild rebuild_;
    RunRecord& run_;
    RunPosition& at_;
    RunFiles& files_;
    nlohmann::json stretchStart_; // engine statistics where the current stretch began
    EngineEnd last_;
};

} // namespace terrace::cli
