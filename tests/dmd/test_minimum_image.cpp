// The inline rounding behind PeriodicBox::minimumImage (core/box.hpp), used in every DMD pair
// prediction, must give std::nearbyint's value below 2^51 (ties to even; a zero may differ in
// sign only), and minimumImage must pick the same image as the library rounding.
#include "core/box.hpp"
#include <bit>
#include <cmath>
#include <cstdint>
#include <gtest/gtest.h>
#include <limits>
#include <random>

namespace test_minimum_image {

namespace {

using namespace terrace;

bool sameBits(double a, double b) {
    return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

TEST(MinimumImage, NearestIntegerEqualsNearbyintOnEdgeCases) {
    const double cases[] = {0.0,
                            -0.0,
                            0.3,
                            -0.3,
                            0.5,
                            -0.5,
                            1.5,
                            -1.5,
                            2.5,
                            -2.5,
                            0.49999999999999994,
                            -0.49999999999999994,
                            1e-310,
                            -1e-310,
                            0x1p51 - 0.5,
                            -0x1p51 + 0.5,
                            0x1p51 - 1.5,
                            -0x1p51 + 1.5};
    for (double x : cases) // == : a zero of either sign matches
        EXPECT_EQ(nearestInteger(x), std::nearbyint(x)) << x;
    EXPECT_TRUE(std::isnan(nearestInteger(std::numeric_limits<double>::quiet_NaN())));
}

TEST(MinimumImage, NearestIntegerEqualsNearbyintOnRandomValues) {
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(-4.0, 4.0);
    for (int k = 0; k < 100000; ++k) {
        const double x = u(rng) * std::pow(10.0, static_cast<int>(k % 12) - 3);
        ASSERT_EQ(nearestInteger(x), std::nearbyint(x)) << x;
    }
}

TEST(MinimumImage, SameImageAsLibraryRounding) {
    const PeriodicBox box{30.6};
    std::mt19937_64 rng(4);
    std::uniform_real_distribution<double> u(-100.0, 100.0);
    for (int k = 0; k < 10000; ++k) {
        const Vec3 d(u(rng), u(rng), u(rng));
        const Vec3 m = box.minimumImage(d);
        for (int a = 0; a < 3; ++a)
            ASSERT_TRUE(sameBits(m[a], d[a] - box.length * std::nearbyint(d[a] / box.length)));
    }
}

// The branch-free rounding holds for unwrapped separations of up to a million boxes (bodies of a
// long gas run), in the form with 1/L passed in that the engine uses.
TEST(MinimumImage, FarSeparationsWithTheCachedInverse) {
    const PeriodicBox box{27.3};
    const double inverse = 1.0 / box.length;
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int k = 0; k < 20000; ++k) {
        const double scale = box.length * std::pow(10.0, k % 7); // 1 … 10⁶ boxes
        const Vec3 d(scale * u(rng), scale * u(rng), scale * u(rng));
        const Vec3 m = box.minimumImage(d, inverse);
        for (int a = 0; a < 3; ++a) {
            ASSERT_TRUE(sameBits(m[a], d[a] - box.length * std::nearbyint(d[a] * inverse))) << d[a];
            ASSERT_LE(std::abs(m[a]), 0.5 * box.length * (1.0 + 1e-9)) << d[a];
        }
    }
}

} // namespace

} // namespace test_minimum_image
