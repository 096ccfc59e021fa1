#include "cli/tradeoff_verdict.hpp"
#include "cli/tradeoff_choice.hpp"
#include "cli/tradeoff_report.hpp"
#include "core/format_text.hpp"
#include <string>

namespace terrace::cli {

namespace {

/// One engine is cheaper than any setting of the other could be: the ratio to the other's
/// cost floor is a lower bound on the true one. `dmd`, `smd`: each engine's cheapest within.
int floorVerdict(const Tradeoff& t, CostWindows& cost, Dominance& dom, const Rung* dmd,
                 const Rung* smd, nlohmann::json& out, Verdict& result) {
    analysis::RatioInterval ratio; // the runs of a window timed in the loop are reused
    if (const int s = cost.timeDominance(dom, ratio)) return s;
    out["cost"] = cost.record();
    const std::string other = dom.bound->setting.engine == "dmd" ? "DMD" : "SMD";
    const std::string why =
        dom.floor.within ? formatText("%s's cheapest setting within is %s", other.c_str(),
                                      describe(dom.bound->setting, t).c_str())
        : dom.floor.ladderEnd
            ? formatText("%s's coarsest setting%s, %s, is the floor: none of that ladder's "
                         "settings is resolved outside with a bias that grows, and none coarser "
                         "is a candidate",
                         other.c_str(), other == "SMD" ? " short of the stability limit" : "",
                         describe(dom.bound->setting, t).c_str())
            : formatText("%s's most accurate setting that bounds it, %s, is outside on %s by "
                         "%.3g +- %.2g tolerances, and its bias grows on the coarser settings",
                         other.c_str(), describe(dom.bound->setting, t).c_str(),
                         observableName(dom.floor.ruling.observable),
                         dom.floor.ruling.bias.mean / dom.floor.ruling.tolerance,
                         dom.floor.ruling.bias.err / dom.floor.ruling.tolerance);
    out["cost"]["bound"] = {{"setting", dom.bound->setting.label()},
                            {"within", dom.floor.within},
                            {"ladder_end", dom.ladderEnd}};
    if (!dom.floor.within && !dom.floor.ladderEnd)
        out["cost"]["bound"]["ruling"] = biasJson(dom.floor.ruling, dom.bound->setting.engine);
    if (ratio.lo > 1.0) {
        result.text =
            formatText("%s is at least %.2fx (%.2f-%.2f, %.0f %%) cheaper than any %s setting "
                       "%s at %s (N %d): %s",
                       describe(dom.chosen->setting, t).c_str(), ratio.median, ratio.lo, ratio.hi,
                       100.0 * ratio.level, other.c_str(),
                       dom.ladderEnd ? "within tolerance no coarser than its ladders' coarsest"
                                     : "within tolerance",
                       toleranceText(t).c_str(), t.scene.state.n, why.c_str());
    } else {
        result.text =
            formatText("no verdict: at N %d the cost window does not resolve %s (%.2fx, "
                       "%.2f-%.2f) as cheaper than %s, the floor of %s's cost at %s",
                       t.scene.state.n, describe(dom.chosen->setting, t).c_str(), ratio.median,
                       ratio.lo, ratio.hi, describe(dom.bound->setting, t).c_str(), other.c_str(),
                       toleranceText(t).c_str());
        if (!dmd || !smd) // what was resolved within is still an answer: the setting to use
            result.text += formatText("; the cheapest within: %s, %.3g CPU s per ps at N %d",
                                      describe(dom.chosen->setting, t).c_str(), dom.chosen->cost(),
                                      t.biasBodies);
        result.status = 1;
    }
    return 0;
}

/// An engine with no setting within: no verdict, with why, and the other engine's choice.
void missingVerdict(const Tradeoff& t, const Rung* dmd, const Rung* smd, Verdict& result) {
    result.text = std::string("no verdict: ") +
                  (!dmd && !smd ? "no setting of either engine"
                   : !dmd       ? "no DMD setting"
                                : "no SMD setting") +
                  " was resolved within tolerance at " + toleranceText(t);
    if (!dmd) result.text += "; DMD: " + unresolvedSummary(t, "dmd");
    if (!smd) result.text += "; SMD: " + unresolvedSummary(t, "smd");
    // What the other engine found is still an answer: the setting to use.
    if (const Rung* found = dmd ? dmd : smd) {
        result.text += formatText("; the cheapest within: %s, %.3g CPU s per ps at N %d",
                                  describe(found->setting, t).c_str(), found->cost(), t.biasBodies);
    }
    result.status = 1;
}

/// Both engines' cheapest settings within, timed against each other.
int ratioVerdict(const Tradeoff& t, CostWindows& cost, const Rung* dmd, const Rung* smd,
                 nlohmann::json& out, Verdict& result) {
    analysis::RatioInterval ratio;
    if (const int s = cost.timeWindow(dmd->setting, smd->setting, "ratio", ratio)) return s;
    out["cost"] = cost.record();
    out["cost"]["cheaper_resolved"] = ratio.lo > 1.0 || ratio.hi < 1.0;
    const std::string comparison =
        costComparison(describe(dmd->setting, t), describe(smd->setting, t), ratio);
    result.text =
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
            open += formatText("%s%s, at %.2g of its cost (from the bias runs), is not resolved "
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
            result.text = formatText("no verdict: the engine cheaper at equal accuracy is not "
                                     "resolved: between the settings resolved within, %s; but %s, "
                                     "which puts DMD's cost over SMD's anywhere in %.2f-%.2f, at "
                                     "%s (N %d)",
                                     comparison.c_str(), open.c_str(), v.least.lo, v.most.hi,
                                     toleranceText(t).c_str(), t.scene.state.n);
            result.status = 1;
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
            result.text = formatText(
                "%s is at least %.2fx (%.2f-%.2f, %.0f %%) cheaper than any %s "
                "setting that may be within tolerance at %s (N %d): %s; but %s",
                winner.c_str(), m, lo, hi, 100.0 * b.level, smdCheaper ? "DMD" : "SMD",
                toleranceText(t).c_str(), t.scene.state.n, comparison.c_str(), open.c_str());
        }
    }
    return 0;
}

} // namespace

int drawVerdict(const Tradeoff& t, CostWindows& cost, bool stoppedByDominance, nlohmann::json& out,
                Verdict& verdict) {
    const Rung* dmd = cheapestOf(t, "dmd");
    const Rung* smd = cheapestOf(t, "smd");
    std::optional<Dominance> dom = t.options.frontier ? std::nullopt : dominance(t);
    if (dom && (stoppedByDominance || !dmd || !smd))
        return floorVerdict(t, cost, *dom, dmd, smd, out, verdict);
    if (!dmd || !smd) {
        missingVerdict(t, dmd, smd, verdict);
        return 0;
    }
    return ratioVerdict(t, cost, dmd, smd, out, verdict);
}

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

} // namespace terrace::cli
