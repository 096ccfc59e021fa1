// lesser and greater (core/branch_free.hpp) are std::min and std::max without a branch: the same
// value for every ordered pair of doubles, infinities and subnormals included. Inputs pass through
// volatile so that the compiler cannot fold the intrinsics at compile time (its folding rules for
// NaN and signed zeros differ from the instructions'); the callers never rely on either.
#include "core/branch_free.hpp"
#include <algorithm>
#include <gtest/gtest.h>
#include <limits>
#include <random>

namespace test_branch_free {

namespace {

using namespace terrace;

double opaque(double x) {
    volatile double v = x;
    return v;
}

TEST(BranchFree, LesserAndGreaterAreMinAndMax) {
    const double inf = std::numeric_limits<double>::infinity();
    const double values[] = {-inf, -1e300, -2.5, -1e-310, 0.0, 1e-310, 0.75, 3.0, 1e300, inf};
    for (double x : values)
        for (double y : values) {
            const double a = opaque(x), b = opaque(y);
            EXPECT_EQ(lesser(a, b), std::min(a, b)) << a << " " << b;
            EXPECT_EQ(greater(a, b), std::max(a, b)) << a << " " << b;
        }
    std::mt19937_64 rng(2);
    std::normal_distribution<double> g(0.0, 10.0);
    for (int k = 0; k < 10000; ++k) {
        const double a = opaque(g(rng)), b = k % 5 == 0 ? a : opaque(g(rng));
        ASSERT_EQ(lesser(a, b), std::min(a, b));
        ASSERT_EQ(greater(a, b), std::max(a, b));
    }
}

} // namespace

} // namespace test_branch_free
