#include "cli/tradeoff_choice.hpp"
#include "cli/tradeoff_report.hpp"
#include "cli/tradeoff_search.hpp"
#include "core/format_text.hpp"
#include <algorithm>
#include <cmath>
#include <map>

namespace terrace::cli {

using analysis::Decision;

namespace {

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

} // namespace

const Rung* cheapestOf(const Tradeoff& t, const std::string& engine) {
    const Rung* best = nullptr;
    for (const auto& ladder : t.ladders) {
        const int c = cheapestWithin(ladder);
        if (c < 0 || ladder[c].setting.engine != engine) continue;
        if (!best || ladder[c].cost() < best->cost()) best = &ladder[c];
    }
    return best;
}

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

} // namespace terrace::cli
