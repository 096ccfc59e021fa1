#pragma once
// Reordering a per-body array in place: a large system's bodies renumbered without a second copy
// of them beside the first (at 10⁶ rods a copy is 96 MB, which at a restart point would set the
// run's peak memory).
#include <cstddef>
#include <utility>
#include <vector>

namespace terrace {

/// Puts into items[i] what was in items[from(i)], for every i, where `from` is a permutation of
/// 0 … n−1: each cycle of it is walked once, one element held aside, so the cost is n moves (and
/// one more per cycle) and n bits. To scatter (item i to place to(i)), gather with the inverse of
/// `to`.
template <class T, class A, class From> void gatherInPlace(std::vector<T, A>& items, From&& from) {
    const int n = static_cast<int>(items.size());
    std::vector<bool> placed(static_cast<std::size_t>(n), false);
    for (int start = 0; start < n; ++start) {
        if (placed[start]) continue;
        T first = std::move(items[start]);
        int to = start;
        for (int f = from(to); f != start; to = f, f = from(to)) {
            items[to] = std::move(items[f]);
            placed[to] = true;
        }
        items[to] = std::move(first);
        placed[to] = true;
    }
}

} // namespace terrace
