#include "cli/tradeoff_cost.hpp"
#include "cli/tradeoff_runs.hpp"
#include <cmath>
#include <string>
#include <vector>

namespace terrace::cli {

int CostWindows::timeWindow(const Setting& dmd, const Setting& smd, const char* kind,
                            analysis::RatioInterval& ratio) {
    std::vector<double> costDmd, costSmd;
    for (int p = 1; p <= t_.options.costPairs; ++p) {
        std::vector<CaseRun> pair;
        for (const Setting* s : {&dmd, &smd})
            pair.push_back({s, 1000 + p, "cost-" + s->label() + "_p" + std::to_string(p)});
        const int s = runCases(t_, pair, "", 1, RunPurpose::Cost);
        if (s >= 128) return s;
        const ReplicaResult a =
            readReplica(t_.runs() / pair[0].label, t_.scene.state.n, t_.scene.potential.epsilon);
        const ReplicaResult b =
            readReplica(t_.runs() / pair[1].label, t_.scene.state.n, t_.scene.potential.epsilon);
        if (std::isfinite(a.cpuPerPs) && std::isfinite(b.cpuPerPs) && a.cpuPerPs > 0 &&
            b.cpuPerPs > 0)
            costDmd.push_back(a.cpuPerPs), costSmd.push_back(b.cpuPerPs);
    }
    ratio = analysis::pairedRatio(costDmd, costSmd);
    record_ = {{"kind", kind},
               {"dmd", dmd.label()},
               {"smd", smd.label()},
               {"dmd_cpu_s_per_ps", costDmd},
               {"smd_cpu_s_per_ps", costSmd},
               {"ratio_dmd_over_smd", ratio.median},
               {"ratio_lo", ratio.lo},
               {"ratio_hi", ratio.hi},
               {"ratio_level", ratio.level},
               {"pairs", ratio.pairs}};
    return 0;
}

int CostWindows::timeDominance(Dominance& d, analysis::RatioInterval& advantage) {
    // The chosen engine's advantage over a rung of the other: the window's ratio, DMD's cost
    // over SMD's, turned so that it is the bounding rung's cost over the chosen one's.
    const auto one = [&](const Rung* bound, analysis::RatioInterval& a) -> int {
        const bool dmdBound = bound->setting.engine == "dmd";
        analysis::RatioInterval r;
        if (const int s = dmdBound ? timeWindow(bound->setting, d.chosen->setting, "at_least", r)
                                   : timeWindow(d.chosen->setting, bound->setting, "at_least", r))
            return s;
        a = dmdBound
                ? r
                : analysis::RatioInterval{1.0 / r.median, 1.0 / r.hi, 1.0 / r.lo, r.pairs, r.level};
        return 0;
    };
    if (const int s = one(d.bound, advantage)) return s;
    nlohmann::json weakest = record_;
    for (const auto& [rung, floor] : d.rivals) {
        analysis::RatioInterval r;
        if (const int s = one(rung, r)) return s;
        if (r.lo < advantage.lo) advantage = r, d.bound = rung, d.floor = floor, weakest = record_;
    }
    record_ = weakest;
    record_["cheaper"] = d.chosen->setting.engine;
    record_["rivals_timed"] = d.rivals.size();
    return 0;
}

} // namespace terrace::cli
