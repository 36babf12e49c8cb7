#include "anascan/gui/scan_preview.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

namespace anascan::gui {
namespace {

/// A point as seen from the sensor: angles across / up (radians) and range (metres).
struct Seen {
    float across = 0.0f, up = 0.0f, range_m = 0.0f;
};

/// The axes of the view: forward = mean direction; up = the scan frame's +Z (a terrestrial
/// scanner), or -Y when looking along Z (a camera frame: y points down in the image).
void view_axes(const Eigen::Vector3d& forward, Eigen::Vector3d& right, Eigen::Vector3d& up) {
    const Eigen::Vector3d hint =
        std::abs(forward.z()) > 0.9 ? Eigen::Vector3d(0, -1, 0) : Eigen::Vector3d(0, 0, 1);
    right = forward.cross(hint).normalized();
    up = right.cross(forward).normalized();
}

std::vector<Seen> seen_from_sensor(const Scan& scan) {
    const PointCloud& cloud = scan.cloud;
    const Eigen::Vector3d sensor = scan.meta.sensor_origin_scan_m.value_or(Eigen::Vector3d::Zero());
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < cloud.size(); ++i)
        sum += (cloud.world_position(i) - sensor).normalized();
    if (sum.norm() < 1e-9) return {};
    const Eigen::Vector3d forward = sum.normalized();
    Eigen::Vector3d right, up;
    view_axes(forward, right, up);
    std::vector<Seen> seen(cloud.size());
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const Eigen::Vector3d v = cloud.world_position(i) - sensor;
        const double f = v.dot(forward);
        seen[i] = {.across = static_cast<float>(std::atan2(v.dot(right), f)),
                   .up = static_cast<float>(std::atan2(v.dot(up), f)),
                   .range_m = static_cast<float>(v.norm())};
    }
    return seen;
}

}  // namespace

ScanPreview make_scan_preview(const Scan& scan, int width_px) {
    ScanPreview preview{.seq = scan.meta.sequence, .points = scan.cloud.size()};
    const std::vector<Seen> seen = seen_from_sensor(scan);
    if (seen.empty() || width_px <= 0) return preview;
    float a0 = std::numeric_limits<float>::max(), a1 = -a0, u0 = a0, u1 = -a0, r0 = a0, r1 = -a0;
    for (const Seen& s : seen) {
        a0 = std::min(a0, s.across), a1 = std::max(a1, s.across);
        u0 = std::min(u0, s.up), u1 = std::max(u1, s.up);
        r0 = std::min(r0, s.range_m), r1 = std::max(r1, s.range_m);
    }
    const float span = std::max({a1 - a0, u1 - u0, 1e-6f});
    const int w = width_px;
    const int h = std::clamp(static_cast<int>(std::ceil(w * (u1 - u0) / span)), 1, w);
    const float px_per_rad = static_cast<float>(w - 1) / span;
    std::vector<float> nearest(static_cast<std::size_t>(w) * h, std::numeric_limits<float>::max());
    for (const Seen& s : seen) {
        const int x = std::clamp(static_cast<int>((s.across - a0) * px_per_rad), 0, w - 1);
        const int y = std::clamp(static_cast<int>((u1 - s.up) * px_per_rad), 0, h - 1);
        float& n = nearest[static_cast<std::size_t>(y) * w + x];
        n = std::min(n, s.range_m);
    }
    preview.width_px = w;
    preview.height_px = h;
    preview.rgb.resize(nearest.size() * 3);
    const float depth = std::max(r1 - r0, 1e-6f);
    for (std::size_t i = 0; i < nearest.size(); ++i) {
        std::uint8_t* p = &preview.rgb[3 * i];
        if (nearest[i] == std::numeric_limits<float>::max()) {
            p[0] = 41, p[1] = 46, p[2] = 56;  // the view's background
            continue;
        }
        const auto grey = static_cast<std::uint8_t>(255.0f - 185.0f * (nearest[i] - r0) / depth);
        p[0] = p[1] = p[2] = grey;
    }
    return preview;
}

}  // namespace anascan::gui
