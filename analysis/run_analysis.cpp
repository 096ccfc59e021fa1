#include "analysis/run_analysis.hpp"
#include "analysis/csv.hpp"
#include "analysis/curves.hpp"
#include "analysis/rdf_accumulator.hpp"
#include "analysis/streaming_correlations.hpp"
#include "core/output_file.hpp"
#include "core/units.hpp"
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace terrace::analysis {

namespace {

/// g(r) far from a body should be 1: "g at large r" is its mean over the outer fifth of its
/// range, r ≥ 0.8 r_max ([0.4, 0.5] L when g(r) runs out to L/2).
constexpr double largeRFraction = 0.8;

/// Summary entries of a g(r): bins, and g averaged over r ≥ from (Å) with a rough error.
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

/// x with each element mapped by f: a column in the units of the CSV.
template <class F> std::vector<double> mapped(const std::vector<double>& x, const F& f) {
    std::vector<double> y(x.size());
    std::transform(x.begin(), x.end(), y.begin(), f);
    return y;
}

/// Writes rdf.csv, vacf.csv, msd.csv and, for rotating bodies, oacf.csv (else removes a stale
/// one) into dir, created if needed; r, t and the MSD in `units` (under real as computed).
void writeCurveFiles(const std::filesystem::path& dir, const RadialDistribution& rdf,
                     const TerracingProfile& terracing, const SampledCurve& vacf,
                     const OrientationalCorrelation* oacf, const SampledCurve& msd,
                     const UnitSystem& units) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) throwIoError("create the directory", dir, ec.value());
    const bool reduced = units.reduced();
    const std::string rName = std::string("r_") + units.lengthSuffix();
    const std::string tName = std::string("t_") + units.timeSuffix();
    const std::string msdName = std::string("msd_") + units.lengthSuffix() + "2";
    auto time = [&](double ps) { return units.time(ps); };
    auto length2 = [&](double a2) { return units.length(units.length(a2)); };
    const std::vector<double> r =
        reduced ? mapped(rdf.r, [&](double a) { return units.length(a); }) : rdf.r;
    if (terracing.empty()) {
        writeCsv(dir / "rdf.csv", {{rName, "g", "err"}, {r, rdf.g, rdf.err}});
    } else {
        std::vector<double> gc(rdf.g.size()), errc(rdf.g.size());
        for (std::size_t k = 0; k < rdf.g.size(); ++k) {
            const double w = terracing.meanWeight(k);
            gc[k] = rdf.g[k] * w, errc[k] = rdf.err[k] * w;
        }
        writeCsv(dir / "rdf.csv", {{rName, "g", "err", "g_continuous", "err_continuous"},
                                   {r, rdf.g, rdf.err, gc, errc}});
    }
    writeCsv(
        dir / "vacf.csv",
        {{tName, "c", "err"}, {reduced ? mapped(vacf.tPs, time) : vacf.tPs, vacf.value, vacf.err}});
    if (oacf)
        writeCsv(dir / "oacf.csv", {{tName, "c1", "c1_err", "c2", "c2_err"},
                                    {reduced ? mapped(oacf->c1.tPs, time) : oacf->c1.tPs,
                                     oacf->c1.value, oacf->c1.err, oacf->c2.value, oacf->c2.err}});
    else if (std::filesystem::remove(dir / "oacf.csv", ec); ec)
        throwIoError("remove", dir / "oacf.csv", ec.value());
    if (reduced)
        writeCsv(dir / "msd.csv",
                 {{tName, msdName, "err"},
                  {mapped(msd.tPs, time), mapped(msd.value, length2), mapped(msd.err, length2)}});
    else
        writeCsv(dir / "msd.csv", {{tName, msdName, "err"}, {msd.tPs, msd.value, msd.err}});
}

} // namespace

RunAnalysis::RunAnalysis(int bodies, double boxLength, double sampleIntervalPs, long plannedSamples,
                         const StreamingOptions& options)
    : options_(options), bodies_(bodies), planned_(plannedSamples), dtPs_(sampleIntervalPs),
      boxLength_(boxLength) {
    if (plannedSamples < 4) throw std::invalid_argument("analysis: need at least 4 samples");
    if (bodies < 2) throw std::invalid_argument("analysis: need at least 2 bodies");
    if (options.blocks < 2)
        throw std::invalid_argument("analysis: need at least 2 blocks for error bars");
    if (options.rdfEvery < 1) throw std::invalid_argument("analysis: rdf_every must be ≥ 1");
    if (options.maxLagPs < 0.0 || !std::isfinite(options.maxLagPs))
        throw std::invalid_argument("analysis: max_lag_ps must be ≥ 0 (0: half the span)");
    // A short run still gets its files: fewer blocks (at least two samples each).
    blocks_ = static_cast<int>(std::min<long>(options.blocks, plannedSamples / 2));
    StreamingCorrelationPlan plan;
    plan.samples = plannedSamples;
    plan.blocks = blocks_;
    plan.maxLag = lagFor(options.maxLagPs, sampleIntervalPs, plannedSamples, blocks_);
    plan.lagsPerLevel = options.lagsPerLevel;
    plan.followBodies = options.followBodies;
    correlations_ = std::make_unique<StreamingCorrelations>(bodies, sampleIntervalPs, plan);
    const double rMax = options.rdfMaxAngstrom > 0.0
                            ? std::min(options.rdfMaxAngstrom, 0.5 * boxLength)
                            : 0.5 * boxLength;
    const long frames = (plannedSamples + options.rdfEvery - 1) / options.rdfEvery;
    rdf_ = std::make_unique<RdfAccumulator>(bodies, boxLength, options.rdfBinAngstrom, rMax, frames,
                                            static_cast<int>(std::min<long>(blocks_, frames)));
    if (options.beta > 0.0)
        terracing_ =
            TerracingProfile(static_cast<int>(std::lround(rdf_->rMax() / options.rdfBinAngstrom)),
                             options.rdfBinAngstrom, options.beta);
}

