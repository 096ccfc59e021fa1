#include "cli/tradeoff_schedule.hpp"
#include <algorithm>
#include <cmath>
#include <limits>

namespace terrace::cli {

namespace {

using analysis::Decision;

/// The rung a ladder offers: from the cheap end, past the rungs resolved Outside, the first one
/// not run yet or that more replicas could resolve; none at or beyond its cheapest Within.
int ladderOffer(const std::vector<ScheduleRung>& ladder) {
    int within = -1;
    for (int i = 0; i < int(ladder.size()); ++i)
        if (ladder[i].decision == Decision::Within) within = i;
    for (int i = int(ladder.size()) - 1; i > within; --i) {
        const ScheduleRung& r = ladder[i];
        if (r.decision == Decision::Outside) continue;
        if (r.target == 0 || r.next > r.target) return i;
    }
    return -1;
}

bool open(const ScheduleRung& r) {
    return r.target == 0 || r.next > r.target;
}

} // namespace

std::vector<std::pair<int, int>> rungsToRaise(const std::vector<std::vector<ScheduleRung>>& ladders,
                                              bool everyLadder) {
    std::vector<std::pair<int, int>> raise;
    const auto chosen = [&](int l, int i) {
        for (const auto& p : raise)
            if (p == std::pair{l, i}) return true;
        return false;
    };
    if (everyLadder) {
        for (int l = 0; l < int(ladders.size()); ++l)
            if (const int i = ladderOffer(ladders[l]); i >= 0) raise.emplace_back(l, i);
    } else {
        // A rung not run yet has no cost: it goes first, since two replicas measure it.
        const auto key = [](const ScheduleRung& r) { return std::isnan(r.cost) ? 0.0 : r.cost; };
        // Each engine's pick, then the cheaper of the two alone: the dearer engine's turn comes
        // once the cheaper one has nothing cheaper to resolve, and by then the early stop (one
        // engine's choice below the other's cost floor) may have made it moot.
        std::vector<std::pair<int, int>> picks;
        for (const bool dmd : {true, false}) {
            double bestWithin = std::numeric_limits<double>::infinity();
            for (const auto& ladder : ladders)
                for (const auto& r : ladder)
                    if (r.dmd == dmd && r.decision == Decision::Within && std::isfinite(r.cost))
                        bestWithin = std::min(bestWithin, r.cost);
            int bestLadder = -1, bestRung = -1;
            for (int l = 0; l < int(ladders.size()); ++l) {
                const int i = ladderOffer(ladders[l]);
                if (i < 0 || ladders[l][i].dmd != dmd) continue;
                const ScheduleRung& r = ladders[l][i];
                if (!(key(r) < bestWithin)) continue; // it could not be the engine's choice
                if (bestLadder < 0 || key(r) < key(ladders[bestLadder][bestRung]))
                    bestLadder = l, bestRung = i;
            }
            if (bestLadder >= 0) picks.emplace_back(bestLadder, bestRung);
        }
        if (!picks.empty())
            raise.push_back(*std::min_element(picks.begin(), picks.end(), [&](auto a, auto b) {
                return key(ladders[a.first][a.second]) < key(ladders[b.first][b.second]);
            }));
    }
    for (int l = 0; l < int(ladders.size()); ++l)
        for (int i = 0; i < int(ladders[l].size()); ++i)
            if (ladders[l][i].pinned && open(ladders[l][i]) && !chosen(l, i))
                raise.emplace_back(l, i);
    return raise;
}

} // namespace terrace::cli
