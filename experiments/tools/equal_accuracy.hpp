#pragma once
// Equal-accuracy efficiency (experiments/fronts.sh): how much cheaper one engine reaches a given
// error than the other.
//
// Each engine setting is a point (cost c in CPU s per simulated ps, error e against the common
// reference). An engine's Pareto front is the set of its points that no other point beats in both:
// sorted by cost, each kept point has a lower error than every cheaper one. Between two front
// points the cost to reach an error e is interpolated linearly in (ln e, ln c), as both fall
// roughly as powers of the resolution (dt or ΔV). An error below the front's best is out of the
// engine's reach (NaN); one above its cheapest point's error costs at most that point's cost, and
// is reported as that cost, flagged as a bound.
//
// The equal-accuracy efficiency of B over A at the error e is c_A(e)/c_B(e): above 1, B reaches
// the accuracy for less.
#include <filesystem>
#include <string>
#include <vector>

namespace terrace::experiments {

struct FrontPoint {
    std::string label;
    double cost = 0.0, error = 0.0;
};

/// The Pareto front of the points with finite positive cost and error, by ascending cost.
std::vector<FrontPoint> paretoFront(std::vector<FrontPoint> points);

struct CostAtError {
    double cost = 0.0;  // CPU s per ps; NaN when the error is out of reach
    bool bound = false; // the error lies above the cheapest point's: cost is an upper bound
    std::string via;    // the front point it is, or "a~b" for the two it lies between
};

/// The cost to reach error e along a front (see above).
CostAtError costAtError(const std::vector<FrontPoint>& front, double e);

/// From a fronts table (columns set, engine, design, param, cpu_s_per_ps, then err_q and floor_q
/// per quantity q, and status; rows whose status is not "ok" take no part) and the label of the
/// reference setting whose errors set the targets (e.g. smd-1.8): one CSV row per design, quantity
/// and target (the reference setting's error, and twice it) — "design,quantity,target,
/// target_error,resolved,smd_cost,design_cost,efficiency,bound,smd_via" — the SMD front against
/// each DMD design's. SMD's front is that of all its rows whatever their scheme (column design),
/// so its cost at a target is that of the cheapest scheme and dt reaching it, named in smd_via.
/// `resolved` is 0 when the reference setting's own error lies within resolvedSigmas of its
/// statistical floor (floor_q; convergence.hpp): the target is then noise, not accuracy.
std::vector<std::string> equalAccuracy(const std::filesystem::path& fronts,
                                       const std::string& targetSet);

} // namespace terrace::experiments
