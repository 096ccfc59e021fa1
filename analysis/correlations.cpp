#include "analysis/correlations.hpp"
#include "analysis/csv.hpp"
#include "analysis/dynamic_correlations.hpp"
#include "analysis/rdf.hpp"
#include "core/output_file.hpp"
#include "core/units.hpp"
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace terrace::analysis {

namespace {

/// g(r) far from a body should be 1: average over the outer fifth of the range, r ∈ [0.4, 0.5] L.
constexpr double largeRFraction = 0.4;

} // namespace

namespace detail {

nlohmann::json rdfSummary(const RadialDistribution& rdf, double from) {
    double sum = 0.0, var = 0.0;
    int count = 0;
    for (std::size_t k = 0; k < rdf.r.size(); ++k)
        if (rdf.r[k] >= from) sum += rdf.g[k], var += rdf.err[k] * rdf.err[k], ++count;
    nlohmann::json j{{"bin_angstrom", rdf.binWidth}, {"bins", rdf.r.size()}};
    if (count > 0) {
        // Bins treated as independent for the error of their mean (neighbouring bins of g(r)
        // share frames, so this is a rough guide, not a rigorous error).
        j["g_large_r"] = sum / count;
        j["g_large_r_err"] = std::sqrt(var) / count;
        j["large_r_from_angstrom"] = from;
    }
    return j;
}

void writeCurveFiles(const std::filesystem::path& dir, const RadialDistribution& rdf,
                     const SampledCurve& vacf, const OrientationalCorrelation* oacf,
                     const SampledCurve& msd) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) throwIoError("create the directory", dir, ec.value());
    writeCsv(dir / "rdf.csv", {{"r_angstrom", "g", "err"}, {rdf.r, rdf.g, rdf.err}});
    writeCsv(dir / "vacf.csv", {{"t_ps", "c", "err"}, {vacf.tPs, vacf.value, vacf.err}});
    if (oacf)
        writeCsv(dir / "oacf.csv",
                 {{"t_ps", "c1", "c1_err", "c2", "c2_err"},
                  {oacf->c1.tPs, oacf->c1.value, oacf->c1.err, oacf->c2.value, oacf->c2.err}});
    else if (std::filesystem::remove(dir / "oacf.csv", ec); ec)
        throwIoError("remove", dir / "oacf.csv", ec.value());
    writeCsv(dir / "msd.csv", {{"t_ps", "msd_angstrom2", "err"}, {msd.tPs, msd.value, msd.err}});
}

double greenKuboDiffusion(const std::vector<double>& tPs, const std::vector<double>& c,
                          double meanSquareVelocity) {
    double integral = 0.0; // ∫ c dt in ps
    for (std::size_t k = 1; k < tPs.size(); ++k)
        integral += 0.5 * (c[k] + c[k - 1]) * (tPs[k] - tPs[k - 1]);
    const double v2 = meanSquareVelocity / (units::psPerTimeUnit * units::psPerTimeUnit); // Å²/ps²
    return v2 * integral / 3.0;
}

} // namespace detail

nlohmann::json writeCorrelations(const std::vector<Snapshot>& samples,
                                 const std::filesystem::path& dir, const Options& options) {
    const double dtPs = sampleIntervalPs(samples);
    const int t = static_cast<int>(samples.size());
    if (options.blocks < 2)
        throw std::invalid_argument("writeCorrelations: need at least 2 blocks for error bars");
    if (t < 4) throw std::invalid_argument("writeCorrelations: need at least 4 samples");
    // A short run still gets its files: fewer blocks (at least two samples each), recorded in
    // the summary, rather than no analysis at the end of a finished run.
    const int blocks = std::min(options.blocks, t / 2);
    const int n = samples.front().size();
    if (n < 2) throw std::invalid_argument("writeCorrelations: need at least 2 bodies");
    const int msdBlocks = std::min(blocks, n); // MSD blocks are groups of bodies
    if (!(options.rdfBinAngstrom > 0.0))
        throw std::invalid_argument("writeCorrelations: rdf bin must be > 0 Å");
    if (options.maxLagPs < 0.0 || !std::isfinite(options.maxLagPs))
        throw std::invalid_argument("writeCorrelations: maxLagPs must be ≥ 0 (0: half the span)");
    const int maxLag = lagFor(options.maxLagPs, dtPs, t, blocks);

    // Everything is computed before anything is written: bad samples leave no files half-way.
    const RadialDistribution rdf = radialDistribution(samples, options.rdfBinAngstrom, blocks);
    double v2 = 0.0;
    const SampledCurve vacf = velocityAutocorrelation(samples, maxLag, blocks, &v2);
    const bool rotating = axesRotate(samples);
    OrientationalCorrelation oacf;
    if (rotating) oacf = orientationalAutocorrelation(samples, maxLag, blocks);
    const SampledCurve msd = meanSquaredDisplacement(samples, maxLag, msdBlocks);
    const Diffusion d = diffusionFromMsd(msd);

    detail::writeCurveFiles(dir, rdf, vacf, rotating ? &oacf : nullptr, msd);

    const double v2ps = v2 / (units::psPerTimeUnit * units::psPerTimeUnit); // Å²/ps²
    nlohmann::json summary{
        {"samples", t},
        {"bodies", samples.front().size()},
        {"sample_interval_ps", dtPs},
        {"blocks", blocks},
        {"blocks_requested", options.blocks},
        {"msd_blocks_of_bodies", msdBlocks},
        {"max_lag_ps", maxLag * dtPs},
        {"rdf", detail::rdfSummary(rdf, largeRFraction * samples.front().boxLength)},
        {"vacf", {{"c0", vacf.value.front()}, {"mean_square_velocity_angstrom2_per_ps2", v2ps}}}};
    if (rotating)
        summary["oacf"] = {{"c1_0", oacf.c1.value.front()}, {"c2_0", oacf.c2.value.front()}};
    else
        summary["oacf"] = "not written: the axes do not change (bodies without rotation)";
    const Diffusion gk = greenKuboDiffusion(vacf, v2);
    summary["diffusion"] = {{"einstein_angstrom2_per_ps", d.coefficient},
                            {"einstein_err", d.err},
                            {"fit_from_ps", d.fromPs},
                            {"fit_to_ps", d.toPs},
                            {"green_kubo_angstrom2_per_ps", gk.coefficient},
                            {"green_kubo_err", gk.err}};
    return summary;
}

} // namespace terrace::analysis
