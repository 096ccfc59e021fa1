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
#include <string>

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

/// What the CSVs hold: the total curves and, for a mixture, the species' and pairs' own.
struct Curves {
    RadialDistribution rdf;
    SampledCurve vacf, msd;
    const OrientationalCorrelation* oacf = nullptr; // null: the bodies do not rotate
    std::vector<std::string> pairNames;             // "A_B", in speciesPairIndex order
    std::vector<RadialDistribution> partial;        // g_ab, in the same order
    std::vector<std::string> speciesNames;
    std::vector<SampledCurve> speciesVacf, speciesMsd;
    // A mixture of rods and spheres: each turning species' OACF (oacfNames[k]'s), the total then
    // over the turning species' bodies alone.
    std::vector<std::string> oacfNames;
    std::vector<OrientationalCorrelation> speciesOacf;
};

/// Appends the column `name` of values `v`.
void addColumn(CsvTable& t, const std::string& name, std::vector<double> v) {
    t.header.push_back(name);
    t.columns.push_back(std::move(v));
}

/// Writes rdf.csv, vacf.csv, msd.csv and, for rotating bodies, oacf.csv (else removes a stale
/// one) into dir, created if needed; r, t and the MSD in `units` (under real as computed). A
/// mixture's columns come after the total's, so that a reader of the first columns reads on.
void writeCurveFiles(const std::filesystem::path& dir, const Curves& c,
                     const TerracingProfile& terracing, const UnitSystem& units) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) throwIoError("create the directory", dir, ec.value());
    const bool reduced = units.reduced();
    const std::string rName = std::string("r_") + units.lengthSuffix();
    const std::string tName = std::string("t_") + units.timeSuffix();
    const std::string msdName = std::string("msd_") + units.lengthSuffix() + "2";
    auto time = [&](double ps) { return units.time(ps); };
    auto length2 = [&](double a2) { return units.length(units.length(a2)); };
    auto inLength2 = [&](const std::vector<double>& a2) {
        return reduced ? mapped(a2, length2) : a2;
    };
    const RadialDistribution& rdf = c.rdf;
    const std::vector<double> r =
        reduced ? mapped(rdf.r, [&](double a) { return units.length(a); }) : rdf.r;
    CsvTable rdfTable{{rName, "g", "err"}, {r, rdf.g, rdf.err}};
    if (!terracing.empty()) {
        std::vector<double> gc(rdf.g.size()), errc(rdf.g.size());
        for (std::size_t k = 0; k < rdf.g.size(); ++k) {
            const double w = terracing.meanWeight(k);
            gc[k] = rdf.g[k] * w, errc[k] = rdf.err[k] * w;
        }
        addColumn(rdfTable, "g_continuous", std::move(gc));
        addColumn(rdfTable, "err_continuous", std::move(errc));
    }
    for (std::size_t p = 0; p < c.partial.size(); ++p) {
        addColumn(rdfTable, "g_" + c.pairNames[p], c.partial[p].g);
        addColumn(rdfTable, "err_" + c.pairNames[p], c.partial[p].err);
    }
    writeCsv(dir / "rdf.csv", rdfTable);

    const std::vector<double> t = reduced ? mapped(c.vacf.tPs, time) : c.vacf.tPs;
    CsvTable vacfTable{{tName, "c", "err"}, {t, c.vacf.value, c.vacf.err}};
    CsvTable msdTable{{tName, msdName, "err"},
                      {reduced ? mapped(c.msd.tPs, time) : c.msd.tPs, inLength2(c.msd.value),
                       inLength2(c.msd.err)}};
    for (std::size_t a = 0; a < c.speciesNames.size(); ++a) {
        const std::string& name = c.speciesNames[a];
        addColumn(vacfTable, "vacf_" + name, c.speciesVacf[a].value);
        addColumn(vacfTable, "err_" + name, c.speciesVacf[a].err);
        addColumn(msdTable, "msd_" + name, inLength2(c.speciesMsd[a].value));
        addColumn(msdTable, "err_" + name, inLength2(c.speciesMsd[a].err));
    }
    writeCsv(dir / "vacf.csv", vacfTable);
    if (c.oacf) {
        CsvTable oacfTable{{tName, "c1", "c1_err", "c2", "c2_err"},
                           {reduced ? mapped(c.oacf->c1.tPs, time) : c.oacf->c1.tPs,
                            c.oacf->c1.value, c.oacf->c1.err, c.oacf->c2.value, c.oacf->c2.err}};
        for (std::size_t k = 0; k < c.oacfNames.size(); ++k) {
            const std::string& name = c.oacfNames[k];
            addColumn(oacfTable, "c1_" + name, c.speciesOacf[k].c1.value);
            addColumn(oacfTable, "c1_err_" + name, c.speciesOacf[k].c1.err);
            addColumn(oacfTable, "c2_" + name, c.speciesOacf[k].c2.value);
            addColumn(oacfTable, "c2_err_" + name, c.speciesOacf[k].c2.err);
        }
        writeCsv(dir / "oacf.csv", oacfTable);
    } else if (std::filesystem::remove(dir / "oacf.csv", ec); ec)
        throwIoError("remove", dir / "oacf.csv", ec.value());
    writeCsv(dir / "msd.csv", msdTable);
}

