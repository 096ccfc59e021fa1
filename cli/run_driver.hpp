#pragma once
// The run loop shared by both engines (STYLE.md items 8-9): sampling in physical time is decided
// here, outside the engines, through the engine contract (core/engine.hpp) alone:
//   equilibration  advanceTo(k·Δt_thermostat), then rescale v, ω to the scene temperature (with
//                  run.heat_bath set, the engine's bath acts instead, as in production)
//   production     advanceTo(t_s) on the sample grid; each sample goes to the SampleSink
//                  (cli/sample_sink.hpp: energies, thermo.csv, trajectory, analysis)
//   restart points every output.restart_every_ps, at production's start and at a signal's stop
//                  (cli/restart_points.hpp): restart.bin (with the analysis' state), and the
//                  engine rebuilt from its bodies
// CPU time is measured around the engine's advanceTo and rescale calls only, so output, analysis
// and restart points do not count against either engine; the analysis' own CPU time is reported
// apart (analysis_cpu_seconds).
//
// Nothing is lost when a run stops: every file is written whole (core/output_file.hpp); a signal
// (cli/interrupt.hpp) ends the run at the next sample with restart.bin, summary.json (saying
// "interrupted" and by which signal) and the analysis written; an engine failure or a failed
// write ends it with what was gathered until then written and the first error raised again.
#include "cli/body_species.hpp"
#include "cli/cpu_clock.hpp"
#include "cli/interrupt.hpp"
#include "cli/melt_check.hpp"
#include "cli/output_dir.hpp"
#include "cli/provenance.hpp"
#include "cli/restart_points.hpp"
#include "cli/run_record.hpp"
#include "cli/sample_sink.hpp"
#include "core/engine.hpp"
#include "core/output_file.hpp"
#include "core/scene.hpp"
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

