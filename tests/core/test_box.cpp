// PeriodicBox: minimum image and wrapping into the primary cell (core/box.hpp).
//
// Positions are kept unwrapped in the engines, so separations can be many box lengths long; the
// minimum image must then still land within ±L/2 and differ from the input by whole box lengths,
// and wrap() must land in [0, L) even for inputs a rounding error below a multiple of L.
#include "core/box.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace terrace::test_box {

constexpr double kEps = std::numeric_limits<double>::epsilon();
// An input d is itself known only to ~ulp(d); the image cannot be sharper than a few such ulps.
constexpr double kImageUlps = 4.0;
// Seed of the random stream of box lengths and separations used below.
constexpr std::uint64_t kBoxSeed = 20240602;

double imageRoundOff(double d, double length) {
    return kImageUlps * kEps * std::max(std::abs(d), length);
}

/// Checks that m is an image of d (d - m a whole number of box lengths) within ±L/2.
void expectMinimumImage(double d, double m, double length) {
    const double tol = imageRoundOff(d, length);
    EXPECT_LE(std::abs(m), 0.5 * length + tol) << "d = " << d << ", L = " << length;
    const double shifts = (d - m) / length;
    EXPECT_NEAR(shifts, std::nearbyint(shifts), tol / length) << "d = " << d;
}

TEST(PeriodicBox, VolumeIsCube) {
    const PeriodicBox box{3.5};
    EXPECT_DOUBLE_EQ(box.volume(), 3.5 * 3.5 * 3.5);
}

TEST(PeriodicBox, MinimumImageLeavesShortSeparationsAlone) {
    const PeriodicBox box{10.0};
    const Vec3 d(1.25, -4.75, 0.0);
    EXPECT_EQ(box.minimumImage(d), d);
}

TEST(PeriodicBox, MinimumImageFoldsEachComponentIndependently) {
    const PeriodicBox box{10.0};
    const Vec3 m = box.minimumImage(Vec3(6.0, -7.5, 23.0));
    EXPECT_DOUBLE_EQ(m.x(), -4.0);
    EXPECT_DOUBLE_EQ(m.y(), 2.5);
    EXPECT_DOUBLE_EQ(m.z(), 3.0);
}

TEST(PeriodicBox, MinimumImageAtExactlyHalfABoxHasMagnitudeHalfABox) {
    // ±L/2 is equidistant from two images; either is acceptable, but never anything longer.
    const PeriodicBox box{10.0};
    for (double d : {5.0, -5.0, 15.0, -15.0, 25.0, -25.0, 1005.0, -1005.0}) {
        const double m = box.minimumImage(Vec3(d, 0.0, 0.0)).x();
        EXPECT_EQ(std::abs(m), 5.0) << "d = " << d;
        expectMinimumImage(d, m, box.length);
    }
}

TEST(PeriodicBox, MinimumImageOfWholeBoxLengthsIsZero) {
    const PeriodicBox box{7.25}; // exactly representable, so k·L is exact
    for (int k = -1000; k <= 1000; k += 37) {
        const Vec3 m = box.minimumImage(Vec3(k * box.length, -k * box.length, 0.0));
        EXPECT_EQ(m, Vec3::Zero()) << "k = " << k;
    }
}

TEST(PeriodicBox, MinimumImageOfFarUnwrappedSeparations) {
    // Unwrapped positions of diffusing bodies drift by many box lengths over a long run.
    std::mt19937_64 rng(kBoxSeed);
    std::uniform_real_distribution<double> lengthDist(5.0, 50.0), fraction(-0.5, 0.5);
    std::uniform_int_distribution<int> shiftDist(-100000, 100000);
    for (int trial = 0; trial < 2000; ++trial) {
        const PeriodicBox box{lengthDist(rng)};
        Vec3 d;
        for (int a = 0; a < 3; ++a)
            d[a] = (shiftDist(rng) + fraction(rng)) * box.length;
        const Vec3 m = box.minimumImage(d);
        for (int a = 0; a < 3; ++a)
            expectMinimumImage(d[a], m[a], box.length);
    }
}