/// The summary's entry for a diffusion coefficient by Einstein and Green–Kubo.
nlohmann::json diffusionEntry(const Diffusion& d, const Diffusion& gk) {
    const auto orNull = [](double x) {
        return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json();
    };
    return {{"einstein_angstrom2_per_ps", orNull(d.coefficient)},
            {"einstein_err", orNull(d.err)},
            {"fit_from_ps", d.fromPs},
            {"fit_to_ps", d.toPs},
            {"green_kubo_angstrom2_per_ps", orNull(gk.coefficient)},
            {"green_kubo_err", orNull(gk.err)}};
}

} // namespace

RunAnalysis::RunAnalysis(int bodies, double boxLength, double sampleIntervalPs, long plannedSamples,
                         const StreamingOptions& options, const SpeciesLabels& species)
    : options_(options), bodies_(bodies), planned_(plannedSamples), dtPs_(sampleIntervalPs),
      boxLength_(boxLength), species_(species) {
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
    species.check(bodies);
    if (!species.empty())
        plan.follow = followedPerSpecies(species.ofBody, species.count(), options.followBodies);
    correlations_ = std::make_unique<StreamingCorrelations>(bodies, sampleIntervalPs, plan);
    if (!species.empty()) {
        const std::vector<int>& followed = correlations_->followedBodies();
        speciesEntries_.assign(species.names.size(), {});
        for (int k = 0; k < static_cast<int>(followed.size()); ++k)
            speciesEntries_[species.ofBody[followed[k]]].push_back(k);
        StreamingCorrelationPlan own = plan; // the same samples, blocks and lags: the same rows
        own.follow.clear(), own.followBodies = 0;
        for (std::size_t a = 0; a < speciesEntries_.size(); ++a) {
            if (speciesEntries_[a].empty())
                throw std::invalid_argument("analysis: species " + species.names[a] +
                                            " has no bodies");
            speciesCurves_.push_back(std::make_unique<StreamingCorrelations>(
                static_cast<int>(speciesEntries_[a].size()), sampleIntervalPs, own));
        }
    }
    const double rMax = options.rdfMaxAngstrom > 0.0
                            ? std::min(options.rdfMaxAngstrom, 0.5 * boxLength)
                            : 0.5 * boxLength;
    const long frames = (plannedSamples + options.rdfEvery - 1) / options.rdfEvery;
    rdf_ = std::make_unique<RdfAccumulator>(bodies, boxLength, options.rdfBinAngstrom, rMax, frames,
                                            static_cast<int>(std::min<long>(blocks_, frames)),
                                            species);
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
    addSpecies(sample, correlations_->followedBodies().data());
    if (samples_ % options_.rdfEvery == 0) rdf_->add(sample);
    ++samples_;
}

