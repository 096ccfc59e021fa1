#pragma once
// Where the per-body blocks of the engine's bookkeeping (dmd/agendas.hpp, dmd/neighbour_lists.hpp)
// take an overflow container from: a pool of them, each returned for reuse when its body fits its
// block again, so that a body that spills now and then allocates nothing in the steady state.
// A pool keeps what a passing crowd of spills left in it (a lattice start spills many more agendas
// at once than the liquid it melts into) until it is compacted.
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace terrace::dmd {

/// The index of a free container of `pool` (`free`: those no body holds), a new one if none is.
template <class S> int takeFromPool(std::vector<S>& pool, std::vector<int>& free) {
    if (free.empty()) {
        pool.emplace_back();
        return static_cast<int>(pool.size() - 1);
    }
    const int s = free.back();
    free.pop_back();
    return s;
}

/// Idle containers a pool may keep beyond as many as are held.
inline constexpr std::size_t idleSpillSlack = 64;

/// When more of `pool`'s containers are idle than held (plus idleSpillSlack), moves the held ones
/// to the front and frees the rest. forEachHolder(f) calls f(index) on every holder's index into
/// the pool (an std::int32_t&, renumbered here), once each. O(bodies) when it compacts; a check
/// otherwise.
template <class S, class ForEachHolder>
void compactPool(std::vector<S>& pool, std::vector<int>& free, ForEachHolder&& forEachHolder) {
    const std::size_t held = pool.size() - free.size();
    if (free.size() <= held + idleSpillSlack) return;
    std::vector<S> kept;
    kept.reserve(held);
    forEachHolder([&](std::int32_t& s) {
        kept.push_back(std::move(pool[static_cast<std::size_t>(s)]));
        s = static_cast<std::int32_t>(kept.size() - 1);
    });
    pool = std::move(kept);
    std::vector<int>().swap(free);
}

} // namespace terrace::dmd
