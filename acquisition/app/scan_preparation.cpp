#include "scan_preparation.hpp"

#include "anascan/processing/io/ply.hpp"

namespace anascan::cli {

void add_sensor_options(CLI::App* cmd, SensorOptions& options) {
    cmd->add_option("--sensor-origin", options.origin_m,
                    "Sensor position X Y Z in each scan's own frame, metres, toward which "
                    "estimated normals point (default 0 0 1: fits Cyberware and structured-"
                    "light scans whose frame looks along +z). PLY normals are used as they are. "
                    "Given explicitly, it is taken as where each scan was taken from: `register` "
                    "then also rejects pair poses that put points where the other scan's sensor "
                    "saw empty space (free-space check)")
        ->expected(3)
        ->each([&options](const std::string&) { options.origin_given = true; });
    cmd->add_flag("--sensor-z", options.sensor_z,
                  "Sensor at (0,0,1) m in each scan frame (the default, stated explicitly)");
    cmd->add_flag("--no-sensor", options.no_sensor,
                  "No known sensor: orient estimated normals consistently (outward)");
}

std::optional<Eigen::Vector3d> sensor_origin(const SensorOptions& options) {
    if (options.no_sensor) return std::nullopt;
    if (options.sensor_z) return Eigen::Vector3d(0.0, 0.0, 1.0);
    return Eigen::Vector3d(options.origin_m[0], options.origin_m[1], options.origin_m[2]);
}

Expected<PointCloud> load_ply_cloud(const std::string& path) {
    auto ply = io::read_ply(path);
    if (!ply) return fail(ply.error());
    return std::move(ply->cloud);
}

}  // namespace anascan::cli
