#include "hole_marker_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace anascan::gui::detail {

MarkerLines hole_marker_lines(std::span<const HoleMarker> holes) {
    constexpr int kSegments = 24;
    MarkerLines lines;
    if (holes.empty()) return lines;
    lines.origin_m = holes.front().centre_m;
    for (const HoleMarker& hole : holes) {
        const Eigen::Vector3d n = hole.normal.normalized();
        // Any unit vector orthogonal to n, then the third axis.
        const Eigen::Vector3d u = n.unitOrthogonal();
        const Eigen::Vector3d v = n.cross(u);
        // Radius of a disc of the hole's area, at least 5 mm so that small holes show.
        const double radius_m = std::max(0.005, std::sqrt(hole.area_m2 / std::numbers::pi));
        const Eigen::Vector3d c = hole.centre_m - lines.origin_m;
        auto ring_point = [&](int k) {
            const double a = 2.0 * std::numbers::pi * k / kSegments;
            return (c + radius_m * (std::cos(a) * u + std::sin(a) * v)).cast<float>().eval();
        };
        for (int k = 0; k < kSegments; ++k) {
            lines.vertices.push_back(ring_point(k));
            lines.vertices.push_back(ring_point(k + 1));
        }
        lines.vertices.push_back(c.cast<float>());
        lines.vertices.push_back((c + 1.5 * radius_m * n).cast<float>());
    }
    return lines;
}

}  // namespace anascan::gui::detail
