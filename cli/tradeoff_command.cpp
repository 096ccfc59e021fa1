#include "cli/tradeoff_command.hpp"
#include "analysis/csv.hpp"
#include "cli/design_command.hpp"
#include "cli/sweep_runner.hpp"
#include "cli/tradeoff_dominance.hpp"
#include "cli/tradeoff_measure.hpp"
#include "cli/tradeoff_schedule.hpp"
#include "core/format_text.hpp"
#include "core/output_file.hpp"
#include "core/scene_json.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

namespace terrace::cli {

namespace {

using analysis::Decision;

const char* decisionName(Decision d) {
    return d == Decision::Within ? "within" : d == Decision::Outside ? "outside" : "unresolved";
}

/// A setting with its replicas and what they say.
struct Rung {
    Setting setting;
    int target = 0; // replicas asked for
    std::vector<ReplicaResult> replicas;
    std::vector<ObservableBias> biases;
    std::vector<ObservableBias> alternatives; // DMD: the estimator not chosen, for comparison
    Decision decision = Decision::Unresolved;
    std::string failure;          // the stability limit, or why a rung cannot be judged
    bool beyondStability = false; // a replica met SMD's stability limit (failure says how)

    int ok() const {
        return int(std::count_if(replicas.begin(), replicas.end(),
                                 [](const ReplicaResult& r) { return r.ok; }));
    }
    double cost() const { // mean production CPU s per ps of the ok replicas
        double sum = 0.0;
        int n = 0;
        for (const auto& r : replicas)
            if (r.ok && std::isfinite(r.cpuPerPs)) sum += r.cpuPerPs, ++n;
        return n ? sum / n : std::numeric_limits<double>::quiet_NaN();
    }
};

std::string replicaName(const Setting& s, int k) {
    return s.label() + "_r" + std::to_string(k);
}

struct Tradeoff {
    TradeoffOptions options;
    Scene scene;        // the user's, at its N: the cost runs
    int biasBodies = 0; // bodies of the bias runs
    std::vector<Observable> observables;
    std::map<Observable, analysis::Tolerance> tolerance;
    Rung reference;
    std::vector<std::vector<Rung>> ladders;
    std::map<Observable, Estimator> dmdEstimator;
    std::vector<int> schedule;
    double z = 2.0;
    double cpuSpent = 0.0;
    std::vector<std::string> notes;
    std::set<std::string> interpolatedLadders;

    std::filesystem::path runs() const { return options.out / "runs"; }

