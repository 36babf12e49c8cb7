// check_free_space: the viewed scan's depth image from its sensor, the other scan's points
// tested against it.
#include "anascan/processing/evaluation/free_space.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "anascan/processing/features/integral_invariants.hpp"

namespace anascan {
namespace {

constexpr float kEmpty = std::numeric_limits<float>::infinity();
constexpr std::size_t kMaxBins = std::size_t{1} << 22;

/// Depth image of a cloud seen from `eye` (cloud-local coordinates): a virtual pinhole
/// camera along the points' mean direction; each bin holds the least depth of the points
/// in it and its eight neighbours (so that edges and grazing faces do not count as free).
struct DepthView {
    Eigen::Vector3f eye = Eigen::Vector3f::Zero();
    Eigen::Matrix3f rows = Eigen::Matrix3f::Identity();  ///< u, v, axis as rows.
    float x0 = 0.0f, y0 = 0.0f, bin = 1.0f;
    int cols = 0, lines = 0;
    std::vector<float> front;  ///< Least depth, lines × cols.

    /// Camera coordinates (x/z, y/z, z) of a local point.
    Eigen::Vector3f project(const Eigen::Vector3f& p) const {
        const Eigen::Vector3f c = rows * (p - eye);
        return {c.x() / c.z(), c.y() / c.z(), c.z()};
    }
    /// Least depth around the bin of (x, y); infinity outside the image or where empty.
    float front_at(float x, float y) const {
        const float col = std::floor((x - x0) / bin), line = std::floor((y - y0) / bin);
        if (!(col >= 0.0f && line >= 0.0f && col < cols && line < lines)) return kEmpty;
        return front[static_cast<std::size_t>(line) * cols + static_cast<std::size_t>(col)];
    }
};

Eigen::Matrix3f camera_rows(const Eigen::Vector3f& axis) {
    const Eigen::Vector3f helper =
        std::abs(axis.x()) < 0.9f ? Eigen::Vector3f::UnitX() : Eigen::Vector3f::UnitY();
    const Eigen::Vector3f u = axis.cross(helper).normalized();
    Eigen::Matrix3f rows;
    rows.row(0) = u;
    rows.row(1) = axis.cross(u);
    rows.row(2) = axis;
    return rows;
}

/// Sets the image bounds and bin size from the projected points; false when none lies in
/// front of the eye.
bool frame_view(const std::vector<Eigen::Vector3f>& projected, double spacing_m,
                const FreeSpaceConfig& config, DepthView& view) {
    std::vector<float> depths;
    Eigen::Array2f lo = Eigen::Array2f::Constant(kEmpty), hi = -lo;
    for (const Eigen::Vector3f& c : projected) {
        if (!(c.z() > 0.0f) || !c.allFinite()) continue;
        depths.push_back(c.z());
        lo = lo.min(c.head<2>().array());
        hi = hi.max(c.head<2>().array());
    }
    if (depths.empty()) return false;
    auto middle = depths.begin() + static_cast<std::ptrdiff_t>(depths.size() / 2);
    std::nth_element(depths.begin(), middle, depths.end());
    const double extent = std::max<double>((hi - lo).maxCoeff(), 1e-9);
    double bin = config.bin_spacing_factor * spacing_m / std::max<double>(*middle, 1e-9);
    const double min_bin = extent / std::sqrt(static_cast<double>(kMaxBins));
    bin = std::max({bin, min_bin, 1e-9});
    view.bin = static_cast<float>(bin);
    view.x0 = lo.x();
    view.y0 = lo.y();
    view.cols = static_cast<int>((hi.x() - lo.x()) / bin) + 1;
    view.lines = static_cast<int>((hi.y() - lo.y()) / bin) + 1;
    return true;
}

/// Each bin's least depth, then the least over its 3×3 neighbourhood.
void fill_front(const std::vector<Eigen::Vector3f>& projected, DepthView& view) {
    const auto cols = static_cast<std::size_t>(view.cols);
    std::vector<float> own(cols * static_cast<std::size_t>(view.lines), kEmpty);
    for (const Eigen::Vector3f& c : projected) {
        if (!(c.z() > 0.0f) || !c.allFinite()) continue;
        const auto col = static_cast<std::size_t>((c.x() - view.x0) / view.bin);
        const auto line = static_cast<std::size_t>((c.y() - view.y0) / view.bin);
        float& depth = own[std::min(line, static_cast<std::size_t>(view.lines) - 1) * cols +
                           std::min(col, cols - 1)];
        depth = std::min(depth, c.z());
    }
    view.front.assign(own.size(), kEmpty);
    for (int line = 0; line < view.lines; ++line) {
        for (int col = 0; col < view.cols; ++col) {
            float least = kEmpty;
            for (int dl = std::max(line - 1, 0); dl <= std::min(line + 1, view.lines - 1); ++dl) {
                for (int dc = std::max(col - 1, 0); dc <= std::min(col + 1, view.cols - 1); ++dc) {
                    least = std::min(
                        least,
                        own[static_cast<std::size_t>(dl) * cols + static_cast<std::size_t>(dc)]);
                }
            }
            view.front[static_cast<std::size_t>(line) * cols + static_cast<std::size_t>(col)] =
                least;
        }
    }
}

bool build_view(const PointCloud& cloud, const Eigen::Vector3d& viewpoint_m, double spacing_m,
                const FreeSpaceConfig& config, DepthView& view) {
    view.eye = (viewpoint_m - cloud.origin_m).cast<float>();
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3f& p : cloud.positions) {
        const Eigen::Vector3f d = p - view.eye;
        if (d.allFinite() && d.squaredNorm() > 0.0f) sum += d.normalized().cast<double>();
    }
    if (!(sum.norm() > 0.0)) return false;
    view.rows = camera_rows(sum.normalized().cast<float>());
    std::vector<Eigen::Vector3f> projected;
    projected.reserve(cloud.size());
    for (const Eigen::Vector3f& p : cloud.positions) projected.push_back(view.project(p));
    if (!frame_view(projected, spacing_m, config, view)) return false;
    fill_front(projected, view);
    return true;
}

}  // namespace

