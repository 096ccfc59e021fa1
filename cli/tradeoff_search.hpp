#pragma once
// The steps of `terrace tradeoff`'s sequential search (cli/tradeoff_command.hpp), each on the
// search's state (cli/tradeoff_state.hpp) after a round's runs are read: the estimators DMD is
// judged by, each rung's decision, the replicas asked for next (within the CPU budget), the
// reference's growth and its dt check, and the settings the bias laws place.
#include "cli/tradeoff_state.hpp"

namespace terrace::cli {

/// For DMD, per observable, the estimator whose biases over the DMD rungs are the smaller
/// (Σ |bias|/tol over the rungs where both are measured).
void chooseEstimators(Tradeoff& t);

/// Rung r's bias on every observable against the reference, and its decision: Outside when one
/// is, or when a replica failed (r.failure says why: SMD's stability limit where a replica met
/// it, else the last replica's); Within when every one is; else Unresolved. DMD's rungs are
/// judged by t.dmdEstimator, so chooseEstimators runs first.
void judge(const Tradeoff& t, Rung& r);

/// The index of a ladder's cheapest Within rung, its last (cost falls as x grows along a
/// ladder); -1: none.
int cheapestWithin(const std::vector<Rung>& ladder);

/// Raises the targets of the rungs cli/tradeoff_schedule.hpp picks: per engine its cheapest open
/// rung below the cost of its cheapest Within (every ladder's open rung under --frontier), and
/// the reference's check rung until it shows the reference converged. False when none is raised.
bool raiseTargets(Tradeoff& t);

/// Takes back the raised targets whose runs would take the CPU spent past the budget, the
/// costliest first; false when none is left to run.
bool fitBudget(Tradeoff& t);

/// The reference's replicas double until its standard error is below a third of every
/// tolerance (so that it adds little to a candidate's) and below the candidate's in every open
/// decision, or the replica budget is reached. False when it is not raised.
bool raiseReference(Tradeoff& t);

/// Places a setting by the bias laws between a ladder's cheapest Within rung and the Outside
/// rung after it; false when there is nothing to place.
bool interpolate(Tradeoff& t, std::vector<Rung>& ladder);

/// A ladder with every rung resolved Outside gets one more, more accurate, rung where its bias
/// laws put the bias at the tolerance (by the margin, at most extrapolationReach below its most
/// accurate rung), checked by its own runs like any other: without it a scene whose tolerance
/// lies below the ladder gets no cost ratio. False when there is nothing to place (with a note
/// when the law puts the setting beyond reach).
bool extrapolate(Tradeoff& t, std::vector<Rung>& ladder);

/// The rung of yoshida4 at twice the reference's step, or null: it bounds the reference's own
/// dt error.
const Rung* referenceCheckRung(const Tradeoff& t);

/// The bound the reference's own dt error gets from one observable's bias on yoshida4 at twice its
/// step: by the dt⁴ law the reference's bias is 1/15 of the difference between the two, taken at
/// |bias| + sigmas·err (sigmas −2: the least the bound could still come to).
double referenceBiasBound(const ObservableBias& b, double sigmas);

/// Whether the reference's own dt error is shown small: its bound below a quarter of every
/// tolerance. `rung` is yoshida4 at twice the reference's step.
bool referenceShownConverged(const Rung& rung);

} // namespace terrace::cli