void RunAnalysis::add(const Snapshot& followed, const PositionOf& positionOf) {
    if (followed.boxLength != boxLength_)
        throw std::invalid_argument("analysis: the box length must not change");
    if (wantsPositions() && !positionOf)
        throw std::invalid_argument("analysis: a g(r) frame needs every body's position");
    correlations_->addFollowed(followed);
    addSpecies(followed, nullptr);
    if (wantsPositions()) rdf_->add(positionOf, bodies_, boxLength_);
    ++samples_;
}

void RunAnalysis::addSpecies(const Snapshot& frame, const int* index) {
    Snapshot& part = speciesPart_; // reused: no allocation per sample once grown
    part.time = frame.time, part.boxLength = frame.boxLength;
    for (std::size_t a = 0; a < speciesCurves_.size(); ++a) {
        part.position.clear(), part.velocity.clear(), part.axis.clear();
        for (const int k : speciesEntries_[a]) {
            const int i = index ? index[k] : k;
            part.position.push_back(frame.position[i]);
            part.velocity.push_back(frame.velocity[i]);
            part.axis.push_back(frame.axis[i]);
        }
        speciesCurves_[a]->addFollowed(part);
    }
}

const std::vector<int>& RunAnalysis::followedBodies() const {
    return correlations_->followedBodies();
}

