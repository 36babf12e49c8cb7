#pragma once
// R(q) of a Hamilton quaternion, written out independently of Eigen's conversion, so
// tests of the .conf convention do not check Eigen against itself.
#include <Eigen/Core>
#include <cmath>

namespace anascan::testing_util {

inline Eigen::Matrix3d hamilton_rotation(double qx, double qy, double qz, double qw) {
    const double n = std::sqrt(qx * qx + qy * qy + qz * qz + qw * qw);
    const double x = qx / n, y = qy / n, z = qz / n, w = qw / n;
    Eigen::Matrix3d R;
    R << 1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w),  //
        2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w),   //
        2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y);
    return R;
}

}  // namespace anascan::testing_util
