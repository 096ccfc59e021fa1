#include "cli/tradeoff_report.hpp"
#include "cli/tradeoff_search.hpp"
#include "core/format_text.hpp"
#include "core/output_file.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>

namespace terrace::cli {

namespace {

nlohmann::json rungJson(const Rung& r) {
    nlohmann::json j{
        {"setting", r.setting.label()},
        {"engine", r.setting.engine},
        {"ladder", r.setting.ladder},
        {r.setting.engine == "dmd" ? "dV_kT" : "dt_fs", r.setting.x},
        {"interpolated", r.setting.interpolated},
        {"replicas", r.target},
        {"replicas_ok", r.ok()},
        {"cpu_s_per_ps", std::isfinite(r.cost()) ? nlohmann::json(r.cost()) : nlohmann::json()},
        {"decision", decisionName(r.decision)}};
    if (!r.failure.empty()) j["failure"] = r.failure;
    if (r.beyondStability) j["beyond_stability"] = true;
    j["biases"] = nlohmann::json::array();
    for (const auto& b : r.biases)
        j["biases"].push_back(biasJson(b, r.setting.engine));
    if (!r.alternatives.empty()) {
        j["other_estimator"] = nlohmann::json::array();
        for (const auto& b : r.alternatives)
            j["other_estimator"].push_back(biasJson(b, r.setting.engine));
    }
    return j;
}

} // namespace

nlohmann::json biasJson(const ObservableBias& b, const std::string& engine) {
    const auto num = [](double x) {
        return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json();
    };
    return {{"observable", observableName(b.observable)},
            {"estimator", estimatorName(b.estimator, engine)},
            {"candidate", num(b.candidate.mean)},
            {"candidate_err", num(b.candidate.err)},
            {"reference", num(b.reference.mean)},
            {"reference_err", num(b.reference.err)},
            {"bias", num(b.bias.mean)},
            {"bias_err", num(b.bias.err)},
            {"tolerance", num(b.tolerance)},
            {"decision", decisionName(b.decision)}};
}

nlohmann::json report(const Tradeoff& t) {
    nlohmann::json out{{"scene", t.scene.name},           {"bias_bodies", t.biasBodies},
                       {"bodies", t.scene.state.n},       {"z", t.z},
                       {"alpha", t.options.alpha},        {"looks", t.schedule},
                       {"cpu_seconds_spent", t.cpuSpent}, {"reference", rungJson(t.reference)}};
    // What the search was allowed: a search that ended without a verdict under these limits
    // would end the same way again (experiments/tradeoff-map.sh reruns only with larger ones).
    out["budget_cpu_hours"] = t.options.budgetCpuHours;
    out["max_replicas"] = t.options.maxReplicas;
    out["tolerances"] = nlohmann::json::object();
    for (const Observable o : t.observables)
        out["tolerances"][observableName(o)] = {{"value", t.tolerance.at(o).value},
                                                {"relative", t.tolerance.at(o).relative}};
    out["dmd_estimators"] = nlohmann::json::object();
    for (const auto& [o, e] : t.dmdEstimator)
        out["dmd_estimators"][observableName(o)] = estimatorName(e, "dmd");
    out["settings"] = nlohmann::json::array();
    for (const auto& ladder : t.ladders)
        for (const Rung& r : ladder)
            out["settings"].push_back(rungJson(r));

    out["notes"] = t.notes;
    return out;
}

void reportReferenceCheck(Tradeoff& t, nlohmann::json& out) {
    const Rung* r = referenceCheckRung(t);
    if (!r) return;
    nlohmann::json check = nlohmann::json::object();
    for (const auto& b : r->biases)
        check[observableName(b.observable)] = {{"bias_at_twice_dt", b.bias.mean},
                                               {"err", b.bias.err},
                                               {"reference_bias_bound", referenceBiasBound(b, 2.0)},
                                               {"tolerance", b.tolerance}};
    out["reference_check"] = check;
    t.notes.push_back(referenceShownConverged(*r)
                          ? "reference converged in dt: yoshida4 at twice its step bounds its "
                            "own bias (dt^4) below a quarter of every tolerance"
                          : "reference NOT shown converged in dt: yoshida4 at twice its step "
                            "leaves a bound on its own bias above a quarter of a tolerance");
}

std::string describe(const Setting& s, const Tradeoff& t) {
    if (s.engine == "dmd") {
        std::string est;
        for (const Observable o : t.observables)
            if (hasConfigurational(o))
                est += std::string(est.empty() ? "" : ", ") + observableName(o) + " " +
                       estimatorName(t.dmdEstimator.at(o), "dmd");
        return formatText("DMD dV = %.4g kT (%s terraces; %s)", s.x,
                          s.ladder == "dmd-optimal" ? "optimal" : "uniform", est.c_str());
    }
    const std::string scheme = s.ladder == "reference" ? "yoshida4" : s.ladder.substr(4);
    return formatText("SMD %s dt = %.4g fs", scheme.c_str(), s.x);
}

std::string toleranceText(const Tradeoff& t) {
    std::string text;
    for (const Observable o : t.observables) {
        const auto tol = t.tolerance.at(o);
        text += (text.empty() ? "" : ", ") +
                (tol.relative ? formatText("%s +-%.3g %%", observableName(o), 100.0 * tol.value)
                              : formatText("%s +-%.3g", observableName(o), tol.value));
    }
    return text;
}

void writeTable(const Tradeoff& t) {
    std::string csv = "setting,engine,ladder,x,interpolated,replicas,cpu_s_per_ps,observable,"
                      "estimator,bias,bias_err,tolerance,decision,rung_decision\n";
    const auto rows = [&](const Rung& r) {
        for (const auto& b : r.biases) {
            csv += formatText("%s,%s,%s,%.6g,%d,%d,%.6g,%s,%s,%.6g,%.6g,%.6g,%s,%s\n",
                              r.setting.label().c_str(), r.setting.engine.c_str(),
                              r.setting.ladder.c_str(), r.setting.x, int(r.setting.interpolated),
                              r.target, r.cost(), observableName(b.observable),
                              estimatorName(b.estimator, r.setting.engine), b.bias.mean, b.bias.err,
                              b.tolerance, decisionName(b.decision), decisionName(r.decision));
        }
        if (r.biases.empty()) {
            csv += formatText("%s,%s,%s,%.6g,%d,%d,%.6g,,,,,,,%s\n", r.setting.label().c_str(),
                              r.setting.engine.c_str(), r.setting.ladder.c_str(), r.setting.x,
                              int(r.setting.interpolated), r.target, r.cost(),
                              decisionName(r.decision));
        }
    };
    for (const auto& ladder : t.ladders)
        for (const Rung& r : ladder)
            rows(r);
    writeFileAtomically(t.options.out / "tradeoff.csv", csv);
}

void writePlot(const Tradeoff& t) {
    std::string data = "# engine cost bias_over_tol err_over_tol observable\n";
    for (const auto& ladder : t.ladders)
        for (const Rung& r : ladder)
            for (const auto& b : r.biases)
                data += r.setting.engine + " " + std::to_string(r.cost()) + " " +
                        std::to_string(b.bias.mean / b.tolerance) + " " +
                        std::to_string(b.bias.err / b.tolerance) + " " +
                        observableName(b.observable) + "\n";
    writeFileAtomically(t.options.out / "tradeoff.dat", data);
    std::FILE* gp = popen("gnuplot 2>/dev/null", "w");
    if (!gp) return;
    const int panels = int(t.observables.size());
    std::string script = "set terminal pngcairo size " + std::to_string(360 * std::min(panels, 4)) +
                         "," + std::to_string(320 * ((panels + 3) / 4)) + "\nset output '" +
                         (t.options.out / "tradeoff.png").string() + "'\n";
    script += "set multiplot layout " + std::to_string((panels + 3) / 4) + "," +
              std::to_string(std::min(panels, 4)) + " title 'bias / tolerance against cost'\n";
    script += "set logscale x\nset xlabel 'CPU s per ps'\nset ylabel 'bias / tolerance'\n"
              "set yrange [*<-1.5:1.5<*]\nset grid\nset key top left font ',8'\n"
              "set object 1 rectangle from graph 0, first -1 to graph 1, first 1 behind "
              "fc rgb '#dddddd' fs solid noborder\n";
    for (const Observable o : t.observables) {
        const std::string name = observableName(o);
        script += "set title '" + name + "' noenhanced\n";
        script += "plot '" + (t.options.out / "tradeoff.dat").string() +
                  "' using 2:(strcol(1) eq 'dmd' && strcol(5) eq '" + name +
                  "' ? $3 : NaN):4 with yerrorbars pt 7 lc rgb '#d62728' title 'DMD', '' using "
                  "2:(strcol(1) eq 'smd' && strcol(5) eq '" +
                  name + "' ? $3 : NaN):4 with yerrorbars pt 5 lc rgb '#1f77b4' title 'SMD'\n";
    }
    script += "unset multiplot\n";
    std::fputs(script.c_str(), gp);
    pclose(gp);
}

} // namespace terrace::cli