    /// The least magnitude a relative tolerance of o is a fraction of (relativeScaleFloor).
    double scaleFloor(Observable o) const {
        return relativeScaleFloor(o, scene.state.density, scene.state.temperature);
    }
};

/// One run of a setting: its seed and its directory under OUT/runs.
struct CaseRun {
    const Setting* setting;
    long seed;
    std::string label;
};

/// The runs as one sweep (each not yet complete on disk is run), `jobs` at once, in order, with
/// --set and `extraSet` for every run; returns the sweep's status. `biasRuns`: runs that measure
/// biases, which take a g(r) frame at every sample; the cost windows keep the scene's frames.
int runCases(const Tradeoff& t, const std::vector<CaseRun>& runs, const std::string& extraSet,
             int jobs, bool biasRuns) {
    nlohmann::json cases = nlohmann::json::array(), labels = nlohmann::json::array();
    for (const CaseRun& r : runs) {
        nlohmann::json c = nlohmann::json::object();
        for (const auto& [key, value] : r.setting->overrides)
            c[key] = value;
        c["seed"] = r.seed;
        cases.push_back(c);
        labels.push_back(r.label);
    }
    if (cases.empty()) return 0;
    // No thermo.csv (on by default): the ladder's costs are its measure, and a row off the g(r)
    // frames adds a pass over the pairs; --set output.thermo_every_fs still asks for one.
    // A bias run takes a g(r) frame, with DMD's configurational U and P, at every sample rather
    // than every 10th: in a liquid frames 9 fs apart are nearly independent, and each replica's
    // variances of g, its peak, U and P shrink 2-10x for 24-69 % more CPU; in a dilute gas only
    // g's shrink (docs/TRADEOFF.md, "Frames"). --set analysis.rdf_every sets another spacing.
    nlohmann::json common{{"output.thermo_every_fs", 0}};
    if (biasRuns) common["analysis.rdf_every"] = 1;
    nlohmann::json sweep{{"axes", {{{"cases", cases}, {"labels", labels}}}}, {"set", common}};
    if (!t.options.scenePath.empty())
        sweep["scene"] = std::filesystem::absolute(t.options.scenePath).string();
    std::vector<std::string> sets = t.options.sets;
    if (!extraSet.empty()) sets.push_back(extraSet);
    SweepOptions so;
    so.out = t.runs();
    so.jobs = jobs;
    so.quiet = t.options.quiet;
    return runSweep(sweepFromJson(sweep.dump(), "tradeoff", ".", sets), so);
}

/// Runs every replica asked for and not yet on disk; returns the sweep's status.
int runPending(const Tradeoff& t, const std::vector<const Rung*>& rungs,
               const std::string& extraSet) {
    std::vector<CaseRun> runs;
    for (const Rung* r : rungs)
        for (int k = 1; k <= r->target; ++k)
            runs.push_back({&r->setting, k, replicaName(r->setting, k)});
    return runCases(t, runs, extraSet, t.options.jobs, true);
}

void readRung(Tradeoff& t, Rung& r, int bodies) {
    r.replicas.clear();
    for (int k = 1; k <= r.target; ++k)
        r.replicas.push_back(
            readReplica(t.runs() / replicaName(r.setting, k), bodies, t.scene.potential.epsilon));
}

std::optional<ObservableBias> biasOf(const Tradeoff& t, const Rung& r, Observable o, Estimator e) {
    if (o == Observable::G)
        return curveBias(e, r.replicas, t.reference.replicas, t.tolerance.at(o).value, t.z);
    return scalarBias(o, e, r.replicas, t.reference.replicas, t.tolerance.at(o), t.scaleFloor(o),
                      t.z);
}

bool hasConfigurational(Observable o) {
    return o == Observable::U || o == Observable::P || o == Observable::G || o == Observable::GPeak;
}

/// For DMD, per observable, the estimator whose biases over the DMD rungs are the smaller
/// (Σ |bias|/tol over the rungs where both are measured).
void chooseEstimators(Tradeoff& t) {
    for (const Observable o : t.observables) {
        if (!hasConfigurational(o)) {
            t.dmdEstimator[o] = Estimator::Own;
            continue;
        }
        double own = 0.0, conf = 0.0;
        for (const auto& ladder : t.ladders)
            for (const Rung& r : ladder) {
                if (r.setting.engine != "dmd") continue;
                const auto a = biasOf(t, r, o, Estimator::Own);
                const auto b = biasOf(t, r, o, Estimator::Configurational);
                if (!a || !b) continue;
                own += std::abs(a->bias.mean) / a->tolerance;
                conf += std::abs(b->bias.mean) / b->tolerance;
            }
        t.dmdEstimator[o] = conf < own ? Estimator::Configurational : Estimator::Own;
    }
}

void judge(Tradeoff& t, Rung& r) {
    r.biases.clear();
    r.alternatives.clear();
    r.failure.clear();
    r.beyondStability = false;
    for (const auto& x : r.replicas)
        if (!x.ok && !x.failure.empty()) {
            // The stability limit is the failure a rung is known by, where a replica met it.
            if (x.beyondStability || !r.beyondStability) r.failure = x.failure;
            r.beyondStability = r.beyondStability || x.beyondStability;
        }
    if (!r.failure.empty()) {
        r.decision = Decision::Outside;
        return;
    }
    bool any = false, outside = false, all = true;
    for (const Observable o : t.observables) {
        const Estimator e = r.setting.engine == "dmd" ? t.dmdEstimator[o] : Estimator::Own;
        const auto b = biasOf(t, r, o, e);
        if (!b) {
            all = false;
            continue;
        }
        r.biases.push_back(*b);
        if (r.setting.engine == "dmd" && hasConfigurational(o)) {
            const Estimator other =
                e == Estimator::Own ? Estimator::Configurational : Estimator::Own;
            if (const auto a = biasOf(t, r, o, other)) r.alternatives.push_back(*a);
        }
        any = true;
        outside = outside || b->decision == Decision::Outside;
        all = all && b->decision == Decision::Within;
    }
    r.decision =
        outside ? Decision::Outside : (any && all ? Decision::Within : Decision::Unresolved);
}

/// Replicas that would resolve rung r's open observables (the next count of the schedule).
int nextTarget(const Tradeoff& t, const Rung& r) {
    int projected = r.target;
    for (const auto& b : r.biases) {
        if (b.decision != Decision::Unresolved) continue;
        if (b.observable == Observable::G) {
            // Decided on the square: project with the square against tol².
            analysis::Estimate square = b.bias;
            square.mean = std::copysign(b.bias.mean * b.bias.mean, b.bias.mean);
            square.err = 2.0 * std::abs(b.bias.mean) * b.bias.err;
            projected = std::max(projected,
                                 analysis::replicasToResolve(square, analysis::Estimate{0.0, 0.0},
                                                             b.tolerance * b.tolerance, t.z,
                                                             t.options.maxReplicas));
        } else {
            projected = std::max(projected,
                                 analysis::replicasToResolve(b.candidate, b.reference, b.tolerance,
                                                             t.z, t.options.maxReplicas));
        }
    }
    return analysis::nextLook(t.schedule, r.target, projected);
}

/// The index of a ladder's cheapest Within rung (-1: none).
int cheapestWithin(const std::vector<Rung>& ladder) {
    int c = -1;
    for (int i = 0; i < int(ladder.size()); ++i)
        if (ladder[i].decision == Decision::Within) c = i;
    return c;
}

/// The bound the reference's own dt error gets from one observable's bias on yoshida4 at twice its
/// step: by the dt⁴ law the reference's bias is 1/15 of the difference between the two, taken at
/// |bias| + sigmas·err (sigmas −2: the least the bound could still come to).
double referenceBiasBound(const ObservableBias& b, double sigmas) {
    return (std::abs(b.bias.mean) + sigmas * b.bias.err) / 15.0;
}

/// Whether the reference's own dt error is shown small: its bound below a quarter of every
/// tolerance. `rung` is yoshida4 at twice the reference's step.
bool referenceShownConverged(const Rung& rung) {
    bool within = !rung.biases.empty();
    for (const auto& b : rung.biases)
        within = within && referenceBiasBound(b, 2.0) < 0.25 * b.tolerance;
    return within;
}

/// Whether more replicas of that rung could still show it: no bias already too large for the
/// bound, whatever its error.
bool referenceCheckOpen(const Rung& rung) {
    for (const auto& b : rung.biases)
        if (referenceBiasBound(b, -2.0) >= 0.25 * b.tolerance) return false;
    return !referenceShownConverged(rung);
}

/// The rung of yoshida4 at twice the reference's step, or null.
const Rung* referenceCheckRung(const Tradeoff& t) {
    for (const auto& ladder : t.ladders)
        for (const Rung& r : ladder)
            if (r.setting.ladder == "smd-yoshida4" &&
                std::abs(r.setting.x - 2.0 * t.reference.setting.x) < 1e-9 * r.setting.x)
                return &r;
    return nullptr;
}

/// Raises the targets of the rungs cli/tradeoff_schedule.hpp picks: per engine its cheapest open
/// rung below the cost of its cheapest Within (every ladder's open rung under --frontier), and
/// the reference's check rung until it shows the reference converged.
bool raiseTargets(Tradeoff& t) {
    const Rung* check = referenceCheckRung(t);
    std::vector<std::vector<ScheduleRung>> views;
    for (const auto& ladder : t.ladders) {
        auto& view = views.emplace_back();
        for (const Rung& r : ladder) {
            ScheduleRung v{r.setting.engine == "dmd",
                           r.cost(),
                           r.decision,
                           r.target,
                           r.target == 0 ? 0 : nextTarget(t, r),
                           false};
            v.pinned = &r == check && r.target > 0 && r.failure.empty() && referenceCheckOpen(r);
            view.push_back(v);
        }
    }
    bool raised = false;
    for (const auto& [l, i] : rungsToRaise(views, t.options.frontier)) {
        Rung& r = t.ladders[l][i];
        // The check rung doubles: its bound needs far fewer replicas than a decision at the
        // tolerance would.
        const int next = r.target == 0 ? t.schedule.front()
                         : views[l][i].pinned
                             ? analysis::nextLook(t.schedule, r.target, r.target + 1)
                             : views[l][i].next;
        if (next > r.target) r.target = next, raised = true;
    }
    return raised;
}

/// CPU seconds per replica of a rung, from its own runs or, before it has any, the mean of its
/// ladder's.
double cpuPerReplica(const std::vector<Rung>& ladder, const Rung& r) {
    const auto mean = [](const Rung& x) {
        double sum = 0.0;
        int n = 0;
        for (const auto& y : x.replicas)
            if (std::isfinite(y.cpuSeconds)) sum += y.cpuSeconds, ++n;
        return n ? sum / n : std::numeric_limits<double>::quiet_NaN();
    };
    if (const double own = mean(r); std::isfinite(own)) return own;
    double sum = 0.0;
    int n = 0;
    for (const Rung& x : ladder)
        if (const double m = mean(x); std::isfinite(m)) sum += m, ++n;
    return n ? sum / n : 0.0;
}

/// Takes back the raised targets whose runs would take the CPU spent past the budget, the
/// costliest first; false when none is left to run.
bool fitBudget(Tradeoff& t) {
    struct Pending {
        Rung* rung;
        double cpu;
    };
    std::vector<Pending> pending;
    double total = 0.0;
    const auto add = [&](std::vector<Rung>& ladder, Rung& r) {
        const int extra = r.target - int(r.replicas.size());
        if (extra <= 0) return;
        pending.push_back({&r, extra * cpuPerReplica(ladder, r)});
        total += pending.back().cpu;
    };
    std::vector<Rung> alone;
    add(alone, t.reference);
    for (auto& ladder : t.ladders)
        for (Rung& r : ladder)
            add(ladder, r);
    std::sort(pending.begin(), pending.end(),
              [](const Pending& a, const Pending& b) { return a.cpu > b.cpu; });
    const double budget = t.options.budgetCpuHours * 3600.0;
    std::size_t kept = pending.size();
    for (auto& p : pending) {
        if (t.cpuSpent + total <= budget) break;
        total -= p.cpu;
        p.rung->target = int(p.rung->replicas.size());
        --kept;
    }
    return kept > 0;
}

/// The reference's replicas double until its standard error is below a third of every
/// tolerance (so that it adds little to a candidate's) and below the candidate's in every open
/// decision, or the replica budget is reached.
bool raiseReference(Tradeoff& t) {
    if (t.reference.target >= t.options.maxReplicas) return false;
    bool short_ = false;
    for (const Observable o : t.observables) {
        if (o == Observable::G) continue; // its noise is taken out of the estimate
        std::vector<double> x;
        for (const auto& r : t.reference.replicas)
            if (r.ok && r.value.count(valueKey(o, Estimator::Own)))
                x.push_back(r.value.at(valueKey(o, Estimator::Own)));
        if (x.size() < 2) continue;
        const analysis::Estimate m = analysis::replicaMean(x);
        const double tol = analysis::absoluteTolerance(t.tolerance.at(o), m.mean, t.scaleFloor(o));
        short_ = short_ || !(m.err <= tol / 3.0);
    }
    // Where the reference is what keeps a decision open: its error the larger share of a bias's.
    for (const auto& ladder : t.ladders)
        for (const Rung& r : ladder)
            for (const auto& b : r.biases)
                short_ = short_ ||
                         (b.decision == Decision::Unresolved && b.reference.err > b.candidate.err);
    if (!short_) return false;
    t.reference.target = std::min(2 * t.reference.target, t.options.maxReplicas);
    return true;
}

/// ΔV/kT (DMD) or dt in fs (SMD) at which the first of the ladder's fitted bias laws reaches its
/// tolerance; +inf where no law is fitted or none reaches it.
double lawSetting(const Tradeoff& t, const std::vector<Rung>& ladder) {
    std::vector<double> x;
    for (const Rung& r : ladder)
        if (r.failure.empty()) x.push_back(r.setting.x);
    std::vector<LadderBiases> observables;
    for (const Observable o : t.observables) {
        LadderBiases l;
        for (const Rung& r : ladder)
            for (const auto& b : r.biases)
                if (b.observable == o && r.failure.empty())
                    l.bias.push_back(b.bias), l.tolerance = b.tolerance;
        // An observable missing on a rung (too few good replicas) is left out of the fits.
        if (l.bias.size() == x.size()) observables.push_back(l);
    }
    return lawCrossing(x, observables, knownOrder(ladder.front().setting));
}

/// The setting of `like`'s ladder at x or just below it, as the engine can run it: ΔV to three
/// decimals of kT, rounded down; dt = sample_fs/k with whole steps in the sampling grid.
Setting settingAtOrBelow(const Tradeoff& t, const Setting& like, double x) {
    if (like.engine == "dmd") return dmdSetting(like.ladder, std::floor(x * 1000.0) / 1000.0);
    const double sample = t.scene.run.sample_fs;
    int k = static_cast<int>(std::ceil(sample / x - 1e-9));
    while (!stepsFitGrid(t.scene, k))
        ++k;
    return smdSetting(like.ladder.substr(4), sample / k);
}

/// Places a setting by the bias laws between a ladder's cheapest Within rung and the Outside
/// rung after it; false when there is nothing to place.
bool interpolate(Tradeoff& t, std::vector<Rung>& ladder) {
    if (ladder.empty() || t.interpolatedLadders.count(ladder.front().setting.ladder)) return false;
    const int c = cheapestWithin(ladder);
    if (c < 0 || c + 1 >= int(ladder.size()) || ladder[c + 1].decision != Decision::Outside ||
        !ladder[c + 1].failure.empty())
        return false;
    t.interpolatedLadders.insert(ladder.front().setting.ladder);
    const double xStar = lawSetting(t, ladder);
    const double lo = ladder[c].setting.x, hi = ladder[c + 1].setting.x;
    if (!(xStar > lo && xStar < hi)) return false;
    Setting s = settingAtOrBelow(t, ladder[c].setting, xStar);
    if (!(s.x > lo * (1 + 1e-9))) return false;
    s.interpolated = true;
    Rung r;
    r.setting = s;
    ladder.insert(ladder.begin() + c + 1, r);
    t.notes.push_back(s.label() + " placed by the bias law between " + ladder[c].setting.label() +
                      " and " + ladder[c + 2].setting.label());
    return true;
}

/// A ladder with every rung resolved Outside gets one more, more accurate, rung where its bias
/// laws put the bias at the tolerance (by the margin, at most extrapolationReach below its most
/// accurate rung), checked by its own runs like any other: without it a scene whose tolerance
/// lies below the ladder gets no cost ratio. False when there is nothing to place (with a note
/// when the law puts the setting beyond reach).
bool extrapolate(Tradeoff& t, std::vector<Rung>& ladder) {
    if (ladder.empty() || t.interpolatedLadders.count(ladder.front().setting.ladder)) return false;
    for (const Rung& r : ladder)
        if (r.decision != Decision::Outside || !r.failure.empty()) return false;
    t.interpolatedLadders.insert(ladder.front().setting.ladder);
    const Setting front = ladder.front().setting; // a copy: the insertion below moves the rungs
    const double xStar = lawSetting(t, ladder);
    if (!(xStar < front.x)) return false;
    const auto below = extensionBelow(front.x, xStar);
    const std::string unit = front.engine == "dmd" ? " kT" : " fs";
    if (!below) {
        t.notes.push_back(front.ladder + ": the bias law reaches the tolerance only at " +
                          showNumber(xStar) + unit + ", beyond the reach of " +
                          showNumber(front.x * extrapolationReach) + unit + "; not run");
        return false;
    }
    Setting s = settingAtOrBelow(t, front, *below);
    if (!(s.x > 0.0 && s.x < front.x)) return false;
    s.interpolated = true;
    Rung r;
    r.setting = s;
    ladder.insert(ladder.begin(), r);
    t.notes.push_back(s.label() + " placed by the bias law below " + front.label() +
                      " (every rung was outside; the law crosses the tolerance at " +
                      showNumber(xStar) + unit + ")");
    return true;
}

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

/// bias/tolerance against cost, one panel per observable, the band |bias| ≤ tolerance shaded.
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

/// Everything measured so far: written after every round (with no verdict yet) and at the end.
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

const Rung* cheapestOf(const Tradeoff& t, const std::string& engine) {
    const Rung* best = nullptr;
    for (const auto& ladder : t.ladders) {
        const int c = cheapestWithin(ladder);
        if (c < 0 || ladder[c].setting.engine != engine) continue;
        if (!best || ladder[c].cost() < best->cost()) best = &ladder[c];
    }
    return best;
}

/// One engine's chosen setting and the other engine's cost floor above it
/// (cli/tradeoff_dominance.hpp).
struct Dominance {
    const Rung* chosen = nullptr; // the cheaper engine's cheapest Within rung
    const Rung* bound = nullptr;  // the rung whose cost bounds the other engine's from below
    CostFloor floor;
    // The other ladders' floors within rivalFactor of the least at the bias runs' N: at the
    // scene's N any of them may be the cheapest, so each is timed and the weakest bound kept.
    std::vector<std::pair<const Rung*, CostFloor>> rivals;
    // Some ladder of the other engine is bounded only by its coarsest rung: the claim covers
    // settings no coarser than its ladders' (whichever floor is stated).
    bool ladderEnd = false;
};

/// Floors further apart than this at the bias runs' N are taken to keep their order at the
/// scene's N.
constexpr double rivalFactor = 1.5;

std::vector<RungView> viewsOf(const std::vector<Rung>& ladder) {
    std::vector<RungView> views;
    for (const Rung& r : ladder)
        views.push_back(
            {r.setting.x, r.cost(), r.decision, !r.failure.empty(), r.beyondStability, r.biases});
    return views;
}

/// One engine's ladders, as the cost floor sees them and as they are.
struct EngineLadders {
    std::vector<std::vector<RungView>> views;
    std::vector<const std::vector<Rung>*> ladders; // the same order
};

EngineLadders laddersOf(const Tradeoff& t, const std::string& engine) {
    EngineLadders out;
    for (const auto& ladder : t.ladders)
        if (!ladder.empty() && ladder.front().setting.engine == engine)
            out.views.push_back(viewsOf(ladder)), out.ladders.push_back(&ladder);
    return out;
}

/// Why an engine with every setting resolved outside still leaves no verdict: its cost floor
/// (cli/tradeoff_dominance.hpp) is not above the other engine's cheapest setting within. This
/// happens where a bias changes sign between rungs (D on LJ at rho* 0.2, T* 3: -7 % at kT/8,
/// +6 % at kT), so only a coarse rung bounds the ladder and a setting between rungs may be
/// within at a smaller cost.
std::string everySettingOutside(const Tradeoff& t, const std::string& engine) {
    std::string out = "every setting resolved outside";
    const Rung* rival = cheapestOf(t, engine == "dmd" ? "smd" : "dmd");
    if (!rival) return out; // no verdict either way: nothing to set the floor against
    const EngineLadders own = laddersOf(t, engine);
    const auto floor = engineCostFloor(own.views, t.z);
    if (!floor) return out + ", and no setting bounds its cost from below";
    if (floor->cost >= dominanceMargin * rival->cost()) return out; // --frontier: no early stop
    const Rung& bound = (*own.ladders[floor->ladder])[floor->rung];
    out += formatText(
        ", but nothing rules out a setting cheaper than %s: the floor of its cost is %s "
        "(%.3g CPU s per ps), ",
        describe(rival->setting, t).c_str(), describe(bound.setting, t).c_str(), bound.cost());
    return out +
           (floor->ladderEnd
                ? std::string("its ladder's coarsest, as no setting is outside on a bias "
                              "that keeps its sign and grows on the coarser ones")
                : formatText("the most accurate setting outside on a bias (%s) that keeps its "
                             "sign and grows on the coarser ones, so a setting between two "
                             "finer rungs may be within",
                             observableName(floor->ruling.observable)));
}

/// Why an engine has no setting within: per observable, on how many of its settings not resolved
/// outside it is still unresolved, and the most replicas those have ("unresolved g_peak on 8 of
/// its 8 settings not outside, at up to 128 replicas"); or that every setting is outside.
std::string unresolvedSummary(const Tradeoff& t, const std::string& engine) {
    int open = 0, most = 0;
    std::map<Observable, int> unresolved;
    for (const auto& ladder : t.ladders)
        for (const Rung& r : ladder) {
            if (r.setting.engine != engine || r.decision == Decision::Outside) continue;
            ++open;
            most = std::max(most, int(r.replicas.size()));
            for (const auto& b : r.biases)
                if (b.decision == Decision::Unresolved) ++unresolved[b.observable];
        }
    if (open == 0) return everySettingOutside(t, engine);
    std::string out;
    for (const auto& [o, n] : unresolved)
        out +=
            (out.empty() ? "" : ", ") + std::string(observableName(o)) + " on " + std::to_string(n);
    if (out.empty()) out = "none";
    return "unresolved " + out + " of its " + std::to_string(open) +
           " settings not outside, at up to " + std::to_string(most) + " replicas";
}

/// The cheapest rung of an engine still Unresolved and cheaper than `chosen`: it may be within
/// tolerance (cli/tradeoff_dominance.hpp, openRungVerdict); nullptr when there is none. A rung
/// of the chosen one's own ladder counts only where it is coarser: cost falls as x grows along
/// a ladder, so a finer one timed cheaper is noise.
const Rung* cheapestOpen(const Tradeoff& t, const Rung& chosen) {
    const Rung* best = nullptr;
    for (const auto& ladder : t.ladders)
        for (const Rung& r : ladder)
            if (r.setting.engine == chosen.setting.engine &&
                (r.setting.ladder != chosen.setting.ladder || r.setting.x > chosen.setting.x) &&
                r.decision == Decision::Unresolved && r.ok() > 0 && r.cost() < chosen.cost() &&
                (!best || r.cost() < best->cost()))
                best = &r;
    return best;
}

/// What keeps an open rung open: its unresolved observable nearest its tolerance's edge, in
/// tolerances, and its replicas ("p at 0.98 +- 0.034 tolerances, 128 replicas").
std::string openBecause(const Rung& r) {
    const ObservableBias* edge = nullptr;
    for (const auto& b : r.biases)
        if (b.decision == Decision::Unresolved && b.tolerance > 0.0 &&
            (!edge || std::abs(std::abs(b.bias.mean) / b.tolerance - 1.0) <
                          std::abs(std::abs(edge->bias.mean) / edge->tolerance - 1.0)))
            edge = &b;
    const std::string replicas = std::to_string(r.replicas.size()) + " replicas";
    if (!edge) return replicas;
    return formatText("%s at %.3g +- %.2g tolerances, %s", observableName(edge->observable),
                      edge->bias.mean / edge->tolerance, edge->bias.err / edge->tolerance,
                      replicas.c_str());
}

/// Whether one engine's cheapest Within rung costs less, by dominanceMargin at the bias runs'
/// N, than any setting of the other engine could cost within tolerance.
std::optional<Dominance> dominance(const Tradeoff& t) {
    for (const std::string engine : {"smd", "dmd"}) {
        const Rung* chosen = cheapestOf(t, engine);
        if (!chosen || !std::isfinite(chosen->cost())) continue;
        const auto [other, ladders] = laddersOf(t, engine == "smd" ? "dmd" : "smd");
        if (other.empty()) continue;
        const auto floor = engineCostFloor(other, t.z);
        if (!floor || !(floor->cost >= dominanceMargin * chosen->cost())) continue;
        Dominance d{chosen, &(*ladders[floor->ladder])[floor->rung], *floor, {}};
        for (int l = 0; l < int(other.size()); ++l) {
            const auto f = ladderCostFloor(other[l], l, t.z);
            d.ladderEnd = d.ladderEnd || (f && f->ladderEnd);
            if (f && l != floor->ladder && f->cost <= rivalFactor * floor->cost)
                d.rivals.push_back({&(*ladders[l])[f->rung], *f});
        }
        return d;
    }
    return std::nullopt;
}

} // namespace

std::string costComparison(const std::string& dmd, const std::string& smd,
                           const analysis::RatioInterval& ratio) {
    if (ratio.lo <= 1.0 && ratio.hi >= 1.0)
        return formatText("neither engine is resolved cheaper: %s costs %.2fx (%.2f-%.2f, %.0f %%) "
                          "what %s costs",
                          dmd.c_str(), ratio.median, ratio.lo, ratio.hi, 100.0 * ratio.level,
                          smd.c_str());
    if (ratio.median >= 1.0)
        return formatText("%s is %.2fx (%.2f-%.2f, %.0f %%) cheaper than %s", smd.c_str(),
                          ratio.median, ratio.lo, ratio.hi, 100.0 * ratio.level, dmd.c_str());
    return formatText("%s is %.2fx (%.2f-%.2f, %.0f %%) cheaper than %s", dmd.c_str(),
                      1.0 / ratio.median, 1.0 / ratio.hi, 1.0 / ratio.lo, 100.0 * ratio.level,
                      smd.c_str());
}

int runTradeoff(const TradeoffOptions& options) {
    Tradeoff t;
    t.options = options;
    t.scene = options.scenePath.empty() ? sceneFromJson(nlohmann::json::object(),
                                                        "<built-in default scene>", options.sets)
                                        : loadScene(options.scenePath.string(), options.sets);
    // Its runs' CSVs are read by their real-unit columns (t_ps), and its tolerances and report
    // are in real units: a scene in reduced units would fail every run one by one.
    if (t.scene.units != "real")
        throw SceneError("units: terrace tradeoff measures in real units; leave units out (or "
                         "set units=real): state.temperature and state.density are reduced "
                         "under both");
    t.biasBodies = options.biasN > 0 ? options.biasN : t.scene.state.n;
    const std::string biasSet =
        options.biasN > 0 ? "state.n=" + std::to_string(options.biasN) : std::string();
    const bool rotating = t.scene.body.kind != "sphere";
    for (const Observable o : allObservables)
        if (o != Observable::TauO || rotating) t.observables.push_back(o);
    if (!options.observables.empty()) t.observables = options.observables;
    for (const Observable o : t.observables)
        if (o == Observable::TauO && !rotating)
            throw SceneError("--observables: tau_o needs bodies that rotate, and " +
                             t.scene.body.kind + "s do not");
    for (const Observable o : t.observables)
        t.tolerance[o] = defaultTolerance(o);
    for (const auto& [o, tol] : options.tolerances)
        t.tolerance[o] = tol;
    t.schedule = analysis::lookSchedule(2, options.maxReplicas);
    t.z = analysis::sequentialZ(options.alpha, int(t.schedule.size()));
    const TradeoffLadders plan = tradeoffLadders(t.scene, options);
    t.reference.setting = plan.reference;
    t.reference.target = std::min(8, options.maxReplicas); // its dof bounds every decision's
    for (const auto& ladder : plan.ladders) {
        std::vector<Rung> rungs;
        for (const auto& s : ladder) {
            if (s.engine == "dmd") { // a terracing the engine would refuse is no candidate
                std::vector<std::string> sets = options.sets;
                if (!biasSet.empty()) sets.push_back(biasSet);
                for (const auto& o : s.overrides)
                    sets.push_back(overrideArgument(o));
                const Scene rungScene =
                    options.scenePath.empty()
                        ? sceneFromJson(nlohmann::json::object(), "<built-in>", sets)
                        : loadScene(options.scenePath.string(), sets);
                const std::string why = dmdRefusal(rungScene);
                if (!why.empty()) {
                    t.notes.push_back(s.label() + " left out: " + why);
                    continue;
                }
            }
            Rung r;
            r.setting = s;
            r.target = t.schedule.front();
            rungs.push_back(r);
        }
        t.ladders.push_back(std::move(rungs));
    }
    std::filesystem::create_directories(t.runs());
    int settingCount = 0;
    for (const auto& ladder : t.ladders)
        settingCount += int(ladder.size());
    if (!options.quiet)
        std::fprintf(stderr,
                     "tradeoff: %s, bias at N = %d, %d settings on %zu ladders, reference %s; "
                     "z = %.3g over %zu looks of at most %d replicas\n",
                     t.scene.name.c_str(), t.biasBodies, settingCount, t.ladders.size(),
                     describe(plan.reference, t).c_str(), t.z, t.schedule.size(),
                     options.maxReplicas);

    nlohmann::json costRecord; // the last cost window timed
    // The cost window: a DMD and an SMD setting at the scene's N, alternated A B A B, one run at
    // a time, each pair a sweep of its own; the ratio DMD/SMD with its interval.
    const auto costWindow = [&](const Setting& a, const Setting& b, const char* kind,
                                analysis::RatioInterval& ratio) -> int {
        std::vector<double> costA, costB;
        for (int p = 1; p <= options.costPairs; ++p) {
            std::vector<CaseRun> pair;
            for (const Setting* s : {&a, &b})
                pair.push_back({s, 1000 + p, "cost-" + s->label() + "_p" + std::to_string(p)});
            const int s = runCases(t, pair, "", 1, false);
            if (s >= 128) return s;
            const ReplicaResult ra =
                readReplica(t.runs() / pair[0].label, t.scene.state.n, t.scene.potential.epsilon);
            const ReplicaResult rb =
                readReplica(t.runs() / pair[1].label, t.scene.state.n, t.scene.potential.epsilon);
            if (std::isfinite(ra.cpuPerPs) && std::isfinite(rb.cpuPerPs) && ra.cpuPerPs > 0 &&
                rb.cpuPerPs > 0)
                costA.push_back(ra.cpuPerPs), costB.push_back(rb.cpuPerPs);
        }
        ratio = analysis::pairedRatio(costA, costB);
        costRecord = {{"kind", kind},
                      {"dmd", a.label()},
                      {"smd", b.label()},
                      {"dmd_cpu_s_per_ps", costA},
                      {"smd_cpu_s_per_ps", costB},
                      {"ratio_dmd_over_smd", ratio.median},
                      {"ratio_lo", ratio.lo},
                      {"ratio_hi", ratio.hi},
                      {"ratio_level", ratio.level},
                      {"pairs", ratio.pairs}};
        return 0;
    };

    // One engine's chosen setting against the other's cost floor: the chosen engine's advantage,
    // the floor's cost over the chosen one's, with its interval.
    // Each rival floor is timed as well, and the weakest advantage (the lowest end of its
    // interval) is the one the verdict states: d.bound and d.floor become its.
    const auto timeDominance = [&](Dominance& d, analysis::RatioInterval& ratio) -> int {
        const auto one = [&](const Rung* bound, analysis::RatioInterval& advantage) -> int {
            const bool dmdBound = bound->setting.engine == "dmd";
            analysis::RatioInterval r;
            if (const int s = dmdBound
                                  ? costWindow(bound->setting, d.chosen->setting, "at_least", r)
                                  : costWindow(d.chosen->setting, bound->setting, "at_least", r))
                return s;
            advantage = dmdBound ? r
                                 : analysis::RatioInterval{1.0 / r.median, 1.0 / r.hi, 1.0 / r.lo,
                                                           r.pairs, r.level};
            return 0;
        };
        if (const int s = one(d.bound, ratio)) return s;
        nlohmann::json weakest = costRecord;
        for (const auto& [rung, floor] : d.rivals) {
            analysis::RatioInterval r;
            if (const int s = one(rung, r)) return s;
            if (r.lo < ratio.lo) ratio = r, d.bound = rung, d.floor = floor, weakest = costRecord;
        }
        costRecord = weakest;
        costRecord["cheaper"] = d.chosen->setting.engine;
        costRecord["rivals_timed"] = d.rivals.size();
        return 0;
    };

    bool budgetSpent = false, stoppedByDominance = false;
    for (int round = 1;; ++round) {
        std::vector<const Rung*> all{&t.reference};
        for (const auto& ladder : t.ladders)
            for (const Rung& r : ladder)
                if (r.target > 0) all.push_back(&r);
        const int status = runPending(t, all, biasSet);
        if (status >= 128) return status;
        t.cpuSpent = 0.0;
        readRung(t, t.reference, t.biasBodies);
        for (const auto& r : t.reference.replicas)
            if (std::isfinite(r.cpuSeconds)) t.cpuSpent += r.cpuSeconds;
        for (auto& ladder : t.ladders)
            for (Rung& r : ladder) {
                readRung(t, r, t.biasBodies);
                for (const auto& x : r.replicas)
                    if (std::isfinite(x.cpuSeconds)) t.cpuSpent += x.cpuSeconds;
            }
        {
            std::vector<std::vector<ReplicaResult>*> sets{&t.reference.replicas};
            for (auto& ladder : t.ladders)
                for (Rung& r : ladder)
                    sets.push_back(&r.replicas);
            setPeakHeights(sets);
        }
        if (t.reference.ok() < 2) {
            std::fprintf(stderr, "tradeoff: the reference (%s) has fewer than two good runs: %s\n",
                         describe(t.reference.setting, t).c_str(),
                         t.reference.replicas.empty()
                             ? "none ran"
                             : t.reference.replicas.front().failure.c_str());
            return 1;
        }
        chooseEstimators(t);
        for (auto& ladder : t.ladders)
            for (Rung& r : ladder)
                judge(t, r);
        writeTable(t);
        nlohmann::json partial = report(t);
        partial["verdict"] = "not reached yet: round " + std::to_string(round) + " done";
        writeFileAtomically(options.out / "tradeoff.json", partial.dump(2) + "\n");
        // One engine already cheaper than any setting of the other could be, at the bias runs' N:
        // timed at the scene's N, a resolved advantage ends the tradeoff.
        if (!options.frontier)
            if (auto d = dominance(t)) {
                analysis::RatioInterval r;
                if (const int s = timeDominance(*d, r)) return s;
                if (r.lo > 1.0) {
                    stoppedByDominance = true;
                    break;
                }
                if (!options.quiet)
                    std::fprintf(stderr,
                                 "tradeoff: %s is not resolved cheaper than %s at N %d (%.2fx, "
                                 "%.2f-%.2f); going on\n",
                                 d->chosen->setting.label().c_str(),
                                 d->bound->setting.label().c_str(), t.scene.state.n, r.median, r.lo,
                                 r.hi);
            }
        if (t.cpuSpent > options.budgetCpuHours * 3600.0) {
            budgetSpent = true;
            break;
        }
        bool more = raiseReference(t);
        more = raiseTargets(t) || more;
        if (!more) { // every ladder decided as far as it can be: place settings by the laws
            bool placed = false;
            for (auto& ladder : t.ladders)
                placed = interpolate(t, ladder) || extrapolate(t, ladder) || placed;
            more = placed && raiseTargets(t);
        }
        if (!more) break;
        if (!fitBudget(t)) {
            budgetSpent = true;
            break;
        }
        if (!options.quiet)
            std::fprintf(stderr,
                         "tradeoff: round %d done, %.0f CPU s spent; more replicas for "
                         "the unresolved settings\n",
                         round, t.cpuSpent);
    }
    if (budgetSpent)
        t.notes.push_back("the CPU budget (" + showNumber(options.budgetCpuHours) +
                          " h) was spent before every decision was resolved");

    nlohmann::json out = report(t);

    // The reference's own dt error, bounded through yoshida4 at twice its step.
    if (const Rung* r = referenceCheckRung(t)) {
        nlohmann::json check = nlohmann::json::object();
        for (const auto& b : r->biases)
            check[observableName(b.observable)] = {
                {"bias_at_twice_dt", b.bias.mean},
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

    const Rung* dmd = cheapestOf(t, "dmd");
    const Rung* smd = cheapestOf(t, "smd");
    std::optional<Dominance> dom = options.frontier ? std::nullopt : dominance(t);
    std::string verdict;
    int status = 0;
    if (dom && (stoppedByDominance || !dmd || !smd)) {
        // One engine is cheaper than any setting of the other could be: the ratio to the other's
        // cost floor is a lower bound on the true one.
        analysis::RatioInterval ratio; // the runs of a window timed in the loop are reused
        if (const int s = timeDominance(*dom, ratio)) return s;
        out["cost"] = costRecord;
        const std::string other = dom->bound->setting.engine == "dmd" ? "DMD" : "SMD";
        const std::string why =
            dom->floor.within ? formatText("%s's cheapest setting within is %s", other.c_str(),
                                           describe(dom->bound->setting, t).c_str())
            : dom->floor.ladderEnd
                ? formatText(
                      "%s's coarsest setting%s, %s, is the floor: none of that ladder's "
                      "settings is resolved outside with a bias that grows, and none coarser "
                      "is a candidate",
                      other.c_str(), other == "SMD" ? " short of the stability limit" : "",
                      describe(dom->bound->setting, t).c_str())
                : formatText("%s's most accurate setting that bounds it, %s, is outside on %s by "
                             "%.3g +- %.2g tolerances, and its bias grows on the coarser settings",
                             other.c_str(), describe(dom->bound->setting, t).c_str(),
                             observableName(dom->floor.ruling.observable),
                             dom->floor.ruling.bias.mean / dom->floor.ruling.tolerance,
                             dom->floor.ruling.bias.err / dom->floor.ruling.tolerance);
        out["cost"]["bound"] = {{"setting", dom->bound->setting.label()},
                                {"within", dom->floor.within},
                                {"ladder_end", dom->ladderEnd}};
        if (!dom->floor.within && !dom->floor.ladderEnd)
            out["cost"]["bound"]["ruling"] =
                biasJson(dom->floor.ruling, dom->bound->setting.engine);
        if (ratio.lo > 1.0) {
            verdict =
                formatText("%s is at least %.2fx (%.2f-%.2f, %.0f %%) cheaper than any %s setting "
                           "%s at %s (N %d): %s",
                           describe(dom->chosen->setting, t).c_str(), ratio.median, ratio.lo,
                           ratio.hi, 100.0 * ratio.level, other.c_str(),
                           dom->ladderEnd ? "within tolerance no coarser than its ladders' coarsest"
                                          : "within tolerance",
                           toleranceText(t).c_str(), t.scene.state.n, why.c_str());
        } else {
            verdict =
                formatText("no verdict: at N %d the cost window does not resolve %s (%.2fx, "
                           "%.2f-%.2f) as cheaper than %s, the floor of %s's cost at %s",
                           t.scene.state.n, describe(dom->chosen->setting, t).c_str(), ratio.median,
                           ratio.lo, ratio.hi, describe(dom->bound->setting, t).c_str(),
                           other.c_str(), toleranceText(t).c_str());
            if (!dmd || !smd) // what was resolved within is still an answer: the setting to use
                verdict += formatText("; the cheapest within: %s, %.3g CPU s per ps at N %d",
                                      describe(dom->chosen->setting, t).c_str(),
                                      dom->chosen->cost(), t.biasBodies);
            status = 1;
        }
    } else if (!dmd || !smd) {
        verdict = std::string("no verdict: ") +
                  (!dmd && !smd ? "no setting of either engine"
                   : !dmd       ? "no DMD setting"
                                : "no SMD setting") +
                  " was resolved within tolerance at " + toleranceText(t);
        if (!dmd) verdict += "; DMD: " + unresolvedSummary(t, "dmd");
        if (!smd) verdict += "; SMD: " + unresolvedSummary(t, "smd");
        // What the other engine found is still an answer: the setting to use.
        if (const Rung* found = dmd ? dmd : smd) {
            verdict += formatText("; the cheapest within: %s, %.3g CPU s per ps at N %d",
                                  describe(found->setting, t).c_str(), found->cost(), t.biasBodies);
        }
        status = 1;
    } else {
        analysis::RatioInterval ratio;
        if (const int s = costWindow(dmd->setting, smd->setting, "ratio", ratio)) return s;
        out["cost"] = costRecord;
        out["cost"]["cheaper_resolved"] = ratio.lo > 1.0 || ratio.hi < 1.0;
        const std::string comparison =
            costComparison(describe(dmd->setting, t), describe(smd->setting, t), ratio);
        verdict =
            comparison + " at " + toleranceText(t) + " (N " + std::to_string(t.scene.state.n) + ")";
        // A cheaper rung left open makes the chosen ratio one end of the equal-accuracy one.
        const Rung* dmdOpen = cheapestOpen(t, *dmd);
        const Rung* smdOpen = cheapestOpen(t, *smd);
        if (dmdOpen || smdOpen) {
            const double dmdShare = dmdOpen ? dmdOpen->cost() / dmd->cost() : 1.0;
            const double smdShare = smdOpen ? smdOpen->cost() / smd->cost() : 1.0;
            const OpenRungVerdict v = openRungVerdict(ratio, dmdShare, smdShare);
            std::string open;
            nlohmann::json openJson = nlohmann::json::array();
            for (const Rung* r : {dmdOpen, smdOpen}) {
                if (!r) continue;
                const Rung* chosen = r->setting.engine == "dmd" ? dmd : smd;
                open +=
                    formatText("%s%s, at %.2g of its cost (from the bias runs), is not resolved "
                               "(%s)",
                               open.empty() ? "" : "; ", describe(r->setting, t).c_str(),
                               r->cost() / chosen->cost(), openBecause(*r).c_str());
                openJson.push_back({{"setting", r->setting.label()},
                                    {"cost_share", r->cost() / chosen->cost()},
                                    {"replicas", r->replicas.size()}});
            }
            out["cost"]["open"] = openJson;
            out["cost"]["chosen_ratio_dmd_over_smd"] = ratio.median;
            out["cost"]["chosen_ratio_lo"] = ratio.lo;
            out["cost"]["chosen_ratio_hi"] = ratio.hi;
            // Whether an engine is resolved cheaper at equal accuracy, not between the chosen two.
            out["cost"]["cheaper_resolved"] = v.cheaper != OpenRungVerdict::Cheaper::Neither;
            if (v.cheaper == OpenRungVerdict::Cheaper::Neither) {
                verdict = formatText("no verdict: the engine cheaper at equal accuracy is not "
                                     "resolved: between the settings resolved within, %s; but %s, "
                                     "which puts DMD's cost over SMD's anywhere in %.2f-%.2f, at "
                                     "%s (N %d)",
                                     comparison.c_str(), open.c_str(), v.least.lo, v.most.hi,
                                     toleranceText(t).c_str(), t.scene.state.n);
                status = 1;
            } else {
                const bool smdCheaper = v.cheaper == OpenRungVerdict::Cheaper::Smd;
                const analysis::RatioInterval& b = smdCheaper ? v.least : v.most;
                out["cost"]["kind"] = "at_least";
                out["cost"]["ratio_dmd_over_smd"] = b.median;
                out["cost"]["ratio_lo"] = b.lo;
                out["cost"]["ratio_hi"] = b.hi;
                const std::string winner = describe(smdCheaper ? smd->setting : dmd->setting, t);
                const double m = smdCheaper ? b.median : 1.0 / b.median;
                const double lo = smdCheaper ? b.lo : 1.0 / b.hi;
                const double hi = smdCheaper ? b.hi : 1.0 / b.lo;
                verdict = formatText(
                    "%s is at least %.2fx (%.2f-%.2f, %.0f %%) cheaper than any %s "
                    "setting that may be within tolerance at %s (N %d): %s; but %s",
                    winner.c_str(), m, lo, hi, 100.0 * b.level, smdCheaper ? "DMD" : "SMD",
                    toleranceText(t).c_str(), t.scene.state.n, comparison.c_str(), open.c_str());
            }
        }
    }
    out["verdict"] = verdict;
    out["notes"] = t.notes;
    writeFileAtomically(options.out / "tradeoff.json", out.dump(2) + "\n");
    writeTable(t);
    writePlot(t);
    std::printf("%s\n", verdict.c_str());
    for (const auto& n : t.notes)
        std::printf("note: %s\n", n.c_str());
    return status;
}

} // namespace terrace::cli
