#include "cli/tradeoff_measure.hpp"
#include "analysis/csv.hpp"
#include "cli/sweep_table.hpp"
#include "core/output_file.hpp"
#include <algorithm>
#include <cmath>
#include <limits>

namespace terrace::cli {

namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

double numberAt(const nlohmann::json& j, std::initializer_list<const char*> path) {
    const nlohmann::json* at = &j;
    for (const char* key : path) {
        if (!at->is_object() || !at->contains(key)) return nan;
        at = &(*at)[key];
    }
    return at->is_number() ? at->get<double>() : nan;
}

std::vector<double> column(const analysis::CsvTable& t, const std::string& name) {
    const int c = t.find(name);
    return c < 0 ? std::vector<double>() : t.columns[std::size_t(c)];
}

} // namespace

const char* estimatorName(Estimator e, const std::string& engine) {
    if (e == Estimator::Configurational) return "configurational";
    return engine == "dmd" ? "terraced" : "own";
}

std::string valueKey(Observable o, Estimator e) {
    const std::string base = observableName(o);
    return e == Estimator::Configurational ? base + "_conf" : base;
}

std::optional<PeakWindow> peakWindow(const std::vector<const std::vector<double>*>& curves) {
    std::size_t bins = std::numeric_limits<std::size_t>::max();
    for (const auto* c : curves)
        bins = std::min(bins, c->size());
    if (curves.empty() || bins == 0) return std::nullopt;
    std::vector<double> mean(bins, 0.0);
    for (const auto* c : curves)
        for (std::size_t k = 0; k < bins; ++k)
            mean[k] += (*c)[k] / double(curves.size());
    const std::size_t top = std::size_t(std::max_element(mean.begin(), mean.end()) - mean.begin());
    if (!(mean[top] > 1.0)) // no peak above the ideal gas's g = 1: its top bin and neighbours
        return PeakWindow{top > 0 ? top - 1 : 0, std::min(bins - 1, top + 1)};
    const double half = 0.5 * (mean[top] - 1.0);
    PeakWindow w{top, top};
    while (w.first > 0 && mean[w.first - 1] - 1.0 >= half)
        --w.first;
    while (w.last + 1 < bins && mean[w.last + 1] - 1.0 >= half)
        ++w.last;
    return w;
}

double windowMean(const std::vector<double>& g, PeakWindow w) {
    if (g.size() <= w.last) return nan;
    double sum = 0.0;
    for (std::size_t k = w.first; k <= w.last; ++k)
        sum += g[k];
    return sum / double(w.last - w.first + 1);
}

void setPeakHeights(const std::vector<std::vector<ReplicaResult>*>& sets) {
    std::vector<const std::vector<double>*> curves;
    for (const auto* set : sets)
        for (const auto& r : *set)
            if (r.ok && !r.g.empty()) curves.push_back(&r.g);
    const auto window = peakWindow(curves);
    if (!window) return;
    for (auto* set : sets)
        for (auto& r : *set) {
            if (!r.ok || r.g.empty()) continue;
            r.value["g_peak"] = windowMean(r.g, *window);
            if (!r.gConf.empty()) r.value["g_peak_conf"] = windowMean(r.gConf, *window);
        }
}

double integral(const std::vector<double>& t, const std::vector<double>& c) {
    // Up to the first zero of c (linearly interpolated), where the tail that only adds noise
    // begins: the running integral's plateau.
    double sum = 0.0;
    for (std::size_t k = 1; k < std::min(t.size(), c.size()); ++k) {
        if (c[k] <= 0.0 && c[k - 1] > 0.0) {
            const double zero = t[k - 1] + (t[k] - t[k - 1]) * c[k - 1] / (c[k - 1] - c[k]);
            return sum + 0.5 * c[k - 1] * (zero - t[k - 1]);
        }
        sum += 0.5 * (c[k] + c[k - 1]) * (t[k] - t[k - 1]);
    }
    return t.size() >= 2 ? sum : nan;
}

