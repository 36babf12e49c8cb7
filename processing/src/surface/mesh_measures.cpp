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

}  // namespace anascan
