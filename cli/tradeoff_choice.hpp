#pragma once
// Which settings `terrace tradeoff`'s verdict compares, from the search's state
// (cli/tradeoff_state.hpp): each engine's cheapest setting within tolerance, the other engine's
// cost floor where one engine is already cheaper than any setting of it could be
// (cli/tradeoff_dominance.hpp), the rungs left open below a chosen one, and why an engine has
// none within.
#include "cli/tradeoff_dominance.hpp"
#include "cli/tradeoff_state.hpp"
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace terrace::cli {

/// An engine's cheapest Within rung over its ladders, or null.
const Rung* cheapestOf(const Tradeoff& t, const std::string& engine);

/// One engine's chosen setting and the other engine's cost floor above it
/// (cli/tradeoff_dominance.hpp).
struct Dominance {
    const Rung* chosen = nullptr; // the cheaper engine's cheapest Within rung
    const Rung* bound = nullptr;  // the rung whose cost bounds the other engine's from below
    CostFloor floor;
    // The other ladders' floors within rivalFactor (1.5) of the least at the bias runs' N: at the
    // scene's N any of them may be the cheapest, so each is timed and the weakest bound kept.
    std::vector<std::pair<const Rung*, CostFloor>> rivals;
    // Some ladder of the other engine is bounded only by its coarsest rung: the claim covers
    // settings no coarser than its ladders' (whichever floor is stated).
    bool ladderEnd = false;
};

/// Whether one engine's cheapest Within rung costs less, by dominanceMargin at the bias runs'
/// N, than any setting of the other engine could cost within tolerance.
std::optional<Dominance> dominance(const Tradeoff& t);

/// Why an engine has no setting within: per observable, on how many of its settings not resolved
/// outside it is still unresolved, and the most replicas those have ("unresolved g_peak on 8 of
/// its 8 settings not outside, at up to 128 replicas"); or that every setting is outside.
std::string unresolvedSummary(const Tradeoff& t, const std::string& engine);

/// The cheapest rung of an engine still Unresolved and cheaper than `chosen`: it may be within
/// tolerance (cli/tradeoff_dominance.hpp, openRungVerdict); nullptr when there is none. A rung
/// of the chosen one's own ladder counts only where it is coarser: cost falls as x grows along
/// a ladder, so a finer one timed cheaper is noise.
const Rung* cheapestOpen(const Tradeoff& t, const Rung& chosen);

/// What keeps an open rung open: its unresolved observable nearest its tolerance's edge, in
/// tolerances, and its replicas ("p at 0.98 +- 0.034 tolerances, 128 replicas").
std::string openBecause(const Rung& r);

} // namespace terrace::cli
