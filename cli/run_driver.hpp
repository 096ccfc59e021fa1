#pragma once
// The run loop shared by both engines (STYLE.md items 8-9): sampling in physical time is decided
// here, outside the engines, on one uniform grid:
//   equilibration  advanceTo(t_k) and rescale v, ω to the scene temperature at every sample time
//   production     advanceTo(t_k), record energies and a Snapshot, write trajectory frames
// CPU time is measured around the engine calls only, so output and analysis do not count against
// either engine. A SIGINT stops the loop at the next sample; everything gathered so far is still
// written, and summary.json says "interrupted": true.
#include "cli/cpu_clock.hpp"
#include "cli/interrupt.hpp"
#include "cli/provenance.hpp"
#include "core/engine.hpp"
#include "core/scene.hpp"
#include "core/units.hpp"
#include "core/xyz.hpp"
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

namespace terrace::cli {

struct RunPlan {
    double sampleInterval = 0.0; // time units
    long equilibrationSamples = 0;
    long productionSamples = 0;
    long trajectoryEvery = 0; // in samples; 0 = none
};

/// Sample times must be reachable by the engine: SMD moves in whole steps, so its interval is the
/// nearest whole number of steps (at least one).
RunPlan planRun(const Scene& scene);

nlohmann::json vec3Json(const Vec3& v);

/// Merges the engine's statistics into the summary: counters (events.*, steps, ...) as their
/// increase over production, everything else as its final value; adds
/// collisions_per_ps (DMD: up + down + reflect) and steps_per_ps (SMD) where those counters exist.
void addEngineStatistics(nlohmann::json& summary, const nlohmann::json& before,
                         const nlohmann::json& after, double simulatedPs);

/// What a run gathered, handed from the engine loop to the summary.
struct RunRecord {
    std::vector<double> tPs, total, potential, kinetic; // per production sample; kJ/mol
    std::vector<Snapshot> samples;
    Vec3 momentumInitial = Vec3::Zero(), momentumFinal = Vec3::Zero(); // internal units
    nlohmann::json statsBefore, statsAfter; // engine statistics around production
    double simulatedPs = 0.0, cpuSeconds = 0.0, cpuEquilibration = 0.0;
    double sampleInterval = 0.0, kT = 0.0;
    int bodies = 0, dof = 0;
    bool interrupted = false;
    std::string failure; // the engine's error, empty when the run went through
};

/// Builds summary.json from the record, runs the correlation analysis into dir and writes both.
nlohmann::json writeSummary(const Scene& scene, const RunRecord& run,
                            const std::filesystem::path& dir);

/// Drives `engine` through the scene's run and writes initial.xyz, trajectory.xyz (optional),
/// summary.json and the correlation CSVs into `dir`. Returns the summary; an engine failure is
/// raised again after everything gathered until then has been written.
template <Engine E>
nlohmann::json drive(E& engine, const Scene& scene, const std::filesystem::path& dir,
                     int rotationalDof, bool quiet = false) {
    const RunPlan plan = planRun(scene);
    RunRecord run;
    run.kT = scene.kT();
    run.sampleInterval = plan.sampleInterval;
    run.bodies = engine.snapshot().size();
    run.dof = degreesOfFreedom(rotationalDof, run.bodies);
    const TrajectoryLayout layout = layoutFor(rotationalDof);
    ProgressReporter progress(quiet);
    CpuClock cpu;
    InterruptGuard interrupt;
    {
        std::ofstream initial(dir / "initial.xyz");
        writeXyzFrame(initial, engine.snapshot(), layout);
    }
    // An engine that fails (an unstable time step, a stuck event cascade) ends the run; what was
    // gathered until then is still written, with the error in summary.json.
    auto guarded = [&](auto&& work) {
        if (!run.failure.empty()) return;
        try {
            work();
        } catch (const std::exception& e) {
            cpu.stop();
            run.failure = e.what();
        }
    };
    long k = 0; // sample index since the start of the run
    guarded([&] {
        for (long e = 0; e < plan.equilibrationSamples && !interrupt.requested(); ++e) {
            cpu.start();
            engine.advanceTo(double(++k) * plan.sampleInterval);
            engine.rescaleTemperature(run.kT);
            cpu.stop();
            progress.report("equilibration", e + 1, plan.equilibrationSamples, engine.time());
        }
    });
    run.cpuEquilibration = cpu.seconds();
    cpu.reset();

    std::ofstream trajectory;
    if (plan.trajectoryEvery > 0) trajectory.open(dir / "trajectory.xyz");
    run.statsBefore = engine.statistics();
    run.momentumInitial = engine.totalMomentum();
    const double tStart = engine.time();
    auto record = [&] {
        const double u = engine.potentialEnergy(), kin = engine.kineticEnergy();
        run.tPs.push_back(units::toPs(engine.time() - tStart));
        run.total.push_back(u + kin);
        run.potential.push_back(u);
        run.kinetic.push_back(kin);
        run.samples.push_back(engine.snapshot());
        const long index = long(run.samples.size()) - 1;
        if (plan.trajectoryEvery > 0 && index % plan.trajectoryEvery == 0) {
            writeXyzFrame(trajectory, run.samples.back(), layout);
            trajectory.flush();
        }
    };
    run.samples.reserve(plan.productionSamples + 1);
    guarded([&] {
        record();
        for (long s = 0; s < plan.productionSamples && !interrupt.requested(); ++s) {
            cpu.start();
            engine.advanceTo(double(++k) * plan.sampleInterval);
            cpu.stop();
            record();
            progress.report("production", s + 1, plan.productionSamples, engine.time());
        }
    });
    run.interrupted = interrupt.requested();
    run.simulatedPs = units::toPs(engine.time() - tStart);
    run.cpuSeconds = cpu.seconds();
    run.momentumFinal = engine.totalMomentum();
    run.statsAfter = engine.statistics();
    auto summary = writeSummary(scene, run, dir);
    if (!run.failure.empty())
        throw std::runtime_error(run.failure + " (output so far in " + dir.string() + ")");
    return summary;
}

} // namespace terrace::cli
