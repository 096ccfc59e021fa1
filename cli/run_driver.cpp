#include "cli/run_driver.hpp"
#include "analysis/cancellation.hpp"
#include "analysis/conservation.hpp"
#include "analysis/correlations.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

namespace terrace::cli {

RunPlan planRun(const Scene& scene) {
    RunPlan plan;
    // On SMD's grid an interval is a whole number of steps (the scene validation refuses any
    // other); rounding the ratio only removes its binary round-off.
    auto onGrid = [&](double fs) {
        const double interval = units::fromFs(fs);
        if (scene.engine != "smd") return interval;
        const double dt = units::fromFs(scene.smd.dt_fs);
        return std::max(1.0, std::round(interval / dt)) * dt;
    };
    plan.sampleInterval = onGrid(scene.run.sample_fs);
    plan.thermostatInterval = onGrid(scene.run.thermostat_fs);
    // The small allowance keeps a run length that is an exact multiple of the interval in
    // decimal from losing its last interval to binary round-off.
    plan.equilibrationTicks =
        long(std::floor(units::fromPs(scene.run.equilibrate_ps) / plan.thermostatInterval + 1e-9));
    plan.productionSamples =
        long(std::floor(units::fromPs(scene.run.time_ps) / plan.sampleInterval + 1e-9));
    auto inSamples = [&](double interval) {
        return interval > 0.0 ? std::max(1L, long(std::llround(interval / plan.sampleInterval)))
                              : 0L;
    };
    plan.trajectoryEvery = inSamples(units::fromFs(scene.output.trajectory_every_fs));
    plan.restartEvery = inSamples(units::fromPs(scene.output.restart_every_ps));
    if (plan.restartEvery > 0)
        plan.restartEveryTicks =
            std::max(1L, long(std::llround(units::fromPs(scene.output.restart_every_ps) /
                                           plan.thermostatInterval)));
    return plan;
}

double RunPlan::productionTime(long s, double tStart) const {
    if (thermostatInterval == sampleInterval)
        return double(equilibrationTicks + s) * sampleInterval;
    return tStart + double(s) * sampleInterval;
}

double storedSampleBytes(const Scene& scene, int rotationalDof) {
    const RunPlan plan = planRun(scene);
    const double n = scene.state.particles.empty() ? double(scene.state.n)
                                                   : double(scene.state.particles.size());
    // position, velocity, axis, ω and a top's quaternion per body, the snapshot and its energies
    const double perBody = 4.0 * sizeof(Vec3) + (rotationalDof == 3 ? sizeof(Quat) : 0.0);
    return (double(plan.productionSamples) + 1.0) * (n * perBody + sizeof(Snapshot) + 32.0);
}

nlohmann::json vec3Json(const Vec3& v) {
    return nlohmann::json::array({v.x(), v.y(), v.z()});
}

namespace {

/// Statistics that count things since the engine was built; the run reports their increase
/// over production. Everything else (sizes, settings, maxima) is reported as it stands at the end.
bool isCounter(const std::string& path) {
    static const std::set<std::string> counters = {
        "steps",        "neighbour_rebuilds", "pair_evaluations",   "cleanups",
        "stale_events", "stale_in_agendas",   "search_evaluations", "searches_screened"};
    return path.rfind("events.", 0) == 0 || counters.count(path) > 0;
}

void addStretch(nlohmann::json& acc, const nlohmann::json& before, const nlohmann::json& after,
                const std::string& path) {
    if (after.is_object()) {
        if (!acc.is_object()) acc = nlohmann::json::object();
        static const nlohmann::json none;
        for (const auto& [key, value] : after.items()) {
            const std::string sub = path.empty() ? key : path + "." + key;
            addStretch(acc[key], before.is_object() && before.contains(key) ? before[key] : none,
                       value, sub);
        }
        return;
    }
    if (isCounter(path) && after.is_number_integer() && before.is_number_integer()) {
        const long long increase = after.get<long long>() - before.get<long long>();
        acc = (acc.is_number_integer() ? acc.get<long long>() : 0LL) + increase;
        return;
    }
    acc = after;
}

} // namespace

void accumulateStatistics(nlohmann::json& production, const nlohmann::json& start,
                          const nlohmann::json& end) {
    addStretch(production, start, end, "");
}

void addEngineStatistics(nlohmann::json& summary, const nlohmann::json& production,
                         double simulatedPs) {
    for (const auto& [key, value] : production.items())
        summary[key] = value;
    if (simulatedPs <= 0.0) return;
    if (production.contains("events")) {
        const auto& ev = production["events"];
        const double collisions =
            ev.value("up", 0.0) + ev.value("down", 0.0) + ev.value("reflect", 0.0);
        summary["collisions_per_ps"] = collisions / simulatedPs;
        summary["events_per_ps"] = ev.value("total", 0.0) / simulatedPs;
        const double cpu = summary.value("cpu_seconds", 0.0);
        if (cpu > 0.0) summary["events_per_cpu_second"] = ev.value("total", 0.0) / cpu;
    }
    if (production.contains("steps"))
        summary["steps_per_ps"] = production["steps"].get<double>() / simulatedPs;
}

namespace {

double mean(const std::vector<double>& x) {
    double m = 0.0;
    for (double v : x)
        m += v / double(x.size());
    return x.empty() ? 0.0 : m;
}

double standardDeviation(const std::vector<double>& x) {
    const double m = mean(x);
    double var = 0.0;
    for (double v : x)
        var += (v - m) * (v - m) / double(x.size());
    return std::sqrt(var);
}

/// Total energy that wanders by more than this fraction of the kinetic energy is no longer a
/// conserving integration (a healthy SMD run at 1.8 fs stays below 1e-3 of it).
constexpr double energyWanderWarning = 0.01;

void addEnergy(nlohmann::json& summary, const RunRecord& run) {
    if (run.tPs.empty()) return;
    const double keMean = mean(run.kinetic);
    summary["temperature_K"] = units::kelvin(2.0 * keMean / run.dof);
    const auto es = analysis::energyStats(run.tPs, run.total, run.potential);
    const double uStd = standardDeviation(run.potential);
    summary["energy"] = {{"initial", es.initial},
                         {"final", es.final},
                         {"mean", es.mean},
                         {"std", es.std},
                         {"max_abs_dev", es.maxAbsDev},
                         {"rel_fluct", es.relFluct},
                         // The paper's "relative fluctuations of the total energy to the potential
                         // energy", read as the ratio of the two standard deviations.
                         {"fluct_ratio_to_U", uStd > 0.0 ? es.std / uStd : 0.0},
                         {"drift_per_ps", es.driftPerPs},
                         {"units", "kJ/mol"}};
    summary["potential_energy_mean"] = mean(run.potential);
    summary["potential_energy_std"] = uStd;
    if (es.maxAbsDev > energyWanderWarning * keMean) {
        char text[256];
        std::snprintf(text, sizeof text,
                      "total energy wandered by %.3g kJ/mol, %.2g%% of the kinetic energy: the "
                      "integration does not conserve energy at this time step",
                      es.maxAbsDev, 100.0 * es.maxAbsDev / keMean);
        summary["warnings"].push_back(text);
        std::fprintf(stderr, "terrace: warning: %s\n", text);
    }
}

nlohmann::json summaryOf(const Scene& scene, const RunRecord& run) {
    nlohmann::json summary;
    summary["engine"] = scene.engine;
    summary["scene"] = scene.name;
    summary["n_bodies"] = run.bodies;
    summary["interrupted"] = !run.interruptedBy.empty();
    if (!run.interruptedBy.empty()) {
        summary["interrupted_by"] = run.interruptedBy;
        summary["interrupted_in"] = run.interruptedIn;
    }
    if (!run.failure.empty()) summary["error"] = run.failure;
    summary["simulated_ps"] = run.simulatedPs;
    summary["sample_fs"] = units::toFs(run.sampleInterval);
    summary["samples"] = run.samples.size();
    summary["cpu_seconds"] = run.cpuSeconds;
    summary["cpu_seconds_equilibration"] = run.cpuEquilibration;
    summary["cpu_seconds_per_ps"] = run.simulatedPs > 0 ? run.cpuSeconds / run.simulatedPs : 0.0;
    summary["temperature_target_K"] = units::kelvin(run.kT);
    summary["warnings"] = run.warnings;
    if (run.restartEveryPs > 0.0)
        summary["restarts"] = {{"every_ps", run.restartEveryPs},
                               {"written", run.restartsWritten},
                               {"continued", run.continuations}};
    addEnergy(summary, run);
    summary["momentum"] = {{"initial", vec3Json(run.momentumInitial / units::psPerTimeUnit)},
                           {"final", vec3Json(run.momentumFinal / units::psPerTimeUnit)},
                           {"units", "g/mol A/ps"}};
    addEngineStatistics(summary, run.production, run.simulatedPs);
    return summary;
}

} // namespace

nlohmann::json writeSummaryAndAnalysis(const Scene& scene, RunRecord& run,
                                       const std::filesystem::path& dir,
                                       const InterruptGuard& interrupt) {
    const int signalsBefore = interrupt.count();
    nlohmann::json summary = summaryOf(scene, run);
    summary["provenance"] = provenance(scene);
    const bool analyse = run.samples.size() >= 4;
    // Written before the analysis, so that a run killed during a long analysis keeps it.
    if (analyse) summary["analysis"] = "not finished: the process ended during the analysis";
    writeFileAtomically(dir / "summary.json", summary.dump(2) + "\n");
    if (!analyse) return summary;
    try {
        // A signal during the analysis cancels it, and so does a second one at any time (the
        // first only stopped the run).
        const int tolerated = std::min(signalsBefore, 1);
        const analysis::ScopedCancellation hook([&] { return interrupt.count() > tolerated; });
        summary["analysis"] = analysis::writeCorrelations(run.samples, dir);
    } catch (const analysis::Cancelled&) {
        summary["analysis"] = {{"error", "cancelled by a signal before it finished"}};
        if (run.interruptedBy.empty()) {
            run.interruptedBy = interrupt.signalName();
            run.interruptedIn = "analysis";
            summary["interrupted"] = true;
            summary["interrupted_by"] = run.interruptedBy;
            summary["interrupted_in"] = run.interruptedIn;
        }
    } catch (const IoError&) {
        throw; // a failed write is an error of the run, not of the analysis
    } catch (const std::exception& e) { // the run's own numbers stay worth keeping
        summary["analysis"] = {{"error", e.what()}};
        std::fprintf(stderr, "terrace: warning: analysis failed: %s\n", e.what());
    }
    writeFileAtomically(dir / "summary.json", summary.dump(2) + "\n");
    return summary;
}

} // namespace terrace::cli
