#pragma once
// The run loop shared by both engines (STYLE.md items 8-9): sampling in physical time is decided
// here, outside the engines:
//   equilibration  advanceTo(k·Δt_thermostat), then rescale v, ω to the scene temperature
//   production     advanceTo(t_s) on the sample grid, record energies, K_trans and the virial,
//                  hand a Snapshot to the analysis (analysis/run_analysis.hpp, which accumulates
//                  g(r) and the time correlations as the run goes and keeps no sample), append
//                  trajectory frames and thermo.csv rows (cli/thermo.hpp) and, with restarts on,
//                  the sample to samples.bin
//   restart points every output.restart_every_ps (cli/restart.hpp): the engine is rebuilt from
//                  its bodies and checkpoint and restart.bin is written
//   re-sort points (DMD, dmd.resort_cells): at a sample or thermostat tick where the bodies'
//                  cell order has decayed, the engine is rebuilt the same way, without the file
// CPU time is measured around the engine's advanceTo and rescale calls and its re-sorts only, so
// output, analysis and restart points do not count against either engine; the analysis' own CPU
// time is reported apart (analysis_cpu_seconds).
//
// Nothing is lost when a run stops: every file is written whole (core/output_file.hpp); a signal
// (cli/interrupt.hpp) ends the run at the next sample with restart.bin, summary.json (saying
// "interrupted" and by which signal) and the analysis written; an engine failure or a failed
// write ends it with what was gathered until then written and the first error raised again.
#include "analysis/run_analysis.hpp"
#include "cli/cpu_clock.hpp"
#include "cli/interrupt.hpp"
#include "cli/output_dir.hpp"
#include "cli/provenance.hpp"
#include "cli/restart.hpp"
#include "cli/thermo.hpp"
#include "core/engine.hpp"
#include "core/huge_pages.hpp"
#include "core/output_file.hpp"
#include "core/scene.hpp"
#include "core/units.hpp"
#include "core/xyz.hpp"
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#if defined(__GLIBC__)
#include <malloc.h> // malloc_trim
#endif
#include <memory>
#include <nlohmann/json.hpp>
#include <numeric>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace terrace::cli {

struct RunPlan {
    double sampleInterval = 0.0;     // time units
    double thermostatInterval = 0.0; // time units
    long equilibrationTicks = 0;     // whole thermostat intervals
    long productionSamples = 0;      // samples after the one at the start of production
    long trajectoryEvery = 0;        // in samples; 0 = none
    long thermoEvery = 0;            // in samples; 0 = none
    long restartEvery = 0;           // in samples; 0 = none
    long restartEveryTicks = 0;      // in thermostat intervals, during equilibration

    /// The time of production sample s. When the thermostat and sample intervals agree this is
    /// (ticks + s)·Δt, one grid from t = 0, as runs have always been sampled.
    double productionTime(long s, double tStart) const;
};

/// The scene's intervals on the engine's grid (the scene validation has checked that they are
/// whole multiples: SMD moves in whole steps, outputs come at whole samples).
RunPlan planRun(const Scene& scene);

/// The analysis settings of a scene (analysis.rdf_max is in σ there, in Å here).
analysis::StreamingOptions streamingOptions(const Scene& scene);

/// Bytes the run's analysis and per-sample records will hold in memory at most.
double analysisBytes(const Scene& scene);

/// Where and how a run writes.
struct RunTarget {
    std::filesystem::path dir;
    OutputMode mode = OutputMode::Fresh;
    bool quiet = false;
    // DIR/restart.bin when continuing; the engine's builder takes its bodies and checkpoint out.
    nlohmann::json* resume = nullptr;
};

/// What a run returns: its summary, and the process's exit status (0, or 128 + a signal).
struct RunOutcome {
    nlohmann::json summary;
    int exitStatus = 0;
};

nlohmann::json vec3Json(const Vec3& v);

/// Adds one stretch of an engine's life (statistics at its start and end) to the production's
/// statistics: counters (events.*, steps, ...) add their increase over the stretch, everything
/// else takes its value at the end. Production is one stretch unless restart points rebuilt the
/// engine.
void accumulateStatistics(nlohmann::json& production, const nlohmann::json& start,
                          const nlohmann::json& end);

