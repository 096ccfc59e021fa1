#pragma once
// Periodic cubic box of edge length L (Å) with the minimum-image convention. Positions inside the
// engines are kept unwrapped (so that the mean squared displacement needs no image counters);
// pair separations are always taken through minimumImage().
#include "core/vec.hpp"
#include <cmath>

namespace terrace {

struct PeriodicBox {
    double length = 0.0; // Å

    double volume() const { return length * length * length; }

    /// The periodic image of d closest to the origin, component by component.
    Vec3 minimumImage(Vec3 d) const {
        for (int a = 0; a < 3; ++a)
            d[a] -= length * std::nearbyint(d[a] / length);
        return d;
    }

    /// The image of r inside [0, L)^3.
    Vec3 wrap(Vec3 r) const {
        for (int a = 0; a < 3; ++a) {
            r[a] -= length * std::floor(r[a] / length);
            if (r[a] >= length) r[a] = 0.0; // -tiny wraps to L in floating point
        }
        return r;
    }
};

} // namespace terrace
