#pragma once
// When one engine's answer makes the other's unnecessary: `terrace tradeoff` need not resolve
// the cheapest DMD setting within tolerance once every DMD setting that could be within costs
// more than an SMD setting already resolved within (or the other way round).
//
// Along a ladder (most accurate first, x = ΔV/kT or dt ascending) cost falls as x grows and so,
// by the bias laws, does accuracy. A rung resolved Outside on an observable whose bias grows
// with x on the coarser rungs (same sign, never resolved smaller) bounds the ladder: every
// setting within tolerance has a smaller x, so costs at least that rung. The least such floor
// over an engine's ladders (a ladder with a Within rung counts that rung's cost too; a ladder
// with no Outside rung that bounds it is bounded by its coarsest rung short of the stability
// limit: no candidate lies above it, the bias laws placing settings only between rungs or below
// the most accurate) bounds the engine's cost at the tolerance from below. When it is above the
// other engine's chosen cost, the question "which is cheaper" is answered with a ratio that is
// itself a lower bound: it says "at least".
#include "analysis/tradeoff_stats.hpp"
#include "cli/tradeoff_measure.hpp"
#include <optional>
#include <vector>

namespace terrace::cli {

/// What the floor needs to know of a rung.
struct RungView {
    double x = 0.0;
    double cost = 0.0; // CPU s per simulated ps (NaN: not measured)
    analysis::Decision decision = analysis::Decision::Unresolved;
    bool failed = false;          // its runs failed: no cost, no bias
    bool beyondStability = false; // failed at SMD's stability limit: no candidate, ends no ladder
    std::vector<ObservableBias> biases;
};

/// The rung bounding a ladder's cost at the tolerance from below.
struct CostFloor {
    int ladder = -1, rung = -1; // indices into the ladders given
    double cost = 0.0;
    bool within = false;   // the floor is a Within rung's own cost (not an Outside rung's)
    ObservableBias ruling; // the observable that rules the Outside rung out (within: unset)
    // Nothing is ruled out on this ladder: its coarsest rung bounds it, within tolerance or not,
    // and the claim covers only settings no coarser (kept where a Within rung is the floor).
    bool ladderEnd = false;
};

/// A ladder's floor (ladder index `index` copied into the result), or nullopt when it has none:
/// nothing bounds it from inside and its coarsest rung short of the stability limit has no cost
/// yet, or failed otherwise (a crash bounds nothing), or every rung is past the limit.
/// `z` is the tradeoff's normal deviate: a coarser rung's |bias| contradicts the growth when it
/// is resolved below the floor rung's, |b| + z·σ_b < |b_o| − z·σ_o.
std::optional<CostFloor> ladderCostFloor(const std::vector<RungView>& ladder, int index, double z);

/// The least floor over an engine's ladders; nullopt when any of them has none.
std::optional<CostFloor> engineCostFloor(const std::vector<std::vector<RungView>>& ladders,
                                         double z);

/// The verdict when rungs are left open. An engine's rung still Unresolved when the search ends
/// (the budget spent, or the replica limit met at the tolerance's edge) and cheaper than that
/// engine's chosen setting may be within tolerance: the engine's cost at the tolerance then lies
/// between that rung's and the chosen one's, and the window's ratio of the chosen settings is
/// only one end of the equal-accuracy ratio. `dmdShare` is the cheapest open DMD rung's cost over
/// DMD's chosen one (1 when none is open), `smdShare` likewise, both at the bias runs' N.
struct OpenRungVerdict {
    enum class Cheaper { Smd, Dmd, Neither } cheaper = Cheaper::Neither;
    // DMD's cost over SMD's at the end that the open rungs could move it to: the bound (from
    // below when SMD is the cheaper, from above when DMD is); when neither is resolved cheaper,
    // the whole range, [least.lo, most.hi].
    analysis::RatioInterval least, most;
};
OpenRungVerdict openRungVerdict(const analysis::RatioInterval& chosen, double dmdShare,
                                double smdShare);

/// The early stop is tried when the other engine's floor is above the chosen cost, both as
/// measured at the bias runs' N (by this factor); the cost window at the scene's N then decides.
constexpr double dominanceMargin = 1.0;

} // namespace terrace::cli
