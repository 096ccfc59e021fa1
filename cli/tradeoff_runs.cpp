#include "cli/tradeoff_runs.hpp"
#include "cli/sweep_runner.hpp"
#include <cmath>

namespace terrace::cli {

namespace {

void readRung(Tradeoff& t, Rung& r, int bodies) {
    r.replicas.clear();
    for (int k = 1; k <= r.target; ++k)
        r.replicas.push_back(
            readReplica(t.runs() / replicaName(r.setting, k), bodies, t.scene.potential.epsilon));
}

} // namespace

int runCases(const Tradeoff& t, const std::vector<CaseRun>& runs, const std::string& extraSet,
             int jobs, RunPurpose purpose) {
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
    if (purpose == RunPurpose::Bias) common["analysis.rdf_every"] = 1;
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

int runPending(const Tradeoff& t, const std::vector<const Rung*>& rungs) {
    std::vector<CaseRun> runs;
    for (const Rung* r : rungs)
        for (int k = 1; k <= r->target; ++k)
            runs.push_back({&r->setting, k, replicaName(r->setting, k)});
    return runCases(t, runs, t.biasSet, t.options.jobs, RunPurpose::Bias);
}

void readRound(Tradeoff& t) {
    std::vector<Rung*> rungs{&t.reference};
    for (auto& ladder : t.ladders)
        for (Rung& r : ladder)
            rungs.push_back(&r);
    t.cpuSpent = 0.0;
    std::vector<std::vector<ReplicaResult>*> sets;
    for (Rung* r : rungs) {
        readRung(t, *r, t.biasBodies);
        for (const auto& x : r->replicas)
            if (std::isfinite(x.cpuSeconds)) t.cpuSpent += x.cpuSeconds;
        sets.push_back(&r->replicas);
    }
    setPeakHeights(sets);
}

} // namespace terrace::cli
