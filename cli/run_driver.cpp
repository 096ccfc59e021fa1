#include "cli/run_driver.hpp"
#include "analysis/conservation.hpp"
#include "analysis/correlations.hpp"
#include <cstdio>
#include <set>

namespace terrace::cli {

RunPlan planRun(const Scene& scene) {
    RunPlan plan;
    double interval = units::fromFs(scene.run.sample_fs);
    if (scene.engine == "smd") {
        const double dt = units::fromFs(scene.smd.dt_fs);
        interval = std::max(1.0, std::round(interval / dt)) * dt;
    }
    plan.sampleInterval = interval;
    // The small allowance keeps a run length that is an exact multiple of the interval in
    // decimal from losing its last sample to binary round-off.
    plan.equilibrationSamples =
        long(std::floor(units::fromPs(scene.run.equilibrate_ps) / interval + 1e-9));
    plan.productionSamples = long(std::floor(units::fromPs(scene.run.time_ps) / interval + 1e-9));
    if (scene.output.trajectory_every_fs > 0.0)
        plan.trajectoryEvery = std::max(
            1L, long(std::llround(units::fromFs(scene.output.trajectory_every_fs) / interval)));
    return plan;
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

nlohmann::json difference(const nlohmann::json& before, const nlohmann::json& after,
                          const std::string& path = "") {
    if (after.is_object()) {
        nlohmann::json out = nlohmann::json::object();
        for (const auto& [key, value] : after.items()) {
            const std::string sub = path.empty() ? key : path + "." + key;
            out[key] = before.is_object() && before.contains(key)
                           ? difference(before[key], value, sub)
                           : value;
        }
        return out;
    }
    if (isCounter(path) && after.is_number_integer() && before.is_number_integer())
        return after.get<long long>() - before.get<long long>();
    return after;
}

} // namespace

void addEngineStatistics(nlohmann::json& summary, const nlohmann::json& before,
                         const nlohmann::json& after, double simulatedPs) {
    const nlohmann::json production = difference(before, after);
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

} // namespace

nlohmann::json writeSummary(const Scene& scene, const RunRecord& run,
                            const std::filesystem::path& dir) {
    nlohmann::json summary;
    summary["engine"] = scene.engine;
    summary["scene"] = scene.name;
    summary["n_bodies"] = run.bodies;
    summary["interrupted"] = run.interrupted;
    if (!run.failure.empty()) summary["error"] = run.failure;
    summary["simulated_ps"] = run.simulatedPs;
    summary["sample_fs"] = units::toFs(run.sampleInterval);
    summary["samples"] = run.samples.size();
    summary["cpu_seconds"] = run.cpuSeconds;
    summary["cpu_seconds_equilibration"] = run.cpuEquilibration;
    summary["cpu_seconds_per_ps"] = run.simulatedPs > 0 ? run.cpuSeconds / run.simulatedPs : 0.0;
    summary["temperature_target_K"] = units::kelvin(run.kT);
    summary["warnings"] = nlohmann::json::array();
    addEnergy(summary, run);
    summary["momentum"] = {{"initial", vec3Json(run.momentumInitial / units::psPerTimeUnit)},
                           {"final", vec3Json(run.momentumFinal / units::psPerTimeUnit)},
                           {"units", "g/mol A/ps"}};
    addEngineStatistics(summary, run.statsBefore, run.statsAfter, run.simulatedPs);
    summary["provenance"] = provenance(scene);
    if (run.samples.size() >= 4) {
        try {
            summary["analysis"] = analysis::writeCorrelations(run.samples, dir);
        } catch (const std::exception& e) { // the run's own numbers stay worth keeping
            summary["analysis"] = {{"error", e.what()}};
            std::fprintf(stderr, "terrace: warning: analysis failed: %s\n", e.what());
        }
    }
    std::ofstream(dir / "summary.json") << summary.dump(2) << '\n';
    return summary;
}

} // namespace terrace::cli