/// Collisions (DMD's events up + down + reflect) in engine statistics; 0 for SMD's.
double collisionCount(const nlohmann::json& statistics);

/// Merges the production's engine statistics into the summary and adds collisions_per_ps
/// (DMD: up + down + reflect) and steps_per_ps (SMD) where those counters exist.
void addEngineStatistics(nlohmann::json& summary, const nlohmann::json& production,
                         double simulatedPs);

/// What a run gathered, handed from the engine loop to the summary.
struct RunRecord {
    std::vector<SampleRecord> records; // per production sample: energies, K_trans, virial, …
    std::unique_ptr<analysis::RunAnalysis> analysis; // null with fewer than 4 samples planned
    CpuClock analysisClock;                          // CPU time of the analysis
    Vec3 momentumInitial = Vec3::Zero(), momentumFinal = Vec3::Zero(); // internal units
    nlohmann::json production = nlohmann::json::object(); // engine statistics over production
    double simulatedPs = 0.0, cpuSeconds = 0.0, cpuEquilibration = 0.0;
    double sampleInterval = 0.0, kT = 0.0;
    double volume = 0.0;                               // Å³
    VirialKind virialKind = VirialKind::Instantaneous; // what records[k].virial holds
    int bodies = 0, dof = 0;
    std::string interruptedBy;         // the signal that stopped the run ("" if none)
    std::string interruptedIn;         // equilibration | production | analysis
    std::string failure;               // the first error that ended the run ("" if none)
    long restartsWritten = 0;          // restart files written over the whole run
    std::size_t hugePageBytes = 0;     // most of the process seen in huge pages at an engine's end
    long resorts = 0;                  // DMD: bodies renumbered at a sample (dmd.resort_cells)
    int continuations = 0;             // times the run was continued from a restart file
    double restartEveryPs = 0.0;       // 0: no restart files
    std::vector<std::string> warnings; // from the scene (sceneWarnings)

    void add(const SampleRecord& e, const Snapshot& s) {
        records.push_back(e);
        if (!analysis) return;
        analysisClock.start();
        analysis->add(s);
        analysisClock.stop();
    }
    /// A sample taken from the engine: the analysis gets only what it reads (the followed
    /// bodies, and on a g(r) frame every position, read from the engine body by body), so that
    /// no large system's sample, nor its positions, is held beside the engine (~0.1 GB of
    /// sample, 24 MB of positions, at 10⁶ rods).
    template <class E> void addParts(const SampleRecord& e, const E& engine) {
        records.push_back(e);
        if (!analysis) return;
        const Snapshot followed = engine.snapshot(analysis->followedBodies());
        analysisClock.start();
        if (analysis->wantsPositions())
            analysis->add(followed, [&engine](int b) { return engine.position(b); });
        else
            analysis->add(followed, nullptr);
        analysisClock.stop();
    }
};

/// Writes summary.json, then the correlation analysis (cancelled by a signal that arrives
/// during it: more than `tolerated` signals in all), then summary.json again with the analysis'
/// results.
/// `analysed`: whether the analysis ran to its end (or was not due: fewer than 4 samples).
nlohmann::json writeSummaryAndAnalysis(const Scene& scene, RunRecord& run,
                                       const std::filesystem::path& dir,
                                       const InterruptGuard& interrupt, int tolerated,
                                       bool& analysed);

/// The bodies as they are now: DMD brings every clock to time(); SMD's are always there.
template <class E> auto currentSystem(const E& engine) {
    if constexpr (requires { engine.synchronisedCopy(); })
        return engine.synchronisedCopy();
    else
        return engine.system();
}

/// The bodies as they are now, from an engine about to be dropped: DMD's are moved out of it
/// (dmd/engine_start.hpp), not copied beside it; SMD's engine is small enough for a copy.
template <class E> auto releasedSystem(E&& engine) {
    if constexpr (requires { releaseSystem(std::move(engine)); })
        return releaseSystem(std::move(engine));
    else
        return currentSystem(engine);
}

