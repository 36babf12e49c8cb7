#include "demo_clouds.hpp"

#include <cmath>
#include <numbers>
#include <random>

#include "anascan/processing/io/ply.hpp"

namespace anascan::field {

Expected<LoadedScan> load_ply_scan(const std::filesystem::path& path, std::int64_t seq) {
    auto ply = io::read_ply(path);
    if (!ply) return fail(ply.error());
    if (ply->cloud.empty()) return fail(ErrorCode::kEmpty, path.string() + ": no points");
    LoadedScan scan;
    scan.row = {.seq = seq,
                .device_id = path.filename().string(),
                .captured_at = std::chrono::system_clock::now(),
                .state = gui::ScanRowState::kRegistered,
                .group = 0};
    scan.cloud = std::move(ply->cloud);
    remove_non_finite(scan.cloud);
    return scan;
}

namespace {

/// A uniform point on the box surface (faces chosen by area), with noise along the normal.
Eigen::Vector3f box_surface_point(const Eigen::Vector3d& half, std::mt19937_64& rng) {
    const double ax = half.y() * half.z(), ay = half.x() * half.z(), az = half.x() * half.y();
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::normal_distribution<double> noise(0.0, 0.001);
    const double pick = std::uniform_real_distribution<double>(0.0, ax + ay + az)(rng);
    const int axis = pick < ax ? 0 : (pick < ax + ay ? 1 : 2);
    Eigen::Vector3d p(u(rng) * half.x(), u(rng) * half.y(), u(rng) * half.z());
    p[axis] = (u(rng) < 0.0 ? -1.0 : 1.0) * half[axis] + noise(rng);
    return p.cast<float>();
}

}  // namespace

std::vector<LoadedScan> synthetic_stone(const SyntheticStoneConfig& config) {
    const int scans = std::max(1, config.scans);
    std::vector<LoadedScan> out(static_cast<std::size_t>(scans));
    const auto now = std::chrono::system_clock::now();
    for (int i = 0; i < scans; ++i) {
        LoadedScan& s = out[static_cast<std::size_t>(i)];
        s.row = {.seq = i + 1,
                 .device_id = "synthetic",
                 .captured_at = now - std::chrono::seconds(40 * (scans - i)),
                 .state = gui::ScanRowState::kRegistered,
                 .rms_mm = 0.3 + 0.1 * (i % 7),
                 .overlap_percent = i == 0 ? 100.0 : 45.0 + 3.0 * (i % 5),
                 .group = 0};
        s.cloud.positions.reserve(config.points / static_cast<std::size_t>(scans) + 1);
    }
    const Eigen::Vector3d half(0.5 * config.size_x_m, 0.5 * config.size_y_m, 0.5 * config.size_z_m);
    std::mt19937_64 rng(42);
    for (std::size_t k = 0; k < config.points; ++k) {
        const Eigen::Vector3f p = box_surface_point(half, rng);
        // The chunk is the azimuth sector the point faces (as a scan from that side).
        const double turns = (std::atan2(p.y(), p.x()) + std::numbers::pi) / (2 * std::numbers::pi);
        const auto i = std::min(scans - 1, static_cast<int>(turns * scans));
        out[static_cast<std::size_t>(i)].cloud.positions.push_back(p);
    }
    return out;
}

}  // namespace anascan::field