FreeSpaceResult check_free_space(const PointCloud& viewed, const Eigen::Vector3d& viewpoint_m,
                                 double spacing_m, const PointCloud& other,
                                 const Pose& T_viewed_other, const FreeSpaceConfig& config) {
    FreeSpaceResult result;
    if (viewed.empty() || other.empty() || config.max_samples == 0) return result;
    if (!(spacing_m > 0.0)) spacing_m = median_sample_spacing_m(viewed);
    DepthView view;
    if (!(spacing_m > 0.0) || !build_view(viewed, viewpoint_m, spacing_m, config, view)) {
        return result;
    }
    result.valid = true;
    const Eigen::Isometry3f T_local = (Eigen::Translation3d(-viewed.origin_m) * T_viewed_other *
                                       Eigen::Translation3d(other.origin_m))
                                          .cast<float>();
    const auto tolerance = static_cast<float>(config.tolerance_spacing_factor * spacing_m);
    const std::size_t stride = std::max<std::size_t>(1, other.size() / config.max_samples);
    for (std::size_t i = 0; i < other.size(); i += stride) {
        ++result.samples;
        const Eigen::Vector3f c = view.project(T_local * other.positions[i]);
        if (!(c.z() > 0.0f) || !c.allFinite()) continue;
        const float front = view.front_at(c.x(), c.y());
        if (front == kEmpty) continue;
        ++result.in_view;
        result.violations += c.z() < front - tolerance;
    }
    if (result.in_view > 0) {
        result.violation_fraction =
            static_cast<double>(result.violations) / static_cast<double>(result.in_view);
    }
    return result;
}

}  // namespace anascan
