#pragma once
// `terrace tradeoff`'s verdict, from the settings chosen (cli/tradeoff_choice.hpp) and the cost
// windows that time them (cli/tradeoff_cost.hpp):
//   floor   one engine cheaper than any setting of the other could be within tolerance: the
//           ratio to the other's cost floor, a lower bound ("at least"), or no verdict where the
//           window does not resolve it
//   missing an engine with no setting within: no verdict, with why, and the other's choice
//   ratio   both engines' cheapest within, timed against each other; a cheaper rung left open
//           makes that ratio one end of the answer (cli/tradeoff_dominance.hpp, openRungVerdict)
#include "cli/tradeoff_cost.hpp"
#include "cli/tradeoff_state.hpp"
#include <nlohmann/json.hpp>
#include <string>

namespace terrace::cli {

/// The verdict line and the exit status it gives (0, or 1 where there is no verdict).
struct Verdict {
    std::string text;
    int status = 0;
};

/// The verdict on the search's end state; tradeoff.json's "cost" goes into `out`.
/// `stoppedByDominance`: the search ended at its early stop (one engine resolved cheaper than the
/// other's floor). Returns
/// 0, or 128 + a signal where one stopped a cost window (the same command goes on later).
int drawVerdict(const Tradeoff& t, CostWindows& cost, bool stoppedByDominance, nlohmann::json& out,
                Verdict& verdict);

/// The verdict's comparison of the engines' chosen settings, `dmd` and `smd` (as described),
/// from the cost window's ratio of DMD's cost to SMD's: the cheaper by how much, or, where the
/// interval holds 1, that neither is resolved cheaper (the ratio is then said as measured).
std::string costComparison(const std::string& dmd, const std::string& smd,
                           const analysis::RatioInterval& ratio);

} // namespace terrace::cli
