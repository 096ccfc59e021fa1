#pragma once
// Where the per-body blocks of the engine's bookkeeping (dmd/agendas.hpp, dmd/neighbour_lists.hpp)
// take an overflow container from: a pool of them, each returned for reuse when its body fits its
// block again, so that a body that spills now and then allocates nothing in the steady state.
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

} // namespace terrace::dmd
