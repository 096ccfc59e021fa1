#pragma once
// Small fixed-size linear algebra used throughout: Eigen's 3-vectors and 3x3 matrices.
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace terrace {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;

/// r + v t, the free flight of a centre (Å, Å per time unit): written per component because the
/// compiler left Eigen's expression for it out of line in the DMD search's innermost loop.
inline Vec3 translated(const Vec3& r, const Vec3& v, double t) {
    return {r.x() + v.x() * t, r.y() + v.y() * t, r.z() + v.z() * t};
}

} // namespace terrace
