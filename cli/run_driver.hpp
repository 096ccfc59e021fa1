#pragma once
// The run loop shared by both engines (STYLE.md items 8-9): sampling in physical time is decided
// here, outside the engines, on one uniform grid:
//   equilibration  advanceTo(t_k) and rescale v, ω to the scene temperature at every sample time
//   production     advanceTo(t_k), record energies and a Snapshot, write trajectory frames
// CPU time is measured around the engine calls only, so output and analysis do not count against
// either engine. A SIGINT stops the loop at the next sample; everything gathered so far is still
// written, and summary.json says "interrupted": true.
#include "analysis/conservation.hpp"
#include "analysis/correlations.hpp"
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

/// Drives `engine` through the scene's run and writes trajectory.xyz (optional), summary.json and
/// the correlation CSVs into `dir`. Returns the summary.
template <Engine E>
nlohmann::json drive(E& engine, const Scene& scene, const std::filesystem::path& dir,
                     TrajectoryLayout layout, bool quiet = false) {
    const RunPlan plan = planRun(scene);
    const double kT = scene.kT();
    const int n = engine.snapshot().size();
    const int dof = (layout == TrajectoryLayout::Sphere ? 3
                     : layout == TrajectoryLayout::Rod  ? 5
                                                        : 6) *
                        n -
                    3;
    ProgressReporter progress(quiet);
    CpuClock cpu;
    InterruptGuard interrupt;

    {
        std::ofstream initial(dir / "initial.xyz");
        writeXyzFrame(initial, engine.snapshot(), layout);
    }
    long k = 0; // sample index since the start of the run
    for (long e = 0; e < plan.equilibrationSamples && !interrupt.requested(); ++e) {
        cpu.start();
        engine.advanceTo(double(++k) * plan.sampleInterval);
        engine.rescaleTemperature(kT);
        cpu.stop();
        progress.report("equilibration", e + 1, plan.equilibrationSamples, engine.time());
    }
    const double equilibrationCpu = cpu.seconds();
    cpu.reset();

    std::ofstream trajectory;
    if (plan.trajectoryEvery > 0) trajectory.open(dir / "trajectory.xyz");
    const nlohmann::json statsBefore = engine.statistics();
    const Vec3 momentumInitial = engine.totalMomentum();
    const double tStart = engine.time();
    std::vector<double> tPs, total, potential, temperature;
    std::vector<Snapshot> samples;
    samples.reserve(plan.productionSamples + 1);
    auto record = [&] {
        const double u = engine.potentialEnergy(), kin = engine.kineticEnergy();
        tPs.push_back(units::toPs(engine.time() - tStart));
        total.push_back(u + kin);
        potential.push_back(u);
        temperature.push_back(units::kelvin(2.0 * kin / dof));
        samples.push_back(engine.snapshot());
        const long index = long(samples.size()) - 1;
        if (plan.trajectoryEvery > 0 && index % plan.trajectoryEvery == 0) {
            writeXyzFrame(trajectory, samples.back(), layout);
            trajectory.flush();
        }
    };
    record();
    for (long s = 0; s < plan.productionSamples && !interrupt.requested(); ++s) {
        cpu.start();
        engine.advanceTo(double(++k) * plan.sampleInterval);
        cpu.stop();
        record();
        progress.report("production", s + 1, plan.productionSamples, engine.time());
    }

    nlohmann::json summary;
    summary["engine"] = scene.engine;
    summary["scene"] = scene.name;
    summary["n_bodies"] = n;
    summary["interrupted"] = interrupt.requested();
    const double simulatedPs = units::toPs(engine.time() - tStart);
    summary["simulated_ps"] = simulatedPs;
    summary["sample_fs"] = units::toFs(plan.sampleInterval);
    summary["samples"] = samples.size();
    summary["cpu_seconds"] = cpu.seconds();
    summary["cpu_seconds_equilibration"] = equilibrationCpu;
    summary["cpu_seconds_per_ps"] = simulatedPs > 0 ? cpu.seconds() / simulatedPs : 0.0;
    double tMean = 0.0;
    for (double x : temperature)
        tMean += x / temperature.size();
    summary["temperature_K"] = tMean;
    summary["temperature_target_K"] = units::kelvin(kT);
    const auto es = analysis::energyStats(tPs, total, potential);
    summary["energy"] = {{"initial", es.initial},
                         {"final", es.final},
                         {"mean", es.mean},
                         {"std", es.std},
                         {"max_abs_dev", es.maxAbsDev},
                         {"rel_fluct", es.relFluct},
                         {"drift_per_ps", es.driftPerPs},
                         {"units", "kJ/mol"}};
    double uMean = 0.0, uVar = 0.0;
    for (double x : potential)
        uMean += x / potential.size();
    for (double x : potential)
        uVar += (x - uMean) * (x - uMean) / potential.size();
    summary["potential_energy_mean"] = uMean;
    summary["potential_energy_std"] = std::sqrt(uVar);
    // The paper's "relative fluctuations of the total energy to the potential energy", read as
    // the ratio of the two standard deviations; rel_fluct above divides by |<U>| instead.
    summary["energy"]["fluct_ratio_to_U"] = uVar > 0.0 ? es.std / std::sqrt(uVar) : 0.0;
    summary["momentum"] = {{"initial", vec3Json(momentumInitial / units::psPerTimeUnit)},
                           {"final", vec3Json(engine.totalMomentum() / units::psPerTimeUnit)},
                           {"units", "g/mol A/ps"}};
    addEngineStatistics(summary, statsBefore, engine.statistics(), simulatedPs);
    summary["provenance"] = provenance(scene);
    if (samples.size() >= 4) summary["analysis"] = analysis::writeCorrelations(samples, dir);
    std::ofstream(dir / "summary.json") << summary.dump(2) << '\n';
    return summary;
}

} // namespace terrace::cli
