// The closest point on a triangle set by CGAL's AABB tree (see triangle_tree.hpp).
#include "anascan/processing/spatial/triangle_tree.hpp"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <vector>

namespace anascan {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Triangles = std::vector<Kernel::Triangle_3>;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, Triangles::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

Kernel::Point_3 point(const Eigen::Vector3f& p) { return {p.x(), p.y(), p.z()}; }
Kernel::Point_3 point(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }

}  // namespace

struct TriangleTree::Impl {
    Triangles triangles;
    std::vector<std::size_t> index;  ///< Input index of each kept triangle.
    Tree tree;
};

TriangleTree::TriangleTree(std::span<const Eigen::Vector3f> v,
                           std::span<const Eigen::Vector3i> triangles)
    : impl_(std::make_unique<Impl>()) {
    impl_->triangles.reserve(triangles.size());
    impl_->index.reserve(triangles.size());
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

TriangleTree::~TriangleTree() = default;
TriangleTree::TriangleTree(TriangleTree&&) noexcept = default;
TriangleTree& TriangleTree::operator=(TriangleTree&&) noexcept = default;

bool TriangleTree::closest(const Eigen::Vector3d& x, Eigen::Vector3d& p,
                           std::size_t& triangle) const {
    if (impl_->triangles.empty()) return false;
    const auto [q, id] = impl_->tree.closest_point_and_primitive(point(x));
    p = Eigen::Vector3d(q.x(), q.y(), q.z());
    triangle = impl_->index[std::size_t(id - impl_->triangles.cbegin())];
    return true;
}

bool TriangleTree::segment_hits(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const {
    if (impl_->triangles.empty() || a == b) return false;
    return impl_->tree.do_intersect(Kernel::Segment_3(point(a), point(b)));
}

std::size_t TriangleTree::size() const { return impl_->triangles.size(); }

}  // namespace anascan
