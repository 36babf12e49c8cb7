#pragma once
// Analytic meshes for the surface tests: boxes with outward winding.
#include <Eigen/Core>

#include "anascan/processing/core/mesh.hpp"

namespace anascan::test {

/// A cube from the origin to (size, size, size), 12 triangles, outward winding.
inline Mesh cube(double size = 1.0) {
    Mesh m;
    for (int i = 0; i < 8; ++i) {
        m.vertices.positions.emplace_back(float(size * (i & 1)), float(size * ((i >> 1) & 1)),
                                          float(size * ((i >> 2) & 1)));
    }
    const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                             {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : quads) {
        m.triangles.emplace_back(q[0], q[1], q[2]);
        m.triangles.emplace_back(q[0], q[2], q[3]);
    }
    return m;
}

/// A box centred at the origin with `size` edge lengths, each face an n x n grid of quads
/// (two triangles each), outward winding; vertices are not shared between faces.
inline Mesh grid_box(const Eigen::Vector3d& size, int n) {
    Mesh m;
    for (int axis = 0; axis < 3; ++axis) {
        for (int side = -1; side <= 1; side += 2) {
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            const int base = int(m.vertices.positions.size());
            for (int i = 0; i <= n; ++i) {
                for (int j = 0; j <= n; ++j) {
                    Eigen::Vector3d p;
                    p[axis] = 0.5 * side * size[axis];
                    p[u] = size[u] * (double(i) / n - 0.5);
                    p[v] = size[v] * (double(j) / n - 0.5);
                    m.vertices.positions.push_back(p.cast<float>());
                }
            }
            for (int i = 0; i < n; ++i) {
                for (int j = 0; j < n; ++j) {
                    const int a = base + i * (n + 1) + j, b = a + n + 1, c = b + 1, d = a + 1;
                    // (u, v, axis) is right-handed: counter-clockwise in (u, v) faces +axis.
                    if (side > 0) {
                        m.triangles.emplace_back(a, b, c);
                        m.triangles.emplace_back(a, c, d);
                    } else {
                        m.triangles.emplace_back(a, c, b);
                        m.triangles.emplace_back(a, d, c);
                    }
                }
            }
        }
    }
    return m;
}

}  // namespace anascan::test
