#include "cli/run_driver.hpp"
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
        "steps",    "neighbour_rebuilds", "pair_evaluations",
        "cleanups", "stale_events",       "search_evaluations"};
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

} // namespace terrace::cli
