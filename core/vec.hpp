#pragma once
// Small fixed-size linear algebra used throughout: Eigen's 3-vectors and 3x3 matrices.
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace terrace {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;

} // namespace terrace
