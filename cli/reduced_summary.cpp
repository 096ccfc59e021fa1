#include "cli/reduced_summary.hpp"
#include <optional>
#include <string>
#include <utility>

namespace terrace::cli {

using nlohmann::json;

namespace {

/// The number at `path` in `j`, if there is one (a null, a missing key or a string is none).
std::optional<double> numberAt(const json& j, std::initializer_list<const char*> path) {
    const json* at = &j;
    for (const char* key : path) {
        if (!at->is_object() || !at->contains(key)) return std::nullopt;
        at = &(*at)[key];
    }
    if (!at->is_number()) return std::nullopt;
    return at->get<double>();
}

/// Sets out[key] to f(the number at path): null when the summary holds null there, absent when
/// it holds nothing.
template <class F>
void put(json& out, const char* key, const json& summary, std::initializer_list<const char*> path,
         const F& f) {
    const json* at = &summary;
    for (const char* k : path) {
        if (!at->is_object() || !at->contains(k)) return;
        at = &(*at)[k];
    }
    if (at->is_null())
        out[key] = nullptr;
    else if (at->is_number())
        out[key] = f(at->get<double>());
}

} // namespace

json reducedSummary(const json& summary, const UnitSystem& u) {
    const double n = summary.value("n_bodies", 1);
    json r;
    r["scale"] = {{"sigma_angstrom", u.sigma()},
                  {"epsilon_kj_per_mol", u.epsilon()},
                  {"mass_g_per_mol", u.mass()},
                  {"tau_fs", u.tauFs()}};
    const auto time = [&](double ps) { return u.time(ps); };
    const auto perBody = [&](double e) { return u.energy(e) / n; };
    const auto temperature = [&](double k) { return u.temperatureOfKelvin(k); };
    const auto same = [](double x) { return x; };
    put(r, "simulated_tau", summary, {"simulated_ps"}, time);
    put(r, "sample_tau", summary, {"sample_fs"}, [&](double fs) { return u.timeOfFs(fs); });
    const auto simulated = numberAt(summary, {"simulated_ps"});
    const auto cpu = numberAt(summary, {"cpu_seconds"});
    if (simulated && cpu)
        r["cpu_seconds_per_tau"] = *simulated > 0 ? *cpu / u.time(*simulated) : 0.0;
    put(r, "temperature", summary, {"temperature_K"}, temperature);
    put(r, "temperature_err", summary, {"temperature_err_K"}, temperature);
    put(r, "temperature_target", summary, {"temperature_target_K"}, temperature);
    put(r, "potential_energy_per_body", summary, {"potential_energy_mean"}, perBody);
    put(r, "potential_energy_per_body_err", summary, {"potential_energy_err"}, perBody);
    put(r, "potential_energy_per_body_std", summary, {"potential_energy_std"}, perBody);
    put(r, "total_energy_per_body", summary, {"energy", "mean"}, perBody);
    // A drift per ps is one per τ over the number of ps in τ.
    put(r, "energy_drift_per_tau_per_body", summary, {"energy", "drift_per_ps"},
        [&](double d) { return perBody(d) * u.tauFs() / 1000.0; });
    put(r, "energy_rel_fluct", summary, {"energy", "rel_fluct"}, same);
    put(r, "pressure", summary, {"pressure", "mean_reduced"}, same);
    put(r, "pressure_err", summary, {"pressure", "error_reduced"}, same);
    if (summary.contains("configurational")) {
        json c;
        put(c, "potential_energy_per_body", summary, {"configurational", "potential_energy_mean"},
            perBody);
        put(c, "potential_energy_per_body_err", summary,
            {"configurational", "potential_energy_err"}, perBody);
        put(c, "pressure", summary, {"configurational", "pressure_reduced"}, same);
        put(c, "pressure_err", summary, {"configurational", "pressure_err_reduced"}, same);
        if (!c.is_null()) r["configurational"] = c;
    }
    if (summary.contains("analysis") && summary["analysis"].contains("diffusion")) {
        json d;
        const auto diffusion = [&](double x) { return u.diffusion(x); };
        put(d, "einstein", summary, {"analysis", "diffusion", "einstein_angstrom2_per_ps"},
            diffusion);
        put(d, "einstein_err", summary, {"analysis", "diffusion", "einstein_err"}, diffusion);
        put(d, "green_kubo", summary, {"analysis", "diffusion", "green_kubo_angstrom2_per_ps"},
            diffusion);
        put(d, "green_kubo_err", summary, {"analysis", "diffusion", "green_kubo_err"}, diffusion);
        // A mixture's species, each as the total (run_analysis.hpp).
        if (summary["analysis"]["diffusion"].contains("species"))
            for (const auto& [name, entry] : summary["analysis"]["diffusion"]["species"].items()) {
                json e;
                constexpr std::pair<const char*, const char*> keys[] = {
                    {"einstein", "einstein_angstrom2_per_ps"},
                    {"einstein_err", "einstein_err"},
                    {"green_kubo", "green_kubo_angstrom2_per_ps"},
                    {"green_kubo_err", "green_kubo_err"}};
                for (const auto& [to, from] : keys)
                    put(e, to, entry, {from}, diffusion);
                d["species"][name] = e;
            }
        d["units"] = "sigma^2/tau";
        r["diffusion"] = d;
    }
    const auto rate = [&](double x) { return u.rate(x); };
    put(r, "collisions_per_tau", summary, {"collisions_per_ps"}, rate);
    put(r, "collisions_per_tau_err", summary, {"collisions_per_ps_err"}, rate);
    return r;
}

} // namespace terrace::cli
