#include <Eigen/Eigenvalues>
#include <algorithm>

#include "anascan/processing/surface/model_report.hpp"

namespace anascan {

double mesh_area_m2(const Mesh& mesh) {
    const auto& p = mesh.vertices.positions;
    double area = 0.0;
    for (const Eigen::Vector3i& t : mesh.triangles) {
        const Eigen::Vector3d a = p[t[0]].cast<double>(), b = p[t[1]].cast<double>(),
                              c = p[t[2]].cast<double>();
        area += 0.5 * (b - a).cross(c - a).norm();
    }
    return area;
}

double mesh_volume_m3(const Mesh& mesh) {
    const auto& p = mesh.vertices.positions;
    double six_v = 0.0;
    for (const Eigen::Vector3i& t : mesh.triangles) {
        six_v += p[t[0]].cast<double>().dot(p[t[1]].cast<double>().cross(p[t[2]].cast<double>()));
    }
    return six_v / 6.0;
}

namespace {

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

}  // namespace

Eigen::Vector3d oriented_box_mm(const Mesh& mesh) {
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
    if (total <= 0.0) return Eigen::Vector3d::Zero();
    mean /= total;
    const Eigen::Matrix3d cov = second / total - mean * mean.transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
    // Principal axes are undefined for isotropic shapes (a cube): the frame's own axes are
    // tried too, and the smaller box wins.
    Eigen::Vector3d size = box_extent_m(p, eig.eigenvectors());
    const Eigen::Vector3d aligned = box_extent_m(p, Eigen::Matrix3d::Identity());
    if (aligned.prod() < size.prod()) size = aligned;
    size *= 1e3;
    std::sort(size.data(), size.data() + 3, std::greater<>());
    return size;
}

}  // namespace anascan
