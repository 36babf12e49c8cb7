// The oriented bounding box of the model report: CGAL's optimal bounding box (Chang, Gorissen
// and Melchior 2011, CGAL::oriented_bounding_box) on an even subset of the vertices, its
// extents then taken over all of them; the principal axes and the frame's axes are tried
// too, and the smallest box wins. Only this file includes CGAL's box.
#define CGAL_EIGEN3_ENABLED 1
#include <CGAL/Simple_cartesian.h>
#include <CGAL/optimal_bounding_box.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <functional>

#include "anascan/processing/surface/model_report.hpp"

namespace anascan {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
// The box of a set is the box of its convex hull, so CGAL's optimisation needs only hull
// points: the extreme points along these many directions (a Fibonacci half-sphere, both
// ends of each) are hull vertices, a few hundred instead of the mesh's 10^5-10^6 vertices.
// CGAL's own hull would need an exact-predicates kernel (GMP and -frounding-math).
constexpr int kHullDirections = 512;

Eigen::Vector3d box_extent_m(const std::vector<Eigen::Vector3f>& points,
                             const Eigen::Matrix3d& axes) {
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
    for (const Eigen::Vector3f& v : points) {
        const Eigen::Vector3d q = axes.transpose() * v.cast<double>();
        lo = lo.cwiseMin(q);
        hi = hi.cwiseMax(q);
    }
    return hi - lo;
}

Eigen::Matrix3d principal_axes(const Mesh& mesh) {
    const auto& p = mesh.vertices.positions;
    double total = 0.0;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
    for (const Eigen::Vector3i& t : mesh.triangles) {
        const Eigen::Vector3d a = p[t[0]].cast<double>(), b = p[t[1]].cast<double>(),
                              c = p[t[2]].cast<double>();
        const double w = 0.5 * (b - a).cross(c - a).norm();
        const Eigen::Vector3d m = (a + b + c) / 3.0;
        total += w;
        mean += w * m;
        second += w * m * m.transpose();
    }
    if (total <= 0.0) return Eigen::Matrix3d::Identity();
    mean /= total;
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(second / total -
                                                             mean * mean.transpose());
    return eig.eigenvectors();
}

std::vector<std::size_t> extreme_points(const std::vector<Eigen::Vector3f>& p) {
    std::vector<Eigen::Vector3f> directions;
    const float golden = 3.14159265f * (3.0f - std::sqrt(5.0f));
    for (int k = 0; k < kHullDirections; ++k) {
        const float z = (k + 0.5f) / kHullDirections;  // upper half: -d gives the other end
        const float r = std::sqrt(1.0f - z * z);
        directions.emplace_back(r * std::cos(golden * k), r * std::sin(golden * k), z);
    }
    std::vector<std::size_t> lo(directions.size(), 0), hi(directions.size(), 0);
    std::vector<float> lo_v(directions.size(), 1e30f), hi_v(directions.size(), -1e30f);
    for (std::size_t i = 0; i < p.size(); ++i) {
        for (std::size_t d = 0; d < directions.size(); ++d) {
            const float s = directions[d].dot(p[i]);
            if (s < lo_v[d]) lo_v[d] = s, lo[d] = i;
            if (s > hi_v[d]) hi_v[d] = s, hi[d] = i;
        }
    }
    std::vector<std::size_t> out(lo);
    out.insert(out.end(), hi.begin(), hi.end());
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

// The rotation of CGAL's optimal box (columns: the box axes), seeded so it repeats.
Eigen::Matrix3d optimal_axes(const std::vector<Eigen::Vector3f>& p) {
    std::vector<Kernel::Point_3> points;
    for (const std::size_t i : extreme_points(p)) points.emplace_back(p[i].x(), p[i].y(), p[i].z());
    Kernel::Aff_transformation_3 T;
    CGAL::oriented_bounding_box(points, T, CGAL::parameters::use_convex_hull(false).random_seed(1));
    Eigen::Matrix3d R;  // T maps the points into the box's axis-aligned frame: rows are axes.
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) R(r, c) = CGAL::to_double(T.m(r, c));
    return R.transpose();
}

}  // namespace

Eigen::Vector3d oriented_box_mm(const Mesh& mesh) {
    const auto& p = mesh.vertices.positions;
    if (p.size() < 4 || mesh.triangles.empty()) return Eigen::Vector3d::Zero();
    Eigen::Vector3d size = box_extent_m(p, Eigen::Matrix3d::Identity());
    for (const Eigen::Matrix3d& axes : {principal_axes(mesh), optimal_axes(p)}) {
        const Eigen::Vector3d s = box_extent_m(p, axes);
        if (s.prod() < size.prod()) size = s;
    }
    size *= 1e3;
    std::sort(size.data(), size.data() + 3, std::greater<>());
    return size;
}

}  // namespace anascan
