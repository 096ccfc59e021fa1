#include "cli/heat_bath_summary.hpp"
#include <cmath>

namespace terrace::cli {

namespace {

nlohmann::json orNull(double x) {
    return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json();
}

} // namespace

nlohmann::json heatBathSummary(const Scene& scene, const SampleStatistics& samples, int dof) {
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
    return j;
}

} // namespace terrace::cli
