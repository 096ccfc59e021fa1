#include "cli/tradeoff_dominance.hpp"
#include <cmath>

namespace terrace::cli {

namespace {

using analysis::Decision;

const ObservableBias* biasOn(const RungView& r, Observable o) {
    for (const auto& b : r.biases)
        if (b.observable == o) return &b;
    return nullptr;
}

/// Whether o's bias on every rung coarser than `at` keeps the sign it has at `at` and is never
/// resolved smaller in magnitude: what "the bias grows with x" can be checked against.
bool growsWithX(const std::vector<RungView>& ladder, int at, const ObservableBias& b, double z) {
    for (int i = 0; i < int(ladder.size()); ++i) {
        const RungView& r = ladder[i];
        if (r.x <= ladder[at].x || r.failed) continue;
        const ObservableBias* c = biasOn(r, b.observable);
        if (!c) continue;
        if (std::signbit(c->bias.mean) != std::signbit(b.bias.mean)) return false;
        if (std::abs(c->bias.mean) + z * c->bias.err < std::abs(b.bias.mean) - z * b.bias.err)
            return false;
    }
    return true;
}

} // namespace

std::optional<CostFloor> ladderCostFloor(const std::vector<RungView>& ladder, int index, double z) {
    std::optional<CostFloor> floor;
    // The most accurate Outside rung whose ruling observable grows with x.
    int order = -1;
    for (int i = 0; i < int(ladder.size()); ++i) {
        const RungView& r = ladder[i];
        if (r.failed || r.decision != Decision::Outside || !std::isfinite(r.cost)) continue;
        if (order >= 0 && ladder[order].x <= r.x) continue;
        for (const auto& b : r.biases)
            if (b.decision == Decision::Outside && growsWithX(ladder, i, b, z)) {
                order = i;
                floor = CostFloor{index, i, r.cost, false, b};
                break;
            }
    }
    if (!floor) {
        // Nothing bounds the ladder from inside, but its candidates do not go past its coarsest
        // rung short of the stability limit (the bias laws place settings between rungs or
        // below the most accurate, never above the coarsest), so, with cost falling as x grows,
        // that rung's cost bounds every setting the ladder holds. It is the coarsest, not the
        // rung timed cheapest: a finer rung timed cheaper by noise would overstate the bound.
        // Untimed, or failed for another reason (a crash says nothing of its cost), it bounds
        // nothing.
        int coarsest = -1;
        for (int i = 0; i < int(ladder.size()); ++i)
            if (!ladder[i].beyondStability && (coarsest < 0 || ladder[i].x > ladder[coarsest].x))
                coarsest = i;
        if (coarsest < 0 || ladder[coarsest].failed || !std::isfinite(ladder[coarsest].cost))
            return std::nullopt;
        floor = CostFloor{index, coarsest, ladder[coarsest].cost, false, {}, true};
    }
    // A Within rung (of any x) is a setting within tolerance: the floor cannot lie above it.
    for (int i = 0; i < int(ladder.size()); ++i)
        if (ladder[i].decision == Decision::Within && std::isfinite(ladder[i].cost) &&
            ladder[i].cost < floor->cost)
            floor = CostFloor{index, i, ladder[i].cost, true, {}, floor->ladderEnd};
    return floor;
}

std::optional<CostFloor> engineCostFloor(const std::vector<std::vector<RungView>>& ladders,
                                         double z) {
    std::optional<CostFloor> least;
    for (int l = 0; l < int(ladders.size()); ++l) {
        const auto f = ladderCostFloor(ladders[l], l, z);
        if (!f) return std::nullopt;
        if (!least || f->cost < least->cost) least = f;
    }
    return least;
}

OpenRungVerdict openRungVerdict(const analysis::RatioInterval& chosen, double dmdShare,
                                double smdShare) {
    // An open DMD rung can only lower DMD's cost, an open SMD rung only SMD's: the ratio moves
    // down by dmdShare at most and up by 1/smdShare at most.
    const auto scaled = [&](double f) {
        analysis::RatioInterval r = chosen;
        r.median *= f, r.lo *= f, r.hi *= f;
        return r;
    };
    OpenRungVerdict v{OpenRungVerdict::Cheaper::Neither, scaled(dmdShare), scaled(1.0 / smdShare)};
    if (v.least.lo > 1.0)
        v.cheaper = OpenRungVerdict::Cheaper::Smd;
    else if (v.most.hi < 1.0)
        v.cheaper = OpenRungVerdict::Cheaper::Dmd;
    return v;
}

} // namespace terrace::cli
