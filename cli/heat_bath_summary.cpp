#include "cli/heat_bath_summary.hpp"
#include "analysis/canonical_kinetic.hpp"
#include "analysis/conservation.hpp"
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

nlohmann::json heatBathSummary(const Scene& scene, const RunRecord& run, nlohmann::json& warnings) {
    const auto& h = scene.run.heat_bath;
    nlohmann::json j{{"kind", h.kind}};
    if (h.kind == "andersen") j["rate_per_ps"] = h.rate_per_ps;
    if (h.kind == "csvr") j["tau_fs"] = h.tau_fs;
    j["degrees_of_freedom"] = run.dof;
    if (run.records.empty()) return j;
    std::vector<double> t, effective, potential, kinetic;
    for (const auto& r : run.records) {
        t.push_back(r.tPs);
        effective.push_back(r.total + r.bath);
        potential.push_back(r.potential);
        kinetic.push_back(r.kinetic);
    }
    j["energy_removed"] = run.records.back().bath - run.records.front().bath;
    const auto es = analysis::energyStats(t, effective, potential);
    j["effective_energy"] = {{"initial", es.initial},
                             {"final", es.final},
                             {"std", es.std},
                             {"max_abs_dev", es.maxAbsDev},
                             {"drift_per_ps", es.driftPerPs},
                             {"units", "kJ/mol"}};
    const int blocks = std::max(2, std::min<int>(scene.analysis.blocks, int(kinetic.size())));
    const auto c = analysis::canonicalKinetic(kinetic, run.dof, run.kT, blocks);
    j["kinetic_energy"] = {{"mean", c.mean.mean},
                           {"mean_err", orNull(c.mean.err)},
                           {"canonical_mean", c.canonicalMean},
                           {"mean_deviation_in_errors", orNull(c.meanDeviation())},
                           {"variance", c.variance.mean},
                           {"variance_err", orNull(c.variance.err)},
                           {"canonical_variance", c.canonicalVariance},
                           {"variance_deviation_in_errors", orNull(c.varianceDeviation())},
                           {"blocks", blocks},
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