namespace terrace::cli {

/// Where and how a run writes.
struct RunTarget {
    std::filesystem::path dir;
    OutputMode mode = OutputMode::Fresh;
    bool quiet = false;
    // DIR/restart.bin when continuing; the engine's builder takes its bodies and checkpoint out.
    nlohmann::json* resume = nullptr;
    // The process's CPU when the run was asked for: the run's CPU (process_cpu_seconds) counts
    // from here, so that building its engine is counted too (an optimal terrace design for rods
    // takes 0.25-0.4 CPU s, about a dilute gas's whole production of 9 ps).
    double processCpuAtStart = CpuClock::now();
};

/// What a run returns: its summary, and the process's exit status (0, or 128 + a signal).
struct RunOutcome {
    nlohmann::json summary;
    int exitStatus = 0;
};

/// After the loop: the run's times and momenta from where it stands (`at`) and where its last
/// engine ended, the summary and analysis written, the first error raised again, and the restart
/// files of a run that went to its end removed.
RunOutcome finishRun(const Scene& scene, RunRecord& run, const RunPosition& at,
                     const EngineEnd& last, const std::filesystem::path& dir,
                     const InterruptGuard& interrupt, bool stopped, bool restarts);

/// scene.json and initial.xyz of a fresh run.
/// Its checksum becomes the run's identity in restart.bin (RunRecord::sceneChecksum).
template <Engine E>
void writeStart(const E& engine, const Scene& scene, RunRecord& run,
                const std::filesystem::path& dir, int rotationalDof) {
    const std::string sceneText = toJson(scene).dump(2) + "\n";
    run.sceneChecksum = crc64(sceneText);
    writeFileAtomically(dir / "scene.json", sceneText);
    writeFileAtomically(dir / "initial.xyz", [&](const PieceSink& sink) {
        writeFrame(engine, run.bodies, layoutFor(rotationalDof), sink);
    });
}

/// Drives the engine through the scene's run into target.dir, which the caller has claimed
/// (cli/output_dir.hpp). `engine` holds the engine built from the scene's initial state, or from
/// the restart file when continuing; `rebuild` builds the one that goes on at a restart point.
/// It is null on return when the run ended at a restart point (a signal's stop, a failed rebuild
/// or restart file).
template <Engine E>
RunOutcome drive(std::unique_ptr<E>& engine, typename RestartPoints<E>::Rebuild rebuild,
                 const Scene& scene, const RunTarget& target, int rotationalDof) {
    const RunPlan plan = planRun(scene);
    const Snapshot where = engine->positions(); // its size and box, without a whole sample
    RunRecord run(scene, plan, int(where.size()), where.boxLength, rotationalDof, E::virialKind,
                  bodySpecies(*engine, scene, int(where.size())));
    run.processCpuAtStart = target.processCpuAtStart;
    for (const auto& w : run.warnings)
        std::fprintf(stderr, "terrace: warning: %s\n", w.c_str());
    RunFiles files;
    RunPosition at;
    if (target.resume)
        at = resumeRun(*target.resume, plan, target.dir, run, files);
    else
        writeStart(*engine, scene, run, target.dir, rotationalDof);
    SampleSink sink(plan, rotationalDof, run, files);
    RestartPoints<E> restarts(plan, target.dir, toJson(scene), std::move(rebuild), run, at, files);
    if (at.inProduction) restarts.beginStretch(*engine);
    ProgressReporter progress(target.quiet, plan.equilibrationEnd + plan.productionLength,
                              run.outputUnits);
    CpuClock cpu;
    InterruptGuard interrupt;
    auto record = [&] { sink.record(*engine, at.sample, restarts.productionCollisions(*engine)); };
    auto guarded = [&](auto&& work) { // the first error ends the run; its output is still written
        try {
            work();
        } catch (const std::exception& e) {
            cpu.stop();
            run.failure = e.what();
        }
    };
    guarded([&] {
        if (!at.inProduction) {
            while (at.tick < plan.equilibrationTicks && !interrupt.requested()) {
                cpu.start();
                engine->advanceTo(plan.tickTime(at.tick + 1));
                // With a heat bath the bath alone equilibrates: its ensemble from the start.
                if (!run.heatBath) engine->rescaleTemperature(run.kT);
                cpu.stop();
                ++at.tick;
                progress.report("equilibration", at.tick, plan.equilibrationTicks, engine->time());
                if (!interrupt.requested() && at.tick < plan.equilibrationTicks &&
                    restarts.dueAfterTick(at.tick))
                    restarts.take(engine, "interval", true, cpu.seconds());
            }
            if (interrupt.requested()) return;
            at.cpuEquilibration += cpu.seconds();
            cpu.reset();
            at.inProduction = true;
            at.tStart = engine->time();
            // A lattice start still ordered after its equilibration (cli/melt_check.hpp).
            if (scene.state.particles.empty() && plan.equilibrationTicks > 0)
                if (auto w = meltWarning(
                        scene, latticeOrder(scene, *engine, run.bodies, rotationalDof > 0),
                        run.bodies, rotationalDof > 0)) {
                    run.meltWarning = *w;
                    std::fprintf(stderr, "terrace: warning: %s\n", w->c_str());
                }
            restarts.beginStretch(*engine);
            run.momentumInitial = engine->totalMomentum();
            sink.openProduction(target.dir);
            record();
            // A kill then costs at most one interval of production, never the equilibration.
            if (restarts.on()) restarts.take(engine, "production", true, cpu.seconds());
        }
        while (at.sample < plan.productionSamples && !interrupt.requested()) {
            cpu.start();
            engine->advanceTo(plan.productionTime(at.sample + 1, at.tStart));
            cpu.stop();
            ++at.sample;
            record();
            progress.report("production", at.sample, plan.productionSamples, engine->time());
            if (!interrupt.requested() && at.sample < plan.productionSamples &&
                restarts.dueAfterSample(at.sample))
                restarts.take(engine, "interval", true, cpu.seconds());
        }
        // A run.time_ps that is no whole number of samples: on to it, unsampled.
        if (plan.unsampledTail && !interrupt.requested()) {
            cpu.start();
            engine->advanceTo(plan.productionEnd(at.tStart));
            cpu.stop();
        }
    });
    const bool stopped = interrupt.requested(); // by a signal, before the run's end
    if (stopped) {
        run.interruptedBy = interrupt.signalName();
        run.interruptedIn = at.inProduction ? "production" : "equilibration";
        // The stop is kept as a restart point too: nothing since the last one is lost.
        if (restarts.on() && run.failure.empty())
            guarded([&] { restarts.take(engine, interrupt.signalName(), false, cpu.seconds()); });
    }
    (at.inProduction ? at.cpuProduction : at.cpuEquilibration) += cpu.seconds();
    return finishRun(scene, run, at, restarts.end(engine.get()), target.dir, interrupt, stopped,
                     restarts.on());
}

} // namespace terrace::cli