TEST(PeriodicBox, MinimumImageNextToHalfBoxBoundaries) {
    // One ulp either side of (k + 1/2)L: the hardest inputs for the rounding in minimumImage.
    std::mt19937_64 rng(kBoxSeed + 1);
    std::uniform_real_distribution<double> lengthDist(5.0, 50.0);
    std::uniform_int_distribution<int> shiftDist(-1000, 1000);
    for (int trial = 0; trial < 2000; ++trial) {
        const PeriodicBox box{lengthDist(rng)};
        const double edge = (shiftDist(rng) + 0.5) * box.length;
        for (double d : {std::nextafter(edge, -INFINITY), edge, std::nextafter(edge, INFINITY)})
            expectMinimumImage(d, box.minimumImage(Vec3(d, 0.0, 0.0)).x(), box.length);
    }
}

TEST(PeriodicBox, WrapIntoPrimaryCell) {
    const PeriodicBox box{10.0};
    const Vec3 w = box.wrap(Vec3(-0.5, 23.0, 10.0));
    EXPECT_DOUBLE_EQ(w.x(), 9.5);
    EXPECT_DOUBLE_EQ(w.y(), 3.0);
    EXPECT_EQ(w.z(), 0.0); // L itself belongs to the next cell: [0, L) is half-open
    EXPECT_EQ(box.wrap(Vec3::Zero()), Vec3::Zero());
}

TEST(PeriodicBox, WrapOfTinyNegativeStaysBelowL) {
    // -tiny + L rounds to L in floating point; the result must still lie in [0, L).
    const PeriodicBox box{10.0};
    const double tiny = std::numeric_limits<double>::denorm_min();
    const Vec3 w = box.wrap(Vec3(-tiny, -1e-17, -kEps));
    for (int a = 0; a < 3; ++a) {
        EXPECT_GE(w[a], 0.0);
        EXPECT_LT(w[a], box.length);
    }
}

TEST(PeriodicBox, WrapNextToMultiplesOfLStaysInPrimaryCell) {
    // r/L is rounded, so floor(r/L) can be one too large for r one ulp below k·L (or one too
    // small just above it); wrap() must still return a value in [0, L) that is an image of r.
    std::mt19937_64 rng(kBoxSeed + 2);
    std::uniform_real_distribution<double> lengthDist(5.0, 50.0);
    std::uniform_int_distribution<int> shiftDist(-1000, 1000);
    for (int trial = 0; trial < 5000; ++trial) {
        const PeriodicBox box{lengthDist(rng)};
        const double multiple = shiftDist(rng) * box.length;
        for (double r :
             {std::nextafter(multiple, -INFINITY), multiple, std::nextafter(multiple, INFINITY)}) {
            const double w = box.wrap(Vec3(r, 0.0, 0.0)).x();
            ASSERT_GE(w, 0.0) << "r = " << r << ", L = " << box.length;
            ASSERT_LT(w, box.length) << "r = " << r << ", L = " << box.length;
            // An image of r: the same point modulo L (0 and L are the same point).
            const double offset = box.minimumImage(Vec3(r - w, 0.0, 0.0)).x();
            EXPECT_LE(std::abs(offset), imageRoundOff(r, box.length)) << "r = " << r;
        }
    }
}

TEST(PeriodicBox, WrapOfFarUnwrappedPositions) {
    std::mt19937_64 rng(kBoxSeed + 3);
    std::uniform_real_distribution<double> lengthDist(5.0, 50.0), fraction(0.0, 1.0);
    std::uniform_int_distribution<int> shiftDist(-100000, 100000);
    for (int trial = 0; trial < 2000; ++trial) {
        const PeriodicBox box{lengthDist(rng)};
        Vec3 r;
        for (int a = 0; a < 3; ++a)
            r[a] = (shiftDist(rng) + fraction(rng)) * box.length;
        const Vec3 w = box.wrap(r);
        for (int a = 0; a < 3; ++a) {
            ASSERT_GE(w[a], 0.0);
            ASSERT_LT(w[a], box.length);
            const double offset = box.minimumImage(Vec3(r[a] - w[a], 0.0, 0.0)).x();
            EXPECT_LE(std::abs(offset), imageRoundOff(r[a], box.length)) << "r = " << r[a];
        }
    }
}

} // namespace terrace::test_box