ReplicaResult readReplica(const std::filesystem::path& dir, int bodies, double epsilon) {
    ReplicaResult r;
    nlohmann::json s;
    try {
        s = nlohmann::json::parse(readWholeFile(dir / "summary.json"));
    } catch (const std::exception& e) {
        r.failure = std::string("no summary: ") + e.what();
        return r;
    }
    r.cpuPerPs = numberAt(s, {"cpu_seconds_per_ps"});
    // The budget counts what a run cost the machine: the whole process where the run says
    // (its samples' configurational sums and g(r) frames can cost a gas more than its engine),
    // else, for runs from before it did, the engine's equilibration and production.
    r.cpuSeconds = numberAt(s, {"process_cpu_seconds"});
    if (!std::isfinite(r.cpuSeconds))
        r.cpuSeconds = numberAt(s, {"cpu_seconds"}) + numberAt(s, {"cpu_seconds_equilibration"});
    if (s.contains("error")) {
        r.failure = s["error"].is_string() ? s["error"].get<std::string>() : "failed";
        // SMD's own refusal to go on (smd/engine.hpp): the step is past the stability limit.
        r.beyondStability = r.failure.find("the integration became unstable") != std::string::npos;
        return r;
    }
    for (const auto& w : s.value("warnings", nlohmann::json::array()))
        if (w.is_string() && w.get<std::string>().find("conserve energy") != std::string::npos) {
            r.failure = w.get<std::string>(); // beyond the stability limit
            r.beyondStability = true;
            return r;
        }
    if (!completeSummary(s)) {
        r.failure = "the run did not finish";
        return r;
    }
    const double perBody = 1.0 / (double(bodies) * epsilon);
    r.value["u"] = numberAt(s, {"potential_energy_mean"}) * perBody;
    r.value["u_conf"] = numberAt(s, {"configurational", "potential_energy_mean"}) * perBody;
    r.value["p"] = numberAt(s, {"pressure", "mean_reduced"});
    r.value["p_conf"] = numberAt(s, {"configurational", "pressure_reduced"});
    r.value["d"] = numberAt(s, {"analysis", "diffusion", "einstein_angstrom2_per_ps"});
    // Block errors, with their blocks' degrees of freedom.
    const double pressureDof = numberAt(s, {"pressure", "blocks"}) - 1.0;
    const double configurationalDof = numberAt(s, {"configurational", "blocks"}) - 1.0;
    const auto withError = [&](const std::string& key, double err, double dof, double scale) {
        if (std::isfinite(r.value[key]) && std::isfinite(err) && err > 0.0 && dof > 0.0)
            r.withError[key] = {r.value[key], err * scale, dof, 1};
    };
    withError("u", numberAt(s, {"potential_energy_err"}), pressureDof, perBody);
    withError("u_conf", numberAt(s, {"configurational", "potential_energy_err"}),
              configurationalDof, perBody);
    withError("p", numberAt(s, {"pressure", "error_reduced"}), pressureDof, 1.0);
    withError("p_conf", numberAt(s, {"configurational", "pressure_err_reduced"}),
              configurationalDof, 1.0);
    withError("d", numberAt(s, {"analysis", "diffusion", "einstein_err"}),
              numberAt(s, {"analysis", "msd_blocks_of_bodies"}) - 1.0, 1.0);
    try {
        const analysis::CsvTable rdf = analysis::readCsv(dir / "rdf.csv");
        r.g = column(rdf, "g");
        r.gConf = column(rdf, "g_continuous");
        // No block error for g_peak (setPeakHeights) and the integrals: a window's would need
        // the covariance of its bins, an integral's that of the lags; their replicas' scatter is
        // the honest error.
        const analysis::CsvTable vacf = analysis::readCsv(dir / "vacf.csv");
        r.value["tau_v"] = integral(column(vacf, "t_ps"), column(vacf, "c"));
        if (std::filesystem::exists(dir / "oacf.csv")) {
            const analysis::CsvTable oacf = analysis::readCsv(dir / "oacf.csv");
            r.value["tau_o"] = integral(column(oacf, "t_ps"), column(oacf, "c1"));
        }
    } catch (const std::exception& e) {
        r.failure = e.what();
        return r;
    }
    r.ok = true;
    return r;
}

