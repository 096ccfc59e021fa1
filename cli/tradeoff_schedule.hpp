#pragma once
// Which settings `terrace tradeoff` gives more replicas next: the CPU of a tradeoff goes where it
// can change the verdict.
//
// The verdict compares each engine's cheapest setting within tolerance. A setting that costs
// more than one of its engine's settings already resolved Within can never be that choice, so
// resolving it buys nothing; and of an engine's open settings the cheapest is the one that, once
// Within, makes the rest moot. So each engine's pick is its cheapest open setting that is cheaper
// than the engine's cheapest Within (a ladder offers the setting its own walk reaches: from the
// cheap end, past the rungs resolved Outside and those at the replica limit), and each round
// raises the cheaper of the two engines' picks alone: once one engine's choice costs less than
// the other's cost floor the tradeoff stops early (cli/tradeoff_dominance.hpp), and on the LJ
// liquid at ρ* 0.3, T* 1.4 raising both at once put 128 replicas into a DMD setting at 3.0 CPU s
// per ps while SMD's at 0.14 was being resolved.
// On the map's dilute rods at the loose tolerances, raising every ladder's open rung at once put
// 740 of the 1990 CPU s into rungs dearer than their engine's choice (results/tradeoff-map).
// --frontier asks for every ladder resolved, so it raises every ladder's open rung as before.
#include "analysis/tradeoff_stats.hpp"
#include <utility>
#include <vector>

namespace terrace::cli {

/// What the schedule needs to know of a rung.
struct ScheduleRung {
    bool dmd = false;  // its engine (the verdict picks one setting per engine)
    double cost = 0.0; // CPU s per simulated ps, NaN before it has runs
    analysis::Decision decision = analysis::Decision::Unresolved;
    int target = 0; // replicas asked for so far (0: not run yet)
    int next = 0;   // the replicas that would resolve its open decisions (≤ target: no more help)
    bool pinned = false; // raised whatever its cost (the rung that checks the reference's dt)
};

/// (ladder, rung) indices of the rungs to raise this round: the cheaper engine's pick, and the
/// pinned rung where it is open; each ladder most accurate first, as the tradeoff keeps them.
/// everyLadder: one open rung of every ladder (--frontier).
std::vector<std::pair<int, int>> rungsToRaise(const std::vector<std::vector<ScheduleRung>>& ladders,
                                              bool everyLadder);

} // namespace terrace::cli
