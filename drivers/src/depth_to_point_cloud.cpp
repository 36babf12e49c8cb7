#include <cmath>

#include "anascan/drivers/depth_camera_scanner.hpp"

namespace anascan::drivers {
namespace {

/// Difference of the valid neighbours along one grid direction (central, else one-sided).
bool grid_difference(const RangeGrid& g, const PointCloud& c, int r, int col, int dr, int dc,
                     Eigen::Vector3f& out) {
    auto at = [&](int rr, int cc) -> std::int32_t {
        if (rr < 0 || cc < 0 || rr >= g.rows || cc >= g.cols) return RangeGrid::kNoSample;
        return g.at(rr, cc);
    };
    const std::int32_t self = at(r, col), next = at(r + dr, col + dc), prev = at(r - dr, col - dc);
    if (next >= 0 && prev >= 0)
        out = c.positions[next] - c.positions[prev];
    else if (next >= 0)
        out = c.positions[next] - c.positions[self];
    else if (prev >= 0)
        out = c.positions[self] - c.positions[prev];
    else
        return false;
    return true;
}

void grid_normals(const RangeGrid& g, PointCloud& c) {
    c.normals.resize(c.size());
    for (int r = 0; r < g.rows; ++r) {
        for (int col = 0; col < g.cols; ++col) {
            const std::int32_t i = g.at(r, col);
            if (i < 0) continue;
            const Eigen::Vector3f toward_sensor = -c.positions[i].normalized();
            Eigen::Vector3f du, dv;
            Eigen::Vector3f n = toward_sensor;
            if (grid_difference(g, c, r, col, 0, 1, du) &&
                grid_difference(g, c, r, col, 1, 0, dv)) {
                const Eigen::Vector3f cross = du.cross(dv);
                if (cross.norm() > 0.0f) n = cross.normalized();
            }
            c.normals[i] = n.dot(toward_sensor) < 0.0f ? Eigen::Vector3f(-n) : n;
        }
    }
}

}  // namespace

Expected<PointCloud> depth_to_point_cloud(const Frame& frame, const DepthIntrinsics& k,
                                          RangeGrid* grid_out) {
    if (frame.format != PixelFormat::kZ16) {
        return fail(ErrorCode::kFormat, "depth frame " + std::to_string(frame.sequence) + " is " +
                                            std::string(to_string(frame.format)) + ", not z16");
    }
    if (!(k.fx_px > 0.0) || !(k.fy_px > 0.0) || !(k.depth_unit_m > 0.0)) {
        return fail(ErrorCode::kInvalidArgument,
                    "depth intrinsics need fx, fy and the depth unit > 0");
    }
    if (auto ok = check_frame(frame, "depth frame"); !ok) return fail(ok.error());
    RangeGrid grid{frame.height, frame.width,
                   std::vector<std::int32_t>(static_cast<std::size_t>(frame.width) * frame.height,
                                             RangeGrid::kNoSample)};
    PointCloud cloud;
    for (int r = 0; r < frame.height; ++r) {
        for (int c = 0; c < frame.width; ++c) {
            const std::uint16_t d = frame.z16_at(r, c);
            if (d == 0) continue;  // no return
            const double z = d * k.depth_unit_m;
            grid.point_index[static_cast<std::size_t>(r) * frame.width + c] =
                static_cast<std::int32_t>(cloud.positions.size());
            cloud.positions.emplace_back(static_cast<float>((c - k.cx_px) * z / k.fx_px),
                                         static_cast<float>((r - k.cy_px) * z / k.fy_px),
                                         static_cast<float>(z));
        }
    }
    grid_normals(grid, cloud);
    if (grid_out) *grid_out = std::move(grid);
    return cloud;
}

}  // namespace anascan::drivers