analysis::Estimate squaredCurveDeviation(const std::vector<std::vector<double>>& a,
                                         const std::vector<std::vector<double>>& b) {
    analysis::Estimate out{nan, nan};
    if (a.size() < 2 || b.size() < 2) return out;
    std::size_t bins = a.front().size();
    for (const auto* set : {&a, &b})
        for (const auto& curve : *set)
            bins = std::min(bins, curve.size());
    if (bins == 0) return out;
    const auto meanAndSe2 = [](const std::vector<std::vector<double>>& set, std::size_t k) {
        double m = 0.0, v = 0.0;
        for (const auto& c : set)
            m += c[k];
        m /= double(set.size());
        for (const auto& c : set)
            v += (c[k] - m) * (c[k] - m);
        const double n = double(set.size());
        return std::pair{m, v / (n - 1.0) / n};
    };
    // Var(d² − σ²) = 4Δ²σ² + 2σ⁴ for a Gaussian d of mean Δ: the noise term is known, the signal
    // term is estimated with Δ² by its unbiased estimate d² − σ² (d² itself overstates it by σ²).
    double sum = 0.0, noiseVar = 0.0, signalVar = 0.0;
    for (std::size_t k = 0; k < bins; ++k) {
        const auto [ma, sa] = meanAndSe2(a, k);
        const auto [mb, sb] = meanAndSe2(b, k);
        const double d = ma - mb, s2 = sa + sb;
        sum += d * d - s2;
        noiseVar += 2.0 * s2 * s2;
        // Left unclipped bin by bin so that the sum over bins stays unbiased.
        signalVar += 4.0 * (d * d - s2) * s2;
    }
    const double m = double(bins);
    out.mean = sum / m;
    // 4Δ²σ² cannot be negative, although its sum's estimate can be where the curves agree within
    // their noise: then the noise alone is the error, never zero while there is noise.
    out.err = std::sqrt(noiseVar + std::max(signalVar, 0.0)) / m;
    out.dof = double(std::min(a.size(), b.size()) - 1);
    out.samples = int(a.size());
    return out;
}

std::optional<ObservableBias> scalarBias(Observable o, Estimator e,
                                         const std::vector<ReplicaResult>& candidate,
                                         const std::vector<ReplicaResult>& reference,
                                         analysis::Tolerance tolerance, double scaleFloor,
                                         double z) {
    // Each side's mean: with the replicas' block errors where all have one, else their scatter.
    const auto estimate = [](const std::vector<ReplicaResult>& set,
                             const std::string& key) -> std::optional<analysis::Estimate> {
        std::vector<double> x;
        std::vector<analysis::Estimate> withError;
        for (const auto& r : set) {
            if (!r.ok) continue;
            const auto it = r.value.find(key);
            if (it == r.value.end() || !std::isfinite(it->second)) continue;
            x.push_back(it->second);
            if (const auto e = r.withError.find(key); e != r.withError.end())
                withError.push_back(e->second);
        }
        if (x.size() < 2) return std::nullopt;
        return withError.size() == x.size() ? analysis::pooledReplicaEstimate(withError)
                                            : analysis::replicaMean(x);
    };
    const auto c = estimate(candidate, valueKey(o, e));
    // The reference is SMD: its own estimator is the continuous model's.
    const auto ref = estimate(reference, valueKey(o, Estimator::Own));
    if (!c || !ref) return std::nullopt;
    ObservableBias b;
    b.observable = o;
    b.estimator = e;
    b.candidate = *c;
    b.reference = *ref;
    b.bias = analysis::difference(b.candidate, b.reference);
    b.tolerance = analysis::absoluteTolerance(tolerance, b.reference.mean, scaleFloor);
    b.decision = analysis::decideBias(b.bias, b.tolerance, z).decision;
    return b;
}

std::optional<ObservableBias> curveBias(Estimator e, const std::vector<ReplicaResult>& candidate,
                                        const std::vector<ReplicaResult>& reference,
                                        double tolerance, double z) {
    std::vector<std::vector<double>> c, ref;
    for (const auto& r : candidate)
        if (r.ok) {
            const auto& curve = e == Estimator::Configurational ? r.gConf : r.g;
            if (!curve.empty()) c.push_back(curve);
        }
    for (const auto& r : reference)
        if (r.ok && !r.g.empty()) ref.push_back(r.g);
    if (c.size() < 2 || ref.size() < 2) return std::nullopt;
    ObservableBias b;
    b.observable = Observable::G;
    b.estimator = e;
    const analysis::Estimate square = squaredCurveDeviation(c, ref);
    // Decided on the square against tol²; reported as an RMS with the error carried through.
    const analysis::BiasDecision d = analysis::decideBias(square, tolerance * tolerance, z);
    b.decision = d.decision;
    const double rms = std::sqrt(std::abs(square.mean));
    b.bias = square;
    b.bias.mean = std::copysign(rms, square.mean);
    b.bias.err = rms > 0.0 ? square.err / (2.0 * rms) : std::sqrt(square.err);
    b.tolerance = tolerance;
    return b;
}

} // namespace terrace::cli
