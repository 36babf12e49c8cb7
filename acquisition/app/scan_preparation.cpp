#include "scan_preparation.hpp"

#include "anascan/processing/io/ply.hpp"

namespace anascan::cli {

void add_sensor_options(CLI::App* cmd, SensorOptions& options) {
    cmd->add_option("--sensor-origin", options.origin_m,
                    "Sensor position X Y Z in each scan's own frame, metres, toward which "
                    "estimated normals point. Without it (the default) each scan's normals are "
                    "oriented as seen from the side it shows its convex face to, as a range scan "
                    "is seen from one side. PLY normals are used as they are. Given, it is also "
                    "taken as where each scan was taken from: `register` then rejects pair poses "
                    "that put points where the other scan's sensor saw empty space")
        ->expected(3)
        ->each([&options](const std::string&) { options.origin_given = true; });
    cmd->add_flag("--sensor-z", options.sensor_z,
                  "Sensor at (0,0,1) m in each scan frame (Cyberware and structured-light "
                  "scans whose frame looks along +z), for orienting normals only");
    cmd->add_flag("--no-sensor", options.no_sensor,
                  "No known sensor (the default): orient estimated normals by the seen side");
}

std::optional<Eigen::Vector3d> sensor_origin(const SensorOptions& options) {
    if (options.no_sensor) return std::nullopt;
    if (options.sensor_z) return Eigen::Vector3d(0.0, 0.0, 1.0);
    if (!options.origin_given) return std::nullopt;
    return Eigen::Vector3d(options.origin_m[0], options.origin_m[1], options.origin_m[2]);
}

Expected<PointCloud> load_ply_cloud(const std::string& path) {
    auto ply = io::read_ply(path);
    if (!ply) return fail(ply.error());
    return std::move(ply->cloud);
}

}  // namespace anascan::cli
