#pragma once
// An analytic box mesh for the reassembly tests: one vertex grid per face, so that every
// face's normals are its own, with an optional relief pushed inward.
#include <cmath>
#include <functional>

#include "anascan/processing/core/mesh.hpp"

namespace anascan::reassembly::testing {

using Relief = std::function<double(int face, double u, double v)>;

// A box centred at the origin, one grid of vertices per face (relief pushed inward), so
// that every face's normals are its own.
inline Mesh box_mesh(const Eigen::Vector3d& size_m, double step_m, const Relief& relief = {}) {
    Mesh mesh;
    for (int f = 0; f < 6; ++f) {
        const int axis = f / 2;
        const double sign = f % 2 == 0 ? 1.0 : -1.0;
        const int ua = (axis + 1) % 3, va = (axis + 2) % 3;
        const int nu = int(std::round(size_m[ua] / step_m)),
                  nv = int(std::round(size_m[va] / step_m));
        const int base = int(mesh.vertices.size());
        for (int j = 0; j <= nv; ++j) {
            for (int i = 0; i <= nu; ++i) {
                Eigen::Vector3d p;
                p[axis] = sign * 0.5 * size_m[axis];
                p[ua] = (double(i) / nu - 0.5) * size_m[ua];
                p[va] = (double(j) / nv - 0.5) * size_m[va];
                if (relief) p[axis] -= sign * relief(f, p[ua], p[va]);
                mesh.vertices.positions.push_back(p.cast<float>());
            }
        }
        for (int j = 0; j < nv; ++j) {
            for (int i = 0; i < nu; ++i) {
                const int a = base + j * (nu + 1) + i, b = a + 1, c = a + nu + 1, d = c + 1;
                if (sign > 0) {
                    mesh.triangles.emplace_back(a, b, d), mesh.triangles.emplace_back(a, d, c);
                } else {
                    mesh.triangles.emplace_back(a, d, b), mesh.triangles.emplace_back(a, c, d);
                }
            }
        }
    }
    return mesh;
}

}  // namespace anascan::reassembly::testing