nlohmann::json RunAnalysis::write(const std::filesystem::path& dir, const UnitSystem& units) const {
    if (samples_ < 4) throw std::invalid_argument("analysis: need at least 4 samples");
    Curves c;
    c.rdf = rdf_->result();
    double v2 = 0.0;
    c.vacf = correlations_->velocity(&v2);
    const bool rotating = correlations_->rotating();
    OrientationalCorrelation oacf;
    if (rotating) oacf = correlations_->orientation(), c.oacf = &oacf;
    c.msd = correlations_->displacement();
    const Diffusion d = diffusionFromMsd(c.msd);
    const Diffusion gk = greenKuboDiffusion(c.vacf, v2);
    const RadialDistribution& rdf = c.rdf;
    const SampledCurve &vacf = c.vacf, &msd = c.msd;

    // A mixture's curves, and each species' D, before anything is written.
    const int species = species_.count();
    nlohmann::json speciesDiffusion, partialsEntry;
    for (int a = 0; a < species; ++a)
        for (int b = a; b < species; ++b) {
            c.pairNames.push_back(species_.names[a] + "_" + species_.names[b]);
            c.partial.push_back(rdf_->partial(a, b));
            const nlohmann::json e = rdfSummary(c.partial.back(), largeRFraction * rdf_->rMax());
            partialsEntry[c.pairNames.back()] = {
                {"pairs", rdf_->pairs(a, b)},
                {"g_large_r", e.value("g_large_r", nlohmann::json())},
                {"g_large_r_err", e.value("g_large_r_err", nlohmann::json())}};
        }
    for (int a = 0; a < species; ++a) {
        double v2a = 0.0;
        c.speciesNames.push_back(species_.names[a]);
        c.speciesVacf.push_back(speciesCurves_[a]->velocity(&v2a));
        c.speciesMsd.push_back(speciesCurves_[a]->displacement());
        // The same samples and lags as the total's: the rows of the CSVs line up.
        if (c.speciesVacf.back().tPs != vacf.tPs || c.speciesMsd.back().tPs != msd.tPs)
            throw std::logic_error("analysis: species " + species_.names[a] +
                                   "'s lags are not the total's");
        speciesDiffusion[species_.names[a]] = diffusionEntry(
            diffusionFromMsd(c.speciesMsd.back()), greenKuboDiffusion(c.speciesVacf.back(), v2a));
        speciesDiffusion[species_.names[a]]["followed_bodies"] = speciesCurves_[a]->followed();
    }

    // Rods among spheres: a sphere's axis never moves, so the total's OACF would sit on the
    // spheres' share. It is taken over the turning species' bodies instead (which ones the
    // labels say, from the scene), each species' mean weighted by its followed bodies (the mean
    // over their union, lag by lag); the error adds the species' in quadrature, as of disjoint
    // sets of bodies.
    std::vector<int> turning;
    for (int a = 0; a < species && !species_.fixedAxis.empty(); ++a)
        if (!species_.fixedAxis[a]) turning.push_back(a);
    if (rotating && !turning.empty()) {
        double followed = 0.0;
        for (const int a : turning) {
            c.oacfNames.push_back(species_.names[a]);
            c.speciesOacf.push_back(speciesCurves_[a]->orientation());
            if (c.speciesOacf.back().c1.tPs != oacf.c1.tPs)
                throw std::logic_error("analysis: species " + species_.names[a] +
                                       "'s lags are not the total's");
            followed += speciesCurves_[a]->followed();
        }
        for (SampledCurve OrientationalCorrelation::*part :
             {&OrientationalCorrelation::c1, &OrientationalCorrelation::c2}) {
            SampledCurve& total = oacf.*part;
            std::fill(total.value.begin(), total.value.end(), 0.0);
            std::fill(total.err.begin(), total.err.end(), 0.0);
            for (std::size_t k = 0; k < turning.size(); ++k) {
                const double w = speciesCurves_[turning[k]]->followed() / followed;
                const SampledCurve& own = c.speciesOacf[k].*part;
                for (std::size_t l = 0; l < total.value.size(); ++l) {
                    total.value[l] += w * own.value[l];
                    total.err[l] += w * w * own.err[l] * own.err[l];
                }
            }
            for (double& e : total.err)
                e = std::sqrt(e);
        }
    }

    writeCurveFiles(dir, c, terracing_, units);

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
    if (!rotating) {
        summary["oacf"] = "not written: the axes do not change (bodies without rotation)";
    } else {
        summary["oacf"] = {{"c1_0", oacf.c1.value.front()}, {"c2_0", oacf.c2.value.front()}};
        if (!c.oacfNames.empty()) {
            summary["oacf"]["species"] = c.oacfNames;
            summary["oacf"]["over"] = "the bodies of the species that turn (the others never do)";
        }
    }
    summary["diffusion"] = diffusionEntry(d, gk);
    if (species > 0) {
        summary["diffusion"]["species"] = speciesDiffusion;
        summary["rdf"]["partials"] = partialsEntry;
    }
    return summary;
}

std::size_t RunAnalysis::bytes() const {
    std::size_t species = sizeof(std::int32_t) * species_.ofBody.size();
    for (std::size_t a = 0; a < speciesCurves_.size(); ++a)
        species += speciesCurves_[a]->bytes() + sizeof(int) * speciesEntries_[a].size();
    return rdf_->bytes() + correlations_->bytes() + species +
           2 * sizeof(double) * static_cast<std::size_t>(terracing_.bins());
}

std::vector<std::uint8_t> RunAnalysis::state() const {
    StateWriter out;
    out.value(std::int64_t(samples_));
    rdf_->save(out);
    correlations_->save(out);
    out.doubles(terracing_.weights()), out.doubles(terracing_.counts());
    // A mixture's species curves last: a plain scene's state is what it was before mixtures.
    for (const auto& curves : speciesCurves_)
        curves->save(out);
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
    for (const auto& curves : speciesCurves_) {
        curves->restore(in);
        if (curves->samples() != samples_)
            throw std::invalid_argument("analysis state: a species' time correlations' samples "
                                        "are not the analysis'");
    }
    in.finish();
}

} // namespace terrace::analysis
