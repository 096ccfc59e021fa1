#include "cli/heat_bath_summary.hpp"
#include <cmath>
#include <cstdio>

namespace terrace::cli {

namespace {

/// As the total energy's under NVE (cli/run_driver.cpp): beyond this fraction of ⟨K⟩ the
/// integration, not the bath, is at fault.
constexpr double effectiveWanderWarning = 0.01;

nlohmann::json orNull(double x) {
    return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json();
}

} // namespace

nlohmann::json heatBathSummary(const Scene& scene, const SampleStatistics& samples, int dof,
                               nlohmann::json& warnings) {
    const auto& h = scene.run.heat_bath;
    nlohmann::json j{{"kind", h.kind}};
    if (h.kind == "andersen") j["rate_per_ps"] = h.rate_per_ps;
    if (h.kind == "csvr") j["tau_fs"] = h.tau_fs;
    j["degrees_of_freedom"] = dof;
    if (samples.count() == 0) return j;
    j["energy_removed"] = samples.bathEnergyRemoved();
    const auto es = samples.effectiveEnergy();
    j["effective_energy"] = {{"initial", es.initial},
                             {"final", es.final},
                             {"std", es.std},
                             {"max_abs_dev", es.maxAbsDev},
                             {"drift_per_ps", es.driftPerPs},
                             {"units", "kJ/mol"}};
    const auto c = samples.canonicalKinetic();
    j["kinetic_energy"] = {{"mean", c.mean.mean},
                           {"mean_err", orNull(c.mean.err)},
                           {"canonical_mean", c.canonicalMean},
                           {"mean_deviation_in_errors", orNull(c.meanDeviation())},
                           {"variance", c.variance.mean},
                           {"variance_err", orNull(c.variance.err)},
                           {"canonical_variance", c.canonicalVariance},
                           {"variance_deviation_in_errors", orNull(c.varianceDeviation())},
                           {"blocks", c.mean.samples},
                           {"units", "kJ/mol, (kJ/mol)^2"}};
    if (es.maxAbsDev > effectiveWanderWarning * c.mean.mean) {
        char text[256];
        std::snprintf(text, sizeof text,
                      "effective energy (H + the energy the heat bath removed) wandered by %.3g "
                      "kJ/mol, %.2g%% of the kinetic energy: the integration's error at this time "
                      "step, which the bath's draws turn from a fluctuation of H into a drift",
                      es.maxAbsDev, 100.0 * es.maxAbsDev / c.mean.mean);
        warnings.push_back(text);
        std::fprintf(stderr, "terrace: warning: %s\n", text);
    }
    return j;
}

} // namespace terrace::cli
