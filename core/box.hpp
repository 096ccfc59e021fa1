#pragma once
// Periodic cubic box of edge length L (Å) with the minimum-image convention. Positions inside the
// engines are kept unwrapped (so that the mean squared displacement needs no image counters);
// pair separations are always taken through minimumImage().
#include "core/vec.hpp"
#include <cfloat>
#include <cmath>

// The rounding below, (x + 1.5·2^52) − 1.5·2^52, needs IEEE double arithmetic as written:
// -ffast-math folds it to x, and x87 excess precision (FLT_EVAL_METHOD 2) does not round at all.
#if defined(__FAST_MATH__) || (defined(FLT_EVAL_METHOD) && FLT_EVAL_METHOD != 0)
#error "core/box.hpp: the minimum image needs IEEE double arithmetic (no -ffast-math, no x87)"
#endif

namespace terrace {

/// Nearest integer of |x| < 2^51, ties to even: the value of std::nearbyint in the default
/// rounding mode, up to the sign of a zero result, without its library call and without a branch.
/// Adding 1.5·2^52 leaves no fraction bits, so the FPU rounds x to nearest-even and the
/// subtraction is exact. NaN stays NaN; beyond 2^51 the answer is wrong.
[[gnu::always_inline]] inline double nearestInteger(double x) {
    constexpr double shifter = 0x1.8p52;
    return (x + shifter) - shifter;
}

struct PeriodicBox {
    double length = 0.0; // Å

    double volume() const { return length * length * length; }

    /// The periodic image of d closest to the origin, component by component, for |d| < 2^51 L
    /// (beyond, the answer is wrong, not NaN; no separation in a simulation comes near that).
    /// Every DMD pair prediction and list rebuild takes one, so it is branch-free and inlined
    /// (nearestInteger). The image is the one std::nearbyint picks for d/L rounded to a double
    /// (tests/dmd/test_minimum_image.cpp). A build with FMA (-march=native) may fuse the
    /// product into the rounding and send an exact half-box tie to the other image: a pair half a
    /// box apart, far beyond any interaction range.
    [[gnu::always_inline]] Vec3 minimumImage(const Vec3& d) const {
        return minimumImage(d, 1.0 / length);
    }
    /// The same with 1/L from a caller that takes many images: the division, ~15 cycles on the
    /// path to everything computed from the separation, is then paid once.
    [[gnu::always_inline]] Vec3 minimumImage(const Vec3& d, double inverseLength) const {
        // Components written out, with L in a local: a loop over d[a] made the compiler reload L
        // from memory at every component (d might have aliased it).
        const double L = length, inverse = inverseLength;
        return {d.x() - L * nearestInteger(d.x() * inverse),
                d.y() - L * nearestInteger(d.y() * inverse),
                d.z() - L * nearestInteger(d.z() * inverse)};
    }

    /// The image of r inside [0, L)^3.
    Vec3 wrap(Vec3 r) const {
        for (int a = 0; a < 3; ++a) {
            r[a] -= length * std::floor(r[a] / length);
            // r/L is rounded (and underflows to -0 for denormal r), so floor() can be one off
            // next to a multiple of L: step back into the cell; -tiny + L can round to L itself.
            if (r[a] < 0.0) r[a] += length;
            if (r[a] >= length) r[a] -= length;
        }
        return r;
    }
};

} // namespace terrace