/// DMD keeps a running impulse virial (its forces are impulses), SMD the virial at the instant.
template <class E> constexpr VirialKind virialKindOf() {
    if constexpr (requires(const E& e) { e.impulseVirial(); })
        return VirialKind::Impulse;
    else
        return VirialKind::Instantaneous;
}
template <class E> double virialOf(const E& engine) {
    if constexpr (virialKindOf<E>() == VirialKind::Impulse)
        return engine.impulseVirial();
    else
        return engine.virial();
}

/// The model's continuous U: DMD computes it apart from its terraced one; SMD's is its own.
template <class E> double continuousPotentialOf(const E& engine) {
    if constexpr (requires { engine.continuousPotentialEnergy(); })
        return engine.continuousPotentialEnergy();
    else
        return engine.potentialEnergy();
}

/// The run's position and accumulators from a restart file: the samples (read back from
/// samples.bin, after checking that the growing files still hold what the file says they did),
/// the phase, and what the file carries over. Fills `run`; returns the open growing files.
struct Resumed {
    bool inProduction = false;
    long tick = 0, sample = 0;
    double tStart = 0.0, cpuEquilibration = 0.0, cpuProduction = 0.0;
    AppendFile trajectory, thermo, samples;
};
Resumed resumeRun(const nlohmann::json& restart, const RunPlan& plan,
                  const std::filesystem::path& dir, int bodies, bool withOrientation,
                  double boxLength, RunRecord& run);

/// The engine's bodies begin … end−1 as a snapshot, taken when a piece of a frame or of a sample
/// record is written: at 10⁶ bodies neither the record's bytes nor its snapshot is held whole.
template <class E> auto bodiesOf(const E& engine) {
    return [&engine, bodies = std::vector<int>()](int begin, int end) mutable {
        bodies.resize(static_cast<std::size_t>(end - begin));
        std::iota(bodies.begin(), bodies.end(), begin);
        return engine.snapshot(std::span<const int>(bodies));
    };
}

/// The engine's bodies as one trajectory frame, handed to `sink` piece by piece.
template <class E>
void writeFrame(const E& engine, int n, TrajectoryLayout layout, const PieceSink& sink) {
    const Snapshot none = engine.snapshot(std::span<const int>()); // its time and box
    writeXyzFramePieces(n, none.time, none.boxLength, layout, bodiesOf(engine), sink);
}

/// The engine's bodies and the sample's energies as one samples.bin record, piece by piece.
template <class E>
void writeSample(const E& engine, int n, const SampleRecord& e, const PieceSink& sink) {
    const Snapshot none = engine.snapshot(std::span<const int>()); // its time
    writeSamplePieces(n, none.time, e, bodiesOf(engine), sink);
}

/// Hands back to the system the pages a dropped engine left free inside the heap. glibc keeps
/// them resident (the old engine's lists and agendas were many blocks, freed in no useful order),
/// and the next engine's arrays would then be counted beside them: at a restart or re-sort point
/// of 262 144 LJ spheres, 40 B a body over the run's peak.
inline void returnFreedMemory() {
#if defined(__GLIBC__)
    malloc_trim(0);
#endif
}

