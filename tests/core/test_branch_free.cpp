// lesser and greater (core/branch_free.hpp) are std::min and std::max without a branch: the same
// value for every ordered pair of doubles, infinities included; only the sign of a zero result
// may differ, which the callers never see.
#include "core/branch_free.hpp"
#include <algorithm>
#include <gtest/gtest.h>
#include <limits>
#include <random>

namespace {

using namespace terrace;

TEST(BranchFree, LesserAndGreaterAreMinAndMax) {
    const double inf = std::numeric_limits<double>::infinity();
    const double values[] = {-inf, -1e300, -2.5, -1e-310, 0.0, 1e-310, 0.75, 3.0, 1e300, inf};
    for (double a : values)
        for (double b : values) {
            EXPECT_EQ(lesser(a, b), std::min(a, b)) << a << " " << b;
            EXPECT_EQ(greater(a, b), std::max(a, b)) << a << " " << b;
        }
    std::mt19937_64 rng(2);
    std::normal_distribution<double> g(0.0, 10.0);
    for (int k = 0; k < 10000; ++k) {
        const double a = g(rng), b = k % 5 == 0 ? a : g(rng);
        ASSERT_EQ(lesser(a, b), std::min(a, b));
        ASSERT_EQ(greater(a, b), std::max(a, b));
    }
    // Signed zeros compare equal; either may come back.
    EXPECT_EQ(lesser(0.0, -0.0), 0.0);
    EXPECT_EQ(greater(-0.0, 0.0), 0.0);
}

} // namespace
