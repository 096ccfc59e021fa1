#include "cli/tradeoff_command.hpp"
#include "cli/design_command.hpp"
#include "cli/tradeoff_choice.hpp"
#include "cli/tradeoff_cost.hpp"
#include "cli/tradeoff_report.hpp"
#include "cli/tradeoff_runs.hpp"
#include "cli/tradeoff_search.hpp"
#include "cli/tradeoff_verdict.hpp"
#include "core/output_file.hpp"
#include "core/scene_json.hpp"
#include <algorithm>
#include <cstdio>

namespace terrace::cli {

namespace {

/// The search as it begins: the scene, the observables and their tolerances, the reference and
/// the ladders (less the DMD settings the engine would refuse, with a note why), each rung at the
/// schedule's first count of replicas.
Tradeoff beginSearch(const TradeoffOptions& options) {
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
    t.biasSet = options.biasN > 0 ? "state.n=" + std::to_string(options.biasN) : std::string();
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
                if (!t.biasSet.empty()) sets.push_back(t.biasSet);
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
    return t;
}

/// How the rounds of the search ended.
struct SearchEnd {
    bool budgetSpent = false;
    bool stoppedByDominance = false; // the early stop: one engine resolved cheaper
};

/// The rounds: run what is asked for, read it, judge every rung, write the record so far, try
/// the early stop, then ask for more replicas (or settings placed by the laws) until nothing is
/// left to ask or the budget is spent. Returns 0; 1 where the reference has fewer than two good
/// runs; 128 + a signal where one stopped a run.
int searchRounds(Tradeoff& t, CostWindows& cost, SearchEnd& end) {
    const TradeoffOptions& options = t.options;
    for (int round = 1;; ++round) {
        std::vector<const Rung*> all{&t.reference};
        for (const auto& ladder : t.ladders)
            for (const Rung& r : ladder)
                if (r.target > 0) all.push_back(&r);
        const int status = runPending(t, all);
        if (status >= 128) return status;
        readRound(t);
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
                if (const int s = cost.timeDominance(*d, r)) return s;
                if (r.lo > 1.0) {
                    end.stoppedByDominance = true;
                    return 0;
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
            end.budgetSpent = true;
            return 0;
        }
        bool more = raiseReference(t);
        more = raiseTargets(t) || more;
        if (!more) { // every ladder decided as far as it can be: place settings by the laws
            bool placed = false;
            for (auto& ladder : t.ladders)
                placed = interpolate(t, ladder) || extrapolate(t, ladder) || placed;
            more = placed && raiseTargets(t);
        }
        if (!more) return 0;
        if (!fitBudget(t)) {
            end.budgetSpent = true;
            return 0;
        }
        if (!options.quiet)
            std::fprintf(stderr,
                         "tradeoff: round %d done, %.0f CPU s spent; more replicas for "
                         "the unresolved settings\n",
                         round, t.cpuSpent);
    }
}

} // namespace

int runTradeoff(const TradeoffOptions& options) {
    Tradeoff t = beginSearch(options);
    std::filesystem::create_directories(t.runs());
    int settingCount = 0;
    for (const auto& ladder : t.ladders)
        settingCount += int(ladder.size());
    if (!options.quiet)
        std::fprintf(stderr,
                     "tradeoff: %s, bias at N = %d, %d settings on %zu ladders, reference %s; "
                     "z = %.3g over %zu looks of at most %d replicas\n",
                     t.scene.name.c_str(), t.biasBodies, settingCount, t.ladders.size(),
                     describe(t.reference.setting, t).c_str(), t.z, t.schedule.size(),
                     options.maxReplicas);

    CostWindows cost(t);
    SearchEnd end;
    if (const int s = searchRounds(t, cost, end)) return s;
    if (end.budgetSpent)
        t.notes.push_back("the CPU budget (" + showNumber(options.budgetCpuHours) +
                          " h) was spent before every decision was resolved");

    nlohmann::json out = report(t);
    reportReferenceCheck(t, out);
    Verdict verdict;
    if (const int s = drawVerdict(t, cost, end.stoppedByDominance, out, verdict)) return s;
    out["verdict"] = verdict.text;
    out["notes"] = t.notes;
    writeFileAtomically(options.out / "tradeoff.json", out.dump(2) + "\n");
    writeTable(t);
    writePlot(t);
    std::printf("%s\n", verdict.text.c_str());
    for (const auto& n : t.notes)
        std::printf("note: %s\n", n.c_str());
    return verdict.status;
}

} // namespace terrace::cli
