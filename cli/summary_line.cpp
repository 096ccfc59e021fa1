#include "cli/summary_line.hpp"
#include "core/format_text.hpp"
#include <cmath>
#include <limits>

namespace terrace::cli {

using nlohmann::json;

namespace {

/// A number, or NaN for a null (an error bar from a single block) or an absent one.
double number(const json& j, const char* key) {
    return j.contains(key) && j[key].is_number() ? j[key].get<double>()
                                                 : std::numeric_limits<double>::quiet_NaN();
}

/// The relative fluctuation of E over |⟨U⟩| (the paper's measure), or that there is none: a run
/// whose U is 0 throughout (hard spheres) has no ⟨U⟩ to measure it by (summary.json: null).
std::string relativeFluctuation(double x) {
    return std::isfinite(x) ? formatText("%.3g", x) : std::string("undefined (<U> = 0)");
}

std::string realLines(const json& s) {
    std::string text;
    const double n = s["n_bodies"].get<double>();
    if (s.contains("energy")) {
        const double u = number(s, "potential_energy_mean");
        text += formatText("  T = %.1f K (target %.1f K), <U>/N = %.4f kJ/mol (<U> = %.4f kJ/mol), "
                           "energy rel. fluctuation %s, drift %.3g kJ/mol/ps\n",
                           number(s, "temperature_K"), number(s, "temperature_target_K"), u / n, u,
                           relativeFluctuation(number(s["energy"], "rel_fluct")).c_str(),
                           number(s["energy"], "drift_per_ps"));
    }
    if (s.contains("pressure") && s["pressure"].contains("mean_bar")) {
        const auto& p = s["pressure"];
        text += formatText("  P = %.4g ± %.2g bar (P* = %.4g ± %.2g)\n", number(p, "mean_bar"),
                           number(p, "error_bar"), number(p, "mean_reduced"),
                           number(p, "error_reduced"));
    }
    if (s.contains("collisions_per_ps"))
        text +=
            formatText("  %.4g collisions/ps, %.4g collisions per CPU s (%.4g events per CPU s "
                       "with cell, relist and virtual ones)\n",
                       number(s, "collisions_per_ps"), s.value("collisions_per_cpu_second", 0.0),
                       s.value("all_events_per_cpu_second", 0.0));
    return text;
}

std::string reducedLines(const json& s) {
    const json& r = s["reduced"];
    std::string text;
    const double n = s["n_bodies"].get<double>();
    if (s.contains("energy")) {
        const double u = number(r, "potential_energy_per_body");
        text += formatText("  T* = %.4g (target %.4g), U/N = %.4f ε (U = %.4g ε), energy rel. "
                           "fluctuation %s, drift %.3g ε/τ per body\n",
                           number(r, "temperature"), number(r, "temperature_target"), u, u * n,
                           relativeFluctuation(number(r, "energy_rel_fluct")).c_str(),
                           number(r, "energy_drift_per_tau_per_body"));
    }
    if (r.contains("pressure"))
        text +=
            formatText("  P* = %.4g ± %.2g\n", number(r, "pressure"), number(r, "pressure_err"));
    if (r.contains("collisions_per_tau"))
        text +=
            formatText("  %.4g collisions/τ, %.4g collisions per CPU s (%.4g events per CPU s "
                       "with cell, relist and virtual ones)\n",
                       number(r, "collisions_per_tau"), s.value("collisions_per_cpu_second", 0.0),
                       s.value("all_events_per_cpu_second", 0.0));
    return text;
}

} // namespace

std::string runSummaryText(const std::string& name, const json& s,
                           const std::filesystem::path& out) {
    const bool reduced = s.contains("reduced");
    std::string text;
    if (reduced)
        text = formatText("%s: %s, N = %d, %.4g τ (τ = %.4g fs) simulated in %.2f CPU s (%.4g CPU "
                          "s/τ)\n",
                          name.c_str(), s["engine"].get<std::string>().c_str(),
                          s["n_bodies"].get<int>(), number(s["reduced"], "simulated_tau"),
                          number(s["reduced"]["scale"], "tau_fs"), number(s, "cpu_seconds"),
                          number(s["reduced"], "cpu_seconds_per_tau"));
    else
        text = formatText("%s: %s, N = %d, %.3f ps simulated in %.2f CPU s (%.3f CPU s/ps)\n",
                          name.c_str(), s["engine"].get<std::string>().c_str(),
                          s["n_bodies"].get<int>(), number(s, "simulated_ps"),
                          number(s, "cpu_seconds"), number(s, "cpu_seconds_per_ps"));
    text += reduced ? reducedLines(s) : realLines(s);
    if (s.value("interrupted", false))
        text += formatText("  interrupted by %s during %s\n",
                           s.value("interrupted_by", std::string("a signal")).c_str(),
                           s.value("interrupted_in", std::string("the run")).c_str());
    return text + formatText("  output in %s/\n", out.c_str());
}

} // namespace terrace::cli