RunAnalysis::~RunAnalysis() = default;

void RunAnalysis::add(const Snapshot& sample) {
    if (sample.boxLength != boxLength_)
        throw std::invalid_argument("analysis: the box length must not change");
    correlations_->add(sample);
    if (samples_ % options_.rdfEvery == 0) rdf_->add(sample);
    ++samples_;
}

void RunAnalysis::add(const Snapshot& followed, const PositionOf& positionOf) {
    if (followed.boxLength != boxLength_)
        throw std::invalid_argument("analysis: the box length must not change");
    if (wantsPositions() && !positionOf)
        throw std::invalid_argument("analysis: a g(r) frame needs every body's position");
    correlations_->addFollowed(followed);
    if (wantsPositions()) rdf_->add(positionOf, bodies_, boxLength_);
    ++samples_;
}

const std::vector<int>& RunAnalysis::followedBodies() const {
    return correlations_->followedBodies();
}

nlohmann::json RunAnalysis::write(const std::filesystem::path& dir, const UnitSystem& units) const {
    if (samples_ < 4) throw std::invalid_argument("analysis: need at least 4 samples");
    const RadialDistribution rdf = rdf_->result();
    double v2 = 0.0;
    const SampledCurve vacf = correlations_->velocity(&v2);
    const bool rotating = correlations_->rotating();
    OrientationalCorrelation oacf;
    if (rotating) oacf = correlations_->orientation();
    const SampledCurve msd = correlations_->displacement();
    const Diffusion d = diffusionFromMsd(msd);
    const Diffusion gk = greenKuboDiffusion(vacf, v2);

    writeCurveFiles(dir, rdf, terracing_, vacf, rotating ? &oacf : nullptr, msd, units);

    const double v2ps = v2 / (units::psPerTimeUnit * units::psPerTimeUnit); // Å²/ps²
    nlohmann::json rdfEntry = rdfSummary(rdf, largeRFraction * rdf_->rMax());
    rdfEntry["r_max_angstrom"] = rdf_->rMax();
    rdfEntry["frames"] = rdf_->frames();
    rdfEntry["every_samples"] = options_.rdfEvery;
    nlohmann::json summary{
        {"samples", samples_},
        {"samples_planned", planned_},
        {"bodies", bodies_},
        {"sample_interval_ps", dtPs_},
        {"blocks", blocks_},
        {"blocks_requested", options_.blocks},
        {"msd_blocks_of_bodies", msd.blocks},
        {"max_lag_ps", vacf.tPs.back()},
        {"lags", vacf.tPs.size()},
        {"lags_per_level", options_.lagsPerLevel},
        {"lag_levels", correlations_->levels()},
        {"followed_bodies", correlations_->followed()},
        {"memory_bytes", bytes()},
        {"rdf", rdfEntry},
        {"vacf", {{"c0", vacf.value.front()}, {"mean_square_velocity_angstrom2_per_ps2", v2ps}}}};
    if (rotating)
        summary["oacf"] = {{"c1_0", oacf.c1.value.front()}, {"c2_0", oacf.c2.value.front()}};
    else
        summary["oacf"] = "not written: the axes do not change (bodies without rotation)";
    const auto orNull = [](double x) {
        return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json();
    };
    summary["diffusion"] = {{"einstein_angstrom2_per_ps", orNull(d.coefficient)},
                            {"einstein_err", orNull(d.err)},
                            {"fit_from_ps", d.fromPs},
                            {"fit_to_ps", d.toPs},
                            {"green_kubo_angstrom2_per_ps", orNull(gk.coefficient)},
                            {"green_kubo_err", orNull(gk.err)}};
    return summary;
}

std::size_t RunAnalysis::bytes() const {
    return rdf_->bytes() + correlations_->bytes() +
           2 * sizeof(double) * static_cast<std::size_t>(terracing_.bins());
}

std::vector<std::uint8_t> RunAnalysis::state() const {
    StateWriter out;
    out.value(std::int64_t(samples_));
    rdf_->save(out);
    correlations_->save(out);
    out.doubles(terracing_.weights()), out.doubles(terracing_.counts());
    return out.take();
}

void RunAnalysis::restore(std::span<const std::uint8_t> state) {
    StateReader in(state);
    const auto samples = in.value<std::int64_t>("samples");
    if (samples < 0) throw std::invalid_argument("analysis state: a negative number of samples");
    samples_ = long(samples);
    rdf_->restore(in);
    if (rdf_->frames() != (samples_ + options_.rdfEvery - 1) / options_.rdfEvery)
        throw std::invalid_argument("analysis state: g(r)'s frames are not those of its samples");
    correlations_->restore(in);
    if (correlations_->samples() != samples_)
        throw std::invalid_argument("analysis state: the time correlations' samples are not the "
                                    "analysis'");
    std::vector<double> weight(terracing_.bins()), count(terracing_.bins());
    in.doubles(weight, "terracing profile's weights");
    in.doubles(count, "terracing profile's counts");
    terracing_.restore(std::move(weight), std::move(count));
    in.finish();
}

} // namespace terrace::analysis