/// Drives the engine through the scene's run into target.dir, which the caller has claimed
/// (cli/output_dir.hpp). `engine` holds the engine built from the scene's initial state, or from
/// the restart file when continuing; every restart point drops it and puts in its place one
/// rebuilt from its bodies and checkpoint. It is null on return when the run ended at a restart
/// point (a signal's stop, a failed rebuild or restart file).
template <class E>
RunOutcome drive(std::unique_ptr<E>& engine, const Scene& scene, const RunTarget& target,
                 int rotationalDof) {
    const RunPlan plan = planRun(scene);
    const std::filesystem::path& dir = target.dir;
    const bool restarts = plan.restartEvery > 0;
    const TrajectoryLayout layout = layoutFor(rotationalDof);
    RunRecord run;
    run.kT = scene.kT();
    run.sampleInterval = plan.sampleInterval;
    const auto [bodies, boxLength] = [&] { // without a whole sample
        const Snapshot where = engine->positions();
        return std::pair{where.size(), where.boxLength};
    }();
    run.bodies = bodies;
    run.dof = degreesOfFreedom(rotationalDof, run.bodies);
    run.volume = std::pow(boxLength, 3);
    run.virialKind = virialKindOf<E>();
    const ThermoLayout thermoLayout{run.virialKind, run.volume, run.dof, run.bodies};
    if (plan.productionSamples + 1 >= 4)
        run.analysis = std::make_unique<analysis::RunAnalysis>(
            run.bodies, boxLength, units::toPs(plan.sampleInterval), plan.productionSamples + 1,
            streamingOptions(scene));
    run.restartEveryPs = scene.output.restart_every_ps;
    run.warnings = sceneWarnings(scene);
    for (const auto& w : run.warnings)
        std::fprintf(stderr, "terrace: warning: %s\n", w.c_str());
    ProgressReporter progress(target.quiet,
                              double(plan.equilibrationTicks) * plan.thermostatInterval +
                                  double(plan.productionSamples) * plan.sampleInterval);
    CpuClock cpu;
    InterruptGuard interrupt;

    // Where the run stands: the phase, thermostat ticks and samples done, production's start.
    Resumed at;
    if (!target.resume) {
        writeFileAtomically(dir / "scene.json", toJson(scene).dump(2) + "\n");
        // In pieces: at 10⁶ bodies the frame's text alone is ~0.3 GB.
        writeFileAtomically(dir / "initial.xyz", [&](const PieceSink& sink) {
            writeFrame(*engine, run.bodies, layout, sink);
        });
    } else {
        at = resumeRun(*target.resume, plan, dir, run.bodies, rotationalDof == 3, boxLength, run);
    }
    bool& inProduction = at.inProduction;
    long &tick = at.tick, &sample = at.sample;
    AppendFile &trajectory = at.trajectory, &thermo = at.thermo, &samplesFile = at.samples;
    nlohmann::json stretchStart; // engine statistics where the current stretch began
    if (inProduction) stretchStart = engine->statistics();

    // Collisions since production began: the stretches before the current engine's, and its own.
    auto productionCollisions = [&] {
        if constexpr (virialKindOf<E>() == VirialKind::Impulse)
            return collisionCount(run.production) + collisionCount(engine->statistics()) -
                   collisionCount(stretchStart);
        else
            return 0.0;
    };
    auto record = [&] {
        const bool frameDue = plan.trajectoryEvery > 0 && sample % plan.trajectoryEvery == 0;
        const double u = engine->potentialEnergy(), kin = engine->kineticEnergy();
        SampleRecord e{units::toPs(engine->time() - at.tStart), u + kin, u, kin};
        e.kineticTranslational = engine->translationalKineticEnergy();
        e.virial = virialOf(*engine);
        e.collisions = productionCollisions();
        e.time = engine->time();
        if (plan.thermoEvery > 0 && sample % plan.thermoEvery == 0) {
            const SampleRecord* before =
                sample > 0 ? &run.records[sample - plan.thermoEvery] : nullptr;
            thermo.append(thermoRow(e, before, continuousPotentialOf(*engine), thermoLayout));
        }
        // Nothing takes the sample whole: beside the engine it would raise the run's peak.
        if (restarts) // what a continued run reads back
            samplesFile.appendPieces(
                [&](const PieceSink& sink) { writeSample(*engine, run.bodies, e, sink); });
        if (frameDue)
            trajectory.appendPieces(
                [&](const PieceSink& sink) { writeFrame(*engine, run.bodies, layout, sink); });
        run.addParts(e, *engine);
    };
    // What the code after the loop reads of the engine, kept at every restart point: the engine
    // is dropped there, and a rebuild that fails leaves none.
    struct EngineEnd {
        nlohmann::json statistics;
        double time = 0.0;
        Vec3 momentum = Vec3::Zero();
    } last;
    auto endOf = [&run](const E& e) {
        // The engine's arrays are all there now: what of the process lies in huge pages.
        run.hugePageBytes = std::max(run.hugePageBytes, processHugePageBytes());
        return EngineEnd{e.statistics(), e.time(), e.totalMomentum()};
    };
    // A restart point: the engine is rebuilt from its bodies and checkpoint, exactly as a run
    // continued from the file written here builds it. Nothing the size of an engine lives beside
    // one: the bodies are moved out of the old engine, which is dropped before the new one is
    // built (the two side by side doubled the run's peak); the file is written in between, and
    // so is kept should the rebuild fail. The growing files reach the disk before the restart
    // file that counts their bytes. At a signal's stop the engine is not rebuilt: the run ends.
    // A re-sort point (DMD, `dmd.resort_cells`) is a restart point without its file: the rebuilt
    // engine numbers the bodies afresh in the cell order of where they are now.
    auto restartPoint = [&](const std::string& reason, bool rebuild, bool keepFile = true) {
        last = endOf(*engine);
        if (inProduction) accumulateStatistics(run.production, stretchStart, last.statistics);
        stretchStart = last.statistics; // the stretch so far is in run.production
        nlohmann::json checkpoint;      // spent by the rebuild
        auto system = [&] {
            try {
                if constexpr (requires { engine->shed(); })
                    engine->shed(); // the checkpoint takes its room
                checkpoint = engine->checkpoint();
                return releasedSystem(std::move(*engine));
            } catch (...) { // a shed engine is fit for nothing else: `last` is its end
                engine.reset();
                throw;
            }
        }();
        engine.reset();
        returnFreedMemory();
        if (keepFile) {
            if (trajectory.isOpen()) trajectory.sync();
            if (thermo.isOpen()) thermo.sync();
            if (samplesFile.isOpen()) samplesFile.sync();
            writeRestart(dir,
                         {{"format", restartFormat},
                          {"reason", reason},
                          {"scene", toJson(scene)},
                          {"phase", inProduction ? "production" : "equilibration"},
                          {"tick", tick},
                          {"sample", sample},
                          {"t_start", at.tStart},
                          {"time_fs", units::toFs(last.time)},
                          {"n_bodies", run.bodies},
                          {"bodies", bodiesToBinary(system.bodies)},
                          {"engine", checkpoint},
                          {"production_statistics", run.production},
                          {"momentum_initial", vec3Json(run.momentumInitial)},
                          {"cpu_seconds", at.cpuProduction + (inProduction ? cpu.seconds() : 0.0)},
                          {"cpu_seconds_equilibration",
                           at.cpuEquilibration + (inProduction ? 0.0 : cpu.seconds())},
                          {"restarts_written", run.restartsWritten + 1},
                          {"resorts", run.resorts},
                          {"continuations", run.continuations},
                          {"files",
                           {{"trajectory_bytes", trajectory.isOpen() ? trajectory.size() : 0},
                            {"thermo_bytes", thermo.isOpen() ? thermo.size() : 0},
                            {"samples_bytes", samplesFile.isOpen() ? samplesFile.size() : 0}}}});
            ++run.restartsWritten;
            if (!rebuild) return;
            returnFreedMemory(); // the restart file's buffers
        }
        engine = std::make_unique<E>(std::move(system), scene, std::move(checkpoint));
        stretchStart = engine->statistics();
    };
    // The bodies renumbered when their order has decayed, with the rebuild's CPU time counted as
    // the engine's (a restart point's is not: it is paid for its file). Not at the run's end, nor
    // where a restart point rebuilds the engine anyway.
    auto resortWhereDecayed = [&] {
        if constexpr (requires { engine->orderHasDecayed(); }) {
            if (!engine->orderHasDecayed()) return;
            cpu.start();
            restartPoint("re-sort", true, false);
            cpu.stop();
            ++run.resorts;
        }
    };
    // The first error ends the run; what was gathered until then is still written.
    auto guarded = [&](auto&& work) {
        try {
            work();
        } catch (const std::exception& e) {
            cpu.stop();
            run.failure = e.what();
        }
    };
    guarded([&] {
        if (!inProduction) {
            while (tick < plan.equilibrationTicks && !interrupt.requested()) {
                cpu.start();
                engine->advanceTo(double(tick + 1) * plan.thermostatInterval);
                engine->rescaleTemperature(run.kT);
                cpu.stop();
                ++tick;
                progress.report("equilibration", tick, plan.equilibrationTicks, engine->time());
                if (interrupt.requested()) continue;
                if (tick < plan.equilibrationTicks) {
                    if (restarts && tick % plan.restartEveryTicks == 0)
                        restartPoint("interval", true);
                    else
                        resortWhereDecayed();
                } else if (!restarts && plan.productionSamples > 0) {
                    resortWhereDecayed(); // (with restarts, production's start rebuilds it)
                }
            }
            if (interrupt.requested()) return;
            at.cpuEquilibration += cpu.seconds();
            cpu.reset();
            inProduction = true;
            at.tStart = engine->time();
            stretchStart = engine->statistics();
            run.momentumInitial = engine->totalMomentum();
            if (plan.trajectoryEvery > 0) trajectory = AppendFile(dir / "trajectory.xyz", 0);
            if (plan.thermoEvery > 0) {
                thermo = AppendFile(dir / "thermo.csv", 0);
                thermo.append(thermoHeader(thermoLayout));
            }
            if (restarts) samplesFile = AppendFile(dir / "samples.bin", 0);
            record();
            // Production's start is a restart point: a kill then costs at most one interval
            // of production, never the equilibration.
            if (restarts) restartPoint("production", true);
        }
        while (sample < plan.productionSamples && !interrupt.requested()) {
            cpu.start();
            engine->advanceTo(plan.productionTime(sample + 1, at.tStart));
            cpu.stop();
            ++sample;
            record();
            progress.report("production", sample, plan.productionSamples, engine->time());
            if (sample == plan.productionSamples || interrupt.requested()) continue;
            if (restarts && sample % plan.restartEvery == 0)
                restartPoint("interval", true);
            else
                resortWhereDecayed();
        }
    });
    const bool stopped = interrupt.requested(); // by a signal, before the run's end
    if (stopped) {
        run.interruptedBy = interrupt.signalName();
        run.interruptedIn = inProduction ? "production" : "equilibration";
        // The stop is kept as a restart point too: nothing since the last one is lost.
        if (restarts && run.failure.empty())
            guarded([&] { restartPoint(interrupt.signalName(), false); });
    }
    if (inProduction) {
        at.cpuProduction += cpu.seconds();
        if (engine) last = endOf(*engine); // else the last restart point's
        accumulateStatistics(run.production, stretchStart, last.statistics);
        run.simulatedPs = units::toPs(last.time - at.tStart);
        run.momentumFinal = last.momentum;
    } else {
        at.cpuEquilibration += cpu.seconds();
    }
    run.cpuSeconds = at.cpuProduction;
    run.cpuEquilibration = at.cpuEquilibration;

    RunOutcome outcome;
    bool analysed = false;
    try {
        outcome.summary =
            writeSummaryAndAnalysis(scene, run, dir, interrupt, stopped ? 1 : 0, analysed);
    } catch (const std::exception& e) {
        if (run.failure.empty()) throw;
        // The first error is the one to report; this one followed from it (e.g. a full disk).
    }
    if (!run.failure.empty())
        throw std::runtime_error(run.failure + " (output so far in " + dir.string() + ")");
    if (!run.interruptedBy.empty()) outcome.exitStatus = interrupt.exitStatus();
    // A run that went to its end and was analysed leaves nothing to continue. One whose analysis
    // a signal cancelled keeps its restart files: continuing redoes the last interval and the
    // analysis.
    if (restarts && !stopped && analysed) {
        std::error_code ec;
        std::filesystem::remove(dir / "restart.bin", ec);
        std::filesystem::remove(dir / "samples.bin", ec);
    }
    return outcome;
}

} // namespace terrace::cli
