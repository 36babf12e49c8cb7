#include "cgal_geometry.hpp"

#include <CGAL/Shape_detection/Efficient_RANSAC.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/convex_hull_2.h>
#include <CGAL/min_quadrilateral_2.h>
#include <CGAL/property_map.h>

#include <algorithm>
#include <utility>

namespace anascan::reassembly::detail {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using PointWithNormal = std::pair<Kernel::Point_3, Kernel::Vector_3>;
using PwnVector = std::vector<PointWithNormal>;
using Traits = CGAL::Shape_detection::Efficient_RANSAC_traits<
    Kernel, PwnVector, CGAL::First_of_pair_property_map<PointWithNormal>,
    CGAL::Second_of_pair_property_map<PointWithNormal>>;
using EfficientRansac = CGAL::Shape_detection::Efficient_RANSAC<Traits>;
using RansacPlane = CGAL::Shape_detection::Plane<Traits>;

DetectedPlane to_detected(const RansacPlane& plane, const PwnVector& input) {
    DetectedPlane out;
    const Kernel::Vector_3 n = plane.plane_normal();
    out.normal = Eigen::Vector3d(n.x(), n.y(), n.z()).normalized();
    out.indices.assign(plane.indices_of_assigned_points().begin(),
                       plane.indices_of_assigned_points().end());
    // Orient the plane like its inliers' normals (CGAL's sign is arbitrary).
    double agreement = 0.0;
    for (std::size_t i : out.indices) {
        const Kernel::Vector_3& m = input[i].second;
        agreement += out.normal.dot(Eigen::Vector3d(m.x(), m.y(), m.z()));
    }
    if (agreement < 0.0) out.normal = -out.normal;
    const Kernel::Point_3& p = input[out.indices.front()].first;
    out.offset_m = out.normal.dot(Eigen::Vector3d(p.x(), p.y(), p.z()));
    return out;
}

}  // namespace

std::vector<DetectedPlane> detect_planes(std::span<const Eigen::Vector3f> points,
                                         std::span<const Eigen::Vector3f> normals,
                                         const RansacParams& params) {
    PwnVector input;
    input.reserve(points.size());
    for (std::size_t i = 0; i < points.size(); ++i)
        input.emplace_back(Kernel::Point_3(points[i].x(), points[i].y(), points[i].z()),
                           Kernel::Vector_3(normals[i].x(), normals[i].y(), normals[i].z()));
    // CGAL draws from its thread-local default generator: seed it for reproducible faces.
    CGAL::get_default_random() = CGAL::Random(static_cast<unsigned int>(params.seed));
    EfficientRansac ransac;
    ransac.set_input(input);
    ransac.add_shape_factory<RansacPlane>();
    EfficientRansac::Parameters p;
    p.probability = params.probability;
    p.min_points = params.min_points;
    p.epsilon = params.epsilon_m;
    p.cluster_epsilon = params.cluster_epsilon_m;
    p.normal_threshold = params.normal_cos;
    ransac.detect(p);
    std::vector<DetectedPlane> planes;
    for (const auto& shape : ransac.shapes()) {
        const auto* plane = dynamic_cast<const RansacPlane*>(shape.get());
        if (plane != nullptr && !plane->indices_of_assigned_points().empty())
            planes.push_back(to_detected(*plane, input));
    }
    std::sort(planes.begin(), planes.end(), [](const DetectedPlane& a, const DetectedPlane& b) {
        return a.indices.size() > b.indices.size();
    });
    return planes;
}

Rectangle2 min_area_rectangle(std::span<const Eigen::Vector2d> points) {
    if (points.size() < 3) return {};
    std::vector<Kernel::Point_2> input, hull;
    input.reserve(points.size());
    for (const Eigen::Vector2d& p : points) input.emplace_back(p.x(), p.y());
    CGAL::convex_hull_2(input.begin(), input.end(), std::back_inserter(hull));
    if (hull.size() < 3) return {};
    std::vector<Kernel::Point_2> corners;
    CGAL::min_rectangle_2(hull.begin(), hull.end(), std::back_inserter(corners));
    if (corners.size() != 4) return {};
    auto vec = [](const Kernel::Point_2& a) { return Eigen::Vector2d(a.x(), a.y()); };
    const Eigen::Vector2d c0 = vec(corners[0]), e1 = vec(corners[1]) - c0,
                          e2 = vec(corners[3]) - c0;
    Rectangle2 r{.centre = c0 + 0.5 * (e1 + e2)};
    const bool first_long = e1.norm() >= e2.norm();
    r.long_axis = (first_long ? e1 : e2).normalized();
    r.long_m = std::max(e1.norm(), e2.norm());
    r.short_m = std::min(e1.norm(), e2.norm());
    return r;
}

}  // namespace anascan::reassembly::detail
