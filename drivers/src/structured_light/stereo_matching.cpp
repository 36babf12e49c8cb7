#include "anascan/drivers/structured_light/stereo_matching.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Core>
#include <Eigen/LU>
#include <cmath>
#include <limits>
#include <opencv2/core.hpp>

namespace anascan::drivers::sl {
namespace {

/// For every projector pixel, the cam2 pixel whose decoded coordinates are closest to its
/// centre (-1 when none).
class ProjectorIndex {
public:
    ProjectorIndex(const ProjectorMap& map, const GrayCodeLayout& projector)
        : width_(projector.projector_width_px),
          height_(projector.projector_height_px),
          cam_width_(map.column_px.cols),
          pixel_(std::size_t(width_) * height_, -1),
          distance_(pixel_.size(), std::numeric_limits<float>::max()) {
        for (int y = 0; y < map.column_px.rows; ++y) {
            const float* col = map.column_px.ptr<float>(y);
            const float* row = map.row_px.ptr<float>(y);
            for (int x = 0; x < cam_width_; ++x) {
                const int cell = cell_of(col[x], row[x]);
                if (cell < 0) continue;
                const float d =
                    std::hypot(col[x] - std::round(col[x]), row[x] - std::round(row[x]));
                if (d < distance_[cell]) {
                    distance_[cell] = d;
                    pixel_[cell] = y * cam_width_ + x;
                }
            }
        }
    }

    /// The indexed cam2 pixel for projector coordinates (u, v), looking at the 3x3 cells
    /// around when its own cell is empty; false when none.
    bool find(float u, float v, cv::Point2i& out) const {
        const int cu = int(std::floor(u + 0.5f)), cv_ = int(std::floor(v + 0.5f));
        for (int ring = 0; ring <= 1; ++ring) {
            for (int dv = -ring; dv <= ring; ++dv) {
                for (int du = -ring; du <= ring; ++du) {
                    const int cell = cell_of(float(cu + du), float(cv_ + dv));
                    if (cell < 0 || pixel_[cell] < 0) continue;
                    out = {pixel_[cell] % cam_width_, pixel_[cell] / cam_width_};
                    return true;
                }
            }
        }
        return false;
    }

private:
    /// The projector pixel containing (u, v), or -1 (also for NaN).
    int cell_of(float u, float v) const {
        const float fu = u + 0.5f, fv = v + 0.5f;  // Pixel c covers [c - 0.5, c + 0.5).
        if (!(fu >= 0.0f && fv >= 0.0f && fu < float(width_) && fv < float(height_))) return -1;
        return int(fv) * width_ + int(fu);
    }

