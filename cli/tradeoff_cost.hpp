#pragma once
// `terrace tradeoff`'s cost windows: a DMD and an SMD setting at the scene's N, alternated A B A B,
// one run at a time (each pair a sweep of its own, so a killed tradeoff keeps the pairs it has
// timed), and the ratio of DMD's CPU per ps to SMD's with its order-statistics interval.
#include "cli/tradeoff_choice.hpp"
#include "cli/tradeoff_state.hpp"
#include <nlohmann/json.hpp>

namespace terrace::cli {

class CostWindows {
public:
    // `t` is the search's state, read (its scene, options and runs directory) at each window
    // as it is then; it outlives the windows.
    explicit CostWindows(const Tradeoff& t) : t_(t) {}

    /// Times `dmd` against `smd` for the options' costPairs pairs: the ratio of DMD's cost to
    /// SMD's into `ratio`, the window into record() (`kind` names what it is for). Returns 0,
    /// or the sweep's status where a signal stopped it (128 + the signal).
    int timeWindow(const Setting& dmd, const Setting& smd, const char* kind,
                   analysis::RatioInterval& ratio);

    /// One engine's chosen setting against the other's cost floor: the chosen engine's
    /// advantage, the floor's cost over the chosen one's, with its interval. Each rival floor is
    /// timed as well, and the weakest advantage (the lowest end of its interval) is the one the
    /// verdict states: d.bound and d.floor become its, and record() its window. Returns as
    /// timeWindow() does.
    int timeDominance(Dominance& d, analysis::RatioInterval& advantage);

    /// The last window timed (timeDominance: the weakest), as tradeoff.json's "cost" holds it.
    const nlohmann::json& record() const { return record_; }

private:
    const Tradeoff& t_;
    nlohmann::json record_;
};

} // namespace terrace::cli
