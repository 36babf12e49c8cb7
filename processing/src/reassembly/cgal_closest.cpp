// The closest point on a triangle set by CGAL's AABB tree (see mesh_distance.hpp).
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include "mesh_distance.hpp"

namespace anascan::reassembly::detail {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Triangles = std::vector<Kernel::Triangle_3>;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, Triangles::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

Kernel::Point_3 point(const Eigen::Vector3f& p) { return {p.x(), p.y(), p.z()}; }

}  // namespace

struct ClosestTriangle::Impl {
    Triangles triangles;
    std::vector<std::size_t> index;  ///< Input index of each kept triangle.
    Tree tree;
};

ClosestTriangle::ClosestTriangle(std::span<const Eigen::Vector3f> v,
                                 std::span<const Eigen::Vector3i> triangles)
    : impl_(std::make_unique<Impl>()) {
    for (std::size_t t = 0; t < triangles.size(); ++t) {
        const Eigen::Vector3i& f = triangles[t];
        const Kernel::Triangle_3 tri(point(v[std::size_t(f[0])]), point(v[std::size_t(f[1])]),
                                     point(v[std::size_t(f[2])]));
        if (tri.is_degenerate()) continue;
        impl_->triangles.push_back(tri);
        impl_->index.push_back(t);
    }
    impl_->tree.insert(impl_->triangles.begin(), impl_->triangles.end());
    impl_->tree.accelerate_distance_queries();
}

ClosestTriangle::~ClosestTriangle() = default;
ClosestTriangle::ClosestTriangle(ClosestTriangle&&) noexcept = default;
ClosestTriangle& ClosestTriangle::operator=(ClosestTriangle&&) noexcept = default;

bool ClosestTriangle::closest(const Eigen::Vector3d& x, Eigen::Vector3d& p,
                              std::size_t& triangle) const {
    if (impl_->triangles.empty()) return false;
    const auto [q, id] =
        impl_->tree.closest_point_and_primitive(Kernel::Point_3(x.x(), x.y(), x.z()));
    p = Eigen::Vector3d(q.x(), q.y(), q.z());
    triangle = impl_->index[std::size_t(id - impl_->triangles.cbegin())];
    return true;
}

}  // namespace anascan::reassembly::detail