    int width_, height_, cam_width_;
    std::vector<int> pixel_;
    std::vector<float> distance_;
};

Eigen::Vector2f code_at(const ProjectorMap& m, int x, int y) {
    return {m.column_px.at<float>(y, x), m.row_px.at<float>(y, x)};
}

bool inside_valid(const ProjectorMap& m, int x, int y) {
    return x >= 0 && y >= 0 && x < m.contrast.cols && y < m.contrast.rows && m.valid(x, y);
}

/// Derivative of the code along (dx, dy) at a valid pixel: central difference when both
/// neighbours are valid, else one-sided; false when neither is.
bool derivative(const ProjectorMap& m, int x, int y, int dx, int dy, Eigen::Vector2f& d) {
    const bool fwd = inside_valid(m, x + dx, y + dy);
    const bool bwd = inside_valid(m, x - dx, y - dy);
    if (fwd && bwd)
        d = 0.5f * (code_at(m, x + dx, y + dy) - code_at(m, x - dx, y - dy));
    else if (fwd)
        d = code_at(m, x + dx, y + dy) - code_at(m, x, y);
    else if (bwd)
        d = code_at(m, x, y) - code_at(m, x - dx, y - dy);
    return fwd || bwd;
}

/// Newton steps q <- q + J^-1 (target - code(q)) over cam2's pixel grid.
/// `det_out`: |det J| at the last step (projector px^2 per cam2 px^2).
bool invert(const ProjectorMap& cam2, Eigen::Vector2f target, cv::Point2i q,
            const StereoMatchConfig& config, cv::Point2f& out, float& det_out) {
    for (int it = 0; it < config.max_iterations; ++it) {
        Eigen::Matrix2f J;
        Eigen::Vector2f dx, dy;
        if (!derivative(cam2, q.x, q.y, 1, 0, dx) || !derivative(cam2, q.x, q.y, 0, 1, dy))
            return false;
        J << dx, dy;
        det_out = std::abs(J.determinant());
        if (det_out < config.min_jacobian_det) return false;
        const Eigen::Vector2f step = J.inverse() * (target - code_at(cam2, q.x, q.y));
        if (std::abs(step.x()) <= 0.5f && std::abs(step.y()) <= 0.5f) {
            out = {float(q.x) + step.x(), float(q.y) + step.y()};
            return true;
        }
        q += cv::Point2i(int(std::lround(step.x())), int(std::lround(step.y())));
        if (!inside_valid(cam2, q.x, q.y)) return false;
    }
    return false;
}

/// |det| of the cam1 code's Jacobian at (x, y), or NaN.
float jacobian_det(const ProjectorMap& m, int x, int y) {
    Eigen::Vector2f dx, dy;
    if (!derivative(m, x, y, 1, 0, dx) || !derivative(m, x, y, 0, 1, dy))
        return std::numeric_limits<float>::quiet_NaN();
    return std::abs(dx.x() * dy.y() - dx.y() * dy.x());
}

/// Both cameras see the surface with similar foreshortening (see StereoMatchConfig).
bool similar_footprints(float det1, float det2, float max_ratio) {
    if (max_ratio <= 0.0f) return true;
    return det2 <= max_ratio * det1 && det1 <= max_ratio * det2;  // False for NaN.
}

/// The sub-pixel cam2 position matching cam1's pixel (x, y), or false.
bool match_pixel(const ProjectorMap& cam1, const ProjectorMap& cam2, const ProjectorIndex& index,
                 int x, int y, const StereoMatchConfig& config, cv::Point2f& q) {
    const Eigen::Vector2f target = code_at(cam1, x, y);
    cv::Point2i start;
    float det2 = 0.0f;
    if (!index.find(target.x(), target.y(), start) || !invert(cam2, target, start, config, q, det2))
        return false;
    return similar_footprints(jacobian_det(cam1, x, y), det2, config.max_foreshortening_ratio);
}

}  // namespace

StereoMatches match_projector_maps(const ProjectorMap& cam1, const ProjectorMap& cam2,
                                   const GrayCodeLayout& projector,
                                   const StereoMatchConfig& config) {
    const ProjectorIndex index(cam2, projector);
    constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
    cv::Mat found(cam1.column_px.size(), CV_32FC2, cv::Scalar(kNaN, kNaN));
    tbb::parallel_for(
        tbb::blocked_range<int>(0, cam1.column_px.rows, 16), [&](const tbb::blocked_range<int>& r) {
            for (int y = r.begin(); y < r.end(); ++y) {
                for (int x = 0; x < cam1.column_px.cols; ++x) {
                    cv::Point2f q;
                    if (cam1.valid(x, y) && match_pixel(cam1, cam2, index, x, y, config, q))
                        found.at<cv::Point2f>(y, x) = q;
                }
            }
        });
    StereoMatches matches;
    matches.cam1_valid = cam1.valid_count;
    for (int y = 0; y < found.rows; ++y) {
        for (int x = 0; x < found.cols; ++x) {
            const cv::Point2f q = found.at<cv::Point2f>(y, x);
            if (std::isnan(q.x)) continue;
            matches.cam1_px.emplace_back(x, y);
            matches.cam2_px.push_back(q);
        }
    }
    return matches;
}

}  // namespace anascan::drivers::sl
