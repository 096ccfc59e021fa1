// gatherInPlace against a gather into a copy, over permutations with one cycle, many, and none.
#include "core/gather_in_place.hpp"
#include <algorithm>
#include <gtest/gtest.h>
#include <numeric>
#include <random>
#include <string>
#include <vector>

namespace test_gather_in_place {

using namespace terrace;

TEST(GatherInPlace, EqualsAGatherIntoACopy) {
    std::mt19937_64 rng(7);
    for (const int n : {0, 1, 2, 7, 100, 4097}) {
        std::vector<int> from(static_cast<std::size_t>(n));
        std::iota(from.begin(), from.end(), 0);
        for (int shape = 0; shape < 3; ++shape) {
            if (shape == 1) std::shuffle(from.begin(), from.end(), rng); // cycles of all lengths
            if (shape == 2 && n > 1) { // one cycle through every item
                std::iota(from.begin(), from.end(), 0);
                std::rotate(from.begin(), from.begin() + 1, from.end());
            }
            std::vector<std::string> items(static_cast<std::size_t>(n)), expected(items.size());
            for (int i = 0; i < n; ++i)
                items[i] = "body " + std::to_string(i);
            for (int i = 0; i < n; ++i)
                expected[i] = items[from[i]];
            gatherInPlace(items, [&](int i) { return from[i]; });
            EXPECT_EQ(items, expected) << n << " bodies, shape " << shape;
        }
    }
}

// Gathering by a permutation and then by its inverse gives the items back: the engine sorts its
// bodies with one (scene number of each engine body) and releases them with the other.
TEST(GatherInPlace, TheInverseUndoesIt) {
    std::mt19937_64 rng(11);
    const int n = 1000;
    std::vector<int> from(n), inverse(n), items(n);
    std::iota(from.begin(), from.end(), 0);
    std::shuffle(from.begin(), from.end(), rng);
    for (int i = 0; i < n; ++i)
        inverse[from[i]] = i;
    std::iota(items.begin(), items.end(), 0);
    gatherInPlace(items, [&](int i) { return from[i]; });
    EXPECT_EQ(items, from);
    gatherInPlace(items, [&](int i) { return inverse[i]; });
    for (int i = 0; i < n; ++i)
        ASSERT_EQ(items[i], i);
}

} // namespace test_gather_in_place
