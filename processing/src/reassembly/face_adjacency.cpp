// The directed face-adjacency graph (paper §5.1, Fig. 14): two faces are adjacent when
// both have inliers near the line where their planes meet, over a common segment.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "feature_steps.hpp"

namespace anascan::reassembly::detail {
namespace {

constexpr double kRadToDeg = 180.0 / std::numbers::pi;
constexpr std::size_t kMaxPointsPerFace = 20000;

struct Line {
    Eigen::Vector3d point, direction;
};

// The line where the two planes meet (the point nearest to both rectangle centres).
Line plane_intersection(const PlanarFace& a, const PlanarFace& b) {
    const Eigen::Vector3d d = a.normal.cross(b.normal).normalized();
    Eigen::Matrix3d A;
    A.row(0) = a.normal.transpose();
    A.row(1) = b.normal.transpose();
    A.row(2) = d.transpose();
    const Eigen::Vector3d rhs(a.offset_m, b.offset_m, d.dot(0.5 * (a.centre_m + b.centre_m)));
    return {A.colPivHouseholderQr().solve(rhs), d};
}

// Robust interval (2nd to 98th percentile) along the line of the face's inliers within
// band_m of it; false when fewer than ten inliers lie there.
bool interval_along(const FeatureInput& in, const FaceBuild& f, const Line& line, double band_m,
                    double& lo, double& hi) {
    const std::size_t stride = std::max<std::size_t>(1, f.inliers.size() / kMaxPointsPerFace);
    std::vector<double> t;
    for (std::size_t k = 0; k < f.inliers.size(); k += stride) {
        const Eigen::Vector3d v = in.points[f.inliers[k]].cast<double>() - line.point;
        const double along = v.dot(line.direction);
        if ((v - along * line.direction).norm() < band_m) t.push_back(along);
    }
    if (t.size() < 10) return false;
    std::sort(t.begin(), t.end());
    lo = t[t.size() / 50];
    hi = t[t.size() - 1 - t.size() / 50];
    return true;
}

}  // namespace

std::vector<FaceEdge> face_adjacency(const FeatureInput& in, const std::vector<FaceBuild>& faces,
                                     const AdjacencyConfig& c) {
    std::vector<FaceEdge> edges;
    for (std::size_t i = 0; i < faces.size(); ++i) {
        for (std::size_t j = i + 1; j < faces.size(); ++j) {
            const PlanarFace &a = faces[i].face, &b = faces[j].face;
            const double angle_deg =
                std::acos(std::clamp(a.normal.dot(b.normal), -1.0, 1.0)) * kRadToDeg;
            if (angle_deg < c.min_angle_deg || angle_deg > 180.0 - c.min_angle_deg) continue;
            const Line line = plane_intersection(a, b);
            double lo_a, hi_a, lo_b, hi_b;
            if (!interval_along(in, faces[i], line, c.band_m, lo_a, hi_a) ||
                !interval_along(in, faces[j], line, c.band_m, lo_b, hi_b))
                continue;
            const double lo = std::max(lo_a, lo_b), hi = std::min(hi_a, hi_b);
            if (hi - lo < c.min_edge_length_m) continue;
            const FaceEdge e{.from = a.id,
                             .to = b.id,
                             .point_m = line.point + 0.5 * (lo + hi) * line.direction,
                             .direction = line.direction,
                             .length_m = hi - lo,
                             .angle_deg = angle_deg};
            edges.push_back(e);
            edges.push_back({.from = b.id,
                             .to = a.id,
                             .point_m = e.point_m,
                             .direction = -e.direction,
                             .length_m = e.length_m,
                             .angle_deg = angle_deg});
        }
    }
    return edges;
}

void snap_to_neighbours(std::vector<FaceBuild>& faces, const std::vector<FaceEdge>& edges,
                        double max_shift_m) {
    for (FaceBuild& f : faces) {
        PlanarFace& face = f.face;
        // Signed half extents: +width, -width, +height, -height sides.
        const Eigen::Vector3d axes[4] = {face.width_axis, -face.width_axis, face.height_axis,
                                         -face.height_axis};
        double half[4] = {0.5 * face.width_m, 0.5 * face.width_m, 0.5 * face.height_m,
                          0.5 * face.height_m};
        for (const FaceEdge& e : edges) {
            if (e.from != face.id) continue;
            const PlanarFace& other = faces[e.to].face;
            for (int s = 0; s < 4; ++s) {
                const double along = other.normal.dot(axes[s]);
                if (along < 0.8) continue;  // This neighbour does not close side s.
                const double t = (other.offset_m - other.normal.dot(face.centre_m)) / along;
                if (std::abs(t - half[s]) < max_shift_m) half[s] = t;
            }
        }
        const double du = 0.5 * (half[0] - half[1]), dv = 0.5 * (half[2] - half[3]);
        face.centre_m += du * face.width_axis + dv * face.height_axis;
        face.width_m = half[0] + half[1];
        face.height_m = half[2] + half[3];
        if (face.height_m > face.width_m) {
            std::swap(face.width_m, face.height_m);
            face.width_axis = face.height_axis;
            face.height_axis = face.normal.cross(face.width_axis);
        }
        face.area_m2 = face.width_m * face.height_m;
    }
}

}  // namespace anascan::reassembly::detail
