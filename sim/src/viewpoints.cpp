#include "anascan/sim/viewpoints.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "anascan/sim/structured_light_rig.hpp"

namespace anascan::sim {
namespace {
constexpr double kDegToRad = std::numbers::pi / 180.0;
}

Pose sensor_looking_at(const Eigen::Vector3d& target_world, const Viewpoint& view) {
    const double az = view.azimuth_deg * kDegToRad, el = view.elevation_deg * kDegToRad;
    const Eigen::Vector3d offset(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az),
                                 std::sin(el));
    return look_at(target_world + view.distance_m * offset, target_world);
}

Pose tripod_pose(const Eigen::Vector3d& target_world, double azimuth_deg, double distance_m,
                 double height_m) {
    const double az = azimuth_deg * kDegToRad;
    Pose T_world_scanner = Pose::Identity();
    // The scanner's x axis points back at the target.
    T_world_scanner.linear() =
        Eigen::AngleAxisd(az + std::numbers::pi, Eigen::Vector3d::UnitZ()).matrix();
    T_world_scanner.translation() =
        Eigen::Vector3d(target_world.x() + distance_m * std::cos(az),
                        target_world.y() + distance_m * std::sin(az), height_m);
    return T_world_scanner;
}

}  // namespace anascan::sim
