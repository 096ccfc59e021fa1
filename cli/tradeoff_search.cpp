#include "cli/tradeoff_search.hpp"
#include "cli/tradeoff_schedule.hpp"
#include "core/scene_json.hpp"
#include <algorithm>
#include <cmath>
#include <limits>

namespace terrace::cli {

using analysis::Decision;

namespace {

std::optional<ObservableBias> biasOf(const Tradeoff& t, const Rung& r, Observable o, Estimator e) {
    if (o == Observable::G)
        return curveBias(e, r.replicas, t.reference.replicas, t.tolerance.at(o).value, t.z);
    return scalarBias(o, e, r.replicas, t.reference.replicas, t.tolerance.at(o), t.scaleFloor(o),
                      t.z);
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

/// Whether more replicas of that rung could still show it: no bias already too large for the
/// bound, whatever its error.
bool referenceCheckOpen(const Rung& rung) {
    for (const auto& b : rung.biases)
        if (referenceBiasBound(b, -2.0) >= 0.25 * b.tolerance) return false;
    return !referenceShownConverged(rung);
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

} // namespace

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

void judge(const Tradeoff& t, Rung& r) {
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
        const Estimator e = r.setting.engine == "dmd" ? t.dmdEstimator.at(o) : Estimator::Own;
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

int cheapestWithin(const std::vector<Rung>& ladder) {
    int c = -1;
    for (int i = 0; i < int(ladder.size()); ++i)
        if (ladder[i].decision == Decision::Within) c = i;
    return c;
}

double referenceBiasBound(const ObservableBias& b, double sigmas) {
    return (std::abs(b.bias.mean) + sigmas * b.bias.err) / 15.0;
}

bool referenceShownConverged(const Rung& rung) {
    bool within = !rung.biases.empty();
    for (const auto& b : rung.biases)
        within = within && referenceBiasBound(b, 2.0) < 0.25 * b.tolerance;
    return within;
}

const Rung* referenceCheckRung(const Tradeoff& t) {
    for (const auto& ladder : t.ladders)
        for (const Rung& r : ladder)
            if (r.setting.ladder == "smd-yoshida4" &&
                std::abs(r.setting.x - 2.0 * t.reference.setting.x) < 1e-9 * r.setting.x)
                return &r;
    return nullptr;
}

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

} // namespace terrace::cli
